"""The motion a friction model is driven by, made from a log: the reconstruction.

A log gives a loop what its sensors give: an encoder position, and sometimes a measured velocity.
A friction model needs a velocity (or a position whose differences are one) at every sample, and
the position for a level or a force that depends on it. The reconstruction says how they are
made (docs/data-and-reports.md#reconstruction), and the same one is used by the fit that chooses
it and by :func:`leuven_rt.predict` (and a compensator fed the same signal):

- ``source="velocity"``: the model is driven by the log's ``v`` (through a zero-phase low-pass at
  ``cutoff`` Hz when one is given), the level and the position force by the log's ``x``;
- ``source="position"``: the model is driven by the log's ``x`` (raw, or through a zero-phase
  low-pass at ``cutoff`` Hz), each step's velocity being the difference of two samples over dt.

The acceleration (for a measured inertia) is the central difference of the velocity through a
zero-phase low-pass at ``acceleration_cutoff`` Hz, or where the reconstruction gives none, at the
lower of ``cutoff`` and a tenth of the Nyquist frequency: a coarse encoder's second difference is
noise, while a fine one's at a high rate holds the quick accelerations of a closed loop that a
tenth of the Nyquist frequency takes away (the fit chooses, :mod:`leuven_rt.fitting.select`).

It also finds where a log cannot tell the direction of motion: without a velocity column, the
motion reverses somewhere between the last encoder count in the old direction and the first in
the new one (:func:`ambiguous_samples`). No model driven by the encoder can place a friction
flip inside that interval, so the fit weighs those samples down.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from .._typing import FloatArray
from ..errors import DataError
from ..modelfile import Reconstruction
from .records import MotionData
from .signals import check_cutoff, lowpass, robust_spread

#: A position whose counts reverse this many times as often as its low-passed version is noisy.
SPURIOUS = 4
#: ... and whose noise exceeds this many counts.
NOISE_COUNTS = 2.0
#: The acceleration's cutoff is at most this share of the Nyquist frequency, where the
#: reconstruction gives none of its own.
ACCELERATION_CUTOFF = 0.1


def describe(reconstruction: Reconstruction) -> str:
    """The reconstruction in words, for reports."""
    if reconstruction.source == "velocity":
        how = (
            "as logged"
            if reconstruction.cutoff is None
            else f"through a zero-phase low-pass at {reconstruction.cutoff:.4g} Hz"
        )
        text = f"the logged velocity, {how}"
    elif reconstruction.cutoff is None:
        text = "the encoder position, raw (differences of consecutive samples)"
    else:
        text = f"the encoder position through a zero-phase low-pass at {reconstruction.cutoff:.4g} Hz"
    if reconstruction.acceleration_cutoff is not None:
        text += (
            f"; its acceleration through a zero-phase low-pass at {reconstruction.acceleration_cutoff:.4g} Hz"
        )
    return text


@dataclass(frozen=True, eq=False)
class Motion:
    """What a model is driven by along a log: ``drive`` (a velocity or a position, per ``input``),
    the velocity ``v`` each step holds, the position ``x`` the level and position force see, and
    the acceleration ``a`` of the measurement's inertia term."""

    reconstruction: Reconstruction
    input: Literal["velocity", "position"]
    drive: FloatArray
    v: FloatArray
    x: FloatArray
    a: FloatArray
    dt: float


def differences(x: FloatArray, dt: float) -> FloatArray:
    """vₖ = (xₖ − xₖ₋₁)/dt, v₀ = 0: the velocity a position-driven model steps with."""
    v = np.empty_like(x)
    v[0] = 0.0
    np.subtract(x[1:], x[:-1], out=v[1:])
    v[1:] /= dt
    return v


def reconstruct(data: MotionData, reconstruction: Reconstruction) -> Motion:
    """The motion of ``data`` under ``reconstruction`` (module documentation)."""
    dt = data.dt
    cutoff = reconstruction.cutoff
    if cutoff is not None:
        cutoff = check_cutoff(cutoff, dt, data.t.size)
    if reconstruction.acceleration_cutoff is None:
        slow = min(cutoff if cutoff is not None else math.inf, ACCELERATION_CUTOFF * 0.5 / dt)
    else:
        # A file's own cutoff, identified on a log at another rate, may be beyond this one's.
        slow = check_cutoff(
            reconstruction.acceleration_cutoff, dt, data.t.size, "reconstruction.acceleration_cutoff"
        )
    if reconstruction.source == "velocity":
        if data.v is None:
            raise DataError(
                "the model is driven by the logged velocity, but the log has no `v` column",
                kind="missing_column",
                field="v",
            )
        v = data.v if cutoff is None else lowpass(data.v, dt, cutoff)
        a = np.gradient(lowpass(data.v, dt, slow), dt)
        return Motion(reconstruction, "velocity", v, v, data.x, a, dt)
    x = data.x if cutoff is None else lowpass(data.x, dt, cutoff)
    a = np.gradient(np.gradient(lowpass(data.x, dt, slow), dt), dt)
    return Motion(reconstruction, "position", x, differences(x, dt), x, a, dt)


