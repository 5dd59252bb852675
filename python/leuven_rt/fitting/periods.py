"""Ripple periods: a force or a friction level that repeats with the position (a screw's pitch,
a gear's teeth, a motor's poles), found in what the current model leaves.

Two forms, two targets (docs/effects.md#ripple-periods): a position force adds the same r(x) in
both directions, so it shows in the residual itself; a ripple of the friction level scales the
contact force, whose sign follows the direction of motion, so it shows in the residual times the
direction. Either target is averaged in bins of equal width along the stroke, and the spectrum
of the bin means is searched between 1/200 and 1/1.5 of the stroke; the strongest peak counts
when its power is at least :data:`PEAK` times the median power there. Its period is then refined
by a bounded scalar search of the least-squares fit of the ripple's harmonics to the target.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import minimize_scalar

from .._typing import FloatArray
from .evaluate import ripple_basis

#: Bins along the stroke: 8 per shortest period searched.
BINS = 1600
#: Shortest and longest period searched, as shares of the stroke.
SHORTEST, LONGEST = 1.0 / 200.0, 1.0 / 1.5
#: A peak counts when its power is this many times the median power of the periods searched.
PEAK = 20.0
#: The refinement searches within this share of the peak's period on either side.
REFINE = 0.03


def find_period(x: FloatArray, target: FloatArray, rows: NDArray[np.bool_]) -> float | None:
    """The strongest period of ``target`` along ``x`` over ``rows``, or None when none stands out."""
    if np.count_nonzero(rows) < 100:
        return None
    xs, ys = x[rows], target[rows]
    low, high = float(xs.min()), float(xs.max())
    stroke = high - low
    if not stroke > 0:
        return None
    index = np.minimum(((xs - low) / stroke * BINS).astype(np.int64), BINS - 1)
    counts = np.bincount(index, minlength=BINS)
    means = np.bincount(index, ys, minlength=BINS) / np.maximum(counts, 1)
    filled = counts > 0
    means[filled] -= means[filled].mean()
    means[~filled] = 0.0
    spectrum = np.abs(np.fft.rfft(means, 4 * BINS)) ** 2
    frequency = np.fft.rfftfreq(4 * BINS, stroke / BINS)  # cycles per unit of x
    searched = (frequency >= 1.0 / (LONGEST * stroke)) & (frequency <= 1.0 / (SHORTEST * stroke))
    if not searched.any():
        return None
    power = np.where(searched, spectrum, 0.0)
    peak = int(np.argmax(power))
    if power[peak] < PEAK * float(np.median(spectrum[searched])):
        return None
    period = 1.0 / float(frequency[peak])

    def misfit(candidate: float) -> float:
        design = np.column_stack([np.ones_like(xs), *ripple_basis(xs, candidate)])
        coefficients = np.linalg.lstsq(design, ys, rcond=None)[0]
        return float(np.sum((ys - design @ coefficients) ** 2))

    refined = minimize_scalar(misfit, bounds=(period * (1 - REFINE), period * (1 + REFINE)), method="bounded",
                              options={"xatol": period * 1e-6})  # fmt: skip
    best = float(refined.x)
    return best if math.isfinite(best) and misfit(best) <= misfit(period) else period


__all__ = ["find_period"]
