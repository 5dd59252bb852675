"""``identify`` and ``diagnose``: the model file a log supports, and the story of how it got there.

``identify`` runs the rounds of :mod:`leuven_rt.fitting` on the log, fixes what the excitation
did not determine (:mod:`leuven_rt.fitting.undetermined`), writes the model file, and measures
it the way :func:`leuven_rt.predict` will: every rms of the report is the simulation error of a
model file along the log, over every sample, and the final one is the written file's.
``diagnose`` is the same fit, returning the story (:class:`~.report.Diagnosis`): where each step
helped, what remains and where.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from threadpoolctl import threadpool_limits

from ..data.reconstruction import describe, travel_since_reversal
from ..data.records import DataLike, as_motion_data
from ..errors import InputError, shown
from ..fitting.file import model_file
from ..fitting.remains import functions, remains
from ..fitting.select import Selection, select
from ..fitting.settings import Settings
from ..fitting.solve import Fitted, fit
from ..fitting.structure import Structure, parse_effects
from ..fitting.undetermined import Undetermined, settle
from ..modelfile import ModelFile, Reconstruction
from ..params import Params
from ..prediction import predict
from ..progress import Progress, reporting
from ..units import Units, unit_names
from .localise import Layout
from .report import Diagnosis, Step

#: The baseline model when none is given.
DEFAULT_BASELINE = ("coulomb", "viscous")


@dataclass(frozen=True, eq=False)
class Identification:
    """What :func:`leuven_rt.identify` returns: the model file and the diagnosis it came from."""

    model: ModelFile
    diagnosis: Diagnosis
    warnings: tuple[str, ...]
    """What the fit could not determine or the file cannot hold (the log's own warnings are in
    the report's ``data_notes``)."""

    @property
    def params(self) -> Params:
        """The friction model of the file."""
        return self.model.friction

    def summary(self) -> str:
        effects = ", ".join((*self.diagnosis.baseline, *self.diagnosis.named_effects))
        lines = [self.diagnosis.story(), f"model file: {effects}"]
        lines.extend(f"warning: {text}" for text in self.warnings)
        return "\n".join(lines)


def identify(
    data: DataLike,
    baseline: str | Sequence[str] = DEFAULT_BASELINE,
    *,
    settings: Settings | None = None,
    progress: bool | Progress = False,
    columns: Mapping[str, str] | None = None,
    units: Units | None = None,
) -> Identification:
    """Fits the friction model ``data`` supports and returns its model file (module documentation).

    ``data``: a :class:`~leuven_rt.MotionData`, a ``.csv`` or EMPS ``.mat`` path, or a mapping of
    columns; ``columns``: the log's names for ``t``, ``x``, ``f``, ``v``; ``units``: the kind of
    axis (``"linear"`` or ``"rotary"``). ``baseline``: effect names, as a list or
    comma-separated. ``settings``: the thresholds (:class:`~leuven_rt.fitting.Settings`).
    ``progress``: report progress on stderr (True, or a :class:`~leuven_rt.progress.Progress`).
    """
    effects = parse_effects(baseline)
    if settings is None:
        settings = Settings()
    elif not isinstance(settings, Settings):
        raise InputError(
            f"`settings` must be a leuven_rt.fitting.Settings or None, got {shown(settings)!r:.80}",
            kind="wrong_type",
            field="settings",
            value=settings,
        )
    record = as_motion_data(data, columns=columns, units=units)
    with reporting(progress, "identify") as bar, threadpool_limits(limits=1, user_api="blas"):
        # One BLAS thread: the fits are many small factorisations, which threads slow down on a
        # busy machine instead of speeding up.
        run = select(record, effects, settings, lambda text: bar.stage(text))
        bar.stage("the parameters the excitation determines")
        final, undetermined = _settle(run, settings)
        bar.stage("the model file and its prediction")
        return _identification(record, run, final, undetermined, effects, settings)


def _settle(run: Selection, settings: Settings) -> tuple[Fitted, list[Undetermined]]:
    final = run.written

    def refit(structure: Structure, fixed: dict[str, float]) -> Fitted:
        return fit(structure, run.file_scales, run.file_target, final.theta, fixed=fixed)

    return settle(final, run.file_scales, run.file_target, run.noise, refit, settings.significance * run.unit)


def _identification(
    record: Any,
    run: Selection,
    final: Fitted,
    undetermined: list[Undetermined],
    baseline: tuple[str, ...],
    settings: Settings,
) -> Identification:
    force = unit_names(record.units).force
    warnings = [item.warning() for item in undetermined]
    if run.drift:
        warnings.append(
            "the friction level drifts over the record (outside the catalogue): the file holds its average"
        )
    reconstruction = run.file_reconstruction
    written = model_file(final.evaluation.values, run.file_scales, record.units, reconstruction)
    prediction = predict(written, record)
    motion = run.target.motion
    usable = run.target.weight > 0
    layout = Layout.of(motion.v, motion.x, motion.a, float(run.scales.grid[-1]), run.target.weight > 0)
    residuals = [record.f - step.before.force for step in run.steps[:1]] or [record.f - run.baseline.force]
    residuals += [record.f - step.after.force for step in run.steps]
    residuals[-1] = record.f - prediction.f_model
    # Each step's numbers are the file's (refitted after the rounds, on the whole record and the
    # reconstruction it is driven by), where the file still holds the effect.
    shown = [final if final.structure.has(step.effect) else step.after for step in run.steps]
    steps = [
        Step(step.effect, layout.where_improved(before, after, force), _rms(before), _rms(after),
             _params(step.effect, model), math.sqrt(run.target.mse(step.before.force)),
             math.sqrt(run.target.mse(step.after.force)))
        for step, model, before, after in zip(run.steps, shown, residuals[:-1], residuals[1:], strict=True)
    ]  # fmt: skip
    travel = travel_since_reversal(motion.x, motion.v)
    table = functions(motion.v, motion.x, motion.a, travel, usable)
    # Judged on the rounds' final model, fitted on the samples a model can place: the written
    # file also answers for the reversals no model can place, a compromise that is not a missing
    # effect.
    left = remains(record.f - run.without_drift.force, run.target.weight, table)
    significant = run.drift or left.gain > settings.unexplained * run.unit
    where = layout.where_unexplained(residuals[-1], run.noise, force)
    if run.drift:
        where = f"the friction level changes over the record (a drift, outside the catalogue); {where}"
    elif significant and (strongest := left.strongest()) is not None:
        where = f"it follows the {strongest}; {where}"
    diagnosis = Diagnosis(
        samples=record.samples, noise_std=run.noise, floor_estimate=run.floor.full,
        reconstruction=_described(reconstruction), named_under=_described(run.reconstruction),
        gross_errors=run.gross,
        baseline=baseline, rms_before=_rms(residuals[0]), rms_after=prediction.rms, steps=steps,
        # An effect whose parameter the excitation leaves undetermined may be gone from the file.
        stand_ins=[dataclasses.asdict(pair) for pair in run.stand_ins if final.structure.has(pair.named)],
        unexplained_significant=bool(significant), unexplained_where=where, drift=run.drift,
        settings=settings.to_dict(),
        final_model={key: value for key, value in written.to_dict().items() if key != "report"},
        regions_before=layout.regions(residuals[0]), regions_after=layout.regions(residuals[-1]),
        layout=layout,
        t=record.t, v=motion.v, x=motion.x, travel=travel, residuals=residuals, units=record.units,
    )  # fmt: skip
    report = diagnosis.to_dict()
    report.pop("final_model")
    report["warnings"] = warnings
    if record.notes:
        report["data_notes"] = list(record.notes)
    model = dataclasses.replace(written, report=report)
    return Identification(model, diagnosis, tuple(warnings))


def _described(reconstruction: Reconstruction) -> dict[str, Any]:
    """``reconstruction`` as the report gives it: its file keys and a description in words."""
    return {**reconstruction.to_dict(), "description": describe(reconstruction)}


def _params(effect: str, fitted: Fitted) -> dict[str, Any]:
    """The numbers of the file that ``effect`` brought, as ``fitted`` (the step's model, or the
    file's) has them."""
    values = fitted.evaluation.values
    friction = values.friction
    if effect == "coulomb":
        return {"Fc": friction["Fc"]}
    if effect == "viscous":
        return {"sigma2": friction["sigma2"]}
    if effect == "stribeck":
        return {"Fs": friction["Fs"], "Vs": friction["Vs"], "delta": friction["delta"]}
    if effect == "asymmetry":
        return {key: friction[key] for key in ("Fc_neg", "Fs_neg", "sigma2_neg")}
    if effect == "presliding_hysteresis":
        weights = np.asarray(values.W)
        return {"elements": int(np.count_nonzero(weights > 1e-9 * weights.max())), "n": friction["n"],
                "sigma1": friction["sigma1"],
                "presliding_range": float(np.max(values.Delta[weights > 1e-9 * weights.max()]))}  # fmt: skip
    if effect == "position_dependence":
        form = fitted.structure.form
        terms = values.level if form == "level" else values.force
        assert terms is not None
        trend, ripples = terms
        return {"form": form, "trend": list(trend), "periods": [period for period, _, _ in ripples]}
    if effect == "offset":
        return {"offset": values.offset}
    if effect == "inertia":
        return {"inertia": values.inertia}
    return {}


def _rms(residual: Any) -> float:
    return math.sqrt(float(np.mean(np.square(residual))))


__all__ = ["DEFAULT_BASELINE", "Identification", "identify"]
