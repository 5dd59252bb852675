"""The sliding part of the model: the Stribeck curve and viscous friction, from sliding samples.

In steady sliding the modified Leuven model's force is s(v) + σ2·v, with
s(v) = sgn(v)·(Fc + (Fs − Fc)·exp(−|v/Vs|^δ)) (the ``_neg`` levels for v < 0 when asked).
This stage fits Fc, Fs, Vs, δ, σ2 (and Fc_neg, Fs_neg) to the samples taken well past the
presliding transition by nonlinear least squares (``scipy.optimize.least_squares``), started
from several Stribeck velocities spread over the measured speeds, keeping the best.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import cast

import numpy as np
from scipy.optimize import least_squares

from .._typing import FloatArray
from ..errors import DataError

#: Bounds of the Stribeck shape exponent δ: outside them the curve is a step or a plateau that
#: the data cannot tell apart from its neighbours.
DELTA_BOUNDS = (0.3, 8.0)
#: Vs is searched within this many decades below and above the measured sliding speeds.
VS_DECADES = 3.0
#: Fewer sliding samples than this cannot determine the sliding curve.
MIN_SLIDING_SAMPLES = 50


@dataclass(frozen=True, eq=False)
class SlidingFit:
    """The fitted sliding curve, with the stage's quality numbers."""

    Fc: float
    Fs: float
    Vs: float
    delta: float
    sigma2: float
    Fc_neg: float | None
    Fs_neg: float | None
    rms: float
    samples: int
    condition: float
    """Condition number of the Jacobian at the optimum, columns scaled to unit norm."""

    def params(self) -> dict[str, float]:
        out = dict(Fc=self.Fc, Fs=self.Fs, Vs=self.Vs, delta=self.delta, sigma2=self.sigma2)
        if self.Fc_neg is not None and self.Fs_neg is not None:
            out.update(Fc_neg=self.Fc_neg, Fs_neg=self.Fs_neg)
        return out


def sliding_force(
    v: FloatArray, Fc: float, Fs: float, Vs: float, delta: float, sigma2: float,
    Fc_neg: float | None = None, Fs_neg: float | None = None,
) -> FloatArray:  # fmt: skip
    """s(v) + σ2·v, the steady-state friction force of the model."""
    negative = v < 0
    fc = np.where(negative, Fc if Fc_neg is None else Fc_neg, Fc)
    fs = np.where(negative, Fs if Fs_neg is None else Fs_neg, Fs)
    force: FloatArray = np.sign(v) * (fc + (fs - fc) * np.exp(-(np.abs(v / Vs) ** delta))) + sigma2 * v
    return force


def dense_jacobian(jacobian: object) -> FloatArray:
    """``least_squares``' Jacobian, typed as what it is here: with a dense Jacobian (finite
    differences or a callable returning an array) and the default ``tr_solver``, scipy returns a
    float64 ndarray; the stubs also allow a sparse matrix or a LinearOperator."""
    return cast(FloatArray, jacobian)


def scaled_condition(jacobian: FloatArray) -> float:
    """Condition number of J with its columns scaled to unit norm (inf when a column is zero)."""
    norms = np.linalg.norm(jacobian, axis=0)
    if np.any(norms == 0.0):
        return float("inf")
    singular = np.linalg.svd(jacobian / norms, compute_uv=False)
    return float(singular[0] / singular[-1]) if singular[-1] > 0 else float("inf")


def fit_sliding(v: FloatArray, force: FloatArray, asymmetric: bool = False) -> SlidingFit:
    """Fits the sliding curve to samples of velocity ``v`` ≠ 0 and force ``force``.

    Parameters are searched as Fc, Fs − Fc ≥ 0, log Vs, δ in :data:`DELTA_BOUNDS`, σ2 ≥ 0 (and
    Fc_neg, Fs_neg − Fc_neg), so every trial is a valid curve.
    """
    if v.size < MIN_SLIDING_SAMPLES:
        raise DataError(
            f"too few sliding samples: need at least {MIN_SLIDING_SAMPLES} samples well past the "
            f"presliding transition, got {v.size}; the data must include sliding at steady speed",
            kind="too_few",
            value=int(v.size),
            bound=MIN_SLIDING_SAMPLES,
        )
    speed = np.abs(v)
    if asymmetric and (
        np.count_nonzero(v > 0) < MIN_SLIDING_SAMPLES // 2
        or np.count_nonzero(v < 0) < MIN_SLIDING_SAMPLES // 2
    ):
        raise DataError(
            "`asymmetric` needs sliding in both directions, but the data slides in one only",
            kind="not_identifiable",
            field="asymmetric",
        )
    # A straight line through the fast half gives Fc and σ2 to start from.
    fast = speed >= np.median(speed)
    slope, level = np.polyfit(speed[fast], np.sign(v[fast]) * force[fast], 1)
    level = max(float(level), 1e-3 * float(np.max(np.abs(force))))
    slope = max(float(slope), 0.0)
    peak = max(float(np.percentile(np.sign(v) * force, 99)), level)

    def unpack(p: FloatArray) -> dict[str, float]:
        out = dict(Fc=p[0], Fs=p[0] + p[1], Vs=float(np.exp(p[2])), delta=p[3], sigma2=p[4])
        if asymmetric:
            out.update(Fc_neg=p[5], Fs_neg=p[5] + p[6])
        return out

    def residual(p: FloatArray) -> FloatArray:
        return sliding_force(v, **unpack(p)) - force

    # Vs is searched within three decades of the measured speeds: beyond them the data says
    # nothing about it, and its logarithm would wander off to where the curve underflows.
    low, high = (max(value, 1e-300) for value in np.percentile(speed, [5, 95]))
    vs_bounds = (np.log(low) - VS_DECADES * np.log(10.0), np.log(high) + VS_DECADES * np.log(10.0))
    lower = [1e-12, 0.0, vs_bounds[0], DELTA_BOUNDS[0], 0.0] + ([1e-12, 0.0] if asymmetric else [])
    upper = [np.inf, np.inf, vs_bounds[1], DELTA_BOUNDS[1], np.inf] + ([np.inf, np.inf] if asymmetric else [])
    best = None
    for start_vs in np.geomspace(low, max(high, 2.0 * low), 5):
        start = [level, peak - level, np.log(start_vs), 2.0, slope] + (
            [level, peak - level] if asymmetric else []
        )
        result = least_squares(residual, start, bounds=(lower, upper), x_scale="jac")
        if best is None or result.cost < best.cost:
            best = result
    assert best is not None
    fitted = unpack(best.x)
    return SlidingFit(
        Fc=fitted["Fc"], Fs=fitted["Fs"], Vs=fitted["Vs"], delta=fitted["delta"], sigma2=fitted["sigma2"],
        Fc_neg=fitted.get("Fc_neg"), Fs_neg=fitted.get("Fs_neg"),
        rms=float(np.sqrt(np.mean(best.fun**2))), samples=int(v.size),
        condition=scaled_condition(dense_jacobian(best.jac)),
    )  # fmt: skip
