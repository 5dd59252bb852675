"""The signals every candidate effect is built from, computed once per record.

Velocity and acceleration come from zero-phase derivatives (the identification's filter, at
:data:`CUTOFF`). The sign of the velocity is the direction of motion read from the position with
a play of ± the position noise (a Maxwell-slip element of that width), so that it flips exactly
where the position turns and noise does not flip it. Where the position is limited by its
quantization rather than by noise, a slow turn can stay inside one step for several samples,
and friction reverses on a sample where the recorded position does not change: between a step
one way and the next step the other way, the turn is placed where the zero-phase filtered
position first falls back from its extreme (one sample of late flip costs (2·Fc)², on the
generated logs ten thousand times the noise variance).

The presliding memory is a bank of Maxwell-slip elements (each element's deflection clipped to
±Δⱼ, Δⱼ log-spaced from :data:`SMALLEST_DEFLECTION` of the stroke, well above the encoder's
resolution so that the bank does not turn into a second Coulomb term, to a hundredth of the
stroke), driven here by the filtered position; once the presliding effect is fitted, its drive
(:mod:`.drive`) drives them by the state z of the model instead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .._typing import FloatArray
from ..data.records import MotionData
from ..data.segments import find_segments
from ..data.signals import estimate_derivatives
from ..data.slip import element_deflections

#: Elements of the Maxwell-slip bank.
ELEMENTS = 12
#: Cutoff of the zero-phase derivative filter, as a share of the sampling rate: twice the
#: identification's default, because the Stribeck curve is steep in v and a velocity smoothed
#: at the plateaus' ramps biases it, while the quantization noise it lets through is small.
CUTOFF = 0.1
#: Samples after which the filter's ringing at a position step (and its transient at either end
#: of the record) has died out: 2/CUTOFF, a dozen time constants of the filter.
SETTLING = math.ceil(2.0 / CUTOFF)
#: How far below its extreme the filtered position must fall to count as a turn, as a share of
#: the quantization step: above the rounding of a settled filter, far below a step.
RETREAT = 0.02
#: Samples of an unchanged position (without a logged velocity) that count as standing still.
REST = 50
#: Largest break deflection of the bank, as a share of the stroke.
LARGEST_DEFLECTION = 1e-2
#: Smallest break deflection of the bank, as a share of the stroke (and at least ten position
#: resolution steps).
SMALLEST_DEFLECTION = 1e-4


@dataclass(frozen=True)
class Scales:
    """The lengths a fitted model's columns depend on: reused to predict another record."""

    deflections: FloatArray
    play: float
    """Half-width of the play that reads the direction of motion [m]."""
    middle: float
    half_stroke: float
    periods: tuple[float, ...] = ()
    """Periods of the position-dependent level's ripple [m] (:mod:`.ripple`), once found."""


@dataclass(frozen=True, eq=False)
class Features:
    """Signals on every sample, and which samples the fits may use."""

    t: FloatArray
    force: FloatArray
    """The measured force to be explained [N]."""
    x: FloatArray
    """Filtered position [m]."""
    v: FloatArray
    a: FloatArray
    sign: FloatArray
    """sgn(v): the direction of motion, in [−1, 1], 0 at rest: read from the position, flipping over
    ± the position noise (turns inside one quantization step placed by the filtered position), or
    the sign of the logged velocity (0 where it is exactly 0) where the log has one and a
    Coulomb-viscous fit leaves less with it."""
    rest: FloatArray
    """At rest, the direction of the last motion (±1); 0 while moving."""
    position: FloatArray
    """Position scaled to [−1, 1] over the stroke."""
    bank: FloatArray
    """(samples, ELEMENTS): normalised element deflections eⱼ/Δⱼ in [−1, 1], driven by the
    filtered position (by z in the features a :class:`~.drive.Drive` returns)."""
    scales: Scales
    travel: FloatArray
    """Distance travelled since the last reversal [m]."""
    usable: NDArray[np.bool_]
    """False on the filters' edge transients at both ends."""
    dt: float
    full: Features | None = None
    """For the features of every ``stride``-th sample (:func:`thin`): the features of every
    sample, which the presliding drive's simulation runs on."""
    index: NDArray[np.intp] | None = None
    """For thinned features: the samples of ``full`` they hold."""


def thin(features: Features, stride: int) -> Features:
    """The features of every ``stride``-th sample (the columns computed at the full rate first:
    the filters, the direction of motion, the bank's slip), for the fits; ``full`` keeps them all."""
    index = np.arange(0, features.t.size, stride)
    return Features(
        t=features.t[index], force=features.force[index], x=features.x[index], v=features.v[index],
        a=features.a[index], sign=features.sign[index], rest=features.rest[index],
        position=features.position[index], bank=np.ascontiguousarray(features.bank[index]),
        scales=features.scales, travel=features.travel[index], usable=features.usable[index],
        dt=features.dt, full=features, index=index,
    )  # fmt: skip


def direction_of_motion(
    raw: FloatArray, filtered: FloatArray, play: float, spread: tuple[float, float]
) -> FloatArray:
    """sgn(v) in [−1, 1] from the recorded position ``raw`` (and its zero-phase ``filtered``
    version, for the turns inside one quantization step when the position's ``spread``,
    (resolution, noise) from :func:`position_spread`, says it is quantization-limited)."""
    sign = element_deflections(raw, np.array([play]))[:, 0]
    resolution, noise = spread
    if noise > 0.5 * resolution:
        return sign
    moves = np.flatnonzero(np.diff(raw)) + 1
    ways = np.sign(raw[moves] - raw[moves - 1])
    for before, after, old, new in zip(moves[:-1], moves[1:], ways[:-1], ways[1:], strict=True):
        if old == new or after - before < 2:
            continue
        # The filter overshoots a step by a few hundredths of it: in a long stretch (a pause
        # inside the step) that ringing is not a turn, so the search starts once it has settled.
        first = before + SETTLING if after - before > 2 * SETTLING else before
        path = old * filtered[first:after]  # grows while the motion goes the old way
        retreat = np.flatnonzero(path[1:] < np.maximum.accumulate(path)[:-1] - RETREAT * resolution)
        if retreat.size:
            sign[first + 1 + retreat[0] : after] = new
    return sign


