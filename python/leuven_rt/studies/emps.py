"""The EMPS benchmark's figure of merit for a model file: the relative error 100·‖y − ŷ‖/‖y‖
(docs/data-provenance.md), on the measured force and the file's ``predict`` output, both
low-passed and decimated as in the benchmark's IDIM-LS (:func:`leuven_rt.data.signals.decimate`),
the first and last decimated samples of one filter length dropped."""

from __future__ import annotations

import numpy as np

from ..data.records import DataLike
from ..data.signals import decimate
from ..modelfile import ModelLike
from ..prediction import Prediction, predict

#: The benchmark's decimation factor.
DECIMATION = 10


def relative_error(prediction: Prediction, decimation: int = DECIMATION) -> float:
    """100·‖y − ŷ‖/‖y‖ [%] of a prediction's ``f_model`` against its ``f``, after decimation."""
    y, model = decimate(prediction.f, decimation), decimate(prediction.f_model, decimation)
    keep = slice(decimation, y.size - decimation)
    return float(100.0 * np.linalg.norm(y[keep] - model[keep]) / np.linalg.norm(y[keep]))


def relative_error_on(model: ModelLike, data: DataLike, decimation: int = DECIMATION) -> float:
    """The relative error of ``model`` (a model file) predicting the record ``data``."""
    return relative_error(predict(model, data), decimation)


__all__ = ["DECIMATION", "relative_error", "relative_error_on"]
