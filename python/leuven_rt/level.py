"""Functions of the position alone: a smooth trend along the stroke and periodic ripples (a
screw's pitch, a gear's teeth, a motor's poles), of one shape,

    r(x) = t1·P1(p) + t2·P2(p) + Σ_r Σ_k (c_rk·cos(2πk·x/P_r) + s_rk·sin(2πk·x/P_r)),

with p = clip((x − middle)/half_stroke, −1, 1) (the trend is flat beyond the stroke it was
identified on) and P1, P2 the Legendre polynomials. Two effects have that shape:

- :class:`PositionLevel`: the friction level, factor(x) = 1 + r(x), scales the contact part of
  the friction (the hysteresis force and the micro-viscous term) and leaves the viscous term
  alone: F = factor(x)·(F_plain − σ2(v)·v) + σ2(v)·v. Its coefficients are relative
  (dimensionless), and the sum of their magnitudes must stay below 1, so the factor is positive
  everywhere.
- :class:`PositionForce`: r(x) itself in force units (N, or N·m for a rotary axis), added in both
  directions of motion whatever the friction level (cogging, gear mesh, a gravity-like torque
  along the stroke): F + r(x). Any finite coefficients.

The periods, ``middle`` and ``half_stroke`` are in the position's unit. Python coerces the types;
gms-core checks the values once (naming the field), including that the half stroke and every
period are at least 2²⁰ ulps of max(|middle| + half_stroke, 1), the largest position the shape
covers, so that their phase can be resolved there. :meth:`PositionLevel.factor` and
:meth:`PositionForce.force` are gms-core's evaluation; the numpy formula is the oracle's
(:func:`leuven_rt.reference.position_series`). docs/model.md#position-dependent-level has the
equations and the rules.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._typing import FloatArray
from .errors import ParameterError, data_of, shown
from .params import _real, _reals

#: Most ripples (distinct periods) a level or a position force holds.
MAX_RIPPLES = 2
#: Most harmonics of each ripple.
MAX_HARMONICS = 8

#: The keys of the JSON form of a level or a position force, and of one of its ripples.
KEYS = ("middle", "half_stroke", "trend", "ripples")
RIPPLE_KEYS = ("period", "cos", "sin")


@dataclass(frozen=True)
class Ripple:
    """One periodic part of a level or a position force: ``period`` [m or rad] and its harmonics'
    amplitudes (``cos[k-1]``, ``sin[k-1]`` for harmonic k; relative for a level, in N or N·m for
    a position force)."""

    period: float
    cos: tuple[float, ...]
    sin: tuple[float, ...]

    def __post_init__(self) -> None:
        # Types only; the values are gms-core's to check, with the ripple's index, when the
        # level or position force holding this ripple is built.
        object.__setattr__(self, "period", _real("period", self.period))
        object.__setattr__(self, "cos", _reals("cos", self.cos))
        object.__setattr__(self, "sin", _reals("sin", self.sin))


@dataclass(frozen=True)
class _Series:
    """The shape shared by :class:`PositionLevel` and :class:`PositionForce`: its fields, their
    coercion, the validated core object, pickling and the JSON form."""

    middle: float = 0.0
    half_stroke: float = 1.0
    trend: tuple[float, float] = (0.0, 0.0)
    ripples: tuple[Ripple, ...] = ()

    #: gms-core's validated form (``_core.CoreLevel`` or ``_core.CorePositionForce``).
    _core_class: ClassVar[Any]

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
        # validated object is kept for the engines as a plain attribute, not a dataclass field,
        # as Params keeps its own.
        object.__setattr__(self, "_validated", self._core_class(self))

    def __getstate__(self) -> dict[str, Any]:
        """The fields only (for pickle and copy): the core object is rebuilt on restore."""
        return {field.name: getattr(self, field.name) for field in fields(self)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        for key, value in state.items():
            object.__setattr__(self, key, value)
        object.__setattr__(self, "_validated", self._core_class(self))

    def _evaluate(self, method: str, x: ArrayLike) -> FloatArray:
        """gms-core's ``method`` at every sample of ``x`` (any shape; NaN where x is not finite)."""
        position = np.asarray(x, dtype=float)
        flat = np.ascontiguousarray(position.reshape(-1))
        out: FloatArray = getattr(vars(self)["_validated"], method)(flat).reshape(position.shape)
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: ``{"middle", "half_stroke", "trend": [t1, t2], "ripples": [{"period",
        "cos", "sin"}, ...]}``, every key written."""
        return {
            "middle": self.middle,
            "half_stroke": self.half_stroke,
            "trend": list(self.trend),
            "ripples": [
                {"period": ripple.period, "cos": list(ripple.cos), "sin": list(ripple.sin)}
                for ripple in self.ripples
            ],
        }

    @classmethod
    def _from_mapping(cls, mapping: Mapping[str, Any]) -> Any:
        if not isinstance(mapping, Mapping):
            raise ParameterError(
                f"a {cls.__name__} must be a mapping, got {type(mapping).__name__}",
                kind="wrong_type",
                value=mapping,
            )
        unknown = sorted(set(mapping) - set(KEYS), key=repr)
        if unknown:
            raise ParameterError(
                f"unknown keys {shown(unknown)}; expected keys among {list(KEYS)}",
                kind="unknown_key",
                field=str(unknown[0]),
                expected=list(KEYS),
                got=sorted(mapping, key=repr),
            )
        return cls(**mapping)


@dataclass(frozen=True)
class PositionLevel(_Series):
    """factor(x) = 1 + r(x) of the module documentation: ``middle`` and ``half_stroke`` [m or rad]
    scale the trend's position, ``trend`` = (t1, t2) its Legendre coefficients, ``ripples`` the
    periodic parts; every coefficient relative to the friction level."""

    _core_class = _core.CoreLevel

    def factor(self, x: ArrayLike) -> FloatArray:
        """factor(x) on every sample of ``x``, as gms-core computes it."""
        return self._evaluate("factor", x)

    @classmethod
    def from_dict(cls, mapping: Mapping[str, Any]) -> PositionLevel:
        """Builds from the JSON form (:meth:`to_dict`); keys left out take the defaults (no
        trend, no ripple), unknown keys raise :class:`ParameterError`."""
        level: PositionLevel = cls._from_mapping(mapping)
        return level


@dataclass(frozen=True)
class PositionForce(_Series):
    """r(x) of the module documentation in force units: ``middle`` and ``half_stroke`` [m or
    rad] scale the trend's position, ``trend`` = (t1, t2) its Legendre coefficients [N or N·m],
    ``ripples`` the periodic parts (amplitudes in N or N·m). Added to the friction in both
    directions of motion, not scaled by the level."""

    _core_class = _core.CorePositionForce

    def force(self, x: ArrayLike) -> FloatArray:
        """r(x) on every sample of ``x``, as gms-core computes it."""
        return self._evaluate("force", x)

    @classmethod
    def from_dict(cls, mapping: Mapping[str, Any]) -> PositionForce:
        """Builds from the JSON form (:meth:`to_dict`); keys left out take the defaults (no
        trend, no ripple), unknown keys raise :class:`ParameterError`."""
        force: PositionForce = cls._from_mapping(mapping)
        return force


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
            keys = set(RIPPLE_KEYS)
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


def core_position_force(force: PositionForce) -> Any:
    """What the engines take: the gms-core position force validated when ``force`` was built."""
    if not isinstance(force, PositionForce):
        raise ParameterError(
            f"`position_force` must be a leuven_rt.level.PositionForce or None, got {type(force).__name__}",
            kind="wrong_type",
            field="position_force",
            value=force,
        )
    return vars(force)["_validated"]
