"""The signals every candidate effect is built from, computed once per record.

Velocity and acceleration come from the identification's zero-phase derivatives; the sign of
the velocity is the direction of motion read from the position with a play of ± the position
noise (a Maxwell-slip element of that width), so that it flips exactly where the position turns
and noise does not flip it; the presliding memory is a bank of Maxwell-slip
elements driven by the filtered position (each element's deflection clipped to ±Δⱼ, Δⱼ
log-spaced from :data:`SMALLEST_DEFLECTION` of the stroke (well above the encoder's resolution,
so that the bank does not turn into a second Coulomb term) to a hundredth of the stroke): any nonnegative
mix of their normalised deflections is a rate-independent Maxwell-slip hysteresis force.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..identification.data import MotionData, estimate_derivatives
from ..identification.motion import find_segments

Array = NDArray[np.float64]

#: Elements of the Maxwell-slip bank.
ELEMENTS = 8
#: Largest break deflection of the bank, as a share of the stroke.
LARGEST_DEFLECTION = 1e-2
#: Smallest break deflection of the bank, as a share of the stroke (and at least ten position
#: resolution steps).
SMALLEST_DEFLECTION = 1e-4


@dataclass(frozen=True)
class Scales:
    """The lengths a fitted model's columns depend on: reused to predict another record."""

    deflections: Array
    play: float
    """Half-width of the play that reads the direction of motion [m]."""
    middle: float
    half_stroke: float


@dataclass(frozen=True, eq=False)
class Features:
    """Signals on every sample, and which samples the fits may use."""

    t: Array
    force: Array
    """The measured force to be explained [N]."""
    x: Array
    """Filtered position [m]."""
    v: Array
    a: Array
    sign: Array
    """sgn(v): the direction of motion, in [−1, 1], flipping over ± the position noise."""
    position: Array
    """Position scaled to [−1, 1] over the stroke."""
    bank: Array
    """(samples, ELEMENTS): normalised element deflections eⱼ/Δⱼ in [−1, 1]."""
    scales: Scales
    travel: Array
    """Distance travelled since the last reversal [m]."""
    usable: NDArray[np.bool_]
    """False on the filters' edge transients at both ends."""
    dt: float


def maxwell_bank(x: Array, deflections: Array) -> Array:
    """Normalised deflections of elements driven by ``x``, all relaxed at the start."""
    state = np.zeros(deflections.size)
    out = np.empty((x.size, deflections.size))
    steps = np.diff(x, prepend=x[0])
    for k, step in enumerate(steps):  # sequential memory: a loop in time, vectorised over elements
        state = np.clip(state + step, -deflections, deflections)
        out[k] = state
    return out / deflections


def compute_features(data: MotionData, scales: Scales | None = None) -> Features:
    """The signals of ``data``. ``scales`` (lengths) taken from another record (the one a model was fitted on)
    build the columns of the model fitted there; by default they are measured on ``data``."""
    derivatives = estimate_derivatives(data)
    x, v = derivatives.x, derivatives.v
    if scales is None:
        scales = measure_scales(data, x)
    segments = find_segments(data.x, x)
    edge = min(math.ceil(2.0 / (derivatives.cutoff * data.dt)), data.samples // 10)
    usable = np.ones(data.samples, dtype=bool)
    usable[:edge] = False
    usable[data.samples - edge :] = False
    return Features(
        t=data.t, force=data.f, x=x, v=v, a=derivatives.a,
        sign=maxwell_bank(data.x, np.array([scales.play]))[:, 0],
        position=(x - scales.middle) / scales.half_stroke, bank=maxwell_bank(x, scales.deflections),
        scales=scales, travel=segments.travel, usable=usable, dt=data.dt,
    )  # fmt: skip


def measure_scales(data: MotionData, x: Array) -> Scales:
    stroke = float(np.ptp(x))
    steps = np.abs(np.diff(data.x))
    resolution = float(np.min(steps[steps > 0]))
    deviation = data.x - x  # robust spread: the filter's misses at sharp turns do not count
    position_noise = max(1.4826 * float(np.median(np.abs(deviation - np.median(deviation)))), 0.3 * resolution)
    smallest = max(10.0 * resolution, SMALLEST_DEFLECTION * stroke)
    largest = max(LARGEST_DEFLECTION * stroke, 10.0 * smallest)
    deflections = np.geomspace(smallest, largest, ELEMENTS)
    middle = 0.5 * (float(np.max(x)) + float(np.min(x)))
    return Scales(deflections, max(0.5 * resolution, position_noise), middle, 0.5 * stroke)