def at_rest(x: FloatArray, v: FloatArray, resolution: float, dt: float) -> NDArray[np.bool_]:
    """Samples where the recorded position ``x`` has not changed for at least REST samples while
    the filtered velocity ``v`` stays below a fifth of one ``resolution`` step per REST samples
    (a slow move inside one encoder step is not a stop)."""
    still = np.concatenate([[False], np.diff(x) == 0.0])
    # the runs of unchanged positions, as (start, stop) pairs
    edges = np.flatnonzero(np.diff(np.concatenate([[0], still.astype(np.int8), [0]])))
    out = np.zeros(x.size, dtype=bool)
    for start, stop in zip(edges[::2], edges[1::2], strict=True):
        if stop - start >= REST:
            out[max(start - 1, 0) : stop] = True
    slow: NDArray[np.bool_] = np.abs(v) < 0.2 * resolution / (REST * dt)
    return out & slow


def _coulomb_viscous_misfit(
    direction: tuple[FloatArray, FloatArray], v: FloatArray, force: FloatArray, rows: NDArray[np.bool_]
) -> float:
    sign, rest = direction
    design = np.column_stack([sign, rest, v, np.ones_like(v)])[rows]
    residual = force[rows] - design @ np.linalg.lstsq(design, force[rows], rcond=None)[0]
    return float(residual @ residual)


def _hold(sign: FloatArray, fallback: FloatArray) -> FloatArray:
    """``sign`` with its zeros replaced by the last nonzero value (``fallback`` before the first)."""
    index = np.where(sign != 0.0, np.arange(sign.size), -1)
    last = np.maximum.accumulate(index)
    return np.where(last >= 0, sign[np.maximum(last, 0)], fallback)


def compute_features(data: MotionData, scales: Scales | None = None) -> Features:
    """The signals of ``data``. ``scales`` (lengths) taken from another record (the one a model was fitted on)
    build the columns of the model fitted there; by default they are measured on ``data``."""
    derivatives = estimate_derivatives(data, CUTOFF / data.dt)
    x, v, a = derivatives.x, derivatives.v, derivatives.a
    if data.v is not None:
        # A logged velocity is taken as logged: filtering it would smooth away the acceleration
        # that the inertia term needs (on generated logs, 3.8x the noise left against 1.0x).
        v = data.v
        a = np.gradient(v, data.dt)
    spread = position_spread(data, x)
    if scales is None:
        scales = measure_scales(x, spread)
    segments = find_segments(data.x, x)
    edge = min(SETTLING, data.samples // 10)  # the filter's transients at both ends
    usable = np.ones(data.samples, dtype=bool)
    usable[:edge] = False
    usable[data.samples - edge :] = False
    from_position = direction_of_motion(data.x, x, scales.play, spread)
    still = at_rest(data.x, derivatives.v, spread[0], data.dt)
    sign, rest = np.where(still, 0.0, from_position), np.where(still, np.sign(from_position), 0.0)
    if data.v is not None:
        # The logged velocity's sign is the direction where it is exact (a simulator's, a good
        # observer's); a velocity from central differences leads each start by a sample, and a
        # noisy one flickers at the turns. The direction kept is the one under which a
        # Coulomb-viscous fit leaves less (each sample of a late or early flip costs (2·Fc)²).
        moving = data.v != 0.0
        held = _hold(np.sign(data.v), from_position)
        logged = (np.where(moving, held, 0.0), np.where(moving, 0.0, np.sign(held)))
        sign, rest = min(
            (sign, rest), logged, key=lambda pair: _coulomb_viscous_misfit(pair, v, data.f, usable)
        )
    return Features(
        t=data.t, force=data.f, x=x, v=v, a=a, sign=sign, rest=rest,
        position=(x - scales.middle) / scales.half_stroke, bank=element_deflections(x, scales.deflections),
        scales=scales, travel=segments.travel, usable=usable, dt=data.dt,
    )  # fmt: skip


def position_spread(data: MotionData, x: FloatArray) -> tuple[float, float]:
    """The position's quantization step and its noise (at least what quantization alone gives)."""
    steps = np.abs(np.diff(data.x))
    resolution = float(np.min(steps[steps > 0]))
    deviation = data.x - x  # robust spread: the filter's misses at sharp turns do not count
    noise = 1.4826 * float(np.median(np.abs(deviation - np.median(deviation))))
    return resolution, max(noise, 0.3 * resolution)


def measure_scales(x: FloatArray, spread: tuple[float, float]) -> Scales:
    """The lengths of a record with filtered position ``x`` and :func:`position_spread` ``spread``."""
    stroke = float(np.ptp(x))
    resolution, position_noise = spread
    smallest = max(10.0 * resolution, SMALLEST_DEFLECTION * stroke)
    largest = max(LARGEST_DEFLECTION * stroke, 10.0 * smallest)
    deflections = np.geomspace(smallest, largest, ELEMENTS)
    middle = 0.5 * (float(np.max(x)) + float(np.min(x)))
    return Scales(deflections, max(0.5 * resolution, position_noise), middle, 0.5 * stroke)
