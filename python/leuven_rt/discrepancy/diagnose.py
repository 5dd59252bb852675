"""``diagnose``: find where a friction model and the data disagree, name the missing effects,
add them, and show the gap shrink.

Each round simulates (evaluates) the current model on the measured motion, localises its
residual (:mod:`.localise`), fits the model with each catalogue effect not yet in it, scores
every candidate by blocked cross-validation in time (:mod:`.scoring`), and adds the best one if
its improvement stands out against the noise floor. It stops when no candidate does, and says
what remains unexplained and where.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from tqdm import tqdm

from .._extras import progress_wanted
from ..data.records import DataLike, as_motion_data
from ..data.signals import noise_floor
from ..units import unit_names
from .effects import CATALOGUE, parse_effects
from .features import compute_features
from .localise import regions, where_improved, where_unexplained
from .model import ModelFit, fit_model
from .report import Diagnosis, Step
from .scoring import blocks, choose, cross_validate, zero_score

#: The baseline model when none is given.
DEFAULT_BASELINE = ("coulomb", "viscous")
#: What remains is significant when its mean square exceeds the noise variance by this share.
UNEXPLAINED = 0.2


def diagnose(
    data: DataLike, baseline: str | Sequence[str] = DEFAULT_BASELINE, *, progress: bool = False
) -> Diagnosis:
    """Names the catalogue effects (docs/effects.md) that ``baseline`` misses in ``data``.

    ``data``: a :class:`~leuven_rt.MotionData`, a ``.csv`` (t, x, f[, v]) or EMPS ``.mat`` path,
    or a mapping of columns. ``baseline``: effect names, as a list or comma-separated.
    ``progress``: a tqdm progress bar on stderr. Bad input raises :class:`InputError`.
    """
    effects = parse_effects(baseline)
    record = as_motion_data(data)
    features = compute_features(record)
    folds = blocks(features)
    noise = noise_floor(record.f)
    usable = features.usable
    unit = unit_names(record.units).force

    def fitted(effect_set: tuple[str, ...]) -> ModelFit:
        return fit_model(effect_set, features, usable)

    def rms(residual: np.ndarray) -> float:
        return float(np.sqrt(np.mean(residual[usable] ** 2)))

    model = fitted(effects)
    residual = features.force - model.predict(features)
    residuals = [residual]
    steps: list[Step] = []
    with tqdm(desc="diagnose", unit=" fits", disable=not progress_wanted(progress), leave=False) as bar:
        current = cross_validate(effects, features, folds) if effects else None
        while True:
            candidates = [name for name in CATALOGUE if name not in effects]
            if not candidates:
                break
            bar.total = (bar.total or 0) + len(candidates)
            bar.refresh()
            scores = []
            for name in candidates:
                bar.set_postfix_str(name)
                scores.append(cross_validate((*effects, name), features, folds))
                bar.update(1)
            if current is None:  # an empty baseline is scored against predicting zero
                current = zero_score(features, folds)
            best = choose(current, scores, noise)
            if best is None:
                break
            added = best.effects[-1]
            effects = best.effects
            model = fitted(effects)
            after = features.force - model.predict(features)
            where = where_improved(features, residual, after, unit)
            steps.append(Step(added, where, rms(residual), rms(after), model.params(added)))
            residual, current = after, best
            residuals.append(residual)
    final = model
    excess = float(np.mean(residual[usable] ** 2)) - noise**2
    return Diagnosis(
        samples=record.samples, noise_std=noise, baseline=parse_effects(baseline),
        rms_before=rms(residuals[0]), rms_after=rms(residual), steps=steps,
        unexplained_significant=bool(excess > UNEXPLAINED * noise**2),
        unexplained_where=where_unexplained(features, residual, noise, unit),
        final_model=final, regions_before=regions(features, residuals[0]),
        regions_after=regions(features, residual), features=features, residuals=residuals,
        units=record.units,
    )  # fmt: skip
