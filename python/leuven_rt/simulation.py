"""Whole signals through the Rust core: velocity or position input, one or many channels."""

from __future__ import annotations

from numpy.typing import ArrayLike

from . import _core
from ._checks import as_signal, as_step, check_scheme
from ._typing import FloatArray, Scheme
from .level import PositionLevel, core_level
from .params import ParamsLike, core_params


def _run(params: ParamsLike, signal: ArrayLike, name: str, dt: float, scheme: Scheme) -> FloatArray:
    validated = core_params(params)
    array, one_dimensional = as_signal(signal, name)
    step = as_step(dt)
    engine = _core.Engine(validated, array.shape[0], check_scheme(scheme))
    # gms-core scans the signal (naming channel and sample of a non-finite value) and checks dt.
    out = engine._run(array, step, name == "x")
    return out[0] if one_dimensional else out


def simulate(params: ParamsLike, v: ArrayLike, dt: float, scheme: Scheme = "implicit") -> FloatArray:
    """Friction force for velocity input ``v`` held over each step of length ``dt``.

    ``v`` has shape (T,) or (B, T): B channels with the same parameters, each starting relaxed.
    Returns the force with the shape of ``v``. The channels run in Rust with the GIL released,
    several at once when B > 1.
    """
    return _run(params, v, "v", dt, scheme)


def simulate_position(
    params: ParamsLike,
    x: ArrayLike,
    dt: float,
    scheme: Scheme = "implicit",
    *,
    level: PositionLevel | None = None,
) -> FloatArray:
    """Friction force for position input ``x``: vₖ = (xₖ − xₖ₋₁)/dt, and v = 0 on the first sample.

    With a position-dependent ``level`` (docs/model.md#position-dependent-level), each force is
    ``level.factor(x)·(F − sigma2·v) + sigma2·v``, F the force without it; the model's state
    evolves as without the level.
    """
    if level is None:
        return _run(params, x, "x", dt, scheme)
    validated_level = core_level(level)
    validated = core_params(params)
    array, one_dimensional = as_signal(x, "x")
    step = as_step(dt)
    engine = _core.Engine(validated, array.shape[0], check_scheme(scheme))
    out = engine._run_position_level(array, step, validated_level)
    return out[0] if one_dimensional else out