#: Changes below this share of the median change are the rounding of a position written as
#: decimal text (0.4235632 − 0.4235625 is not 7e-7 in binary), not encoder steps.
ROUNDING = 1e-3


def resolution(x: FloatArray) -> float:
    """The encoder step: the smallest change between samples that is not rounding (0 if the
    position never changes)."""
    steps = np.abs(np.diff(x))
    steps = steps[steps > 0]
    if not steps.size:
        return 0.0
    steps = steps[steps >= ROUNDING * float(np.median(steps))]
    return float(steps.min())


def ambiguous_samples(x: FloatArray, margin: int) -> NDArray[np.bool_]:
    """Samples where an encoder cannot tell the direction of motion: from the last count in the old
    direction to the first count in the new one at every reversal, widened by ``margin`` samples
    on each side (the smearing of a filter)."""
    out = np.zeros(x.size, dtype=bool)
    steps = np.diff(x)
    counts = np.flatnonzero(steps) + 1  # the samples at which the position changed
    if counts.size < 2:
        return out
    sign = np.sign(steps[counts - 1])
    for j in np.flatnonzero(sign[1:] != sign[:-1]):
        out[max(counts[j] - margin, 0) : min(counts[j + 1] + margin, x.size)] = True
    return out


#: A run of at least this many samples at rest is a stop (shorter ones are slow motion between
#: counts).
REST_RUN = 5
#: At rest, a logged velocity moves the axis by less than this share of an encoder step a sample.
REST_SHARE = 1e-3
#: A stop whose force spreads by more than this many times the noise is held by the drive.
WANDER = 3.0
#: A log whose stops all hold one force, the means of its stops spread by less than this share of
#: the force between sliding in +x and in −x, releases its friction at a stop.
RELEASED = 0.03
#: ... judged only where at least this many stops were reached from each direction.
RELEASE_STOPS = 3


def before_first_count(x: FloatArray) -> NDArray[np.bool_]:
    """Samples before the encoder first counts. The force the axis holds there rests on the state
    the log began in, which the log does not give: a closed loop started at rest holds a load with
    friction while its drive outputs nothing, and a model starts with no friction held."""
    out = np.zeros(x.size, dtype=bool)
    counts = np.flatnonzero(np.diff(x))
    out[: int(counts[0]) + 1 if counts.size else x.size] = True
    return out


def stops(x: FloatArray, v: FloatArray, dt: float) -> list[tuple[int, int]]:
    """The runs ``[begin, end)`` of at least :data:`REST_RUN` samples where a log with a velocity
    column shows the axis stopped: the encoder does not count and the velocity moves the axis by
    less than :data:`REST_SHARE` of a step per sample."""
    step = resolution(x)
    still = np.zeros(x.size, dtype=bool)
    still[1:] = (np.diff(x) == 0) & (np.abs(v[1:]) * dt < REST_SHARE * step)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], still.astype(np.int8), [0]))))
    return [(int(b), int(e)) for b, e in zip(edges[::2], edges[1::2], strict=True) if e - b >= REST_RUN]


def held_by_drive(x: FloatArray, v: FloatArray, f: FloatArray, dt: float) -> NDArray[np.bool_]:
    """Samples where a log with a velocity column shows the axis stopped (:func:`stops`) while the
    force wanders: it spreads about its mean by more than :data:`WANDER` times the noise (read
    from the force's one-sample differences, robustly). Friction that holds at a stop holds its
    force there; a force that wanders while the axis stands is the drive's (a closed loop's
    integrator winding up on a stuck mass), which no model driven by the motion can follow."""
    differences = np.diff(f)
    noise = robust_spread(differences) / math.sqrt(2.0)
    out = np.zeros(x.size, dtype=bool)
    for begin, end in stops(x, v, dt):
        if float(np.std(f[begin:end])) > WANDER * noise:
            out[begin:end] = True
    return out


def stops_and_spread(
    x: FloatArray, v: FloatArray, f: FloatArray, dt: float
) -> tuple[list[tuple[int, int]], float]:
    """The stops of a log with a velocity column (:func:`stops`, after the encoder first counts),
    and how far the forces held there differ: the spread of the stops' means over the force
    between sliding in +x and in −x (the medians of the faster half of the moving samples); nan
    where fewer than :data:`RELEASE_STOPS` stops were reached from either direction (the direction
    of the encoder's last count before the stop: a velocity decaying to rest, or a closed loop's
    overshoot, can leave its last nonzero sample's sign the other way) or the axis did not slide
    both ways by its velocity."""
    counts = np.flatnonzero(np.diff(x))
    if counts.size == 0:
        return [], math.nan
    runs = [(b, e) for b, e in stops(x, v, dt) if b > counts[0]]
    last = counts[np.searchsorted(counts, [b for b, _ in runs]) - 1]
    arrived = np.sign(x[last + 1] - x[last])
    if min(np.count_nonzero(arrived > 0), np.count_nonzero(arrived < 0)) < RELEASE_STOPS:
        return runs, math.nan
    moving = np.flatnonzero(v != 0)
    if moving.size == 0:  # a velocity column that never moves: no sliding force to compare with
        return runs, math.nan
    speed = np.abs(v[moving])
    fast = moving[speed >= np.median(speed)]
    forward, backward = f[fast[v[fast] > 0]], f[fast[v[fast] < 0]]
    if forward.size == 0 or backward.size == 0:
        return runs, math.nan
    split = float(np.median(forward) - np.median(backward))
    means = np.array([np.mean(f[b:e]) for b, e in runs])
    return runs, (float(np.std(means)) / split if split > 0 else math.nan)


