"""``identify``: the workflow's fit, ending in the model file a compensator runs.

``identify`` and :func:`~leuven_rt.diagnose` are one fit: the rounds of :mod:`.diagnose` choose
the effects the log supports, and :mod:`.deploy` turns the final model into a
:class:`~leuven_rt.ModelFile` (the friction model, its position-dependent level, the measurement
terms). What the data could not determine is fixed at a safe value and named in the warnings;
only unusable data (too short, not finite, time not increasing) is refused.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

from ..data.records import DataLike, MotionData, as_motion_data
from ..data.signals import estimate_derivatives
from ..modelfile import ModelFile
from ..params import Params
from ..progress import Progress, reporting
from .deploy import deploy
from .diagnose import DEFAULT_BASELINE, diagnose
from .refine import refine
from .report import Diagnosis
from .settings import Settings


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
) -> Identification:
    """Fits the friction model ``data`` supports and returns its model file (module documentation).

    ``data``: a :class:`~leuven_rt.MotionData`, a ``.csv`` or EMPS ``.mat`` path, or a mapping
    of columns. ``baseline``, ``settings``, ``progress``: as for :func:`~leuven_rt.diagnose`.
    """
    record = as_motion_data(data)
    with reporting(progress, "identify") as reporter:
        return _identify(record, baseline, settings, reporter)


def _identify(
    record: MotionData, baseline: str | Sequence[str], settings: Settings | None, progress: Progress
) -> Identification:
    diagnosis = diagnose(record, baseline, settings=settings, progress=progress)
    progress.stage("model file")
    report = diagnosis.to_dict()
    report.pop("final_model", None)  # the file holds the model itself
    if record.notes:
        report["data_notes"] = list(record.notes)
    deployment = deploy(diagnosis.final_model, diagnosis.features, record.units, report)
    # predict's signals (docs/data-and-reports.md#predict): the file is refined on what it will run on
    motion = estimate_derivatives(record)
    usable = diagnosis.features.usable
    model, before, after = refine(deployment.model, motion.x, motion.a, record.dt, record.f, usable, progress)
    fitted = {**(model.report or {}), "simulation_rms": {"mapped": before, "refined": after}}
    model = dataclasses.replace(model, report=fitted)
    return Identification(model, diagnosis, deployment.warnings)
