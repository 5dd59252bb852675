"""Logs in, signals out: the data toolkit both workflows (identification and discrepancy) build on.

- :mod:`.records`: :class:`MotionData`, loading (CSV, EMPS ``.mat``), validation, resampling;
- :mod:`.signals`: zero-phase derivatives, the benchmark's decimation, the force noise floor;
- :mod:`.segments`: reversals, travel since each, the presliding transition lengths;
- :mod:`.slip`: the deflections of Maxwell-slip elements driven by a position;
- :mod:`.regression`: linear least squares on named regressor columns;
- :mod:`.synthetic`, :mod:`.scenarios`: logs and excitations made by the simulator, with the
  standard parameter set.

It imports only the public face, never a workflow.
"""

from .._extras import require

require("scipy", extra="analysis", needed_by="leuven_rt.data")


from .records import MotionData, as_motion_data, load_columns
from .regression import LinearFit, fit_linear
from .segments import Segments, find_segments
from .signals import Derivatives, decimate, estimate_derivatives, noise_floor
from .slip import element_deflections

__all__ = [
    "Derivatives",
    "LinearFit",
    "MotionData",
    "Segments",
    "as_motion_data",
    "decimate",
    "element_deflections",
    "estimate_derivatives",
    "find_segments",
    "fit_linear",
    "load_columns",
    "noise_floor",
]
