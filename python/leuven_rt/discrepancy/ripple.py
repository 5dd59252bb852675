"""The periods of a friction level that repeats with the position (a screw's pitch, a gear's teeth,
a motor's poles): found in the residual of the current model, for the ``position_dependence``
effect's ripple columns.

The residual times the direction of motion (a level change shows in both directions with the
direction's sign) is averaged in bins of equal width along the stroke, which puts it on a uniform
grid in position; the strongest peak of that grid's spectrum is refined by least squares on every
sample. The search covers periods from :data:`SHORTEST` to :data:`LONGEST` of the stroke: a longer
change is the smooth trend's, and a shorter one has too few samples per period. A second period is
searched in what the first leaves.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import minimize_scalar

from .._typing import FloatArray

#: Shortest and longest period searched, as shares of the stroke.
SHORTEST = 1.0 / 200.0
LONGEST = 1.0 / 1.5
#: Harmonics of each period in the ripple columns.
HARMONICS = 2
#: Most periods searched.
PERIODS = 2
#: A peak counts when its power is this many times the spectrum's median (a flat spectrum of
#: noise has peaks of a few times its median; a ripple of the noise's size, hundreds).
PEAK = 20.0
#: A period's columns must lower the residual's sum of squares by this many σ²: far above what
#: the best of the thousands of periods searched gains on noise alone (about 2·ln(periods)
#: + the columns, some 20 σ²).
EVIDENCE = 100.0
#: Bins per shortest period.
BINS_PER_PERIOD = 8


def ripple_columns(
    sign: FloatArray, x: FloatArray, period: float, harmonics: int = HARMONICS
) -> list[FloatArray]:
    """sgn(v)·cos(2πk·x/P) and sgn(v)·sin(2πk·x/P) for k = 1..``harmonics``."""
    phase = 2.0 * np.pi * x / period
    out = []
    for k in range(1, harmonics + 1):
        out.extend([sign * np.cos(k * phase), sign * np.sin(k * phase)])
    return out


def find_periods(
    sign: FloatArray, x: FloatArray, residual: FloatArray, rows: NDArray[np.bool_], noise_std: float
) -> tuple[float, ...]:
    """Up to :data:`PERIODS` periods of a ripple in ``residual`` (force − model) on ``rows``; a
    period counts when its columns lower the residual's sum of squares by more than
    :data:`EVIDENCE`·σ² (σ = ``noise_std``)."""
    moving = rows & (sign != 0.0)
    if np.count_nonzero(moving) < 100:
        return ()
    stroke = float(np.ptp(x[moving]))
    if stroke <= 0.0:
        return ()
    target = (residual * sign)[moving]
    position = x[moving]
    found: list[float] = []
    for _ in range(PERIODS):
        period = _strongest(position, target - _fitted(position, target, found), stroke)
        if period is None:
            break
        period = _refine(position, target, found, period)
        before = target - _fitted(position, target, found)
        after = target - _fitted(position, target, [*found, period])
        if float(before @ before - after @ after) < EVIDENCE * noise_std**2:
            break
        # closer than two resolution steps of the spectrum to a period found: the first's leakage
        if any(abs(1.0 / period - 1.0 / other) < 2.0 / stroke for other in found):
            break
        found.append(period)
    return tuple(found)


def _design(position: FloatArray, periods: list[float]) -> FloatArray:
    # the level's smooth trend (P0..P2 along the stroke) is fitted with the ripple, so that its
    # leakage into the long periods is not taken for one
    p = 2.0 * (position - np.min(position)) / max(float(np.ptp(position)), 1e-300) - 1.0
    columns = [np.ones_like(position), p, 1.5 * p * p - 0.5]
    for period in periods:
        columns.extend(ripple_columns(np.ones_like(position), position, period))
    return np.column_stack(columns)


def _fitted(position: FloatArray, target: FloatArray, periods: list[float]) -> FloatArray:
    design = _design(position, periods)
    fitted: FloatArray = design @ np.linalg.lstsq(design, target, rcond=None)[0]
    return fitted


def _strongest(position: FloatArray, target: FloatArray, stroke: float) -> float | None:
    bins = int(np.ceil(BINS_PER_PERIOD / SHORTEST))
    low = float(np.min(position))
    index = np.minimum(((position - low) / stroke * bins).astype(int), bins - 1)
    counts = np.bincount(index, minlength=bins)
    sums = np.bincount(index, weights=target, minlength=bins)
    visited = counts > 0
    means = np.zeros(bins)
    means[visited] = sums[visited] / counts[visited]
    means[visited] -= np.mean(means[visited])
    padded = 4 * bins  # zero padding: a finer grid of periods to start the refinement from
    power = np.abs(np.fft.rfft(means, padded)) ** 2
    periods = np.full(power.size, np.inf)
    periods[1:] = stroke * padded / bins / np.arange(1, power.size)
    search = (periods >= SHORTEST * stroke) & (periods <= LONGEST * stroke)
    if not search.any():
        return None
    best = int(np.flatnonzero(search)[np.argmax(power[search])])
    if power[best] < PEAK * float(np.median(power[search])):
        return None
    return float(periods[best])


def _refine(position: FloatArray, target: FloatArray, found: list[float], period: float) -> float:
    def cost(candidate: float) -> float:
        residual = target - _fitted(position, target, [*found, candidate])
        return float(residual @ residual)

    # within the spectrum's resolution around the peak (a quarter of its spacing on each side)
    result = minimize_scalar(cost, bounds=(0.97 * period, 1.03 * period), method="bounded",
                             options={"xatol": 1e-6 * period})  # fmt: skip
    return float(result.x)
