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

from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._typing import FloatArray
from .errors import ParameterError, data_of, shown
from .params import _real, _reals

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

    def __post_init__(self) -> None:
        # Types only; the values are gms-core's to check, with the ripple's index, when a
        # PositionLevel holding this ripple is built.
        object.__setattr__(self, "period", _real("period", self.period))
        object.__setattr__(self, "cos", _reals("cos", self.cos))
        object.__setattr__(self, "sin", _reals("sin", self.sin))


@dataclass(frozen=True)
class PositionLevel:
    """factor(x) of the module documentation: ``middle`` and ``half_stroke`` [m or rad] scale the
    trend's position, ``trend`` = (t1, t2) its Legendre coefficients, ``ripples`` the periodic parts."""

    middle: float = 0.0
    half_stroke: float = 1.0
    trend: tuple[float, float] = (0.0, 0.0)
    ripples: tuple[Ripple, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "middle", _real("middle", self.middle))
        object.__setattr__(self, "half_stroke", _real("half_stroke", self.half_stroke))
        trend = _reals("trend", self.trend)
        if len(trend) != 2:
            raise ParameterError(
                f"`trend` must have 2 coefficients (t1, t2), got {len(trend)}: {trend!r:.80}",
                kind="wrong_length",
                field="trend",
                expected=2,
                got=len(trend),
            )
        object.__setattr__(self, "trend", trend)
        object.__setattr__(self, "ripples", _ripples(self.ripples))
        # gms-core checks the values once (ParameterError naming the first rule broken); the
        # validated level is kept for the engines as a plain attribute, not a dataclass field,
        # as Params keeps its own.
        object.__setattr__(self, "_validated", _core.CoreLevel(self))

    def __getstate__(self) -> dict[str, Any]:
        """The fields only (for pickle and copy): the core object is rebuilt on restore."""
        return {field.name: getattr(self, field.name) for field in fields(self)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        for key, value in state.items():
            object.__setattr__(self, key, value)
        object.__setattr__(self, "_validated", _core.CoreLevel(self))

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


def _ripples(ripples: Any) -> tuple[Ripple, ...]:
    """``ripples`` as a tuple of :class:`Ripple`; mappings with the keys period, cos, sin are
    turned into ripples (as a model file holds them)."""
    if isinstance(ripples, (str, bytes, bytearray, Mapping)) or not hasattr(ripples, "__iter__"):
        raise ParameterError(
            f"`ripples` must be a sequence of Ripple, got {shown(ripples)!r:.80}",
            kind="wrong_type",
            field="ripples",
            value=ripples,
        )
    out = []
    for index, ripple in enumerate(ripples):
        if isinstance(ripple, Ripple):
            out.append(ripple)
        elif isinstance(ripple, Mapping):
            keys = {"period", "cos", "sin"}
            if set(ripple) != keys:
                given = sorted(ripple, key=repr)
                missing, unknown = sorted(keys - set(ripple)), sorted(set(ripple) - keys, key=repr)
                raise ParameterError(
                    f"`ripples[{index}]` must have the keys {sorted(keys)}, got {given}",
                    kind="missing_key" if missing else "unknown_key",
                    field=f"ripples[{index}].{(missing or unknown)[0]}",
                    index=index,
                    expected=sorted(keys),
                    got=given,
                )
            try:
                out.append(Ripple(**ripple))
            except ParameterError as error:
                raise ParameterError(
                    f"`ripples[{index}]`: {error}",
                    **{**data_of(error), "field": f"ripples[{index}].{error.field}"},
                ) from None
        else:
            raise ParameterError(
                f"`ripples[{index}]` must be a Ripple, got {shown(ripple)!r:.80}",
                kind="wrong_type",
                field=f"ripples[{index}]",
                value=ripple,
                index=index,
            )
    return tuple(out)


def core_level(level: PositionLevel) -> Any:
    """What the engines take: the gms-core level validated when ``level`` was built."""
    if not isinstance(level, PositionLevel):
        raise ParameterError(
            f"`level` must be a leuven_rt.level.PositionLevel or None, got {type(level).__name__}",
            kind="wrong_type",
            field="level",
            value=level,
        )
    return vars(level)["_validated"]
