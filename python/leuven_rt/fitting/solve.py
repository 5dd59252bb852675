"""Output-error least squares: θ that minimises the weighted simulation error of a candidate.

Bounded Gauss–Newton with a trust region (``scipy.optimize.least_squares``, method ``trf``) on
the residual √w·(f_model(θ) − f) over the rows with weight > 0, with the exact Jacobian of
:mod:`.evaluate`: an iteration costs one simulation with its sensitivities, not one per
parameter. The bank's shares are defined up to a common factor (W depends on shares/Σshares), so
one more residual row, λ·(Σshares − 1), fixes their scale without changing the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._extras import require

require("scipy", extra="analysis", needed_by="leuven_rt.fitting")

from scipy.optimize import least_squares  # noqa: E402

from .._typing import FloatArray  # noqa: E402
from ..data.reconstruction import Motion  # noqa: E402
from ..errors import ParameterError  # noqa: E402
from .evaluate import Evaluation, evaluate  # noqa: E402
from .structure import Scales, Structure, bounds, start  # noqa: E402

#: The robust loss of scipy's least_squares used with a scale.
LOSS = "cauchy"


def robust(square: FloatArray, scale: float) -> FloatArray:
    """scipy's ``cauchy`` loss of squared errors at ``scale``, in the units of a squared error."""
    out: FloatArray = scale**2 * np.log1p(square / scale**2)
    return out


#: Iterations of one fit: enough for a candidate that starts at the model it extends.
ITERATIONS = 60


@dataclass(frozen=True, eq=False)
class Fitted:
    """A fitted candidate: its structure, θ, its force at every sample and the weighted mean
    squared error it leaves."""

    structure: Structure
    theta: dict[str, float]
    evaluation: Evaluation
    mse: float
    iterations: int

    @property
    def force(self) -> FloatArray:
        return self.evaluation.force


@dataclass(frozen=True, eq=False)
class Target:
    """What a fit matches: the measured force, the weights (0: not fitted), the motion."""

    force: FloatArray
    weight: FloatArray
    motion: Motion
    tau: FloatArray
    """Time scaled to [−1, 1] over the record (the drift's coordinate)."""
    recorded_x: FloatArray
    """The position as the log recorded it (the encoder's counts)."""
    judged: NDArray[np.bool_]
    """The samples a prediction is judged on, as :func:`leuven_rt.predict` judges it: every
    sample but the filters' edges (and on a sampled record, its lead-ins: :mod:`.sample`)."""
    stride: int = 1
    """The fit's residual and Jacobian take every ``stride``-th weighted sample (a long record is
    simulated whole but fitted on a subsample); mean squared errors take them all."""

    @property
    def rows(self) -> NDArray[np.bool_]:
        rows = self.weight > 0
        if self.stride > 1:
            rows &= np.arange(rows.size) % self.stride == 0
        return rows

    scale: float | None = None
    """With a scale, errors are counted robustly (``LOSS`` at this scale): a sample missed by far
    more than the scale counts little more than one missed by the scale."""
    let_go: NDArray[np.bool_] | None = None
    """The stops where the log's friction lets go (:func:`~leuven_rt.data.reconstruction.released_at_stops`),
    weighed out of the fit: there the force is the measurement's own, which tells an offset from
    an asymmetry of the levels (docs/effects.md#how-an-effect-is-chosen, stand-ins)."""

    def unweighted(self, model_force: FloatArray) -> FloatArray:
        """Each sample's loss before its weight: the squared error, or its robust form with a
        scale."""
        square = (model_force - self.force) ** 2
        if self.scale is not None:
            square = robust(square, self.scale)
        return square

    def losses(self, model_force: FloatArray) -> FloatArray:
        """Each sample's weighted loss (:meth:`unweighted` times the weight)."""
        out: FloatArray = self.weight * self.unweighted(model_force)
        return out

    def mse(self, model_force: FloatArray) -> float:
        return float(np.sum(self.losses(model_force)) / np.sum(self.weight))


