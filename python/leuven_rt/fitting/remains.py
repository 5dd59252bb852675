"""What remains after the fit: is there structure left in the residual, and where?

Noise, white or coloured, cannot be predicted from the motion; a missing effect can. So the
residual is significant when a generic predictor built from the motion predicts it on samples it
was not fitted on: a sum of piecewise-constant functions of the signed speed, the position in
each direction, the travel since the last reversal in each direction, and the acceleration
(bins of equal counts), fitted by backfitting on all blocks of the record in time but one and
scored on that one (:data:`FOLDS` blocks). Its held-out gain, the mean squared residual minus
the mean squared error of its prediction, is compared with the unit of evidence. The function
that gains most says where the residual sits.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .._typing import FloatArray

#: Contiguous blocks in time: each is predicted by the predictor fitted on the others.
FOLDS = 4
#: Bins of each function.
BINS = 12
#: A bin fitted on fewer samples than this predicts 0.
MIN_COUNT = 30
#: Backfitting passes.
PASSES = 4


@dataclass(frozen=True)
class Remains:
    """The held-out gain of the generic predictor [force²], and each function's share of it."""

    gain: float
    by_function: dict[str, float]

    def strongest(self) -> str | None:
        if not self.by_function:
            return None
        name, value = max(self.by_function.items(), key=lambda item: item[1])
        return name if value > 0 else None


def _quantile_bins(values: FloatArray, rows: NDArray[np.bool_], bins: int) -> NDArray[np.int64]:
    edges = np.unique(np.quantile(values[rows], np.linspace(0.0, 1.0, bins + 1)[1:-1]))
    return np.searchsorted(edges, values).astype(np.int64)


def functions(
    v: FloatArray, x: FloatArray, a: FloatArray, travel: FloatArray, rows: NDArray[np.bool_]
) -> dict[str, NDArray[np.int64]]:
    """The bin index of every sample under each function of the predictor."""
    half = BINS // 2
    direction = (v < 0).astype(np.int64)
    speed = _quantile_bins(np.abs(v), rows, half)
    position = _quantile_bins(x, rows, BINS)
    since = _quantile_bins(np.log(np.maximum(travel, 1e-300)), rows, half)
    return {
        "speed in each direction": direction * half + speed,
        "position, moving in +x": np.where(v >= 0, position, -1),
        "position, moving in -x": np.where(v < 0, position, -1),
        "travel since the last reversal": direction * half + since,
        "acceleration": _quantile_bins(a, rows, BINS),
    }


def _fit(
    residual: FloatArray, table: dict[str, NDArray[np.int64]], train: NDArray[np.bool_]
) -> dict[str, FloatArray]:
    values = {name: np.zeros(int(index.max()) + 2) for name, index in table.items()}
    left = residual.copy()
    for _ in range(PASSES):
        for name, index in table.items():
            valid = train & (index >= 0)
            left[valid] += values[name][index[valid]]
            sums = np.bincount(index[valid], left[valid], minlength=values[name].size)
            counts = np.bincount(index[valid], minlength=values[name].size)
            fresh = np.where(counts >= MIN_COUNT, sums / np.maximum(counts, 1), 0.0)
            values[name] = fresh
            left[valid] -= fresh[index[valid]]
    return values


def _predict(
    values: dict[str, FloatArray], table: dict[str, NDArray[np.int64]], rows: NDArray[np.bool_]
) -> dict[str, FloatArray]:
    out = {}
    for name, index in table.items():
        part = np.zeros(int(rows.sum()))
        chosen = index[rows]
        valid = chosen >= 0
        part[valid] = values[name][chosen[valid]]
        out[name] = part
    return out


def remains(residual: FloatArray, weight: FloatArray, table: dict[str, NDArray[np.int64]]) -> Remains:
    """The held-out gain of the generic predictor on ``residual`` (weighted samples only)."""
    rows = weight > 0
    order = np.flatnonzero(rows)
    if order.size < FOLDS * 2 * MIN_COUNT:
        return Remains(0.0, {})
    gain = 0.0
    parts = {name: 0.0 for name in table}
    for block in np.array_split(order, FOLDS):
        test = np.zeros(residual.size, dtype=bool)
        test[block] = True
        values = _fit(residual, table, rows & ~test)
        predicted = _predict(values, table, test)
        target = residual[test]
        total = sum(predicted.values())
        gain += float(np.sum(target**2 - (target - total) ** 2))
        for name, part in predicted.items():
            parts[name] += float(np.sum(target**2 - (target - part) ** 2))
    count = float(order.size)
    return Remains(gain / count, {name: value / count for name, value in parts.items()})


__all__ = ["Remains", "functions", "remains"]
