"""Online identification: recursive least squares on the friction terms that enter linearly.

The model is F = Σᵢ Wᵢ·ψᵢ(x) + Fc·sgn(v) + sigma2·v + offset, where ψᵢ ∈ [−1, 1] is the response
of a Maxwell-slip element with a fixed break deflection Δᵢ driven by the position x (the paper's
presliding identification, with Δᵢ pre-assigned). The estimator runs in gms-core (Rust,
allocation-free, the same code a control loop would run): :class:`OnlineIdentifier` is stepped
sample by sample (``update``) or run over a whole log (``run``, GIL released).

:func:`regressors` builds the same regressors in numpy, for batch least squares and checks.

Identifiability: in steady sliding every ψᵢ = sgn(v), so sliding data only determine
``Fc + sum(W)``; the split between them, and among the Wᵢ, needs reversals of several
amplitudes below the largest Δᵢ. The initial covariance acts as a ridge prior on what the data
leave undetermined, and ``max_trace`` stops its wind-up under forgetting.
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _core
from ._core import MAX_ELEMENTS
from .errors import InputError, ParameterError
from .inputs import as_signal

#: Names of the terms after the N element weights, in the order of the estimate.
EXTRA_TERMS = ("Fc", "sigma2", "offset")


def _real(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(f"`{name}` must be a real number, got {value!r}")
    return float(value)


def _vector(name: str, values: Any, length: int | None = None) -> list[float]:
    if isinstance(values, (str, bytes)) or not (
        isinstance(values, Sequence) or hasattr(values, "__array__")
    ):
        raise ParameterError(f"`{name}` must be a sequence of real numbers, got {values!r}")
    array = np.asarray(values)
    if array.ndim != 1 or array.dtype.kind not in "iuf":
        raise ParameterError(
            f"`{name}` must be a flat sequence of real numbers, got {values!r}"
        )
    if length is not None and array.shape[0] != length:
        raise ParameterError(f"`{name}` must have {length} values, got {array.shape[0]}")
    return [float(value) for value in array]


def _log(x: ArrayLike, v: ArrayLike, f: ArrayLike | None) -> list[NDArray[np.float64]]:
    """x, v (and f) as finite float64 arrays of one common shape (T,), T ≥ 1."""
    named = [("x", x), ("v", v)] + ([("f", f)] if f is not None else [])
    arrays = []
    for name, values in named:
        array, one_dimensional = as_signal(values, name)
        if not one_dimensional:
            raise InputError(f"`{name}` must have shape (T,), got shape {np.shape(values)}")
        arrays.append(array[0])
    length = arrays[0].shape[0]
    for (name, _), array in zip(named[1:], arrays[1:]):
        if array.shape[0] != length:
            raise InputError(f"`{name}` must have the length of `x`, {length}, got {array.shape[0]}")
    return arrays


def _scalar(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"`{name}` must be a real number, got {value!r}")
    return float(value)


class OnlineIdentifier(_core.OnlineIdentifier):
    """Recursive least squares on ``[W[0], …, W[N-1], Fc, sigma2, offset]``.

    ``Delta``: the N fixed break deflections [m] (1 ≤ N ≤ ``MAX_ELEMENTS``), for example equally
    spaced up to the presliding range. ``forgetting`` λ ∈ (0, 1]: 1 weighs every sample alike,
    λ < 1 forgets with a memory of about 1/(1 − λ) samples, to track drifting friction.
    ``initial_covariance`` p₀: the prior variance of each parameter around ``initial`` (zeros by
    default); with λ = 1, the estimate after T samples is the ridge solution
    argmin Σ eₖ² + |θ − initial|²/p₀. ``max_trace``: upper bound of trace(P), against covariance
    wind-up when the data stop exciting some direction (default 1000 × the initial trace).

    The first position relaxes every element there (ψ = 0). Raises :class:`ParameterError` for
    settings that break their rule.
    """

    def __new__(
        cls,
        Delta: ArrayLike,
        *,
        forgetting: float = 1.0,
        initial_covariance: float = 1e4,
        max_trace: float | None = None,
        initial: ArrayLike | None = None,
    ) -> OnlineIdentifier:
        delta = _vector("Delta", Delta)
        if not 1 <= len(delta) <= MAX_ELEMENTS:
            raise ParameterError(f"`Delta` must have 1 to {MAX_ELEMENTS} elements, got {len(delta)}")
        parameters = len(delta) + len(EXTRA_TERMS)
        start = [0.0] * parameters if initial is None else _vector("initial", initial, parameters)
        if not all(np.isfinite(start)):
            raise ParameterError(f"`initial` must be finite, got {start}")
        covariance = _real("initial_covariance", initial_covariance)
        bound = 1e3 * parameters * covariance if max_trace is None else _real("max_trace", max_trace)
        return super().__new__(cls, delta, start, _real("forgetting", forgetting), covariance, bound)

    def __repr__(self) -> str:
        return f"OnlineIdentifier(elements={self.elements}, estimate={self.estimate_dict()!r})"

    @property
    def names(self) -> tuple[str, ...]:
        """The name of each entry of the estimate: ``W[0]``, …, ``W[N-1]``, ``Fc``, ``sigma2``,
        ``offset``."""
        return tuple(f"W[{i}]" for i in range(self.elements)) + EXTRA_TERMS

    @property
    def estimate(self) -> NDArray[np.float64]:
        """A copy of the current estimate, shape (N + 3,), in the order of :attr:`names`."""
        return self._estimate()

    @property
    def covariance(self) -> NDArray[np.float64]:
        """A copy of the covariance P, shape (N + 3, N + 3); times the noise variance, it is the
        covariance of the estimate."""
        return self._covariance()

    def run(self, x: ArrayLike, v: ArrayLike, f: ArrayLike) -> NDArray[np.float64]:
        """Continues over a log of positions ``x`` [m], velocities ``v`` [m/s] and forces ``f``
        [N], each of shape (T,); returns the estimate after each sample, shape (T, N + 3).

        All or nothing: a rejected log leaves the identifier as it was.
        """
        xs, vs, fs = _log(x, v, f)
        return self._run(xs, vs, fs)

    def predict(self, x: float, v: float) -> float:
        """The force that the current estimate predicts for position ``x`` and velocity ``v``,
        with the elements moved from where the last update left them; nothing changes."""
        return super().predict(_scalar("x", x), _scalar("v", v))

    def estimate_dict(self) -> dict[str, Any]:
        """The estimate by name: ``{"W": [...], "Delta": [...], "Fc": ..., "sigma2": ...,
        "offset": ...}``."""
        estimate = self.estimate
        n = self.elements
        return {
            "W": estimate[:n].tolist(),
            "Delta": list(self.Delta),
            "Fc": float(estimate[n]),
            "sigma2": float(estimate[n + 1]),
            "offset": float(estimate[n + 2]),
        }

    def sliding_params(self) -> dict[str, float]:
        """The keys of :class:`leuven_rt.Params` that this estimate determines, with their
        meaning in the Leuven model: ``Fc``, the sliding friction level away from the Stribeck
        region (``Fc + sum(W)`` here: in sliding every element is saturated), and ``sigma2``.

        Merge them into a full parameter set, ``Params(**{**base.to_dict(),
        **identifier.sliding_params()})``. The element weights are not returned: the Leuven
        model drives its elements by the state z and needs ``sum(W) > Fs``, so these position-
        driven weights are not its W. ``offset`` is a bias of the measurement, not friction.
        """
        estimate = self.estimate
        n = self.elements
        return {"Fc": float(estimate[n] + estimate[:n].sum()), "sigma2": float(estimate[n + 1])}



def regressors(Delta: ArrayLike, x: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
    """The regressor of every sample, shape (T, N + 3): ``[ψ_0, …, ψ_{N−1}, sgn(v), v, 1]``.

    Plain numpy (a loop over samples, vectorised over elements), written from the definition:
    element i keeps its deflection x − ζᵢ within ±Δᵢ and slips beyond; ψᵢ is that deflection
    over Δᵢ; the first position relaxes every element. ``numpy.linalg.lstsq(regressors(...), f)``
    is the batch estimate that :class:`OnlineIdentifier` approaches.
    """
    delta = np.asarray(_vector("Delta", Delta), dtype=np.float64)
    if delta.size == 0 or not (np.isfinite(delta).all() and (delta > 0).all()):
        raise ParameterError(f"`Delta` must be at least one finite value > 0, got {delta.tolist()}")
    xs, vs = _log(x, v, None)
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
