"""Log to loop: point it at a log of a machine, and it writes the friction model the log supports
(:func:`identify`, a model file the compensator runs) and tells how it got there
(:func:`diagnose`): where the baseline model and the data disagree, which effects of the
catalogue (docs/effects.md) it named, how the gap shrank, and what remains.

The fit is :mod:`leuven_rt.fitting` (the output-error engine); this room adds the story:
:mod:`.identify` (the model file and its report), :mod:`.diagnose`, :mod:`.report` (the JSON of
docs/data-and-reports.md#diagnosis-report and the sentences), :mod:`.localise` (where, in
numbers), :mod:`.plot` (the figure) and :mod:`.hidden` (generated logs with hidden effects, to
try it on).
"""

from .._extras import require

require("scipy", "tqdm", "threadpoolctl", extra="analysis", needed_by="leuven_rt.discrepancy")


from ..fitting.settings import Settings
from ..fitting.structure import CATALOGUE, parse_effects
from .diagnose import diagnose
from .identify import DEFAULT_BASELINE, Identification, identify
from .report import Diagnosis, Step

__all__ = [
    "CATALOGUE",
    "DEFAULT_BASELINE",
    "Diagnosis",
    "Identification",
    "Settings",
    "Step",
    "diagnose",
    "identify",
    "parse_effects",
]
