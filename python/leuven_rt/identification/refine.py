"""Simulation-error stages: σ1 and n, then every parameter at once.

The stagewise fits assume z follows x in presliding and steady state in sliding; neither holds
near the transition. These stages fix that by minimising the error of the whole model, simulated
by the Rust core (``leuven_rt.simulate_position``, a few milliseconds per record) on the
filtered position, over the training samples (``scipy.optimize.least_squares``). The break
deflections Δ stay where the presliding stage put them: with Δ free the problem loses its
linear structure in W and gains many poor local minima.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from .._typing import BoolArray, FloatArray
from ..params import Params
from ..simulation import simulate_position
from .sliding import DELTA_BOUNDS, VS_DECADES, dense_jacobian, scaled_condition

#: Bounds of the transition-curve exponent n searched.
N_BOUNDS = (0.5, 8.0)
#: Relative change of the cost and of the parameters at which the least-squares stages stop: the
#: force noise makes finer optima meaningless.
TOLERANCE = 1e-6
#: sum(W) is kept at least this factor above max(Fs, Fs_neg) (the model's rule is "greater than").
WEIGHT_MARGIN = 1.001


def model_params(values: dict[str, float], W: FloatArray, Delta: FloatArray) -> Params:
    """A :class:`Params` from sliding values, n, σ1 and the elements; weights too weak to balance
    the Stribeck curve (the model's rule sum(W) > max(Fs, Fs_neg)) are scaled up to just balance
    it, so that every trial of an optimiser is a valid model."""
    peak = max(values["Fs"], values.get("Fs_neg", values["Fs"]))
    total = float(np.sum(W))
    if total <= WEIGHT_MARGIN * peak:
        W = W * (WEIGHT_MARGIN * peak / total)
    return Params(W=tuple(W), Delta=tuple(Delta), **values)


@dataclass(frozen=True, eq=False)
class SimulationFit:
    params: Params
    rms: float
    """RMS simulation error over the fitted samples [N]."""
    evaluations: int
    condition: float
    """Condition number of the Jacobian at the optimum (columns scaled to unit norm)."""


class SimulationError:
    """Residual of the simulated force against the measured one on the chosen rows.

    :meth:`jacobian` differences the residual forward in every parameter, the simulations running
    on a thread pool: the Rust core releases the GIL, so the columns go as fast as there are cores.
    """

    def __init__(
        self, x: FloatArray, dt: float, force: FloatArray, rows: BoolArray, tick: Callable[[], object]
    ) -> None:
        self.x, self.dt, self.force, self.rows, self.tick = x, dt, force, rows, tick
        self.evaluations = 0
        self._count = threading.Lock()
        self._last: tuple[FloatArray, FloatArray] | None = None

    def residual(self, params: Params) -> FloatArray:
        with self._count:
            self.evaluations += 1
            self.tick()
        return (simulate_position(params, self.x, self.dt) - self.force)[self.rows]

    def function(self, build: Callable[[FloatArray], Params]) -> Callable[[FloatArray], FloatArray]:
        """The residual as a function of the parameter vector (the last value is kept)."""

        def residual(p: FloatArray) -> FloatArray:
            value = self.residual(build(p))
            self._last = (np.array(p, copy=True), value)
            return value

        return residual

    def jacobian(
        self, build: Callable[[FloatArray], Params], lower: FloatArray, upper: FloatArray
    ) -> Callable[[FloatArray], FloatArray]:
        """Forward differences with least_squares' step, √eps·max(1, |p|), taken backward
        where a step forward would leave the bounds."""

        def jacobian(p: FloatArray) -> FloatArray:
            if self._last is not None and np.array_equal(self._last[0], p):
                base = self._last[1]
            else:
                base = self.function(build)(p)
            steps = np.sqrt(np.finfo(np.float64).eps) * np.maximum(1.0, np.abs(p))
            steps = np.where(p + steps > upper, -steps, steps)

            def column(j: int) -> FloatArray:
                moved = np.array(p, copy=True)
                moved[j] += steps[j]
                change: FloatArray = (self.residual(build(moved)) - base) / (moved[j] - p[j])
                return change

            with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
                return np.column_stack(list(pool.map(column, range(p.size))))

        return jacobian


def _solve(objective: SimulationError, build: Callable[[FloatArray], Params], p0: FloatArray,
           lower: FloatArray, upper: FloatArray,
           max_evaluations: int) -> tuple[Params, FloatArray, FloatArray]:  # fmt: skip
    """least_squares from ``p0`` within the bounds; the fitted params, residual and Jacobian."""
    lower, upper = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
    p0 = np.clip(np.asarray(p0, dtype=float), lower, upper)
    result = least_squares(objective.function(build), p0, jac=objective.jacobian(build, lower, upper),
                           bounds=(lower, upper), x_scale="jac", ftol=TOLERANCE, xtol=TOLERANCE,
                           max_nfev=max_evaluations)  # fmt: skip
    return build(result.x), result.fun, dense_jacobian(result.jac)


def fit_transition(base: Params, objective: SimulationError, max_evaluations: int) -> SimulationFit:
    """σ1 ≥ 0 and n in :data:`N_BOUNDS` with everything else fixed, from the values in ``base``."""
    fixed = {key: value for key, value in base.to_dict().items() if key not in ("n", "sigma1", "W", "Delta")}
    W, Delta = np.asarray(base.W), np.asarray(base.Delta)

    def build(p: FloatArray) -> Params:
        return model_params({**fixed, "sigma1": float(p[0]), "n": float(p[1])}, W, Delta)

    params, residual, jacobian = _solve(objective, build, np.array([base.sigma1, base.n]),
                                        np.array([0.0, N_BOUNDS[0]]), np.array([np.inf, N_BOUNDS[1]]),
                                        max_evaluations)  # fmt: skip
    return SimulationFit(params, float(np.sqrt(np.mean(residual**2))), objective.evaluations,
                         scaled_condition(jacobian))  # fmt: skip


def refine_jointly(start: Params, objective: SimulationError, max_evaluations: int) -> SimulationFit:
    """Every parameter but Δ: Fc, Fs − Fc ≥ 0, log Vs, δ, n, σ1 ≥ 0, σ2 ≥ 0, W > 0 (and the
    ``_neg`` levels when the start has them)."""
    assert start.W is not None and start.Delta is not None  # the start comes from model_params
    Delta = np.asarray(start.Delta)
    asymmetric = start.Fc_neg is not None
    count = Delta.size
    tiny = 1e-9 * start.Fc

    def build(p: FloatArray) -> Params:
        values = dict(
            Fc=p[0], Fs=p[0] + p[1], Vs=float(np.exp(p[2])), delta=p[3], n=p[4], sigma1=p[5], sigma2=p[6]
        )
        if asymmetric:
            values.update(Fc_neg=p[7 + count], Fs_neg=p[7 + count] + p[8 + count])
        return model_params({key: float(value) for key, value in values.items()}, p[7 : 7 + count], Delta)

    p0 = [start.Fc, start.Fs - start.Fc, np.log(start.Vs), start.delta, start.n, start.sigma1, start.sigma2,
          *start.W]  # fmt: skip
    # log Vs may move three decades from the sliding stage's value, no further (see sliding.py).
    log_vs = (np.log(start.Vs) - VS_DECADES * np.log(10.0), np.log(start.Vs) + VS_DECADES * np.log(10.0))
    lower = [tiny, 0.0, log_vs[0], DELTA_BOUNDS[0], N_BOUNDS[0], 0.0, 0.0, *([tiny] * count)]
    upper = [np.inf, np.inf, log_vs[1], DELTA_BOUNDS[1], N_BOUNDS[1], np.inf, np.inf, *([np.inf] * count)]
    if asymmetric:
        p0 += [start.Fc_negative, start.Fs_negative - start.Fc_negative]
        lower += [tiny, 0.0]
        upper += [np.inf, np.inf]
    params, residual, jacobian = _solve(objective, build, np.array(p0), np.array(lower), np.array(upper),
                                        max_evaluations)  # fmt: skip
    return SimulationFit(params, float(np.sqrt(np.mean(residual**2))), objective.evaluations,
                         scaled_condition(jacobian))  # fmt: skip
