"""Scores a model on data it was not fitted to: blocked cross-validation in time, and whether an
improvement stands out against the estimated noise floor.

The usable samples are cut into :data:`FOLDS` contiguous blocks; each block is predicted by the
model fitted to the other blocks. Blocks (not random samples) keep neighbouring, correlated
samples on the same side of the split, so a term that only fits the noise gains nothing and a
term that fits a slow change over time (which the catalogue does not have) does not carry over
from one block to the next.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .._typing import FloatArray
from ..errors import InputError
from .features import Features
from .model import fit_model

#: Contiguous blocks of the cross-validation.
FOLDS = 4
#: Each block must hold at least this many samples.
MIN_FOLD_SAMPLES = 100
#: An added effect counts when it lowers the held-out mean squared error by more than this share
#: of the noise variance σ² (and candidates within it of the best are as good: the one with the
#: fewest coefficients is chosen among them).
SIGNIFICANCE = 0.2
#: ... and raises no block's mean squared error by more than this share of σ². An effect that
#: helps in some blocks and hurts in others is fitting something that changes over time, which
#: no effect here is (a drift costs its blocks several σ²); an effect whose signature is absent
#: from a block, such as inertia in a block without acceleration, ties there.
TIE = 0.1


@dataclass(frozen=True, eq=False)
class Score:
    effects: tuple[str, ...]
    held_out: FloatArray
    """Held-out residual (force − prediction) on every usable sample, block by block."""
    fold_mse: FloatArray
    coefficients: int

    @property
    def mse(self) -> float:
        return float(np.mean(self.held_out**2))


def blocks(features: Features) -> list[NDArray[np.bool_]]:
    """The cross-validation blocks: FOLDS contiguous runs of usable samples."""
    index = np.flatnonzero(features.usable)
    if index.size < FOLDS * MIN_FOLD_SAMPLES:
        raise InputError(
            "data too short to split for validation: "
            f"need at least {FOLDS * MIN_FOLD_SAMPLES} usable samples ({FOLDS} blocks of {MIN_FOLD_SAMPLES}) "
            f"after the filter edges, got {index.size}"
        )
    masks = []
    for part in np.array_split(index, FOLDS):
        mask = np.zeros(features.usable.size, dtype=bool)
        mask[part] = True
        masks.append(mask)
    return masks


def cross_validate(effects: Sequence[str], features: Features, folds: list[NDArray[np.bool_]]) -> Score:
    """Held-out residuals of ``effects``: every block predicted by the model (its coefficients,
    the Stribeck shape and the presliding drive) fitted to the other blocks."""
    residual = np.empty(features.usable.size)
    fold_mse = []
    coefficients = 0
    for fold in folds:
        fit = fit_model(effects, features, features.usable & ~fold)
        error = features.force[fold] - fit.predict(features)[fold]
        residual[fold] = error
        fold_mse.append(float(np.mean(error**2)))
        coefficients = len(fit.coefficients)
    return Score(tuple(effects), residual[features.usable], np.asarray(fold_mse), coefficients)


def significant(current: Score, candidate: Score, noise_std: float) -> bool:
    """The candidate lowers the held-out error by more than SIGNIFICANCE·σ², and raises no
    block's by more than TIE·σ²."""
    variance = noise_std**2
    return bool(current.mse - candidate.mse > SIGNIFICANCE * variance
                and np.all(candidate.fold_mse < current.fold_mse + TIE * variance))  # fmt: skip


def choose(current: Score, candidates: list[Score], noise_std: float) -> Score | None:
    """The significant candidate to add, or None: the fewest coefficients among those within
    SIGNIFICANCE·σ² of the best."""
    winners = [score for score in candidates if significant(current, score, noise_std)]
    if not winners:
        return None
    best = min(score.mse for score in winners)
    close = [score for score in winners if score.mse - best <= SIGNIFICANCE * noise_std**2]
    return min(close, key=lambda score: (score.coefficients, score.mse))


def zero_score(features: Features, folds: list[NDArray[np.bool_]]) -> Score:
    """The score of predicting no force at all (an empty baseline)."""
    fold_mse = np.array([float(np.mean(features.force[fold] ** 2)) for fold in folds])
    return Score((), features.force[features.usable], fold_mse, 0)
