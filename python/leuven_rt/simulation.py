"""Whole signals through the Rust core: velocity or position input, one or many channels."""

from __future__ import annotations

from numpy.typing import ArrayLike

from . import _core
from ._checks import as_signal, check_dt, check_scheme
from ._typing import FloatArray, ParamsLike
from .params import as_params


def _run(params: ParamsLike, signal: ArrayLike, name: str, dt: float, scheme: str) -> FloatArray:
    params = as_params(params)
    array, one_dimensional = as_signal(signal, name)
    dt = check_dt(dt)
    engine = _core.Engine(params, array.shape[0], check_scheme(scheme))
    out = engine._run(array, dt, name == "x")
    return out[0] if one_dimensional else out


def simulate(params: ParamsLike, v: ArrayLike, dt: float, scheme: str = "implicit") -> FloatArray:
    """Friction force for velocity input ``v`` held over each step of length ``dt``.

    ``v`` has shape (T,) or (B, T): B channels with the same parameters, each starting relaxed.
    Returns the force with the shape of ``v``. The channels run in Rust with the GIL released,
    several at once when B > 1.
    """
    return _run(params, v, "v", dt, scheme)


def simulate_position(params: ParamsLike, x: ArrayLike, dt: float, scheme: str = "implicit") -> FloatArray:
    """Friction force for position input ``x``: vₖ = (xₖ − xₖ₋₁)/dt, and v = 0 on the first sample."""
    return _run(params, x, "x", dt, scheme)
