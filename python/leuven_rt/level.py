"""A friction level that depends on the position: a smooth trend along the stroke and periodic
ripples (a screw's pitch, a gear's teeth, a motor's poles).

The contact part of the friction (the hysteresis force and the micro-viscous term) is scaled by

    factor(x) = 1 + t1·P1(p) + t2·P2(p) + Σ_r Σ_k (c_rk·cos(2πk·x/P_r) + s_rk·sin(2πk·x/P_r)),

with p = clip((x − middle)/half_stroke, −1, 1) (the trend is flat beyond the stroke it was
identified on) and P1, P2 the Legendre polynomials; the viscous term σ2·v is not scaled:

    F = factor(x)·(Fh + σ1·dz/dt) + σ2·v.

All coefficients are relative to the level (dimensionless); the periods are in the position's
unit. The sum of the coefficients' magnitudes must stay below 1, so the factor is positive
everywhere. docs/model.md#position-dependent-level has the equations and the rules.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ._typing import FloatArray

#: Most ripples (distinct periods) a level holds.
MAX_RIPPLES = 2
#: Most harmonics of each ripple.
MAX_HARMONICS = 8


@dataclass(frozen=True)
class Ripple:
    """One periodic part of the level: ``period`` [m or rad] and its harmonics' relative
    amplitudes (``cos[k-1]``, ``sin[k-1]`` for harmonic k)."""

    period: float
    cos: tuple[float, ...]
    sin: tuple[float, ...]


@dataclass(frozen=True)
class PositionLevel:
    """factor(x) of the module documentation: ``middle`` and ``half_stroke`` [m or rad] scale the
    trend's position, ``trend`` = (t1, t2) its Legendre coefficients, ``ripples`` the periodic parts."""

    middle: float = 0.0
    half_stroke: float = 1.0
    trend: tuple[float, float] = (0.0, 0.0)
    ripples: tuple[Ripple, ...] = ()

    def factor(self, x: ArrayLike) -> FloatArray:
        """factor(x) on every sample of ``x``."""
        position = np.asarray(x, dtype=float)
        p = np.clip((position - self.middle) / self.half_stroke, -1.0, 1.0)
        out: FloatArray = 1.0 + self.trend[0] * p + self.trend[1] * (1.5 * p * p - 0.5)
        for ripple in self.ripples:
            phase = 2.0 * np.pi * position / ripple.period
            for k, (c, s) in enumerate(zip(ripple.cos, ripple.sin, strict=True), start=1):
                out = out + c * np.cos(k * phase) + s * np.sin(k * phase)
        return out