def fit(
    structure: Structure,
    scales: Scales,
    target: Target,
    previous: dict[str, float],
    iterations: int = ITERATIONS,
    fixed: dict[str, float] | None = None,
) -> Fitted:
    """θ of ``structure`` minimising the weighted simulation error, starting from ``previous``
    (the values of the model it extends; :func:`~.structure.start` fills in the rest); the
    parameters in ``fixed`` keep the values given."""
    elements = scales.deltas.size
    every = structure.names() + structure.share_names(elements)
    fixed = dict(fixed or {})
    low_all, high_all = bounds(structure, scales, elements)
    initial = start(structure, scales, elements, previous)
    initial.update(fixed)
    free = [i for i, name in enumerate(every) if name not in fixed]
    names = [every[i] for i in free]
    low, high = low_all[free], high_all[free]
    x0 = np.clip(np.array([initial[name] for name in names]), low, high)

    def full(x: FloatArray) -> dict[str, float]:
        theta = dict(fixed)
        theta.update(zip(names, x.tolist(), strict=True))
        return theta

    rows = target.rows
    root_weight = np.sqrt(target.weight[rows])
    # In units of the log's force, so that the solver's tolerances mean the same at any scale.
    row_scale = root_weight / scales.force
    measured = target.force[rows]
    shares = [i for i, name in enumerate(names) if name.startswith("share_")]
    scale_row = math.sqrt(float(rows.sum())) * 0.1
    every_free = len(free) == len(every)
    cache: dict[bytes, tuple[FloatArray, FloatArray, Evaluation | None]] = {}
    # The force of the last point whose Jacobian the solver asked for, which is the last it
    # accepted: the point it returns, whose force is then not simulated again.
    accepted: dict[bytes, Evaluation | None] = {}

    def both(x: FloatArray) -> tuple[FloatArray, FloatArray, Evaluation | None]:
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            try:
                result = evaluate(structure, scales, full(x), target.motion, target.tau, rows)
            except ParameterError:
                # Outside the model's rules (a parameter set gms-core refuses, a position term no
                # file could hold): a large, flat residual.
                worst = np.full(rows.sum() + bool(shares), 10.0)
                cache[key] = (worst, np.zeros((worst.size, len(names))), None)
                return cache[key]
            assert result.jacobian is not None
            count = row_scale.size
            residual = np.empty(count + bool(shares))
            # Column-major, as the solver has always been given it: its products round by the
            # layout, so keeping it keeps every fit bit for bit.
            jac = np.empty((count + bool(shares), len(names)), order="F")
            np.multiply(result.force[rows] - measured, row_scale, out=residual[:count])
            np.multiply(result.jacobian if every_free else result.jacobian[:, free], row_scale[:, None],
                        out=jac[:count])  # fmt: skip
            if shares:
                residual[count] = scale_row * (x[shares].sum() - 1.0)
                jac[count] = 0.0
                jac[count, shares] = scale_row
            cache[key] = (residual, jac, Evaluation(result.values, result.force, None))
        return cache[key]

    if not names:
        theta = full(x0)
        final = evaluate(structure, scales, theta, target.motion, target.tau, None)
        return Fitted(structure, theta, final, target.mse(final.force), 1)
    robustly: dict[str, Any] = (
        {} if target.scale is None else {"loss": LOSS, "f_scale": target.scale / scales.force}
    )

    def residual(x: FloatArray) -> FloatArray:
        return both(x)[0]

    def jacobian(x: FloatArray) -> FloatArray:
        _, jac, evaluation = both(x)
        accepted.clear()
        accepted[x.tobytes()] = evaluation
        return jac

    result = least_squares(residual, x0, jac=jacobian, bounds=(low, high),
                           x_scale="jac", max_nfev=iterations, method="trf", ftol=1e-10, xtol=1e-10,
                           gtol=1e-10, **robustly)  # fmt: skip
    theta = full(result.x)
    simulated = accepted.get(result.x.tobytes())
    if simulated is None:
        simulated = evaluate(structure, scales, theta, target.motion, target.tau, None)
    return Fitted(structure, theta, simulated, target.mse(simulated.force), int(result.nfev))


__all__ = ["ITERATIONS", "Fitted", "Target", "fit"]
