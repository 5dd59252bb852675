"""Slip responses: how the Maxwell-slip elements of a bank deflect when driven by a position.

Both workflows regress on these: the identification's presliding weights, and the discrepancy
workflow's presliding bank driven by the model's state.
"""

from __future__ import annotations

import numpy as np

from .._core import slip_responses
from .._typing import FloatArray
from ..errors import InputError


def element_deflections(x: FloatArray, Delta: FloatArray) -> FloatArray:
    """φᵢ(x) = (x − ζᵢ)/Δᵢ of every element (columns) at every sample (rows), each element
    starting relaxed at x[0] and slipping (ζᵢ follows x at distance Δᵢ) when over-stretched.

    gms-core's slip rule runs them (``SlipRegressor``); it checks the values and names the
    offending sample or element."""
    x = np.ascontiguousarray(x, dtype=np.float64)
    Delta = np.ascontiguousarray(Delta, dtype=np.float64)
    for name, values in (("x", x), ("Delta", Delta)):
        if values.ndim != 1:
            raise InputError(
                f"`{name}` must be one-dimensional, got shape {values.shape}",
                kind="shape",
                field=name,
                expected="(T,)" if name == "x" else "(N,)",
                got=values.shape,
            )
    return slip_responses(x, Delta)
