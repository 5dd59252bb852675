"""The EMPS benchmark's figure of merit for a diagnosed model: the relative error
100·‖y − ŷ‖/‖y‖ (SOURCE.md), on force and prediction low-passed and decimated in parallel as in
the benchmark's IDIM-LS (:func:`leuven_rt.data.signals.decimate`), edges dropped;
and the same error of that model (fitted on one record) on another record, such as the
validation set."""

from __future__ import annotations

import math

import numpy as np

from ..data.records import DataLike, as_motion_data
from ..data.signals import decimate
from ..discrepancy.features import Features, compute_features
from ..discrepancy.model import ModelFit

#: The benchmark's decimation factor.
DECIMATION = 10


def relative_error(fit: ModelFit, features: Features, decimation: int = DECIMATION) -> float:
    """100·‖y − ŷ‖/‖y‖ [%] of ``fit`` on ``features``' record, after decimation."""
    y = decimate(features.force, decimation)
    prediction = decimate(fit.predict(features), decimation)
    edge = math.ceil(np.count_nonzero(~features.usable[: features.usable.size // 2]) / decimation) + 1
    keep = slice(edge, y.size - edge)
    return float(100.0 * np.linalg.norm(y[keep] - prediction[keep]) / np.linalg.norm(y[keep]))


def relative_error_on(fit: ModelFit, fitted_on: Features, data: DataLike) -> float:
    """The relative error of ``fit`` (fitted on ``fitted_on``'s record) on another record."""
    return relative_error(fit, compute_features(as_motion_data(data), fitted_on.scales))
