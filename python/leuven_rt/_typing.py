"""Type aliases shared across the package, so that every module spells an array, a scheme or a
mode the same way. (A parameter set is :data:`leuven_rt.params.ParamsLike`; a log is
:data:`leuven_rt.data.records.DataLike`.)"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import NDArray

#: A float64 array of any shape: signals (T,) or (B, T), regressor matrices, states.
FloatArray = NDArray[np.float64]
#: A boolean mask over samples (T,), e.g. the rows a fit uses.
BoolArray = NDArray[np.bool_]

#: The integration scheme of a step (docs/model.md#discrete-step).
Scheme = Literal["implicit", "explicit"]
#: What a compensator takes each sample: the desired velocity, or the measured position.
Mode = Literal["feedforward", "observer"]

__all__ = ["BoolArray", "FloatArray", "Mode", "Scheme"]
