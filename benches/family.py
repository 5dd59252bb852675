"""A family of generated friction logs that vary what real logs vary, in two splits: `tuning`, to
tune the workflow on, and `held-out`, to report apart and never to tune on.

    python benches/family.py OUT [--split tuning|held-out|all] [--seed-base N] [--law leuven|lugre]
                             [--quick] [--force]

writes ``OUT/<name>.csv`` (columns ``t,x,f`` and, in half of the logs, ``v``; SI units) and
``OUT/manifest.json``: per log ``name``, ``split``, ``hidden_effects``, ``extra`` (``"drift"``
or null), ``noise_std`` (the std of the noise actually added), ``scale`` (``linear``/``rotary``),
``floor_rms`` and ``floor_from``, with the truth, the sensor, the excitation and the noise for
people. It is the manifest a hidden-effect scorer reads (``name``, ``hidden_effects``, ``extra``,
``noise_std``, ``scale``, ``floor_rms``; no ``judge``: every log is judged on its model file's
error as well as on the effects named). Nothing is stored in the repository: the logs are made
here, at run time, from the seeds. ``--quick``: 4 logs a split, 8 to 12 s each; the default is 24
a split, 10 to 30 s each. Score one split at a time (write each to its own folder) to report
the held-out part apart.

**The truth** is the modified Leuven model (docs/model.md) with Maxwell-slip elements and
σ1 = 0, run by the package's simulator at a step ``SUBSTEPS`` times finer than the log's, on
the true continuous motion, and read at the sampling instants, as a real machine's friction is
sampled. The viscous term (σ2 for v > 0, ``sigma2_neg`` for v < 0), the position-dependent level
and the drift are applied in numpy on that fine grid. Where presliding is not hidden, the bank is
one element of ``STIFF_DELTA`` (1e-10 m or rad): the friction flips within far less than one
encoder step. The hidden effects (docs/effects.md):

- ``stribeck``: Fs/Fc 1.2–1.8, Vs, δ 0.8–2 (otherwise Fs = Fc);
- ``asymmetry``: every −x level (Fc, Fs, σ2) × 0.7–0.9 or × 1.1–1.35;
- ``presliding_hysteresis``: 5–15 elements, linear or geometric Δ grid, weights falling
  geometrically, ΣW 1.05–1.3 × the larger static level, exponent n 1.5–3;
- ``position_dependence``: the level times 1 + a ripple (5–15 %, 3–8 periods over the stroke)
  or a smooth trend (±10–20 % slope, a curvature), or a cogging force that depends on the
  position alone (3–10 % of Fc, a pole pitch and its second harmonic);
- ``offset``: a constant load (gravity), ±0.15–0.4 Fc;
- ``inertia``: the force is the actuator's, m·ẍ included (m·|ẍ| at its 99th percentile
  0.15–0.6 Fc in the position-driven logs);
- null cases (Coulomb + viscous only) and drift cases (``extra: "drift"``: the contact level
  rises by 20–35 % over the record, outside the catalogue).

**Another law** (``--law lugre``): the contact part is the LuGre model instead (a linear bristle
σ0 in place of the Maxwell-slip elements, n = 1, and a micro-damping σ1 = 0.5–2 σ2), which
the catalogue's bank only approximates: its presliding curve is exponential, never a staircase
of breaking elements, and σ1 damps it. With F the larger static level, σ0 = 3·F/range where
presliding is hidden (95 % of F reached over the experimenter's presliding range); otherwise
σ0 = F/``STIFF_DELTA`` (95 % within 3·``STIFF_DELTA``: the friction flips far below an encoder
step, and σ1 has nothing to damp). ``presliding_range`` is where 95 % is reached. Everything else
(recipe, sensors, excitation, noise, the other true values) is drawn as for ``leuven`` from the
same seed: the two laws' logs of one seed base are pairs. Report the LuGre logs apart: the
workflow was never tuned on them.

**What each split varies.** The held-out split has seeds of its own AND generator paths the
tuning split never uses (marked *only held-out*):

| | tuning (24; ``--quick`` 4) | held-out (24; ``--quick`` 4) |
|---|---|---|
| axis | linear (1 nm–1 µm), rotary (2¹⁷–2²⁴ counts/turn) | the same |
| ``v`` column | half with the true velocity, half without | the same |
| sampling | 500, 1000, 1500 Hz | 2, 2.5, 4, 5 kHz (*only held-out*); closed loop 0.5–5 kHz |
| force noise | white; coloured | white; coloured; 1/f-like (*only held-out*) |
| excitation | identification; reversals | the same; closed loop (*only held-out*) |
| truth | friction at 10 sub-steps | the same; mass + friction at 10 sub-steps (*only held-out*) |

- coloured noise: white noise through a first-order low-pass at 10–100 Hz, plus a little white;
  1/f-like: pink above a 1–3 Hz corner, flat below, plus a little white;
- identification: presliding loops (growing, then shrinking), a sliding sine, velocity plateaus
  over two decades in both directions, in a random order; reversals: legs of random length
  (nested) and speed over two decades; each with or without a 0–0.1 s dwell at the reversals;
- closed loop: a mass on the true friction (``leuven_rt.MassSystem``) under a PID position loop
  with acceleration feedforward, tracking point-to-point moves (0.05–0.6 s dwell after each) or
  sines; the controller reads the encoder and holds its force over the sample; the log is the
  encoder, the true velocity and the actuator's force, so m·ẍ and the loop's correlations are in
  it.

**The floor** (``floor_rms``): the rms error of the TRUE friction law, with the true measurement
terms, driven by what the log gives, at the log's own rate: the logged ``v``, the raw encoder
differences, or the encoder position through a zero-phase 4th-order Butterworth low-pass at
0.2, 0.1 or 0.05 of the Nyquist frequency; and, where the force holds m·ẍ, the acceleration
from the central differences of any of these. The smallest is kept and ``floor_from`` names it.
Even with the true velocity logged, the floor is the noise only where the law at the log's step
can follow the truth: a sample taken while the friction flips (within 1e-10 of travel after a
start or a reversal, which a jerk-limited start or a slow reversal can stretch over a good part
of a sample) finds the truth between its levels while the law has flipped whole, and a presliding
curve steeper than the sampling resolves is integrated coarsely. Where the mass sticks in the
closed loop, the force is whatever the controller applies, which no law driven by the motion
places when presliding is below the encoder step. Each costs what it costs, and the floor says
how much.
"""

