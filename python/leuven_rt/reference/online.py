"""The regressors of :class:`leuven_rt.OnlineIdentifier` in plain numpy, written as the
specification: the Rust estimator must build the same ones (the tests compare the two).

The module's name mirrors the public :mod:`leuven_rt.online` on purpose: it is that module's oracle."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._checks import as_log, as_real_list, require_finite
from .._typing import FloatArray
from ..errors import ParameterError
from ..online import EXTRA_TERMS


def regressors(Delta: ArrayLike, x: ArrayLike, v: ArrayLike) -> FloatArray:
    """The regressor of every sample, shape (T, N + 3): ``[ψ_0, …, ψ_{N−1}, sgn(v), v, 1]``.

    Plain numpy (a loop over samples, vectorised over elements), written from the definition:
    element i keeps its deflection x − ζᵢ within ±Δᵢ and slips beyond; ψᵢ is that deflection
    over Δᵢ; the first position relaxes every element. ``numpy.linalg.lstsq(regressors(...), f)``
    is the batch estimate that :class:`OnlineIdentifier` approaches.
    """
    delta = np.asarray(as_real_list("Delta", Delta), dtype=np.float64)
    if delta.size == 0 or not (np.isfinite(delta).all() and (delta > 0).all()):
        bad = [index for index, value in enumerate(delta.tolist()) if not (np.isfinite(value) and value > 0)]
        raise ParameterError(
            f"`Delta` must be at least one finite value > 0, got {delta.tolist()}",
            kind="deflection_count" if delta.size == 0 else "element",
            field="Delta" if delta.size == 0 else f"Delta[{bad[0]}]",
            value=0 if delta.size == 0 else float(delta[bad[0]]),
            index=None if delta.size == 0 else bad[0],
        )
    xs, vs = as_log(x, v, None)
    require_finite(xs, "x", True)
    require_finite(vs, "v", True)
    out = np.empty((xs.shape[0], delta.size + len(EXTRA_TERMS)))
    zeta = np.full(delta.size, xs[0])
    for k, position in enumerate(xs):
        stretched = position - zeta
        deflection = np.clip(stretched, -delta, delta)
        # Only slipping elements move (rewriting a sticking ζ as x − (x − ζ) would round).
        zeta = np.where(deflection != stretched, position - deflection, zeta)
        out[k, : delta.size] = deflection / delta
    out[:, delta.size] = np.sign(vs)
    out[:, delta.size + 1] = vs
    out[:, delta.size + 2] = 1.0
    return out
