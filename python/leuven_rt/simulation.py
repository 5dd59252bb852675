"""Whole signals through the Rust core: velocity or position input, one or many channels."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _core
from .inputs import as_signal, check_dt, check_scheme
from .params import Params, as_params


def _run(
    params: Params | Mapping[str, Any], signal: ArrayLike, name: str, dt: float, scheme: str
) -> NDArray[np.float64]:
    params = as_params(params)
    array, one_dimensional = as_signal(signal, name)
    dt = check_dt(dt)
    engine = _core.Engine(params, array.shape[0], check_scheme(scheme))
    out = engine._run(array, dt, name == "x")
    return out[0] if one_dimensional else out


def simulate(
    params: Params | Mapping[str, Any], v: ArrayLike, dt: float, scheme: str = "implicit"
) -> NDArray[np.float64]:
    """Friction force for velocity input ``v`` held over each step of length ``dt``.

    ``v`` has shape (T,) or (B, T): B channels with the same parameters, each starting relaxed.
    Returns the force with the shape of ``v``. The channels run in Rust with the GIL released,
    several at once when B > 1.
    """
    return _run(params, v, "v", dt, scheme)


def simulate_position(
    params: Params | Mapping[str, Any], x: ArrayLike, dt: float, scheme: str = "implicit"
) -> NDArray[np.float64]:
    """Friction force for position input ``x``: vₖ = (xₖ − xₖ₋₁)/dt, and v = 0 on the first sample."""
    return _run(params, x, "x", dt, scheme)