def released_at_stops(x: FloatArray, v: FloatArray, f: FloatArray, dt: float) -> NDArray[np.bool_]:
    """The stops (:func:`stops`) of a log with a velocity column whose friction lets go there: every
    stop holds one force, whichever way the axis arrived (the spread of :func:`stops_and_spread`
    below :data:`RELEASED`). Friction that holds at a stop holds the force it slid with, which
    differs with the direction; a force that is the same at every stop is what a static friction
    curve gives at zero speed, or a drive that drops its force while a brake holds the axis. A
    model whose state holds friction cannot follow it, and what it does there tells nothing of an
    effect: a Stribeck dip or a level falling where the stops are would buy error back at those
    stops alone."""
    out = np.zeros(x.size, dtype=bool)
    runs, spread = stops_and_spread(x, v, f, dt)
    if spread < RELEASED:
        for begin, end in runs:
            out[begin:end] = True
    return out


def reversals(x: FloatArray) -> int:
    """How many times the encoder's counts change direction."""
    steps = np.diff(x)
    sign = np.sign(steps[steps != 0])
    return int(np.count_nonzero(sign[1:] != sign[:-1]))


def noisy_position(x: FloatArray, dt: float) -> bool:
    """Whether the position's own noise reverses it: its counts change direction more than
    :data:`SPURIOUS` times as often as the position through a low-pass at a twentieth of the
    Nyquist frequency does, and its sample-to-sample noise (the robust spread of its second
    differences over √6) is more than :data:`NOISE_COUNTS` counts. An encoder's counts jitter by
    a count, and reverse where the motion does (a servo hunting about its set point reverses for
    real); a position read with noise (a joint's position estimate, an analogue sensor) jumps by
    many counts and reverses at every other sample of slow motion: its raw differences are not
    the motion."""
    cutoff = 0.05 * 0.5 / dt
    step = resolution(x)
    if x.size < 8 or not cutoff * x.size * dt >= 8.0 or not step > 0:
        return False
    second = np.diff(x, 2)
    spread = robust_spread(second) / math.sqrt(6.0)
    if not spread > NOISE_COUNTS * step:
        return False
    return reversals(x) > SPURIOUS * max(reversals(lowpass(x, dt, cutoff)), 1)


def median_excursion(x: FloatArray) -> float:
    """The travel between reversals that half the path is made in: the median of the excursions
    weighed by their length. Counted per excursion, a servo's dither by a count about its set
    point and the noise of a position estimate (thousands of reversals of a few counts) would set
    it, and the presliding bank would be too narrow for a closed-loop log's or a joint's
    presliding (a Franka joint's friction builds up over milliradians of travel, its noisy
    position reverses every few micro-radians)."""
    steps = np.diff(x)
    steps = steps[steps != 0]
    if steps.size == 0:
        return 0.0
    turns = np.flatnonzero(np.sign(steps[1:]) != np.sign(steps[:-1]))
    path = np.cumsum(steps)
    points = np.concatenate(([0.0], path[turns], [path[-1]]))
    lengths = np.sort(np.abs(np.diff(points)))
    travelled = np.cumsum(lengths)
    return float(lengths[np.searchsorted(travelled, 0.5 * travelled[-1])])


def last_reversal(v: FloatArray) -> NDArray[np.int64]:
    """At every sample, the sample where the direction of motion last changed (0 before the
    first change)."""
    direction = np.sign(v)
    moving = np.flatnonzero(direction)
    turns = np.zeros(v.size, dtype=bool)
    if moving.size > 1:
        flips = moving[1:][direction[moving[1:]] != direction[moving[:-1]]]
        turns[flips] = True
    turns[0] = True
    out: NDArray[np.int64] = np.maximum.accumulate(np.where(turns, np.arange(v.size), 0))
    return out


def travel_since_reversal(x: FloatArray, v: FloatArray) -> FloatArray:
    """|x − x at the last change of the direction of motion| at every sample."""
    out: FloatArray = np.abs(x - x[last_reversal(v)])
    return out


def filter_margin(reconstruction: Reconstruction, dt: float) -> int:
    """How many samples a reconstruction's filter smears a reversal over (2 for raw differences)."""
    if reconstruction.cutoff is None:
        return 2
    return max(2, math.ceil(0.5 / (reconstruction.cutoff * dt)))


__all__ = [
    "Motion",
    "ambiguous_samples",
    "before_first_count",
    "describe",
    "differences",
    "filter_margin",
    "last_reversal",
    "median_excursion",
    "noisy_position",
    "reconstruct",
    "released_at_stops",
    "resolution",
    "reversals",
    "stops",
    "stops_and_spread",
    "travel_since_reversal",
]
