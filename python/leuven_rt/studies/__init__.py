"""What the command line and the README reproduce: each study returns its data and its text, and
draws through :mod:`leuven_rt._plot`.

- :mod:`.demo`: the presliding-to-sliding scenario and the diagnose story (``leuven-rt demo``);
- :mod:`.figures`: the paper's figures with their numbers (``leuven-rt figures``);
- :mod:`.accuracy`: explicit against implicit steps, velocity- and force-driven
  (``leuven-rt accuracy``);
- :mod:`.closed_loop`: PID on a simulated stage with and without compensation
  (``leuven-rt control``);
- :mod:`.emps`: the EMPS benchmark's figure of merit for a model file;
- :mod:`.idim`: the benchmark's own inverse-model least squares (IDIM-LS), reproduced.

Studies may import every room of the package but the command line.
"""

from .._extras import require

require("scipy", "tqdm", extra="analysis", needed_by="leuven_rt.studies")