from __future__ import annotations

import argparse
import copy
import dataclasses
import json
import math
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import signal

import leuven_rt as lr

Array = npt.NDArray[np.float64]

#: Friction steps per log sample: the truth is integrated on this finer grid.
SUBSTEPS = 10
#: The break deflection of the single element where presliding is not hidden [m or rad].
STIFF_DELTA = 1e-10
#: Cutoffs of the floor's filtered drives, as fractions of the Nyquist frequency.
FLOOR_CUTOFFS = (0.2, 0.1, 0.05)
#: A case's seed is 2·(100·seed_base + index) + this: the splits never share a seed.
SPLIT_PARITY = {"tuning": 0, "held-out": 1}
SPLITS = ("tuning", "held-out")
#: The contact laws of the truth (module documentation, "Another law").
LAWS = ("leuven", "lugre")
#: A LuGre bristle reaches 1 − e⁻³ (95 %) of its level over this many Fs/σ0.
LUGRE_REACH = 3.0
#: The prefix of each split's log names.
PREFIX = {"tuning": "tune", "held-out": "held"}
LINEAR_ENCODERS = (1e-9, 2e-9, 5e-9, 1e-8, 2e-8, 5e-8, 1e-7, 2e-7, 5e-7, 1e-6)  # m per count
ROTARY_BITS = tuple(range(17, 25))  # counts per turn 2^17 ... 2^24
CLOSED_LOOP = ("point_to_point", "sine_tracking")


@dataclasses.dataclass(frozen=True)
class Recipe:
    """What a log hides and how it is excited; everything else is drawn from its seed."""

    hidden: tuple[str, ...]
    excitation: str  # "identification", "reversals", or one of CLOSED_LOOP
    extra: str | None = None
    position: str | None = None  # "ripple", "trend" or "cogging" with position_dependence


def _r(
    *hidden: str, excitation: str = "identification", extra: str | None = None, position: str | None = None
) -> Recipe:
    return Recipe(tuple(sorted(hidden)), excitation, extra, position)


PS, ST, AS, PD, OF, IN = (
    "presliding_hysteresis",
    "stribeck",
    "asymmetry",
    "position_dependence",
    "offset",
    "inertia",
)
#: The tuning split, the first four its ``--quick`` part.
TUNING = (
    _r(PS, ST),
    _r(excitation="reversals"),
    _r(AS, excitation="reversals"),
    _r(PD, position="ripple"),
    _r(ST, excitation="reversals"),
    _r(PS),
    _r(IN, ST),
    _r(OF, excitation="reversals"),
    _r(PD, position="trend"),
    _r(ST, extra="drift"),
    _r(AS, PS, ST),
    _r(),
    _r(PD, position="cogging", excitation="reversals"),
    _r(IN, PS),
    _r(OF, ST),
    _r(AS, IN, excitation="reversals"),
    _r(PS, PD, position="ripple"),
    _r(AS, ST, excitation="reversals"),
    _r(AS, extra="drift"),
    _r(ST),
    _r(PS, ST, excitation="reversals"),
    _r(IN),
    _r(OF, IN, ST, excitation="reversals"),
    _r(PD, ST, position="trend"),
)
#: The held-out split, the first four its ``--quick`` part. The closed-loop logs hold m·ẍ
#: (the actuator's force), so each hides inertia; their position dependence is cogging (a force
#: on the mass), since a level scales the friction inside the simulated machine.
HELD_OUT = (
    _r(IN, ST, excitation="point_to_point"),
    _r(),
    _r(IN, PD, position="cogging", excitation="sine_tracking"),
    _r(ST, extra="drift", excitation="reversals"),
    _r(PS, ST),
    _r(AS, IN, excitation="point_to_point"),
    _r(IN, excitation="sine_tracking"),
    _r(IN, OF, excitation="point_to_point"),
    _r(PD, position="ripple"),
    _r(AS, PS, ST, excitation="reversals"),
    _r(IN, PS, excitation="sine_tracking"),
    _r(excitation="reversals"),
    _r(ST, excitation="reversals"),
    _r(IN, ST, excitation="sine_tracking"),
    _r(PD, position="trend", excitation="reversals"),
    _r(AS),
    _r(OF, ST),
    _r(AS, IN, ST, excitation="point_to_point"),
    _r(PS, excitation="reversals"),
    _r(extra="drift"),
    _r(IN, OF, ST, excitation="point_to_point"),
    _r(IN, PD, position="cogging", excitation="point_to_point"),
    _r(AS, ST),
    _r(IN, PS, ST, excitation="point_to_point"),
)
RECIPES = {"tuning": TUNING, "held-out": HELD_OUT}
#: The sampling rates [Hz] each split draws from: position-driven, closed loop.
RATES = {
    "tuning": ((500.0, 1000.0, 1500.0), ()),
    "held-out": ((2000.0, 2500.0, 4000.0, 5000.0), (500.0, 1000.0, 2000.0, 4000.0, 5000.0)),
}
#: The force noise models each split cycles through.
NOISES = {
    "tuning": ("coloured", "white", "coloured"),
    "held-out": ("coloured", "pink", "coloured", "white", "pink"),
}


@dataclasses.dataclass(frozen=True)
class Axis:
    """The ranges a linear stage or a rotary joint draws from, in its own SI units."""

    kind: str
    unit_x: str
    unit_f: str
    fc: tuple[float, float]  # Coulomb level
    vs: tuple[float, float]  # Stribeck velocity
    vmax: tuple[float, float]  # fastest speed of the excitation
    stroke: tuple[float, float]
    presliding: tuple[float, float]  # presliding range (largest Δ)
    amax: tuple[float, float]  # acceleration limit of the position-driven moves
    friction_acceleration: tuple[float, float]  # closed loop: Fc over the mass (or inertia)
    centre: tuple[float, float]


LINEAR = Axis(
    "linear",
    "m",
    "N",
    (5.0, 50.0),
    (5e-4, 3e-3),
    (0.05, 0.25),
    (0.05, 0.25),
    (1e-5, 5e-5),
    (0.5, 3.0),
    (0.3, 3.0),
    (-0.1, 0.2),
)
ROTARY = Axis(
    "rotary",
    "rad",
    "N·m",
    (2.0, 15.0),
    (4e-3, 1.5e-2),
    (0.4, 1.5),
    (0.4, 2.0),
    (1e-4, 6e-4),
    (3.0, 15.0),
    (3.0, 30.0),
    (-1.0, 1.0),
)


