"""Normal equations of a design, block by block: XᵀX, Xᵀy and yᵀy of every cross-validation
block, accumulated once and reused by every fit on a union of blocks (a fold's fit is the total
minus the held-out block's share), instead of a QR factorisation of the rows for each fit.

The Gram matrix squares the condition number of the columns, so it is solved with its columns
scaled to unit norm (Cholesky factor, then the same bounded or plain least squares as
:func:`~leuven_rt.data.regression.fit_linear` on that factor), and only while the scaled Gram
matrix's condition number stays below :data:`GRAM_CONDITION`. Above it (nearly collinear
columns, such as bank elements that never slip and so deflect in proportion, or a column that is
zero on the rows) the fit is made as :func:`~leuven_rt.data.regression.fit_linear` makes it,
from the triangular factor R of the rows' QR factorisation, without forming the Gram matrix: the
R of each block is made once (when first needed), and a fit's R is the QR factorisation of its
blocks' factors stacked (a tall-skinny QR), p + 1 rows per block instead of the block's samples.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import cast

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import solve_triangular
from scipy.optimize import lsq_linear

from .._typing import BoolArray, FloatArray
from ..data.regression import factor_errors, solve_factor

#: Largest condition number of the column-scaled Gram matrix that is solved directly (a relative
#: error of about 1e-6 in the coefficients at most); above it the rows are factorised (QR).
GRAM_CONDITION = 1e10

Span = slice | NDArray[np.intp]


def spans(rows: BoolArray, blocks: Sequence[BoolArray]) -> list[Span]:
    """Each block's positions among ``rows`` (a slice when they are contiguous, as the
    cross-validation blocks are)."""
    out: list[Span] = []
    for block in blocks:
        index = np.flatnonzero(block[rows])
        contiguous = index.size > 0 and index[-1] - index[0] + 1 == index.size
        out.append(slice(int(index[0]), int(index[-1]) + 1) if contiguous else index)
    return out


def rows_matrix(columns: Sequence[FloatArray], rows: BoolArray) -> FloatArray:
    """The (rows, columns) matrix of ``columns`` on ``rows``, built once, column by column."""
    index = np.flatnonzero(rows)
    matrix = np.empty((index.size, len(columns)), order="F")
    if index.size and index[-1] - index[0] + 1 == index.size:
        take: slice | NDArray[np.intp] = slice(int(index[0]), int(index[-1]) + 1)
    else:
        take = index
    for j, column in enumerate(columns):
        matrix[:, j] = np.broadcast_to(column, rows.shape)[take]
    return matrix


@dataclass(frozen=True, eq=False)
class Normal:
    """A design's columns on the fitted rows, and their normal equations per block."""

    names: tuple[str, ...]
    parts: tuple[FloatArray, ...]
    """The columns on the rows, as (rows, k) matrices side by side (a fixed part, then any
    columns added by :meth:`extend`)."""
    target: FloatArray
    spans: tuple[Span, ...]
    gram: FloatArray
    """(blocks, p, p)."""
    moment: FloatArray
    """(blocks, p): Xᵀy of each block."""
    square: FloatArray
    """(blocks,): yᵀy of each block."""
    count: NDArray[np.intp]
    factors: dict[int, FloatArray] = field(default_factory=dict, repr=False)
    """R of each block's [X y] (QR), made when a fit first needs them."""

    @classmethod
    def build(
        cls,
        columns: Mapping[str, FloatArray],
        force: FloatArray,
        rows: BoolArray,
        blocks: Sequence[BoolArray],
    ) -> Normal:
        names = tuple(columns)
        matrix = rows_matrix([columns[name] for name in names], rows)
        target = np.ascontiguousarray(force[rows])
        where = tuple(spans(rows, blocks))
        gram = np.stack([matrix[s].T @ matrix[s] for s in where])
        moment = np.stack([matrix[s].T @ target[s] for s in where])
        square = np.array([float(target[s] @ target[s]) for s in where])
        count = np.array([target[s].size for s in where], dtype=np.intp)
        return cls(names, (matrix,), target, where, gram, moment, square, count)

    def extend(self, columns: Mapping[str, FloatArray], rows: BoolArray) -> Normal:
        """These normal equations with ``columns`` (on every sample) added after the others."""
        added = rows_matrix(list(columns.values()), rows)
        gram = []
        moment = []
        for block, s in enumerate(self.spans):
            cross = np.concatenate([part[s].T @ added[s] for part in self.parts])
            corner = added[s].T @ added[s]
            gram.append(np.block([[self.gram[block], cross], [cross.T, corner]]))
            moment.append(np.concatenate([self.moment[block], added[s].T @ self.target[s]]))
        return Normal(
            (*self.names, *columns), (*self.parts, added), self.target, self.spans,
            np.stack(gram), np.stack(moment), self.square, self.count,
        )  # fmt: skip

    def predict(self, theta: FloatArray, block: int) -> FloatArray:
        """X·θ on ``block``'s rows."""
        s = self.spans[block]
        out = np.zeros(self.target[s].size)
        start = 0
        for part in self.parts:
            out += part[s] @ theta[start : start + part.shape[1]]
            start += part.shape[1]
        return out

    def residual(self, theta: FloatArray, block: int) -> FloatArray:
        """y − X·θ on ``block``'s rows."""
        out: FloatArray = self.target[self.spans[block]] - self.predict(theta, block)
        return out

    def solve(
        self, use: Sequence[int], nonnegative: Collection[str]
    ) -> tuple[dict[str, float], dict[str, float]]:
        """Coefficients (``nonnegative``: those bounded at 0) and their standard errors, fitted on
        the blocks ``use``."""
        solved = self._from_gram(list(use), nonnegative)
        if solved is None:  # ill-conditioned: from the rows' QR factor
            solved = self._from_factors(list(use), nonnegative)
        theta, errors = solved
        return (
            {name: float(value) for name, value in zip(self.names, theta, strict=True)},
            {name: float(value) for name, value in zip(self.names, errors, strict=True)},
        )

    def _factor(self, block: int) -> FloatArray:
        if block not in self.factors:
            s = self.spans[block]
            stacked = np.column_stack([*(part[s] for part in self.parts), self.target[s]])
            # mode="r" returns R alone; numpy's stubs type every mode as the (Q, R) result.
            self.factors[block] = cast(FloatArray, np.linalg.qr(stacked, mode="r"))
        return self.factors[block]

    def _from_factors(self, use: list[int], nonnegative: Collection[str]) -> tuple[FloatArray, FloatArray]:
        p = len(self.names)
        factors = [self._factor(block) for block in use]
        augmented = (
            factors[0] if len(factors) == 1 else cast(FloatArray, np.linalg.qr(np.vstack(factors), mode="r"))
        )
        if augmented.shape[0] < p + 1:  # fewer rows than columns: pad R with zero rows
            augmented = np.vstack([augmented, np.zeros((p + 1 - augmented.shape[0], p + 1))])
        r, projected, last = augmented[:p, :p], augmented[:p, p], float(augmented[p, p])
        theta = solve_factor(r, projected, np.array([name in nonnegative for name in self.names]))
        misfit = r @ theta - projected
        rss = float(misfit @ misfit) + last * last
        sigma = float(np.sqrt(rss / max(int(self.count[use].sum()) - p, 1)))
        return theta, factor_errors(r, sigma)

    def _from_gram(
        self, use: list[int], nonnegative: Collection[str]
    ) -> tuple[FloatArray, FloatArray] | None:
        gram = self.gram[use].sum(axis=0)
        moment = self.moment[use].sum(axis=0)
        samples = int(self.count[use].sum())
        p = len(self.names)
        scale = np.sqrt(np.diag(gram))
        if samples < p or not np.all(scale > 0.0):
            return None
        scaled = gram / np.outer(scale, scale)
        condition = float(np.linalg.cond(scaled))
        if not np.isfinite(condition) or condition > GRAM_CONDITION:
            return None
        try:
            lower = np.linalg.cholesky(scaled)
        except np.linalg.LinAlgError:
            return None
        # ‖Xθ − y‖² = ‖Lᵀθ' − L⁻¹b'‖² + const, with θ' = θ·scale and b' = Xᵀy/scale
        projected = solve_triangular(lower, moment / scale, lower=True)
        upper = lower.T
        bounded = np.array([name in nonnegative for name in self.names])
        if bounded.any():
            bounds = (np.where(bounded, 0.0, -np.inf), np.full(p, np.inf))
            theta_scaled = lsq_linear(upper, projected, bounds=bounds, method="bvls").x
        else:
            theta_scaled = solve_triangular(upper, projected, lower=False)
        theta = theta_scaled / scale
        rss = float(self.square[use].sum() - 2.0 * theta @ moment + theta @ gram @ theta)
        sigma = np.sqrt(max(rss, 0.0) / max(samples - p, 1))
        inverse = np.linalg.inv(scaled)
        errors = sigma * np.sqrt(np.clip(np.diag(inverse), 0.0, None)) / scale
        return np.asarray(theta, dtype=np.float64), np.asarray(errors, dtype=np.float64)
