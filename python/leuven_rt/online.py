"""Online identification: recursive least squares on the friction terms that enter linearly.

The model is F = Σᵢ Wᵢ·ψᵢ(x) + Fc·sgn(v) + sigma2·v + offset, where ψᵢ ∈ [−1, 1] is the response
of a Maxwell-slip element with a fixed break deflection Δᵢ driven by the position x (the paper's
presliding identification, with Δᵢ pre-assigned). The estimator runs in gms-core (Rust,
allocation-free, the same code a control loop would run): :class:`OnlineIdentifier` is stepped
sample by sample (``update``) or run over a whole log (``run``, GIL released).

:func:`leuven_rt.reference.online.regressors` builds the same regressors in numpy, for batch least
squares and checks.

Identifiability: in steady sliding every ψᵢ = sgn(v), so sliding data only determine
``Fc + sum(W)``; the split between them, and among the Wᵢ, needs reversals of several
amplitudes below the largest Δᵢ. The initial covariance acts as a ridge prior on what the data
leave undetermined, and ``max_trace`` stops its wind-up under forgetting.
"""

from __future__ import annotations

from typing import Any

from numpy.typing import ArrayLike

from . import _core
from ._checks import as_log, as_real_list, real_number
from ._typing import FloatArray
from .errors import InputError, ParameterError

#: Names of the terms after the N element weights, in the order of the estimate.
EXTRA_TERMS = ("Fc", "sigma2", "offset")


def _real(name: str, value: Any) -> float:
    return real_number(value, name, ParameterError)


def _scalar(name: str, value: Any) -> float:
    return real_number(value, name, InputError)


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
    settings that break their rule. Calling it from a second thread while one is inside
    ``run`` (which releases the GIL) raises :class:`~leuven_rt.errors.ConcurrentUseError` and
    changes nothing.
    """

    _fixed: tuple[int, list[float]]

    def __new__(
        cls,
        Delta: ArrayLike,
        *,
        forgetting: float = 1.0,
        initial_covariance: float = 1e4,
        max_trace: float | None = None,
        initial: ArrayLike | None = None,
    ) -> OnlineIdentifier:
        # Python coerces types and lengths; gms-core checks the values (the number of elements of
        # `Delta`, finite `initial`, the ranges of the settings).
        delta = as_real_list("Delta", Delta)
        parameters = len(delta) + len(EXTRA_TERMS)
        start = [0.0] * parameters if initial is None else as_real_list("initial", initial, parameters)
        covariance = _real("initial_covariance", initial_covariance)
        bound = 1e3 * parameters * covariance if max_trace is None else _real("max_trace", max_trace)
        identifier = super().__new__(cls, delta, start, _real("forgetting", forgetting), covariance, bound)
        # Fixed for the identifier's life, and readable while another thread runs it.
        core: Any = super(OnlineIdentifier, identifier)
        identifier._fixed = (core.elements, core.Delta)
        return identifier

    @property
    def elements(self) -> int:
        """Number N of Maxwell-slip elements (fixed break deflections)."""
        return self._fixed[0]

    @property
    def Delta(self) -> list[float]:
        """The fixed break deflections Δᵢ [m] (a copy)."""
        return list(self._fixed[1])

    def __repr__(self) -> str:
        return f"OnlineIdentifier(elements={self.elements}, estimate={self.estimate_dict()!r})"

    @property
    def names(self) -> tuple[str, ...]:
        """The name of each entry of the estimate: ``W[0]``, …, ``W[N-1]``, ``Fc``, ``sigma2``,
        ``offset``."""
        return tuple(f"W[{i}]" for i in range(self.elements)) + EXTRA_TERMS

    @property
    def estimate(self) -> FloatArray:
        """A copy of the current estimate, shape (N + 3,), in the order of :attr:`names`."""
        return self._estimate()

    @property
    def covariance(self) -> FloatArray:
        """A copy of the covariance P, shape (N + 3, N + 3); times the noise variance, it is the
        covariance of the estimate."""
        return self._covariance()

    def run(self, x: ArrayLike, v: ArrayLike, f: ArrayLike) -> FloatArray:
        """Continues over a log of positions ``x`` [m], velocities ``v`` [m/s] and forces ``f``
        [N], each of shape (T,); returns the estimate after each sample, shape (T, N + 3).

        All or nothing: a rejected log leaves the identifier as it was.
        """
        xs, vs, fs = as_log(x, v, f)
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
