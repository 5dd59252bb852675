"""Standard parameter sets and excitations used by the demo, the benchmarks and the docs."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._typing import FloatArray
from ..params import Params


def standard_params(elements: int = 10) -> Params:
    """A stage with Fc = 1 N, Fs = 1.5 N and a 10 µm presliding range.

    Break deflections are equally spaced up to the presliding range (the paper's choice), and
    the saturation forces fall off linearly, so that the virgin curve is concave and smooth.
    """
    index = np.arange(1, elements + 1)
    delta = 1e-5 * index / elements
    weights = (elements + 1 - index).astype(float)
    w = 2.0 * weights / weights.sum()
    return Params(
        Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=30.0, sigma2=0.4, W=w.tolist(), Delta=delta.tolist()
    )


@dataclass(frozen=True)
class Excitation:
    """A sampled position signal, its envelope and its step."""

    t: FloatArray
    x: FloatArray
    amplitude: FloatArray
    dt: float


def presliding_to_sliding(duration: float = 6.0, dt: float = 1e-4) -> Excitation:
    """A 1 Hz position oscillation whose amplitude grows from 0.1 µm to 200 µm.

    The first cycles stay inside the presliding range (closed hysteresis loops in force vs
    displacement); the last ones slide, and the force saturates at the Stribeck level.
    """
    t = np.arange(round(duration / dt), dtype=np.float64) * dt
    amplitude = 1e-7 * (2e-4 / 1e-7) ** (t / duration)
    return Excitation(t=t, x=amplitude * np.sin(2.0 * np.pi * t), amplitude=amplitude, dt=dt)