@dataclasses.dataclass(frozen=True)
class Case:
    """One log to make: its recipe, the draws of its seed, and the truth behind it."""

    name: str
    split: str
    seed: int
    recipe: Recipe
    axis: Axis
    rate: float
    quantization: float
    counts_per_turn: int | None
    has_v: bool
    noise_kind: str
    noise_std_set: float
    dwell: tuple[float, float]
    duration: float
    truth: dict[str, Any]

    @property
    def dt(self) -> float:
        return 1.0 / self.rate


@dataclasses.dataclass(frozen=True, eq=False)
class Log:
    """A generated log: what the sensors give, and what is known about it."""

    case: Case
    t: Array
    x: Array
    f: Array
    v: Array | None
    force_true: Array
    """The force before noise, at the sampling instants."""
    noise: Array
    floor_rms: float
    floor_from: str
    facts: dict[str, Any] = dataclasses.field(default_factory=dict)


def _loguniform(rng: np.random.Generator, bounds: tuple[float, float]) -> float:
    return float(math.exp(rng.uniform(math.log(bounds[0]), math.log(bounds[1]))))


# --------------------------------------------------------------------------------------------
# The draws
# --------------------------------------------------------------------------------------------


def draw_case(split: str, index: int, seed_base: int = 0, quick: bool = False, law: str = "leuven") -> Case:
    """The ``index``-th log of ``split``: sensors, excitation and truth drawn from its seed.
    The sensors' share (velocity column, rotary axis, noise model, dwell) follows the index,
    shifted by ``seed_base``, so that every part of a split holds each kind. ``law``: the
    contact law of the truth (:data:`LAWS`)."""
    recipes = RECIPES[split]
    if seed_base < 0:
        raise ValueError(f"`seed_base` must be >= 0, got {seed_base}")
    if law not in LAWS:
        raise ValueError(f"`law` must be one of {list(LAWS)}, got {law!r}")
    if not 0 <= index < len(recipes):  # at most 100: the seeds below stay apart
        raise ValueError(f"`index` must be in [0, {len(recipes)}) for the {split} split, got {index}")
    recipe = recipes[index]
    seed = 2 * (100 * seed_base + index) + SPLIT_PARITY[split]
    rng = np.random.default_rng(seed)
    turn = index + seed_base
    closed = recipe.excitation in CLOSED_LOOP
    axis = ROTARY if turn % 3 == 1 else LINEAR
    rate = float(rng.choice(RATES[split][1] if closed else RATES[split][0]))
    if axis is ROTARY:
        bits = int(rng.choice(ROTARY_BITS))
        counts: int | None = 2**bits
        q = 2.0 * math.pi / 2**bits
    else:
        counts, q = None, float(rng.choice(LINEAR_ENCODERS))
    has_v = turn % 2 == 0
    noise_kind = NOISES[split][turn % len(NOISES[split])]
    dwell = (0.0, 0.1) if turn % 4 < 2 else (0.0, 0.0)
    duration = rng.uniform(8.0, 12.0) if quick else rng.uniform(10.0, 30.0)
    truth = _draw_truth(recipe, axis, q, rng)
    noise_std = rng.uniform(0.005, 0.03) * truth["Fc"]
    if law == "lugre":
        # From a stream of its own: the draws above stay those of the Leuven law's log.
        truth = _lugre(truth, PS in recipe.hidden, np.random.default_rng([seed, 2]))
    return Case(
        name=f"{PREFIX[split]}_{index + 1:02d}",
        split=split,
        seed=seed,
        recipe=recipe,
        axis=axis,
        rate=rate,
        quantization=q,
        counts_per_turn=counts,
        has_v=has_v,
        noise_kind=noise_kind,
        noise_std_set=noise_std,
        dwell=dwell,
        duration=duration,
        truth=truth,
    )


def _draw_truth(recipe: Recipe, axis: Axis, q: float, rng: np.random.Generator) -> dict[str, Any]:
    hidden = set(recipe.hidden)
    fc = _loguniform(rng, axis.fc)
    fs = fc * (rng.uniform(1.2, 1.8) if ST in hidden else 1.0)
    vmax = _loguniform(rng, axis.vmax)
    sigma2 = rng.uniform(0.3, 1.2) * fc / vmax
    if AS in hidden:
        ratio = rng.uniform(0.7, 0.9) if rng.random() < 0.5 else rng.uniform(1.1, 1.35)
    else:
        ratio = 1.0
    # The experimenter's guess of the presliding range: the loops of the excitation are made
    # of it whether or not the truth holds presliding. At least 20 encoder steps, or no log
    # could show it.
    presliding_range = max(_loguniform(rng, axis.presliding), 20.0 * q)
    top = max(fs, fs * ratio)
    if PS in hidden:
        elements = int(rng.integers(5, 16))
        grid = "linear" if rng.random() < 0.5 else "geometric"
        if grid == "linear":
            deltas = presliding_range * np.arange(1, elements + 1) / elements
        else:
            deltas = presliding_range * np.geomspace(1.0 / rng.uniform(20.0, 60.0), 1.0, elements)
        weights = rng.uniform(0.7, 0.92) ** np.arange(elements)
        weights *= rng.uniform(1.05, 1.3) * top / weights.sum()
        n = rng.uniform(1.5, 3.0)
    else:
        grid = "one stiff element: presliding far below the encoder step"
        deltas = np.array([STIFF_DELTA])
        weights = np.array([rng.uniform(1.05, 1.3) * top])
        n = 2.0
    truth: dict[str, Any] = {
        "law": "leuven",
        "Fc": fc,
        "Fs": fs,
        "Fc_neg": fc * ratio,
        "Fs_neg": fs * ratio,
        "Fs/Fc": fs / fc,
        "negative_direction_ratio": ratio,
        "Vs": _loguniform(rng, axis.vs),
        "delta": rng.uniform(0.8, 2.0),
        "n": n,
        "sigma1": 0.0,
        "sigma2": sigma2,
        "sigma2_neg": sigma2 * ratio,
        "N": int(deltas.size),
        "grid": grid,
        "W": weights.tolist(),
        "Delta": deltas.tolist(),
        "presliding_range": float(deltas.max()),
        "excitation_presliding_range": presliding_range,
        "vmax": vmax,
        "stroke": _loguniform(rng, axis.stroke),
        "amax": _loguniform(rng, axis.amax),
        "offset": 0.0,
        "mass": 0.0,
        "level": None,
        "cogging": None,
        "drift": None,
    }
    if OF in hidden:
        truth["offset"] = float(rng.choice((-1.0, 1.0)) * rng.uniform(0.15, 0.4) * fc)
    if IN in hidden:
        # Position-driven logs set m from the motion (make_log); the closed loop needs it first.
        truth["mass"] = fc / _loguniform(rng, axis.friction_acceleration)
        truth["inertia_share"] = rng.uniform(0.15, 0.6)
    if PD in hidden and recipe.position == "ripple":
        truth["level"] = {
            "kind": "ripple",
            "relative_amp": rng.uniform(0.05, 0.15),
            "second_harmonic": rng.uniform(0.0, 0.3),
            "periods_over_stroke": rng.uniform(3.0, 8.0),
            "phase": rng.uniform(0, 2 * math.pi),
            "phase2": rng.uniform(0, 2 * math.pi),
        }
    elif PD in hidden and recipe.position == "trend":
        slope = rng.choice((-1.0, 1.0)) * rng.uniform(0.1, 0.2)
        truth["level"] = {
            "kind": "trend",
            "a1": float(slope),
            "a2": rng.uniform(-0.1, 0.1),
            "form": "1 + a1*xi + a2*(xi^2 - 1/3), xi in [-1, 1] over the visited stroke",
        }
    elif PD in hidden and recipe.position == "cogging":
        truth["cogging"] = {
            "amplitude": rng.uniform(0.03, 0.1) * fc,
            "second_harmonic": rng.uniform(0.1, 0.4),
            "periods_over_stroke": rng.uniform(5.0, 15.0),
            "phase": rng.uniform(0, 2 * math.pi),
            "phase2": rng.uniform(0, 2 * math.pi),
            "form": "A*(sin(2 pi x/P + phase) + b*sin(4 pi x/P + phase2)), on position alone",
        }
    if recipe.extra == "drift":
        truth["drift"] = {
            "kind": "the contact level rises linearly in time",
            "relative_rise": rng.uniform(0.2, 0.35),
        }
    return truth


