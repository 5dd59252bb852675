"""The presliding part: Maxwell-slip weights W for pre-assigned break deflections Δ.

The paper's method (Lampaert, Swevers, Al-Bender 2002, §IV): pre-assign the Δᵢ equally spaced up
to the presliding range; the hysteresis force Fh = Σ Wᵢ·φᵢ, with φᵢ the normalised deflection of
element i, is then linear in W, found here by non-negative least squares on the samples inside
the presliding transition, where the state follows the position (z ≈ x). The number of elements
N is given, or chosen by the error on held-out presliding segments.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._typing import BoolArray, FloatArray
from ..data.regression import LinearFit, fit_linear
from ..data.slip import element_deflections
from ..errors import DataError

#: Candidate numbers of elements when N is chosen from the data.
CANDIDATE_ELEMENTS = tuple(range(1, 13))
#: N is the smallest candidate whose held-out error is within this factor of the best one:
#: more elements that do not lower the error only cost time in the loop.
PARSIMONY = 1.02
#: Elements that the regression leaves at W = 0 start the refinement at this share of the mean W.
IDLE_SHARE = 0.01
#: Fewer presliding samples than this cannot determine the weights.
MIN_PRESLIDING_SAMPLES = 20


def equally_spaced(elements: int, presliding_range: float) -> FloatArray:
    """Δᵢ = i·range/N, i = 1..N."""
    return presliding_range * np.arange(1, elements + 1) / elements


@dataclass(frozen=True, eq=False)
class PreslidingFit:
    """Weights for the chosen Δ grid, and how the choice of N went."""

    W: FloatArray
    Delta: FloatArray
    viscous: float
    """Coefficient of v in presliding (σ1 + σ2 when z follows x)."""
    fit: LinearFit
    held_out_rms: dict[int, float]
    """Held-out RMS error [N] for each candidate N."""

    @property
    def elements(self) -> int:
        return int(self.W.size)


def _regressors(phi: FloatArray, v: FloatArray, rows: BoolArray) -> dict[str, FloatArray]:
    columns = {f"W{i}": phi[rows, i] for i in range(phi.shape[1])}
    columns["viscous"] = v[rows]
    return columns


def fit_presliding(
    x: FloatArray,
    v: FloatArray,
    force: FloatArray,
    fit_rows: BoolArray,
    check_rows: BoolArray,
    presliding_range: float,
    elements: int | Sequence[int] | None = None,
) -> PreslidingFit:
    """Non-negative W (and the presliding viscous coefficient) for Δ equally spaced up to
    ``presliding_range``; ``elements`` is N, or the candidates to choose from by the RMS error
    on ``check_rows`` (default :data:`CANDIDATE_ELEMENTS`). The final fit uses both row sets.

    Elements whose weight comes out zero are kept with a small weight (:data:`IDLE_SHARE`).
    """
    if np.count_nonzero(fit_rows) < MIN_PRESLIDING_SAMPLES:
        raise DataError(
            f"too few presliding samples: need at least {MIN_PRESLIDING_SAMPLES} samples within the "
            f"presliding range after a reversal or the start, got {np.count_nonzero(fit_rows)}",
            kind="too_few",
            value=int(np.count_nonzero(fit_rows)),
            bound=MIN_PRESLIDING_SAMPLES,
        )
    candidates = (elements,) if isinstance(elements, int) else tuple(elements or CANDIDATE_ELEMENTS)
    errors: dict[int, float] = {}
    if len(candidates) > 1 and np.count_nonzero(check_rows) >= MIN_PRESLIDING_SAMPLES:
        # One pass over the record for every candidate grid at once.
        grids = [equally_spaced(count, presliding_range) for count in candidates]
        phi_all = element_deflections(x, np.concatenate(grids))
        first = 0
        for count in candidates:
            phi = phi_all[:, first : first + count]
            first += count
            trial = fit_linear(_regressors(phi, v, fit_rows), force[fit_rows], nonnegative=True)
            theta = np.array(list(trial.coefficients.values()))
            prediction = np.column_stack(list(_regressors(phi, v, check_rows).values())) @ theta
            errors[count] = float(np.sqrt(np.mean((force[check_rows] - prediction) ** 2)))
        best = min(errors.values())
        chosen = min(count for count, error in errors.items() if error <= PARSIMONY * best)
    else:
        chosen = max(candidates)
    Delta = equally_spaced(chosen, presliding_range)
    rows = fit_rows | check_rows
    phi = element_deflections(x, Delta)
    fit = fit_linear(_regressors(phi, v, rows), force[rows], nonnegative=True)
    W = np.array([fit.coefficients[f"W{i}"] for i in range(chosen)])
    if not (W > 0.0).any():
        raise DataError(
            "the presliding fit gave no element a positive weight: the force does not rise with the "
            "displacement after reversals",
            kind="not_identifiable",
            field="W",
        )
    # The model needs every W > 0, and the joint refinement can still use an element that the
    # z ≈ x regression left idle: start idle ones at a small share of the mean weight.
    W = np.maximum(W, IDLE_SHARE * float(np.mean(W)))
    return PreslidingFit(W=W, Delta=Delta, viscous=fit.coefficients["viscous"], fit=fit, held_out_rms=errors)
