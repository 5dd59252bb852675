"""Scores a model on data it was not fitted to: blocked cross-validation in time, and whether an
improvement stands out against the estimated noise floor.

The usable samples are cut into ``settings.folds`` contiguous blocks; each block is predicted by
the model fitted to the other blocks (its coefficients and Stribeck shape; the presliding drive,
a simulation of the record, is fitted once on all usable samples and shared by the folds).
Blocks (not random samples) keep neighbouring, correlated samples on the same side of the split,
so a term that only fits the noise gains nothing and a term that fits a slow change over time
(which the catalogue does not have) does not carry over from one block to the next.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .._typing import FloatArray
from ..errors import InputError
from .drive import Drive
from .features import Features
from .model import PRESLIDING, Design, ModelFit, fit_driven
from .settings import Settings

#: Each block must hold at least this many samples.
MIN_FOLD_SAMPLES = 100


@dataclass(frozen=True, eq=False)
class Score:
    effects: tuple[str, ...]
    held_out: FloatArray
    """Held-out residual (force − prediction) on every usable sample, block by block."""
    fold_mse: FloatArray
    coefficients: int
    fit: ModelFit | None = None
    """The fit on every usable sample, when the score made it on the way (the presliding drive)."""

    @property
    def mse(self) -> float:
        return float(np.mean(self.held_out**2))


def blocks(features: Features, folds: int) -> list[NDArray[np.bool_]]:
    """The cross-validation blocks: ``folds`` contiguous runs of usable samples."""
    index = np.flatnonzero(features.usable)
    if index.size < folds * MIN_FOLD_SAMPLES:
        raise InputError(
            "data too short to split for validation: "
            f"need at least {folds * MIN_FOLD_SAMPLES} usable samples ({folds} blocks of {MIN_FOLD_SAMPLES}) "
            f"after the filter edges, got {index.size}",
            kind="too_few",
            value=int(index.size),
            bound=folds * MIN_FOLD_SAMPLES,
        )
    masks = []
    for part in np.array_split(index, folds):
        mask = np.zeros(features.usable.size, dtype=bool)
        mask[part] = True
        masks.append(mask)
    return masks


def cross_validate(
    effects: Sequence[str],
    features: Features,
    folds: list[NDArray[np.bool_]],
    held: tuple[Drive, Features] | None = None,
) -> Score:
    """Held-out residuals of ``effects``: every block predicted by the model (its coefficients and
    the Stribeck shape) fitted to the other blocks, from normal equations formed once per block.

    The presliding drive (the nonlinear part of that effect, a simulation of the whole record for
    each trial) is fitted once on all usable samples and held by every fold: one exponent of
    three and the weights' ratios, against tens of thousands of held-out samples, so that it
    adds nothing measurable to the held-out error, while fitting it per fold took four times the
    simulations. ``held``: a drive and ``features`` driven by it, held instead (no simulation)."""
    effects = tuple(effects)
    usable = features.usable
    whole, drive, driven = None, None, features
    if held is not None and PRESLIDING in effects:
        drive, driven = held
    elif PRESLIDING in effects:
        whole = fit_driven(effects, features, usable)
        if whole.driven is not None:
            drive, driven = whole.drive, whole.driven[1]
    design = Design(effects, driven, usable, folds)
    residual = np.empty(int(np.count_nonzero(usable)))
    fold_mse = []
    coefficients = 0
    for out in range(len(folds)):
        fit, normal = design.fit([block for block in range(len(folds)) if block != out], drive)
        error = normal.residual(np.array([fit.coefficients[name] for name in normal.names]), out)
        residual[design.spans[out]] = error
        fold_mse.append(float(np.mean(error**2)))
        coefficients = len(fit.coefficients)
    return Score(effects, residual, np.asarray(fold_mse), coefficients, whole)


def gain(current: Score, candidate: Score, chunks: int) -> tuple[float, float, float]:
    """The held-out mean squared error the candidate saves, and over ``chunks`` contiguous runs of
    held-out samples, the sum of the runs' gains and the sum of their losses (both >= 0)."""
    saved = current.held_out**2 - candidate.held_out**2
    runs = np.array([float(np.mean(part)) for part in np.array_split(saved, chunks)])
    return float(np.mean(saved)), float(np.sum(np.maximum(runs, 0.0))), float(np.sum(np.maximum(-runs, 0.0)))


def significant(current: Score, candidate: Score, noise_std: float, settings: Settings) -> bool:
    """The candidate lowers the held-out error by more than ``settings.significance``·σ², and the
    runs where it does worse lose less than ``settings.loss`` times what the others gain: an
    effect that helps in some runs and hurts in as many is fitting something that changes over
    time, which no effect here is; an effect whose signature is absent from a run (inertia in a
    run without acceleration) ties there; and one run that rises a little does not veto a gain
    many times larger."""
    mean, gained, lost = gain(current, candidate, settings.chunks)
    return bool(mean > settings.significance * noise_std**2 and lost < settings.loss * gained)


def choose(current: Score, candidates: list[Score], noise_std: float, settings: Settings) -> Score | None:
    """The significant candidate to add, or None: the fewest coefficients among those within
    ``settings.significance``·σ² of the best."""
    winners = [score for score in candidates if significant(current, score, noise_std, settings)]
    if not winners:
        return None
    best = min(score.mse for score in winners)
    close = [score for score in winners if score.mse - best <= settings.significance * noise_std**2]
    return min(close, key=lambda score: (score.coefficients, score.mse))


def zero_score(features: Features, folds: list[NDArray[np.bool_]]) -> Score:
    """The score of predicting no force at all (an empty baseline)."""
    fold_mse = np.array([float(np.mean(features.force[fold] ** 2)) for fold in folds])
    return Score((), features.force[features.usable], fold_mse, 0)