def _lugre(truth: dict[str, Any], presliding: bool, rng: np.random.Generator) -> dict[str, Any]:
    """``truth`` with its contact part made the LuGre model (module documentation)."""
    top = max(truth["Fs"], truth["Fs_neg"])
    # The stiff bristle's σ0 holds the larger static level at STIFF_DELTA, as the stiff element does.
    sigma0 = LUGRE_REACH * top / truth["excitation_presliding_range"] if presliding else top / STIFF_DELTA
    return {
        **truth,
        "law": "lugre",
        "n": 1.0,
        "sigma0": sigma0,
        "sigma1": rng.uniform(0.5, 2.0) * truth["sigma2"],
        "N": 0,
        "grid": (
            "LuGre: a linear bristle, 95 % of the larger static level over the presliding range"
            if presliding
            else "LuGre: a linear bristle, the friction flips far below the encoder step"
        ),
        "W": None,
        "Delta": None,
        # Where 95 % of the larger static level is reached (1 - e^-3, over LUGRE_REACH·top/σ0).
        "presliding_range": LUGRE_REACH * top / sigma0,
    }


# --------------------------------------------------------------------------------------------
# Motion
# --------------------------------------------------------------------------------------------


class Profile:
    """A velocity signal on a uniform grid of step ``h``, built from smooth pieces; the position
    is tracked as it grows, so that legs can be kept inside the stroke."""

    def __init__(self, h: float) -> None:
        self.h = h
        self.parts: list[Array] = [np.zeros(1)]
        self.v = 0.0
        self.x = 0.0
        self.samples = 1

    @property
    def seconds(self) -> float:
        return self.samples * self.h

    def _add(self, part: Array) -> None:
        if part.size:
            previous = self.v
            self.parts.append(part)
            self.x += self.h * (0.5 * (previous + part[0]) + float(np.sum(part[:-1] + part[1:])) * 0.5)
            self.v = float(part[-1])
            self.samples += part.size

    def rest(self, seconds: float) -> None:
        self._add(np.full(round(seconds / self.h), self.v))

    def go(self, target: float, amax: float, shortest: float = 0.01) -> None:
        """To ``target`` by a raised cosine whose peak acceleration is ``amax``: through zero
        without stopping when the sign changes."""
        seconds = max(shortest, 0.5 * math.pi * abs(target - self.v) / amax)
        steps = max(2, round(seconds / self.h))
        share = 0.5 - 0.5 * np.cos(np.pi * np.arange(1, steps + 1) / steps)
        part = self.v + (target - self.v) * share
        part[-1] = target
        self._add(part)

    def cycles(self, amplitude: float, frequency: float, count: int) -> None:
        """Whole cycles of a 1 − cos displacement of peak-to-peak ``amplitude`` (signed), from
        rest to rest."""
        steps = max(2, round(count / (frequency * self.h)))
        frequency = count / (steps * self.h)  # whole cycles on the grid
        part = (
            0.5
            * amplitude
            * 2
            * math.pi
            * frequency
            * np.sin(2 * math.pi * frequency * np.arange(1, steps + 1) * self.h)
        )
        part[-1] = 0.0  # at rest, not creeping at the rounding of the sine
        self._add(part)

    def leg(self, speed: float, distance: float, amax: float, dwell: float) -> None:
        """Move ``distance`` (signed) at ``speed``; a reversal first stops for ``dwell`` if > 0."""
        # A ramp covers at most half the leg, and a leg lasts at least 50 ms.
        speed = min(speed, math.sqrt(2.0 * amax * abs(distance) / math.pi), abs(distance) / 0.05)
        target = math.copysign(speed, distance)
        if dwell > 0.0 and self.v * target < 0.0:
            self.go(0.0, amax)
            self.rest(dwell)
        start = self.x
        self.go(target, amax)
        # The hold covers what the ramps leave of the distance (the ramp down is the next leg's).
        left = distance - (self.x - start) - 0.5 * target * max(0.01, 0.5 * math.pi * speed / amax)
        self.rest(max(0.0, left / target))

    def stop(self, amax: float, dwell: float) -> None:
        self.go(0.0, amax)
        self.rest(dwell)

    def velocity(self) -> Array:
        return np.concatenate(self.parts)


