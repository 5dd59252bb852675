"""Synthetic measurements made by the project's own simulator, for testing identification.

:func:`make_data` drives a known parameter set with a varied position excitation (presliding
loops of growing and shrinking amplitude, a sliding sine, constant-velocity plateaus in both
directions from below the Stribeck velocity to a hundred times above it, each joined by smooth reversals)
and returns what a sensor would log: the position quantized to the encoder resolution and the
force with white measurement noise, next to the truth they came from.

The excitation is built from pieces (:func:`excitation`), so that later generators can add
hidden effects (inertia, offset, position dependence, ...) to ``force_true`` without touching it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._typing import FloatArray
from ..params import Params, ParamsLike, as_params
from ..simulation import simulate_position
from .records import MotionData
from .scenarios import standard_params


@dataclass(frozen=True, eq=False)
class SyntheticData:
    """A simulated log: ``data`` is what the sensors give, the rest is the truth behind it."""

    data: MotionData
    params: Params
    x_true: FloatArray
    force_true: FloatArray
    noise_std: float
    quantization: float


def _smooth_step(samples: int) -> FloatArray:
    """0 → 1 over ``samples`` samples with zero slope at both ends (raised cosine)."""
    return 0.5 - 0.5 * np.cos(np.pi * np.arange(1, samples + 1) / samples)


def _sine_cycles(amplitude: float, frequency: float, cycles: int, dt: float) -> FloatArray:
    """Displacement of whole cycles of 1 − cos (starts and ends at rest, at zero displacement)."""
    t = np.arange(1, round(cycles / (frequency * dt)) + 1, dtype=np.float64) * dt
    return 0.5 * amplitude * (1.0 - np.cos(2.0 * np.pi * frequency * t))


def _plateau(speed: float, hold: float, ramp: float, dt: float) -> FloatArray:
    """Displacement of a move: velocity ramps smoothly from 0 to ``speed``, holds, ramps back."""
    ramp_samples = max(round(ramp / dt), 2)
    up = _smooth_step(ramp_samples)
    v = np.concatenate((up, np.ones(round(hold / dt)), up[::-1])) * speed
    return np.cumsum(v) * dt


def excitation(
    dt: float,
    presliding_range: float,
    stribeck_velocity: float,
    rng: np.random.Generator,
    speeds: Sequence[float] | None = None,
) -> FloatArray:
    """A position signal [m] that starts at rest and visits presliding and sliding.

    - presliding: 1 − cos cycles at 5 Hz with amplitudes from 0.1 to 3 presliding ranges, growing
      then shrinking (closed minor loops, then loops inside loops);
    - a sliding sine: 3 cycles of 2 Hz whose velocity amplitude is 10 Stribeck velocities;
    - plateaus: constant-velocity moves at ``speeds`` (default: 0.3 to 100 Stribeck velocities,
      in a random order), each forward then back, long enough to reach steady sliding.
    """
    pieces: list[FloatArray] = [np.zeros(round(0.02 / dt))]
    amplitudes = presliding_range * np.array([0.1, 0.3, 0.6, 1.0, 2.0, 3.0, 1.5, 0.5, 0.2])
    amplitudes *= rng.uniform(0.8, 1.2, amplitudes.size)
    for sign, amplitude in zip(np.resize([1.0, -1.0], amplitudes.size), amplitudes, strict=True):
        pieces.append(sign * _sine_cycles(amplitude, 5.0, 1, dt))
    velocity = 10.0 * stribeck_velocity
    pieces.append(_sine_cycles(velocity / (np.pi * 2.0), 2.0, 3, dt))
    levels: Sequence[float] | FloatArray = (
        stribeck_velocity * np.array([0.3, 0.6, 1.0, 1.5, 2.5, 4.0, 7.0, 12.0, 25.0, 50.0, 100.0])
        if speeds is None
        else speeds
    )
    for index in rng.permutation(len(levels)):
        speed = float(levels[index])
        hold = max(0.05, 10.0 * presliding_range / speed)
        for sign in (1.0, -1.0):  # every speed in both directions, so asymmetry is identifiable
            pieces.append(sign * _plateau(speed, hold, 0.02, dt))
    # Each piece is a displacement from its own start: chain them into one position signal.
    position: list[FloatArray] = []
    offset = 0.0
    for piece in pieces:
        position.append(offset + piece)
        offset = float(position[-1][-1]) if piece.size else offset
    return np.concatenate(position)


def make_data(
    params: ParamsLike | None = None,
    dt: float = 2e-4,
    noise_std: float = 0.02,
    quantization: float = 1e-8,
    seed: int = 0,
    presliding_range: float | None = None,
    speeds: Sequence[float] | None = None,
) -> SyntheticData:
    """Simulates ``params`` (default: :func:`leuven_rt.data.scenarios.standard_params`) under
    :func:`excitation` and measures it: force + N(0, noise_std²) [N], position rounded to
    multiples of ``quantization`` [m] (0: exact). ``presliding_range`` defaults to max(Delta)."""
    params = standard_params() if params is None else as_params(params)
    if presliding_range is None:
        # Linear hysteresis: the spring reaches Fs at Fs/sigma0; a few times that covers the transition.
        presliding_range = (
            max(params.Delta) if params.Delta is not None else 3.0 * params.Fs / (params.sigma0 or 1.0)
        )
    rng = np.random.default_rng(seed)
    x_true = excitation(dt, presliding_range, params.Vs, rng, speeds)
    force_true = simulate_position(params, x_true, dt)
    force = force_true + rng.normal(0.0, noise_std, x_true.size) if noise_std > 0 else force_true.copy()
    x = np.round(x_true / quantization) * quantization if quantization > 0 else x_true.copy()
    t = np.arange(x_true.size, dtype=np.float64) * dt
    return SyntheticData(
        data=MotionData(t, x, force, source=f"synthetic(seed={seed})"),
        params=params,
        x_true=x_true,
        force_true=force_true,
        noise_std=noise_std,
        quantization=quantization,
    )
