"""Inverse dynamic model by linear least squares (IDIM-LS), the robotics standard.

force ≈ Σ θⱼ·φⱼ(q, q̇, q̈), with regressors such as M·q̈ + Fv·q̇ + Fc·sign(q̇) + offset, estimated as
in the EMPS benchmark (Janot, Gautier, Brunot 2019, §3): the position is low-passed by a
zero-phase Butterworth filter and differentiated by central differences; every regressor column
and the force are then low-passed and decimated in parallel (the "decimate process"), and the
first and last samples, where the zero-phase filters' edge transients live, are dropped.

The regressors are named, so that other fits (the discrepancy workflow's candidate effects) can
pick the columns they need from :data:`REGRESSORS`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from .._typing import FloatArray
from ..data.records import MotionData
from ..data.regression import LinearFit, fit_linear
from ..data.signals import Derivatives, decimate, estimate_derivatives
from ..errors import DataError, shown

#: Regressor columns of the inverse model, by the name of their coefficient.
REGRESSORS: dict[str, Callable[[Derivatives], FloatArray]] = {
    "M": lambda d: d.a,  # inertia: mass times acceleration
    "Fv": lambda d: d.v,  # viscous
    "Fc": lambda d: np.sign(d.v),  # Coulomb
    "offset": lambda d: np.ones_like(d.v),  # a constant bias of the force measurement
    "Fv_pos": lambda d: np.where(d.v > 0, d.v, 0.0),  # direction-dependent viscous, v > 0
    "Fc_pos": lambda d: (d.v > 0).astype(np.float64),
    "Fv_neg": lambda d: np.where(d.v < 0, d.v, 0.0),  # v < 0
    "Fc_neg": lambda d: -(d.v < 0).astype(np.float64),
}

#: The EMPS benchmark's reference model: force = M·q̈ + Fv·q̇ + Fc·sign(q̇) + offset.
RIGID_BODY = ("M", "Fv", "Fc", "offset")


def fit_inverse_model(
    data: MotionData,
    parameters: Sequence[str] = RIGID_BODY,
    cutoff: float = 100.0,
    order: int = 4,
    decimation: int = 10,
    edge: float | None = None,
) -> LinearFit:
    """IDIM-LS estimate of the named ``parameters`` (keys of :data:`REGRESSORS`).

    ``cutoff`` [Hz] and ``order``: the Butterworth filter on the position. ``decimation``: the
    decimation factor. ``edge`` [s]: dropped at each end after filtering (default 5/cutoff, five
    time constants of the position filter).
    """
    unknown = [name for name in parameters if name not in REGRESSORS]
    if unknown or not parameters:
        raise DataError(
            f"`parameters` must be names among {sorted(REGRESSORS)}, got {list(parameters)}",
            kind="invalid_choice",
            field="parameters",
            value=unknown[0] if unknown else None,
            expected=sorted(REGRESSORS),
            got=list(parameters),
        )
    if isinstance(decimation, bool) or not isinstance(decimation, int) or decimation < 1:
        integer = isinstance(decimation, int) and not isinstance(decimation, bool)
        raise DataError(
            f"`decimation` must be an integer >= 1, got {shown(decimation)!r}",
            kind="out_of_range" if integer else "not_integer",
            field="decimation",
            value=decimation,
            bound=1 if integer else None,
        )
    edge = 5.0 / cutoff if edge is None else float(edge)
    derivatives = estimate_derivatives(data, cutoff, order)
    drop = math.ceil(edge / (data.dt * decimation))
    y = decimate(data.f, decimation)
    if y.size - 2 * drop < 4 * len(parameters):
        raise DataError(
            f"too few samples for the inverse model: {data.samples} samples leave {y.size - 2 * drop} "
            f"after decimation by {decimation} and dropping {edge:g} s at each end",
            kind="too_few",
            value=y.size - 2 * drop,
            bound=4 * len(parameters),
        )
    keep = slice(drop, y.size - drop)
    columns = {name: decimate(REGRESSORS[name](derivatives), decimation)[keep] for name in parameters}
    return fit_linear(columns, y[keep])