def _speeds(case: Case, rng: np.random.Generator, count: int, lowest: float | None = None) -> Array:
    """``count`` speeds over two decades, from ``lowest`` (default 0.2-0.5) Stribeck velocities,
    capped at vmax."""
    truth = case.truth
    low = (rng.uniform(0.2, 0.5) if lowest is None else lowest) * truth["Vs"]
    high = min(100.0 * low, truth["vmax"])
    return np.geomspace(high / 100.0, high, count)


def _dwell(case: Case, rng: np.random.Generator) -> float:
    return float(rng.uniform(*case.dwell)) if case.dwell[1] > 0 else 0.0


def _reversal_legs(profile: Profile, case: Case, rng: np.random.Generator, seconds: float) -> None:
    """Legs of random length (from a few presliding ranges to half the stroke, nested: each
    shorter leg reverses inside the last) and random speed over two decades, within the stroke."""
    truth = case.truth
    speeds = _speeds(case, rng, 32)
    small, stroke = 3.0 * truth["excitation_presliding_range"], truth["stroke"]
    direction = 1.0 if profile.x <= 0.0 else -1.0
    while profile.seconds < seconds:
        speed = float(rng.choice(speeds))
        # At most 2 s a leg, so that the slow speeds do not take the whole record.
        length = _loguniform(rng, (small, max(small, min(0.5 * stroke, 2.0 * speed))))
        # Keep inside [-stroke/2, stroke/2] around the start.
        room = 0.5 * stroke - direction * profile.x
        if room < small:
            direction = -direction
            room = 0.5 * stroke - direction * profile.x
        length = min(length, room)
        profile.leg(speed, direction * length, truth["amax"], _dwell(case, rng))
        direction = -direction
    profile.stop(truth["amax"], 0.05)


def _identification(profile: Profile, case: Case, rng: np.random.Generator, seconds: float) -> None:
    """Presliding loops (growing, then shrinking: minor loops inside larger ones), a sliding
    sine, then velocity plateaus over two decades, each forward then back, in a random order;
    reversal legs fill what is left of the duration."""
    truth = case.truth
    amax, span = truth["amax"], truth["excitation_presliding_range"]
    profile.rest(rng.uniform(0.05, 0.2))
    amplitudes = span * np.array([0.1, 0.3, 0.6, 1.0, 2.0, 3.0, 1.5, 0.5, 0.2]) * rng.uniform(0.8, 1.2, 9)
    frequency = rng.uniform(1.0, 5.0)
    for sign, amplitude in zip(np.resize([1.0, -1.0], 9), amplitudes, strict=True):
        profile.cycles(sign * amplitude, frequency, 1)
        profile.rest(_dwell(case, rng))
    # A 1 − cos of amplitude A at f Hz peaks at the speed π·f·A and the acceleration 2π²·f²·A.
    peak = min(rng.uniform(10.0, 30.0) * truth["Vs"], 0.5 * truth["vmax"])
    frequency = max(peak / (math.pi * 0.4 * truth["stroke"]), rng.uniform(0.7, 2.0))
    peak = min(peak, amax / (2.0 * math.pi * frequency))
    profile.cycles(peak / (math.pi * frequency), frequency, int(rng.integers(2, 4)))
    for speed in rng.permutation(_speeds(case, rng, int(rng.integers(9, 13)))):
        # Steady sliding for 0.3-0.8 s (at least 15 presliding ranges, at most 2 s), within the stroke.
        distance = min(
            0.4 * truth["stroke"], max(15.0 * span, float(speed) * rng.uniform(0.3, 0.8)), float(speed) * 2.0
        )
        profile.leg(float(speed), distance, amax, 0.0)
        profile.leg(float(speed), -distance, amax, _dwell(case, rng))
        profile.stop(amax, rng.uniform(0.0, 0.05))
        if profile.seconds >= seconds:
            return
    _reversal_legs(profile, case, rng, seconds)


def _closed_loop_reference(case: Case, rng: np.random.Generator) -> Profile:
    """The reference of the position loop: point-to-point moves (dwell 0.05–0.6 s after each, some
    of a few presliding ranges) or sines of 2–4 cycles, speeds over two decades, the
    acceleration kept so that m·ẍ stays within 0.2–0.8 Fc."""
    truth = case.truth
    profile = Profile(case.dt)
    amax = rng.uniform(0.2, 0.8) * truth["Fc"] / truth["mass"]
    # From 0.5-1.5 Vs up: a machine's moves rarely crawl far below the Stribeck velocity.
    speeds = _speeds(case, rng, 24, rng.uniform(0.5, 1.5))
    stroke, small = truth["stroke"], 3.0 * truth["excitation_presliding_range"]
    profile.rest(0.2)
    direction = 1.0
    while profile.seconds < case.duration:
        speed = float(rng.choice(speeds))
        if case.recipe.excitation == "point_to_point":
            length = small * rng.uniform(1.0, 3.0) if rng.random() < 0.2 else speed * rng.uniform(0.3, 1.2)
            room = 0.5 * stroke - direction * profile.x
            if room < small:
                direction = -direction
                room = 0.5 * stroke - direction * profile.x
            length = max(min(length, room), small)
            profile.leg(min(speed, length / 0.05), direction * length, amax, 0.0)
            profile.stop(amax, rng.uniform(0.05, 0.6))
            direction = direction if rng.random() < 0.3 else -direction
        else:
            # Peak speed π·f·A of a 1 − cos of amplitude A; bound the frequency by amax = 2π²f²A.
            length = min(_loguniform(rng, (small, 0.5 * stroke)), 0.5 * stroke - abs(profile.x))
            length = max(length, small)
            frequency = float(np.clip(speed / (math.pi * length), 0.5, 5.0))
            length = min(length, speed / (math.pi * frequency))
            frequency = min(frequency, math.sqrt(amax / (2 * math.pi**2 * length)))
            sign = -1.0 if profile.x > 0 else 1.0
            profile.cycles(sign * length, frequency, int(rng.integers(2, 5)))
            profile.rest(rng.uniform(0.0, 0.3))
    profile.rest(0.3)
    return profile


# --------------------------------------------------------------------------------------------
# The truth
# --------------------------------------------------------------------------------------------


def contact_params(truth: dict[str, Any]) -> lr.Params:
    """The contact part (σ2 = 0; σ1 = 0 but for LuGre's): the viscous term is added apart,
    because its −x level may differ (asymmetry) and the level does not scale it."""
    levels = {key: truth[key] for key in ("Fc", "Fs", "Fc_neg", "Fs_neg", "Vs", "delta", "n")}
    if truth.get("law") == "lugre":
        return lr.Params(**levels, sigma0=truth["sigma0"], sigma1=truth["sigma1"], sigma2=0.0)
    return lr.Params(**levels, sigma1=0.0, sigma2=0.0, W=truth["W"], Delta=truth["Delta"])


