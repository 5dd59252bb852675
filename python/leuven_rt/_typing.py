"""Type aliases shared across the package, so that every module spells an array, a parameter
set or a log the same way."""

from __future__ import annotations

from collections.abc import Mapping
from os import PathLike
from typing import TYPE_CHECKING, Any, Literal, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from .data.records import MotionData
    from .params import Params

#: A float64 array of any shape: signals (T,) or (B, T), regressor matrices, states.
FloatArray = NDArray[np.float64]
#: A boolean mask over samples (T,), e.g. the rows a fit uses.
BoolArray = NDArray[np.bool_]
#: A parameter set: a :class:`leuven_rt.Params`, or a mapping with its keys.
ParamsLike = Union["Params", Mapping[str, Any]]
#: A log: a :class:`leuven_rt.MotionData`, a path to a ``.csv`` or EMPS ``.mat`` file, or a
#: mapping of the columns ``t``, ``x``, ``f`` (and optionally ``v``).
DataLike = Union["MotionData", str, "PathLike[str]", Mapping[str, ArrayLike]]

#: The integration scheme of a step (docs/model.md#discrete-step).
Scheme = Literal["implicit", "explicit"]
#: What a compensator takes each sample: the desired velocity, or the measured position.
Mode = Literal["feedforward", "observer"]

__all__ = ["BoolArray", "DataLike", "FloatArray", "Mode", "ParamsLike", "Scheme"]
