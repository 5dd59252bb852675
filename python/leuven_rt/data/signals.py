"""Signals derived from a log: zero-phase derivative estimates, the low-pass-and-decimate of the
EMPS benchmark's IDIM-LS, and the noise floor of the force.

Every fit works from these: the identification stages and the discrepancy workflow's features.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import signal

from .._checks import real_number
from .._typing import FloatArray
from ..errors import DataError
from .records import MotionData

#: The fewest periods of the cutoff a record must hold: the zero-phase filter's transients last
#: about two periods at each end (docs/data-and-reports.md#measured-data), and far below one period per record
#: the filter's design is singular (a LinAlgError at 1e-6 Hz) or passes nothing of the motion.
#: The default cutoff, a tenth of the Nyquist frequency, gives ten on the shortest record.
MIN_CUTOFF_PERIODS = 8


@dataclass(frozen=True, eq=False)
class Derivatives:
    """Zero-phase estimates from the position: filtered position, velocity and acceleration."""

    x: FloatArray
    v: FloatArray
    a: FloatArray
    cutoff: float


def check_cutoff(cutoff: object, dt: float, samples: int, name: str = "cutoff") -> float:
    """``cutoff`` [Hz] as a float, if a record of ``samples`` samples at step ``dt`` supports it:
    below the Nyquist frequency 0.5/dt, and at least :data:`MIN_CUTOFF_PERIODS` periods of it
    in the record's ``samples·dt`` seconds. Every cutoff given to a filter passes here;
    :class:`DataError` otherwise, with the bound, naming the cutoff ``name``."""
    value = real_number(cutoff, name, DataError)
    nyquist = 0.5 / dt
    if not value < nyquist:  # NaN too
        raise DataError(
            f"`{name}` must be below {nyquist:g} Hz (the Nyquist frequency of a {dt:g} s step), "
            f"got {value!r} Hz",
            kind="out_of_range",
            field=name,
            value=value,
            bound=nyquist,
        )
    duration = samples * dt
    lowest = MIN_CUTOFF_PERIODS / duration
    if not value >= lowest:
        raise DataError(
            f"`{name}` must be at least {lowest:.3g} Hz for a record of {duration:g} s ({samples} samples): "
            f"the record must hold {MIN_CUTOFF_PERIODS} periods of the cutoff for the filter's transients "
            f"at its ends to die out, got {value!r} Hz",
            kind="out_of_range",
            field=name,
            value=value,
            bound=lowest,
        )
    return value


def lowpass(values: FloatArray, dt: float, cutoff: float, order: int = 4) -> FloatArray:
    """Butterworth low-pass of ``order`` at ``cutoff`` [Hz] (checked by :func:`check_cutoff`),
    run forward and backward (zero phase)."""
    cutoff = check_cutoff(cutoff, dt, values.size)
    sos = signal.butter(order, cutoff, fs=1.0 / dt, output="sos")
    return np.asarray(signal.sosfiltfilt(sos, values), dtype=np.float64)


def default_cutoff(dt: float) -> float:
    """The derivative filter's default cutoff: a tenth of the Nyquist frequency."""
    return 0.05 / dt


def estimate_derivatives(data: MotionData, cutoff: float | None = None, order: int = 4) -> Derivatives:
    """Velocity and acceleration by a zero-phase Butterworth low-pass and central differences.

    The measured ``v`` is used (filtered the same way) where the data has it; otherwise the
    velocity is the central difference of the filtered position. ``cutoff`` [Hz]: default a
    tenth of the Nyquist frequency; one the record does not support is refused
    (:func:`check_cutoff`).
    """
    dt = data.dt
    cutoff = default_cutoff(dt) if cutoff is None else check_cutoff(cutoff, dt, data.samples)
    x = lowpass(data.x, dt, cutoff, order)
    v = np.gradient(x, dt) if data.v is None else lowpass(data.v, dt, cutoff, order)
    return Derivatives(x=x, v=v, a=np.gradient(v, dt), cutoff=cutoff)


def robust_spread(values: FloatArray) -> float:
    """The standard deviation of normally distributed ``values``, read robustly: 1.4826 times
    their median absolute deviation, which a few outliers (a friction flip, a spike) do not move."""
    return 1.4826 * float(np.median(np.abs(values - np.median(values))))


#: Lags [samples] at which the noise of a model's residual is read.
RESIDUAL_LAGS = (1, 2, 4, 8, 16, 32, 64)


def residual_noise(residual: FloatArray, rows: NDArray[np.bool_] | None = None) -> float:
    """Standard deviation of the noise in what a model leaves, white or coloured.

    As :func:`noise_floor`, from robust differences over a lag that doubles until the estimate
    settles (rises by less than PLATEAU), but without stopping where the growth speeds up: a
    model's residual has none of the force's own fast changes, and coloured noise settles only
    after a few correlation times (a 20 Hz noise sampled at 1 kHz: lag 16). Only differences
    between two samples both among ``rows`` count.
    """
    estimates: list[float] = []
    for lag in RESIDUAL_LAGS:
        differences = residual[lag:] - residual[:-lag]
        if rows is not None:
            differences = differences[rows[lag:] & rows[:-lag]]
        if differences.size <= 2 * lag:
            break
        spread = robust_spread(differences)
        estimates.append(spread / math.sqrt(2.0))
        if len(estimates) >= 2 and estimates[-1] < (1.0 + PLATEAU) * estimates[-2]:
            return max(estimates[-2:])
    return estimates[-1] if estimates else 0.0


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


def noise_floor(force: FloatArray, rows: NDArray[np.bool_] | None = None) -> float:
    """Standard deviation of the noise on ``force``, white or coloured.

    From differences over a lag L: 1.4826·MAD(f[k+L] − f[k])/√2 (robust, so that steps at reversals
    do not count). For white noise every lag gives σ; noise correlated over a few samples cancels
    in short differences and is underestimated there (at lag 1 by 20–50 % for the coloured noise
    of real logs), so the lag doubles while the estimate grows. Coloured noise grows less at each
    doubling and settles (rises by less than PLATEAU); the force's own changes grow more at each
    doubling: when the growth speeds up, the estimate before it is kept.

    ``rows``: only differences between two samples that are both among these count (a fit's
    weighted samples: what a model leaves at reversals an encoder cannot place is not noise).
    """
    estimates: list[float] = []
    for lag in NOISE_LAGS:
        if force.size <= 2 * lag:
            break
        differences = force[lag:] - force[:-lag]
        if rows is not None:
            differences = differences[rows[lag:] & rows[:-lag]]
            if differences.size <= 2 * lag:
                break
        spread = robust_spread(differences)
        estimates.append(spread / math.sqrt(2.0))
        if len(estimates) >= 2:
            growth = estimates[-1] / max(estimates[-2], 1e-300)
            if growth < 1.0 + PLATEAU:
                return estimates[-2]
            if len(estimates) >= 3 and growth >= estimates[-2] / max(estimates[-3], 1e-300):
                return estimates[-3]
    return estimates[-1] if estimates else 0.0