def viscous(truth: dict[str, Any], v: Array) -> Array:
    return np.asarray(np.where(v >= 0.0, truth["sigma2"], truth["sigma2_neg"]) * v, dtype=np.float64)


def level_factor(truth: dict[str, Any], x: Array, t: Array) -> Array:
    """The factor of the contact part at positions ``x`` and times ``t``: the position level and
    the drift (1 without them)."""
    factor = np.ones_like(x)
    level = truth["level"]
    if level is not None and level["kind"] == "ripple":
        phase = 2.0 * math.pi * x / level["wavelength"]
        factor += level["relative_amp"] * (
            np.sin(phase + level["phase"]) + level["second_harmonic"] * np.sin(2 * phase + level["phase2"])
        )
    elif level is not None:
        xi = np.clip((x - level["middle"]) / level["half_stroke"], -1.0, 1.0)
        factor += level["a1"] * xi + level["a2"] * (xi**2 - 1.0 / 3.0)
    drift = truth["drift"]
    if drift is not None:
        factor *= 1.0 + drift["relative_rise"] * t / drift["duration"]
    return factor


def cogging(truth: dict[str, Any], x: Array) -> Array:
    spec = truth["cogging"]
    if spec is None:
        return np.zeros_like(x)
    phase = 2.0 * math.pi * x / spec["period"]
    shape = np.sin(phase + spec["phase"]) + spec["second_harmonic"] * np.sin(2 * phase + spec["phase2"])
    return np.asarray(spec["amplitude"] * shape, dtype=np.float64)


def _place_position_terms(truth: dict[str, Any], x: Array, duration: float) -> None:
    """Fixes the position terms' lengths on the stroke the motion visits."""
    low, high = float(np.min(x)), float(np.max(x))
    if truth["level"] is not None and truth["level"]["kind"] == "ripple":
        truth["level"]["wavelength"] = (high - low) / truth["level"]["periods_over_stroke"]
    elif truth["level"] is not None:
        truth["level"]["middle"], truth["level"]["half_stroke"] = 0.5 * (low + high), 0.5 * (high - low)
    if truth["drift"] is not None:
        truth["drift"]["duration"] = duration
    if truth["cogging"] is not None:
        truth["cogging"]["period"] = (high - low) / truth["cogging"]["periods_over_stroke"]


