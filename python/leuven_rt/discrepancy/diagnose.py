"""``diagnose``: find where a friction model and the data disagree, name the missing effects,
add them, and show the gap shrink.

Each round simulates (evaluates) the current model on the measured motion, localises its
residual (:mod:`.localise`), fits the model with each catalogue effect not yet in it, scores
every candidate by blocked cross-validation in time (:mod:`.scoring`), and adds the best one if
its improvement stands out against the noise floor. It stops when no candidate does, and says
what remains unexplained and where.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from threadpoolctl import threadpool_limits

from .._typing import FloatArray
from ..data.records import DataLike, MotionData, as_motion_data
from ..data.signals import noise_floor
from ..errors import InputError, shown
from ..progress import Progress, reporting
from ..units import unit_names
from .drive import Drive
from .effects import CATALOGUE, DRIFT, parse_effects
from .features import Features, compute_features, thin
from .localise import regions, where_improved, where_unexplained
from .model import PRESLIDING, ModelFit, fit_model
from .report import Diagnosis, Step
from .ripple import find_periods
from .scoring import Score, blocks, choose, cross_validate, significant, zero_score
from .settings import Settings

#: The baseline model when none is given.
DEFAULT_BASELINE = ("coulomb", "viscous")
#: Effects tried in pairs when none counts alone: the best this many single additions.
PAIRED = 4
#: Most usable samples the fits and scores use: a longer record is fitted on every k-th sample
#: (docs/effects.md#fitting-mechanics), its signals and the presliding simulation computed on
#: every sample first.
FIT_SAMPLES = 2**16
#: Hold the current model's presliding drive while candidates are scored, instead of searching it
#: again for each (six simulations of the record per candidate): the held drive screens them.
HOLD_DRIVE = True
#: With the drive held: how many of the best candidates that gain are scored again with the drive
#: searched for them. The added effect is chosen on those scores, and its model (the final one
#: included) always gets a drive search of its own (docs/effects.md#how-an-effect-is-fitted).
SEARCHED = 1


@dataclass
class _Selection:
    """The state of the rounds: the model so far, and what each step did."""

    effects: tuple[str, ...]
    features: Features
    model: ModelFit
    score: Score
    """The held-out score of ``effects``."""
    residual: FloatArray
    residuals: list[FloatArray]
    steps: list[Step]
    models: list[ModelFit]
    """The model of each residual."""


@dataclass
class _Fits:
    """The candidate fits made so far and known to come, for the progress report."""

    report: Progress
    done: int = 0
    total: int = 0


def diagnose(
    data: DataLike,
    baseline: str | Sequence[str] = DEFAULT_BASELINE,
    *,
    settings: Settings | None = None,
    progress: bool | Progress = False,
) -> Diagnosis:
    """Names the catalogue effects (docs/effects.md) that ``baseline`` misses in ``data``.

    ``data``: a :class:`~leuven_rt.MotionData`, a ``.csv`` (t, x, f[, v]) or EMPS ``.mat`` path,
    or a mapping of columns. ``baseline``: effect names, as a list or comma-separated.
    ``settings``: the thresholds (:class:`~leuven_rt.discrepancy.Settings`; the defaults when
    None). ``progress``: report the stages on stderr (True: a bar on a terminal, lines otherwise;
    or a :class:`~leuven_rt.progress.Progress`). Bad input raises :class:`InputError`.
    """
    effects = parse_effects(baseline)
    if settings is None:
        settings = Settings()
    elif not isinstance(settings, Settings):
        raise InputError(
            f"`settings` must be a leuven_rt.discrepancy.Settings or None, got {shown(settings)!r:.80}",
            kind="wrong_type",
            field="settings",
            value=settings,
        )
    record = as_motion_data(data)
    with reporting(progress, "diagnose") as report:
        return _diagnose(record, effects, settings, report)


def _diagnose(
    record: MotionData, effects: tuple[str, ...], settings: Settings, report: Progress
) -> Diagnosis:
    report.stage("signals")
    full = compute_features(record)
    stride = math.ceil(np.count_nonzero(full.usable) / FIT_SAMPLES)
    features = thin(full, stride) if stride > 1 else full
    folds = blocks(features, settings.folds)
    usable = features.usable
    # The noise is read from the force and from what the baseline leaves (its steps at reversals
    # and slow changes gone); each can only overstate it, by the force's own changes that the
    # differences keep, and neither can exceed what the baseline leaves.
    baseline_fit = fit_model(effects, features, usable)
    start = full.force - baseline_fit.predict(full)
    noise = min(noise_floor(record.f), noise_floor(start[full.usable]), _rms(start, full.usable))
    unit = unit_names(record.units).force

    # One BLAS thread: the fits are many small factorisations, which threads slow down on a busy
    # machine (a QR 4-10x slower with the cores shared) instead of speeding up.
    with threadpool_limits(limits=1, user_api="blas"):
        fits = _Fits(report)
        run = _select(effects, features, folds, noise, settings, fits, unit, baseline_fit)
        # A level that changes over the record makes effects look useful that are not there: when
        # the final model still gains from a level drifting in time, the rounds are run again
        # with the drift fitted alongside, and the drift is reported as unexplained.
        drift = significant(
            run.score,
            cross_validate((*run.effects, DRIFT.name), run.features, folds, _held(run.model, run.features)),
            noise,
            dataclasses.replace(settings, significance=settings.drift),
        )
        if drift:
            run = _select((*effects, DRIFT.name), features, folds, noise, settings, fits, unit)

    final, residuals = run.features, run.residuals
    if features is not full:  # every sample's residuals, for the report
        final = dataclasses.replace(full, scales=run.features.scales)
        residuals = [start if model is baseline_fit else _full_residual(model, final) for model in run.models]
        usable = final.usable
    residual = residuals[-1]
    excess = float(np.mean(residual[usable] ** 2)) - noise**2
    where = where_unexplained(final, residual, noise, unit)
    if drift:
        where = f"{DRIFT.missing} (a drift, outside the catalogue); {where}"
    return Diagnosis(
        samples=record.samples, noise_std=noise, baseline=effects,
        rms_before=_rms(residuals[0], usable), rms_after=_rms(residual, usable), steps=run.steps,
        unexplained_significant=bool(drift or excess > settings.unexplained * noise**2),
        unexplained_where=where, drift=drift, settings=settings,
        final_model=run.model, regions_before=regions(final, residuals[0]),
        regions_after=regions(final, residual), features=final, residuals=residuals,
        units=record.units,
    )  # fmt: skip


def _select(
    effects: tuple[str, ...],
    features: Features,
    folds: list[NDArray[np.bool_]],
    noise: float,
    settings: Settings,
    fits: _Fits,
    unit: str,
    model: ModelFit | None = None,
) -> _Selection:
    """The rounds from ``effects`` (``model``: their fit, when already made): add the best
    significant effect (or pair) until none is."""
    usable = features.usable
    if model is None:
        model = fit_model(effects, features, usable)
    residual = features.force - model.predict(features)
    current = cross_validate(effects, features, folds) if effects else zero_score(features, folds)
    run = _Selection(effects, features, model, current, residual, [residual], [], [model])
    while True:
        candidates = [name for name in CATALOGUE if name not in run.effects]
        if not candidates:
            break
        known: dict[str, Score] = {}  # scores the ripple search has already made
        if "position_dependence" in candidates:
            run.features, position = _ripples(run, folds, noise)
            if position is not None:
                known["position_dependence"] = position
        held = _held(run.model, run.features)
        fresh = iter(
            _score(run.effects, [(n,) for n in candidates if n not in known], run.features, folds, fits, held)
        )
        scores = [known[name] if name in known else next(fresh) for name in candidates]  # catalogue order
        scores = _searched(current, scores, run.features, folds, fits, held)
        best = _choose_present(current, scores, run.features, noise, settings)
        if best is None and current.mse > (1.0 + settings.joint) * noise**2 and len(candidates) > 1:
            # No effect helps alone, yet the model is far from the data: some effects only help
            # together (the Stribeck curve and presliding hysteresis each fit the other's part).
            # Among the effects that gain on their own, if not enough: the PAIRED best of them.
            ranked = sorted(scores, key=lambda score: score.mse)[:PAIRED]
            gaining = [score.effects[-1] for score in ranked if score.mse < current.mse]
            pairs: list[tuple[str, ...]] = list(itertools.combinations(gaining, 2))
            paired = _score(run.effects, pairs, run.features, folds, fits, held)
            paired = _searched(current, paired, run.features, folds, fits, held)
            best = _choose_present(current, paired, run.features, noise, settings)
        if best is None:
            break
        best_score, best_fit = best
        if held is not None:  # the score of the chosen set with its own drive (no simulation)
            best_score = _own_drive(best_score, best_fit, run.features, folds)
        added = best_score.effects[len(run.effects) :]
        for name in added:  # a pair is added one effect at a time, each step with its numbers
            effects_now = (*run.effects, name)
            same = effects_now == best_fit.effects
            model = best_fit if same else fit_model(effects_now, run.features, usable)
            after = run.features.force - model.predict(run.features)
            run.steps.append(
                Step(
                    name,
                    where_improved(run.features, run.residual, after, unit),
                    _rms(run.residual, usable),
                    _rms(after, usable),
                    model.params(name),
                )
            )
            run.effects, run.model, run.residual = effects_now, model, after
            run.residuals.append(after)
            run.models.append(model)
        current = run.score = best_score
    return run


def _choose_present(
    current: Score, scores: list[Score], features: Features, noise: float, settings: Settings
) -> tuple[Score, ModelFit] | None:
    """:func:`~.scoring.choose`, passing over a candidate whose own coefficients the whole record
    fits at exactly 0 (held at a bound, such as Fs − Fc ≥ 0): what gained in the blocks is not
    the effect. Returns the candidate with its fit on the whole record."""
    left = list(scores)
    while (best := choose(current, left, noise, settings)) is not None:
        fit = best.fit if best.fit is not None else fit_model(best.effects, features, features.usable)
        added = best.effects[len(current.effects) :]
        if all(any(fit.coefficients[name] != 0.0 for name in fit.groups[effect]) for effect in added):
            return best, fit
        left.remove(best)
    return None


def _ripples(run: _Selection, folds: list[NDArray[np.bool_]], noise: float) -> tuple[Features, Score | None]:
    """The features with the ripple periods of the position effect: those found in what the model
    leaves now, as many of them (none, the first, both) as predict the held-out blocks best (a
    period that fits where the record dwells can extrapolate badly to where it travels once);
    and the held-out score of the model with the position effect on them, when it was made."""
    found = find_periods(run.features.sign, run.features.x, run.residual, run.features.usable, noise)
    options = [
        dataclasses.replace(
            run.features, scales=dataclasses.replace(run.features.scales, periods=found[:count])
        )
        for count in range(len(found) + 1)
    ]
    if len(options) == 1:
        return options[0], None
    effects = (*run.effects, "position_dependence")
    scored = [
        (cross_validate(effects, features, folds, _held(run.model, features)), features)
        for features in options
    ]
    score, features = min(scored, key=lambda pair: pair[0].mse)
    return features, score


def _score(
    effects: tuple[str, ...],
    additions: list[tuple[str, ...]],
    features: Features,
    folds: list[NDArray[np.bool_]],
    fits: _Fits,
    held: tuple[Drive, Features] | None = None,
) -> list[Score]:
    fits.total += len(additions)
    scores = []
    for addition in additions:
        fits.report.stage("fits", fits.done, fits.total, "+".join(addition))
        scores.append(cross_validate((*effects, *addition), features, folds, held))
        fits.done += 1
    fits.report.stage("fits", fits.done, fits.total)
    return scores


def _searched(
    current: Score,
    scores: list[Score],
    features: Features,
    folds: list[NDArray[np.bool_]],
    fits: _Fits,
    held: tuple[Drive, Features] | None,
) -> list[Score]:
    """``scores``, made with the drive ``held``, with the :data:`SEARCHED` best of those that gain
    on ``current`` scored again with the drive searched for them."""
    if held is None:
        return scores
    gaining = sorted((score for score in scores if score.mse < current.mse), key=lambda score: score.mse)
    chosen = gaining[:SEARCHED]
    additions = [score.effects[len(current.effects) :] for score in chosen]
    again = dict(zip(map(id, chosen), _score(current.effects, additions, features, folds, fits), strict=True))
    return [again.get(id(score), score) for score in scores]


def _own_drive(score: Score, fit: ModelFit, features: Features, folds: list[NDArray[np.bool_]]) -> Score:
    """``score`` of the set ``fit`` was fitted for, made again with ``fit``'s own drive when it was
    made with a held one: the score the next round compares with is that of the model it has."""
    if PRESLIDING not in score.effects or score.fit is fit:
        return score
    held = (fit.drive, fit.driven[1]) if fit.drive is not None and fit.driven is not None else None
    return dataclasses.replace(cross_validate(score.effects, features, folds, held), fit=fit)


def _held(model: ModelFit, features: Features) -> tuple[Drive, Features] | None:
    """With :data:`HOLD_DRIVE`: the presliding drive of the current ``model`` and ``features``
    driven by it, held while the candidates are scored; the step that adds the chosen effect
    searches it again."""
    if model.drive is None or not HOLD_DRIVE:
        return None
    if model.driven is not None:
        return model.drive, dataclasses.replace(model.driven[1], scales=features.scales)
    return model.drive, model.drive.apply(features)


def _full_residual(model: ModelFit, features: Features) -> FloatArray:
    """The residual of ``model`` on every sample of ``features`` (with the ripple periods it was
    fitted with), its driven bank made one element at a time."""
    scales = dataclasses.replace(features.scales, periods=model.periods)
    out: FloatArray = features.force - model.predict_by_element(dataclasses.replace(features, scales=scales))
    return out


def _rms(residual: FloatArray, usable: NDArray[np.bool_]) -> float:
    return float(np.sqrt(np.mean(residual[usable] ** 2)))
