"""Linear least squares on named regressor columns: y ≈ Σ θⱼ·φⱼ.

The building block of every linear stage (the IDIM-LS inverse model, the Maxwell-slip weights W,
and the candidate effects of the discrepancy workflow): columns come in by name and the fitted
coefficients go out by name, with the numbers that say how well determined they are.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass
from typing import cast

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import lsq_linear

from .._typing import FloatArray
from ..errors import DataError


@dataclass(frozen=True, eq=False)
class LinearFit:
    """Coefficients by name, and the quality of the fit."""

    coefficients: dict[str, float]
    prediction: FloatArray
    residual: FloatArray
    """y − prediction."""
    condition: float
    """Condition number of the regressor matrix (its columns as given, not rescaled)."""
    r_diagonal: dict[str, float]
    """|diag(R)| of the QR factorisation, per column: near zero means poorly excited."""
    standard_errors: dict[str, float]
    """σ̂·sqrt(diag((ΦᵀΦ)⁻¹)) with σ̂² = ‖residual‖²/(samples − columns)."""

    @property
    def rms(self) -> float:
        return float(np.sqrt(np.mean(self.residual**2)))

    @property
    def relative_error(self) -> float:
        """100·‖y − ŷ‖/‖y‖ [%], the IDIM-LS figure of merit."""
        y = self.prediction + self.residual
        return float(100.0 * np.linalg.norm(self.residual) / np.linalg.norm(y))


def regressor_matrix(regressors: Mapping[str, ArrayLike], samples: int) -> tuple[list[str], FloatArray]:
    """The (samples, columns) matrix of the named columns; a scalar column is broadcast."""
    if not regressors:
        raise DataError("at least one regressor column is needed, got none", kind="too_few", value=0, bound=1)
    names = list(regressors)
    columns = []
    for name in names:
        column = np.broadcast_to(np.asarray(regressors[name], dtype=np.float64), (samples,))
        if not np.isfinite(column).all():
            raise DataError(f"regressor `{name}` must be finite everywhere", kind="not_finite", field=name)
        columns.append(column)
    return names, np.column_stack(columns)


def solve_factor(r: FloatArray, projected: FloatArray, bounded: NDArray[np.bool_]) -> FloatArray:
    """θ minimising ‖Rθ − Qᵀy‖ for the triangular factor R of a design's QR factorisation (the
    reduced form of its least squares), with the coefficients ``bounded`` held ≥ 0."""
    if bounded.any():
        lower = np.where(bounded, 0.0, -np.inf)
        return np.asarray(lsq_linear(r, projected, bounds=(lower, np.inf), method="bvls").x, dtype=np.float64)
    return np.asarray(np.linalg.lstsq(r, projected, rcond=None)[0], dtype=np.float64)


def factor_errors(r: FloatArray, sigma: float) -> FloatArray:
    """Standard errors σ̂·sqrt(diag((RᵀR)⁻¹)) of the coefficients fitted on the factor R (RᵀR is
    the design's XᵀX); infinite when RᵀR is singular."""
    try:
        covariance = np.linalg.inv(r.T @ r)
    except np.linalg.LinAlgError:
        return np.full(r.shape[1], np.inf)
    return np.asarray(sigma * np.sqrt(np.clip(np.diag(covariance), 0.0, None)), dtype=np.float64)


def fit_linear(
    regressors: Mapping[str, ArrayLike], y: ArrayLike, nonnegative: bool | Collection[str] = False
) -> LinearFit:
    """Least-squares coefficients of the named columns; ``nonnegative`` (all, or the named ones)
    bounds coefficients at 0 (bounded-variable least squares, ``scipy.optimize.lsq_linear``)."""
    target = np.asarray(y, dtype=np.float64)
    names, matrix = regressor_matrix(regressors, target.size)
    if target.ndim != 1 or not np.isfinite(target).all():
        raise DataError(
            "the fitted signal must be one-dimensional and finite",
            kind="shape" if target.ndim != 1 else "not_finite",
            field="y",
        )
    if target.size < len(names):
        raise DataError(
            f"need at least {len(names)} samples for {len(names)} coefficients, got {target.size}",
            kind="too_few",
            field="y",
            value=target.size,
            bound=len(names),
        )
    bounded = set(names) if nonnegative is True else set(nonnegative or ())
    unknown = bounded - set(names)
    if unknown:
        raise DataError(
            f"`nonnegative` names columns that are not regressors: {sorted(unknown)}",
            kind="unknown_key",
            field="nonnegative",
            value=sorted(unknown)[0],
            expected=names,
        )
    # Everything below works on the small triangular factor: ‖Aθ − y‖² = ‖Rθ − Qᵀy‖² + const
    # for A = QR, so the solution, the singular values and the covariance are those of A. One
    # Householder QR of [A y] gives both R and Qᵀy without forming Q.
    columns = len(names)
    # mode="r" returns R alone; numpy's stubs type every mode as the (Q, R) result.
    augmented = cast(FloatArray, np.linalg.qr(np.column_stack((matrix, target)), mode="r"))
    r, projected = augmented[:columns, :columns], augmented[:columns, columns]
    theta = solve_factor(r, projected, np.array([name in bounded for name in names]))
    prediction = matrix @ theta
    residual = target - prediction
    singular = np.linalg.svd(r, compute_uv=False)
    condition = float(singular[0] / singular[-1]) if singular[-1] > 0 else float("inf")
    dof = max(target.size - len(names), 1)
    sigma = float(np.linalg.norm(residual) / np.sqrt(dof))
    errors = factor_errors(r, sigma)
    r = np.abs(np.diag(r))
    return LinearFit(
        coefficients={name: float(value) for name, value in zip(names, theta, strict=True)},
        prediction=prediction,
        residual=residual,
        condition=condition,
        r_diagonal={name: float(value) for name, value in zip(names, r, strict=True)},
        standard_errors={name: float(value) for name, value in zip(names, errors, strict=True)},
    )
