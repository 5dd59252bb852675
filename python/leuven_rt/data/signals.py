"""Signals derived from a log: zero-phase derivative estimates, the low-pass-and-decimate of the
EMPS benchmark's IDIM-LS, and the noise floor of the force.

Every fit works from these: the identification stages and the discrepancy workflow's features.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import signal

from .._typing import FloatArray
from ..errors import DataError, shown
from .records import MotionData


@dataclass(frozen=True, eq=False)
class Derivatives:
    """Zero-phase estimates from the position: filtered position, velocity and acceleration."""

    x: FloatArray
    v: FloatArray
    a: FloatArray
    cutoff: float


def lowpass(values: FloatArray, dt: float, cutoff: float, order: int = 4) -> FloatArray:
    """Butterworth low-pass of ``order`` at ``cutoff`` [Hz], run forward and backward (zero phase)."""
    nyquist = 0.5 / dt
    if not 0.0 < cutoff < nyquist:
        raise DataError(
            f"`cutoff` must be in (0, {nyquist:g}) Hz (the Nyquist frequency), got {shown(cutoff)!r}",
            kind="out_of_range",
            field="cutoff",
            value=cutoff,
            bound=nyquist if cutoff > 0.0 else 0.0,
        )
    sos = signal.butter(order, cutoff, fs=1.0 / dt, output="sos")
    return np.asarray(signal.sosfiltfilt(sos, values), dtype=np.float64)


def default_cutoff(dt: float) -> float:
    """The derivative filter's default cutoff: a tenth of the Nyquist frequency."""
    return 0.05 / dt


def estimate_derivatives(data: MotionData, cutoff: float | None = None, order: int = 4) -> Derivatives:
    """Velocity and acceleration by a zero-phase Butterworth low-pass and central differences.

    The measured ``v`` is used (filtered the same way) where the data has it; otherwise the
    velocity is the central difference of the filtered position.
    """
    dt = data.dt
    cutoff = default_cutoff(dt) if cutoff is None else float(cutoff)
    x = lowpass(data.x, dt, cutoff, order)
    v = np.gradient(x, dt) if data.v is None else lowpass(data.v, dt, cutoff, order)
    return Derivatives(x=x, v=v, a=np.gradient(v, dt), cutoff=cutoff)


def decimate(values: FloatArray, factor: int) -> FloatArray:
    """Low-pass (8th-order Chebyshev I at 0.8 of the new Nyquist frequency, zero phase) and keep
    one sample in ``factor``: MATLAB's and scipy's ``decimate``."""
    if factor == 1:
        return values
    return np.asarray(signal.decimate(values, factor, ftype="iir", zero_phase=True), dtype=np.float64)


#: Lags [samples] at which the noise floor is read from differences, shortest first.
NOISE_LAGS = (1, 2, 4, 8, 16)
#: The estimate has settled when doubling the lag raises it by less than this share.
PLATEAU = 0.05


def noise_floor(force: FloatArray) -> float:
    """Standard deviation of the noise on ``force``, white or coloured.

    From differences over a lag L: 1.4826·MAD(f[k+L] − f[k])/√2 (robust, so that steps at reversals
    do not count). For white noise every lag gives σ; noise correlated over a few samples cancels
    in short differences and is underestimated there (at lag 1 by 20–50 % for the coloured noise
    of real logs), so the lag doubles while the estimate grows. Coloured noise grows less at each
    doubling and settles (rises by less than PLATEAU); the force's own changes grow more at each
    doubling: when the growth speeds up, the estimate before it is kept.
    """
    estimates: list[float] = []
    for lag in NOISE_LAGS:
        if force.size <= 2 * lag:
            break
        differences = force[lag:] - force[:-lag]
        spread = 1.4826 * float(np.median(np.abs(differences - np.median(differences))))
        estimates.append(spread / math.sqrt(2.0))
        if len(estimates) >= 2:
            growth = estimates[-1] / max(estimates[-2], 1e-300)
            if growth < 1.0 + PLATEAU:
                return estimates[-2]
            if len(estimates) >= 3 and growth >= estimates[-2] / max(estimates[-3], 1e-300):
                return estimates[-3]
    return estimates[-1] if estimates else 0.0