def _position_driven(case: Case, rng: np.random.Generator) -> tuple[Array, Array, Array, dict[str, Any]]:
    """The true motion on the fine grid, the friction on it, and the log's x, v, clean force."""
    truth, h = case.truth, case.dt / SUBSTEPS
    profile = Profile(h)
    if case.recipe.excitation == "identification":
        _identification(profile, case, rng, case.duration)
    else:
        profile.rest(rng.uniform(0.05, 0.2))
        _reversal_legs(profile, case, rng, case.duration)
    v_fine = profile.velocity()
    # The log ends at its duration, in motion or not, as a recording does.
    samples = min((v_fine.size - 1) // SUBSTEPS, round(case.duration / case.dt))
    v_fine = v_fine[: samples * SUBSTEPS + 1]
    centre = rng.uniform(*case.axis.centre)
    x_fine = centre + np.concatenate(([0.0], np.cumsum(0.5 * (v_fine[1:] + v_fine[:-1]) * h)))
    a_fine = np.gradient(v_fine, h)
    t_fine = np.arange(v_fine.size, dtype=np.float64) * h
    _place_position_terms(truth, x_fine, float(t_fine[-1]))
    if truth["mass"] > 0.0:
        # m·|ẍ| at its 99th percentile is the drawn share of Fc.
        truth["mass"] = truth["inertia_share"] * truth["Fc"] / float(np.percentile(np.abs(a_fine), 99))
    contact = lr.simulate_position(contact_params(truth), x_fine, h)
    force_fine = (
        level_factor(truth, x_fine, t_fine) * contact
        + viscous(truth, v_fine)
        + truth["mass"] * a_fine
        + truth["offset"]
        + cogging(truth, x_fine)
    )
    pick = slice(None, None, SUBSTEPS)
    return x_fine[pick], v_fine[pick], force_fine[pick], {"acc_p99": float(np.percentile(np.abs(a_fine), 99))}


def _closed_loop(case: Case, rng: np.random.Generator) -> tuple[Array, Array, Array, dict[str, Any]]:
    """A mass on the true friction under a PID position loop at the log's rate: the controller
    reads the encoder and holds its force over the sample; the machine runs ``SUBSTEPS`` steps of
    ``leuven_rt.MassSystem`` a sample, with the load terms (offset, cogging, the −x viscous
    excess) held with it. The log is the encoder, the true velocity and the actuator's force."""
    truth, dt = case.truth, case.dt
    reference = _closed_loop_reference(case, rng)
    v_ref = reference.velocity()[: round(case.duration / dt) + 1]
    centre = rng.uniform(*case.axis.centre)
    x_ref = centre + np.concatenate(([0.0], np.cumsum(0.5 * (v_ref[1:] + v_ref[:-1]) * dt)))
    a_ref = np.gradient(v_ref, dt)
    _place_position_terms(truth, x_ref, float(x_ref.size * dt))
    mass = truth["mass"]
    bandwidth = min(rng.uniform(10.0, 30.0), case.rate / 30.0)
    omega = 2.0 * math.pi * bandwidth
    kp, kd, ki = mass * omega**2, 2.0 * 0.8 * mass * omega, mass * omega**3 / 5.0
    feedforward = mass * rng.uniform(0.8, 1.2)
    derivative_cutoff = min(4.0 * bandwidth, 0.1 * case.rate)
    derivative_pole = math.exp(-2.0 * math.pi * derivative_cutoff * dt)
    truth["controller"] = {
        "bandwidth_hz": bandwidth,
        "kp": kp,
        "ki": ki,
        "kd": kd,
        "mass_feedforward": feedforward,
        "derivative_lowpass_hz": derivative_cutoff,
    }
    params = lr.Params(**{**contact_params(truth).to_dict(), "sigma2": truth["sigma2"]})
    machine = lr.MassSystem(params, mass)
    machine.place(float(x_ref[0]), 0.0)
    samples, q, h = x_ref.size, case.quantization, dt / SUBSTEPS
    x_true, v_true, u_log = np.empty(samples), np.empty(samples), np.empty(samples)
    x, v = float(x_ref[0]), 0.0
    integral, derivative = 0.0, 0.0
    error_before = float(x_ref[0] - math.floor(x / q) * q)
    excess = truth["sigma2_neg"] - truth["sigma2"]
    cog = truth["cogging"]
    for k in range(samples):
        encoder = math.floor(x / q) * q
        error = float(x_ref[k]) - encoder
        integral += error * dt
        derivative = derivative_pole * derivative + (1.0 - derivative_pole) * (error - error_before) / dt
        error_before = error
        u = feedforward * float(a_ref[k]) + kp * error + ki * integral + kd * derivative
        x_true[k], v_true[k], u_log[k] = x, v, u
        for _ in range(SUBSTEPS):
            # The loads act on the mass at each sub-step's start (explicit: they are slow).
            load = truth["offset"] + excess * min(v, 0.0)
            if cog is not None:
                phase = 2.0 * math.pi * x / cog["period"]
                load += cog["amplitude"] * (
                    math.sin(phase + cog["phase"])
                    + cog["second_harmonic"] * math.sin(2.0 * phase + cog["phase2"])
                )
            _, x, v = machine.step(u - load, h)
    facts = {
        "tracking_error_rms": float(np.sqrt(np.mean((x_ref - x_true) ** 2))),
        "acc_p99": float(np.percentile(np.abs(np.gradient(v_true, dt)), 99)),
        # Where the mass sticks (below a thousandth of Vs), the force is whatever the controller
        # applies: no law driven by the motion places it when presliding is below the encoder step.
        "still_share": float(np.mean(np.abs(v_true) < 1e-3 * truth["Vs"])),
    }
    return x_true, v_true, u_log, facts


# --------------------------------------------------------------------------------------------
# Noise and the floor
# --------------------------------------------------------------------------------------------


def force_noise(case: Case, samples: int, rng: np.random.Generator) -> tuple[Array, dict[str, Any]]:
    """The noise of the force sensor, zero-mean, of std about ``case.noise_std_set``."""
    sigma, dt = case.noise_std_set, case.dt
    if case.noise_kind == "white":
        noise = rng.normal(0.0, sigma, samples)
        info: dict[str, Any] = {"kind": "white"}
    else:
        share = rng.uniform(0.2, 0.35)  # of the little white noise on top
        if case.noise_kind == "coloured":
            cutoff = min(_loguniform(rng, (10.0, 100.0)), 0.2 / dt)
            pole = math.exp(-2.0 * math.pi * cutoff * dt)
            shaped = signal.lfilter([1.0 - pole], [1.0, -pole], rng.normal(0.0, 1.0, samples))
            info = {"kind": "first-order low-pass white noise + white", "cutoff_hz": cutoff}
        else:
            corner = rng.uniform(1.0, 3.0)
            frequencies = np.fft.rfftfreq(samples, dt)
            gain = 1.0 / np.sqrt(np.maximum(frequencies, corner))
            shaped = np.fft.irfft(np.fft.rfft(rng.normal(0.0, 1.0, samples)) * gain, samples)
            info = {"kind": "1/f-like (pink above a corner, flat below) + white", "corner_hz": corner}
        shaped = shaped / np.std(shaped)
        scale = sigma / math.sqrt(1.0 + share**2)
        noise = scale * shaped + rng.normal(0.0, share * scale, samples)
        info.update({"coloured_std_set": scale, "white_std_set": share * scale})
    noise = noise - np.mean(noise)
    return noise, info


def floor(case: Case, t: Array, x: Array, f: Array, v: Array | None) -> tuple[float, str]:
    """The rms error of the true law and measurement terms driven by what the log gives (module
    documentation): the smallest over the drives of the friction and of the acceleration."""
    truth, dt = case.truth, case.dt
    params = contact_params(truth)
    drives: dict[str, tuple[Array, Array, Array]] = {}  # name: (position, velocity, contact force)
    if v is not None:
        drives["logged v"] = (x, v, lr.simulate(params, v, dt))
    steps = np.concatenate(([0.0], np.diff(x) / dt))
    drives["differences"] = (x, steps, lr.simulate_position(params, x, dt))
    nyquist = 0.5 / dt
    for share in FLOOR_CUTOFFS:
        sos = signal.butter(4, share * nyquist, fs=1.0 / dt, output="sos")
        smooth = signal.sosfiltfilt(sos, x)
        drives[f"filtered at {share:g} of Nyquist"] = (
            smooth,
            np.concatenate(([0.0], np.diff(smooth) / dt)),
            lr.simulate_position(params, smooth, dt),
        )
    accelerations: dict[str, Array] = {"none": np.zeros_like(x)}
    if truth["mass"] > 0.0:
        accelerations = {
            name: np.gradient(np.gradient(position, dt), dt)
            for name, (position, _, _) in drives.items()
            if name != "logged v"
        }
        if v is not None:
            accelerations["logged v"] = np.gradient(v, dt)
    best, source = math.inf, ""
    for name, (position, velocity, contact) in drives.items():
        law = (
            level_factor(truth, position, t) * contact
            + viscous(truth, velocity)
            + truth["offset"]
            + cogging(truth, position)
        )
        for acceleration_name, acceleration in accelerations.items():
            rms = float(np.sqrt(np.mean((f - law - truth["mass"] * acceleration) ** 2)))
            if rms < best:
                best = rms
                source = (
                    name if acceleration_name == "none" else f"{name}; acceleration from {acceleration_name}"
                )
    return best, source


# --------------------------------------------------------------------------------------------
# One log, a split, the files
# --------------------------------------------------------------------------------------------


def make_log(case: Case) -> Log:
    """Simulates ``case`` (deterministic in its seed) and measures it. The log's case holds the
    truth completed by the motion (the level's and cogging's lengths, the mass of a
    position-driven log, the controller); ``case`` itself is left as it was."""
    case = dataclasses.replace(case, truth=copy.deepcopy(case.truth))
    rng = np.random.default_rng([case.seed, 1])  # the motion's and noise's stream, apart from the draws
    if case.recipe.excitation in CLOSED_LOOP:
        x_true, v_true, force, facts = _closed_loop(case, rng)
    else:
        x_true, v_true, force, facts = _position_driven(case, rng)
    q = case.quantization
    x = np.floor(x_true / q) * q  # an encoder counts whole steps
    t = np.arange(x.size, dtype=np.float64) * case.dt
    noise, info = force_noise(case, x.size, rng)
    f = force + noise
    v = v_true if case.has_v else None
    floor_rms, floor_from = floor(case, t, x, f, v)
    signs = np.sign(v_true[np.abs(v_true) > 1e-3 * np.max(np.abs(v_true))])
    facts.update(
        {
            "noise": info,
            "samples": int(x.size),
            "duration_s": float(t[-1]),
            "x_range": [float(np.min(x)), float(np.max(x))],
            "v_max_abs": float(np.max(np.abs(v_true))),
            "reversals": int(np.count_nonzero(np.diff(signs))),
            "force_rms_about_mean": float(np.std(force)),
        }
    )
    return Log(case, t, x, f, v, force, noise, floor_rms, floor_from, facts)


def describe(case: Case) -> str:
    recipe = case.recipe
    hidden = "+".join(recipe.hidden) or "null (Coulomb + viscous)"
    if recipe.position:
        hidden += f" ({recipe.position})"
    if recipe.extra:
        hidden = f"{recipe.extra} (outside the catalogue) + {hidden}"
    encoder = (
        f"2^{int(math.log2(case.counts_per_turn))} counts/turn"
        if case.counts_per_turn
        else f"q {case.quantization:g} m"
    )
    dwell = "0-0.1 s dwell at reversals" if case.dwell[1] > 0 else "no dwell"
    if recipe.excitation in CLOSED_LOOP:
        dwell = "closed loop"
    law = "LuGre law, " if case.truth.get("law") == "lugre" else ""
    return (
        f"{law}{case.axis.kind}, {hidden}, {recipe.excitation}, {case.rate:g} Hz, {encoder}, "
        f"{case.noise_kind} noise, {'with' if case.has_v else 'no'} v, {dwell}"
    )


def manifest_entry(log: Log) -> dict[str, Any]:
    """The log's manifest entry: the scorer's keys, then the truth, sensor and excitation."""
    case = log.case
    truth = dict(case.truth)
    truth["units"] = {"unit_x": case.axis.unit_x, "unit_f": case.axis.unit_f}
    truth.pop("inertia_share", None)
    entry: dict[str, Any] = {
        "name": case.name,
        "split": case.split,
        "description": describe(case),
        "hidden_effects": sorted(case.recipe.hidden),
        "extra": case.recipe.extra,
        "noise_std": float(np.std(log.noise)),
        "scale": case.axis.kind,
        "floor_rms": log.floor_rms,
        "floor_from": log.floor_from,
        "seed": case.seed,
        "generator": {
            "truth": (
                "leuven_rt.MassSystem (mass and friction, implicit) under a PID position loop"
                if case.recipe.excitation in CLOSED_LOOP
                else "leuven_rt.simulate_position on the true motion"
            ),
            "substeps_per_sample": SUBSTEPS,
        },
        "sensor": {
            "rate_hz": case.rate,
            "dt": case.dt,
            "quantization": case.quantization,
            "counts_per_turn": case.counts_per_turn,
            "has_v": case.has_v,
        },
        "excitation": {
            "kind": case.recipe.excitation,
            "reversal_dwell_s": list(case.dwell) if case.recipe.excitation not in CLOSED_LOOP else None,
        },
        "truth": truth,
    }
    entry.update(log.facts)
    return entry


def write_csv(path: Path, log: Log) -> None:
    columns = [log.t, log.x, log.f] + ([log.v] if log.v is not None else [])
    header = "t,x,f" + (",v" if log.v is not None else "")
    fmt = ["%.10g", "%.15g", "%.10g", "%.10g"][: len(columns)]
    np.savetxt(path, np.column_stack(columns), fmt=fmt, delimiter=",", header=header, comments="")


def cases(split: str, seed_base: int = 0, quick: bool = False, law: str = "leuven") -> list[Case]:
    """The cases of ``split`` ("tuning", "held-out" or "all") under the contact ``law``."""
    chosen = SPLITS if split == "all" else (split,)
    count = 4 if quick else None
    return [
        draw_case(name, index, seed_base, quick, law)
        for name in chosen
        for index in range(len(RECIPES[name]))[:count]
    ]


def generate(
    out: Path,
    split: str,
    seed_base: int = 0,
    quick: bool = False,
    progress: Callable[[str], None] | None = None,
    law: str = "leuven",
) -> list[dict[str, Any]]:
    """Writes every log of ``split`` under the contact ``law`` and the manifest into ``out``;
    returns the manifest."""
    out.mkdir(parents=True, exist_ok=True)
    manifest = []
    for case in cases(split, seed_base, quick, law):
        start = time.perf_counter()
        log = make_log(case)
        write_csv(out / f"{case.name}.csv", log)
        manifest.append(manifest_entry(log))
        if progress is not None:
            ratio = log.floor_rms / manifest[-1]["noise_std"]
            progress(
                f"{case.name}: {describe(case)}; floor {ratio:.2f}x noise ({log.floor_from}); "
                f"{time.perf_counter() - start:.1f} s"
            )
    (out / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
    return manifest


def _seed_base(text: str) -> int:
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {value}")
    return value


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path, help="the folder to write the logs and manifest.json into")
    parser.add_argument("--split", choices=("tuning", "held-out", "all"), default="all")
    parser.add_argument(
        "--seed-base", type=_seed_base, default=0, help="shifts every seed (another family of the same kind)"
    )
    parser.add_argument(
        "--law",
        choices=LAWS,
        default="leuven",
        help="the truth's contact law (lugre: another law than the bank's)",
    )
    parser.add_argument("--quick", action="store_true", help="4 logs a split, 8-12 s each")
    parser.add_argument("--force", action="store_true", help="replace an existing manifest.json in OUT")
    args = parser.parse_args(argv)
    if (args.out / "manifest.json").exists() and not args.force:
        print(f"family.py: {args.out / 'manifest.json'} exists; give --force to replace it", file=sys.stderr)
        return 2
    start = time.perf_counter()
    manifest = generate(
        args.out,
        args.split,
        args.seed_base,
        args.quick,
        lambda line: print(line, file=sys.stderr, flush=True),
        args.law,
    )
    print(f"{len(manifest)} logs and manifest.json in {args.out} ({time.perf_counter() - start:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
