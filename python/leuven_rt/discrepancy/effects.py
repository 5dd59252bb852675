"""The effect catalogue of docs/effects.md: each effect is a set of named regressor columns (a model
term that can be added, fitted and removed), built from :class:`~.features.Features`.

The model is linear in its coefficients once the shape of the Stribeck curve (Vs, δ) is fixed;
:mod:`.model` fits that shape by variable projection. Columns that must stay nonnegative (the
Maxwell-slip weights) are listed per effect.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from .._typing import FloatArray
from ..errors import InputError, shown
from .features import ELEMENTS, Features
from .ripple import ripple_columns

#: Samples at rest the Coulomb effect needs to fit the force at rest apart.
MIN_REST = 20
#: Degree of the Legendre polynomials in position that scale the friction level along the stroke.
POSITION_DEGREE = 2


@dataclass(frozen=True)
class Shape:
    """The Stribeck curve's nonlinear parameters."""

    Vs: float
    delta: float


Columns = Callable[[Features, Collection[str], Shape | None], dict[str, FloatArray]]


@dataclass(frozen=True)
class Effect:
    name: str
    missing: str
    """What is missing from a model without it (docs/effects.md#the-effects)."""
    columns: Columns
    nonnegative: tuple[str, ...] = ()


def _coulomb(f: Features, model: Collection[str], shape: Shape | None) -> dict[str, FloatArray]:
    # At rest the force is whatever holds the axis: a share of the level in the direction of the
    # last motion, from none (the force released) to all of it (the friction holds its value).
    out = {"Fc": f.sign}
    if np.count_nonzero(f.rest[f.usable]) >= MIN_REST:
        out["Fc_rest"] = f.rest
    return out


def _asymmetry(f: Features, model: Collection[str], shape: Shape | None) -> dict[str, FloatArray]:
    # The levels of the negative direction move by these amounts, each level the model has; a
    # pure level shift (the same in both directions) is `offset`.
    out = {"Fc_neg_shift": np.minimum(f.sign, 0.0)}
    if "viscous" in model:
        out["sigma2_neg_shift"] = np.minimum(f.v, 0.0)
    if "stribeck" in model and shape is not None:
        out["Fs_neg_shift"] = np.minimum(_stribeck(f, model, shape)["Fs_minus_Fc"], 0.0)
    return out


def _stribeck(f: Features, model: Collection[str], shape: Shape | None) -> dict[str, FloatArray]:
    if shape is None:
        raise ValueError("the Stribeck columns need a shape (Vs, delta)")
    return {"Fs_minus_Fc": f.sign * np.exp(-(np.abs(f.v / shape.Vs) ** shape.delta))}


def shape_columns(f: Features, model: Collection[str], shape: Shape) -> dict[str, FloatArray]:
    """The columns of ``model`` that depend on the Stribeck shape: the Stribeck curve's, and with
    ``asymmetry`` its negative direction's shift (the columns of :data:`CATALOGUE`, in order)."""
    out = _stribeck(f, model, shape)
    if "asymmetry" in model:
        out["Fs_neg_shift"] = np.minimum(out["Fs_minus_Fc"], 0.0)
    return out


def _position(f: Features, model: Collection[str], shape: Shape | None) -> dict[str, FloatArray]:
    out = {}
    for degree in range(1, POSITION_DEGREE + 1):
        coefficients = np.zeros(degree + 1)
        coefficients[degree] = 1.0
        out[f"Fc_P{degree}"] = f.sign * legendre.legval(np.clip(f.position, -1.0, 1.0), coefficients)
    for number, period in enumerate(f.scales.periods, 1):
        columns = ripple_columns(f.sign, f.x, period)
        for k in range(len(columns) // 2):
            out[f"Fc_R{number}_cos{k + 1}"] = columns[2 * k]
            out[f"Fc_R{number}_sin{k + 1}"] = columns[2 * k + 1]
    return out


CATALOGUE: dict[str, Effect] = {
    effect.name: effect
    for effect in (
        Effect("coulomb", "a constant friction level Fc·sgn(v)", _coulomb, nonnegative=("Fc",)),
        Effect("viscous", "sigma2·v", lambda f, m, s: {"sigma2": f.v}, nonnegative=("sigma2",)),
        Effect("stribeck", "Fs > Fc, Vs, δ", _stribeck, nonnegative=("Fs_minus_Fc",)),
        Effect("asymmetry", "levels differ between v > 0 and v < 0", _asymmetry),
        Effect(
            "presliding_hysteresis",
            "the dynamic state z with Maxwell-slip Fh",
            lambda f, m, s: {f"W{j + 1}": f.bank[:, j] for j in range(f.bank.shape[1])},
            nonnegative=tuple(f"W{j + 1}" for j in range(ELEMENTS)),
        ),
        Effect("position_dependence", "the friction level varies along the stroke", _position),
        Effect(
            "offset",
            "a constant force bias in the measurement",
            lambda f, m, s: {"offset": np.ones_like(f.v)},
        ),
        Effect("inertia", "the force includes m·ẍ", lambda f, m, s: {"M": f.a}),
    )
}


def _drift(f: Features, model: Collection[str], shape: Shape | None) -> dict[str, FloatArray]:
    time = 2.0 * (f.t - f.t[0]) / max(float(f.t[-1] - f.t[0]), f.dt) - 1.0
    # linear in time: a held-out block at either end of the record extrapolates it
    return {"Fc_T1": f.sign * time}


#: Outside the catalogue: a friction level that changes over the record (wear, temperature). It is
#: never named; when it is in the data, it is fitted alongside so that no effect is named for it,
#: and reported as what remains unexplained.
DRIFT = Effect("drift", "the friction level changes over the record", _drift)
#: Every term a model can hold: the catalogue and the drift.
TERMS: dict[str, Effect] = {**CATALOGUE, DRIFT.name: DRIFT}


def parse_effects(names: str | Sequence[str], argument: str = "baseline") -> tuple[str, ...]:
    """Effect names from a list or a comma-separated string; unknown or repeated names are refused."""
    given: object = names  # checked as what may come, not as what is declared
    if not isinstance(given, (str, Sequence)) or isinstance(given, (bytes, bytearray)):
        raise InputError(
            f"`{argument}` must be effect names, as a list or comma-separated, got {shown(names)!r:.80}",
            kind="wrong_type",
            field=argument,
            value=names,
        )
    items = [name.strip() for name in names.split(",")] if isinstance(names, str) else list(names)
    items = [name for name in items if name]
    if any(not isinstance(name, str) for name in items):
        raise InputError(
            f"`{argument}` must be effect names (strings), got {shown(items)!r}",
            kind="wrong_type",
            field=argument,
            value=next(name for name in items if not isinstance(name, str)),
        )
    unknown = [name for name in items if name not in CATALOGUE]
    if unknown:
        raise InputError(
            f"`{argument}` names unknown effects {unknown}: expected names among {list(CATALOGUE)}",
            kind="invalid_choice",
            field=argument,
            value=unknown[0],
            expected=list(CATALOGUE),
        )
    if len(set(items)) != len(items):
        raise InputError(
            f"`{argument}` repeats effects: got {items}",
            kind="repeated",
            field=argument,
            value=next(name for name in items if items.count(name) > 1),
        )
    return tuple(items)
