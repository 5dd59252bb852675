"""Whole signals through the Rust core: velocity or position input, one or many channels, with
the position-dependent terms (a level and a position force) where they are given."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._checks import as_signal, as_step, check_scheme
from ._typing import FloatArray, Scheme
from .errors import InputError
from .level import PositionForce, PositionLevel, core_level, core_position_force
from .params import ParamsLike, core_params


def _terms(level: PositionLevel | None, position_force: PositionForce | None) -> tuple[Any, Any]:
    """The validated level and position force (each None when not given)."""
    return (
        None if level is None else core_level(level),
        None if position_force is None else core_position_force(position_force),
    )


def simulate(
    params: ParamsLike,
    v: ArrayLike,
    dt: float,
    scheme: Scheme = "implicit",
    *,
    x: ArrayLike | None = None,
    level: PositionLevel | None = None,
    position_force: PositionForce | None = None,
) -> FloatArray:
    """Friction force for velocity input ``v`` held over each step of length ``dt``.

    ``v`` has shape (T,) or (B, T): B channels with the same parameters, each starting relaxed.
    Returns the force with the shape of ``v``. The channels run in Rust with the GIL released,
    several at once when B > 1.

    With a position-dependent ``level`` or a ``position_force``
    (docs/model.md#position-dependent-level), the positions ``x`` (the shape of ``v``) place them:
    each force is ``level.factor(x)·(F − σ2(v)·v) + σ2(v)·v + position_force.force(x)``, F the
    force without them. This is how a log with a measured velocity column drives the model: the
    velocity is the model's input, the position only places the terms (the model's state evolves
    as without them). ``x`` is needed with either term and refused without one.
    """
    validated = core_params(params)
    array, one_dimensional = as_signal(v, "v")
    step = as_step(dt)
    if x is None:
        if level is not None or position_force is not None:
            given = "level" if level is not None else "position_force"
            raise InputError(
                f"`{given}` is placed by the positions `x`: give `x`, the shape of `v`",
                kind="missing",
                field="x",
            )
        engine = _core.Engine(validated, array.shape[0], check_scheme(scheme))
        # gms-core scans the signal (naming channel and sample of a non-finite value) and checks
        # dt; it writes every force into `out`, which is therefore not zeroed first.
        out = np.empty_like(array)
        engine._run(array, step, False, out)
        return out[0] if one_dimensional else out
    if level is None and position_force is None:
        raise InputError(
            "`x` places a `level` or a `position_force`, and neither was given: leave `x` out to "
            "run the velocities alone",
            kind="not_applicable",
            field="x",
        )
    positions, positions_one_dimensional = as_signal(x, "x")
    if positions.shape != array.shape:
        shown = [a.shape[1:] if flat else a.shape for a, flat in ((array, one_dimensional),
                 (positions, positions_one_dimensional))]  # fmt: skip
        raise InputError(
            f"`x` must have the shape of `v`, {shown[0]}, got {shown[1]}",
            kind="shape",
            field="x",
            expected=shown[0],
            got=shown[1],
        )
    validated_level, validated_force = _terms(level, position_force)
    engine = _core.Engine(validated, array.shape[0], check_scheme(scheme))
    out = np.empty_like(array)
    engine._run_level(array, positions, step, validated_level, validated_force, out)
    return out[0] if one_dimensional else out


def simulate_position(
    params: ParamsLike,
    x: ArrayLike,
    dt: float,
    scheme: Scheme = "implicit",
    *,
    level: PositionLevel | None = None,
    position_force: PositionForce | None = None,
) -> FloatArray:
    """Friction force for position input ``x``: vₖ = (xₖ − xₖ₋₁)/dt, and v = 0 on the first sample.

    With a position-dependent ``level`` or a ``position_force``
    (docs/model.md#position-dependent-level), each force is
    ``level.factor(x)·(F − σ2(v)·v) + σ2(v)·v + position_force.force(x)``, F the force without
    them; the model's state evolves as without them.
    """
    validated = core_params(params)
    array, one_dimensional = as_signal(x, "x")
    step = as_step(dt)
    engine = _core.Engine(validated, array.shape[0], check_scheme(scheme))
    out = np.empty_like(array)
    if level is None and position_force is None:
        engine._run(array, step, True, out)
    else:
        engine._run_position_level(array, step, *_terms(level, position_force), out)
    return out[0] if one_dimensional else out
