"""``predict``: what a model says a log's force should have been, next to what was measured.

The model is driven by what the log gives a loop, through the reconstruction the model file
records (docs/data-and-reports.md#reconstruction): the logged velocity (a compensator in
feedforward mode fed that velocity at the logged positions) or the encoder position, raw or
through a zero-phase low-pass (a compensator in observer mode fed that position). Then

    friction = factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x),    f_model = friction + offset + inertia·a,

where F is the friction model along the motion, factor(x) the position-dependent level, r(x) the
position force (each absent in a file without it) and a the reconstruction's acceleration.
``friction`` is what a compensator adds to the command; ``f_model`` adds the measurement terms,
to compare with the measured force ``f``.

Two errors are reported: ``rms``, of this run (a zero-phase filter sees the future: fine offline,
and the number the identification's report states), and ``rms_causal``, of the same model driven
by the signal as a live loop has it (the logged velocity as logged, or the raw position).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from os import PathLike
from pathlib import Path

import numpy as np

from ._typing import FloatArray
from .data.reconstruction import Motion, describe, reconstruct
from .data.records import DataLike, MotionData, as_motion_data
from .data.signals import check_cutoff
from .errors import DataError
from .modelfile import ModelFile, ModelLike, Reconstruction, as_model_file
from .simulation import simulate, simulate_position
from .units import Units, check_units, unit_names

#: The columns of the prediction CSV, in order.
CSV_COLUMNS = ("t", "f", "f_model", "friction")
#: A model file that does not say how it reconstructs the motion (version 1) is driven by the
#: position through a zero-phase low-pass at this share of the Nyquist frequency.
LEGACY_CUTOFF = 0.1


@dataclass(frozen=True, eq=False)
class Prediction:
    """A model's force along a log: time ``t`` [s], the measured force ``f``, the model's whole
    force ``f_model`` (friction and measurement terms), its ``friction`` alone, and the motion it
    was driven by. ``rms`` is the RMS of ``f_model − f`` over every sample, ``rms_causal`` the
    same for the signal as a live loop has it; ``notes`` the warnings of the log and the run."""

    t: FloatArray
    f: FloatArray
    f_model: FloatArray
    friction: FloatArray
    x: FloatArray
    v: FloatArray
    rms: float
    rms_causal: float
    reconstruction: Reconstruction
    units: Units
    source: str
    notes: tuple[str, ...]

    @property
    def samples(self) -> int:
        return int(self.t.size)

    @property
    def dt(self) -> float:
        """The sampling step [s]."""
        return float((self.t[-1] - self.t[0]) / (self.t.size - 1))

    def summary(self) -> str:
        """A few lines: the log, the signal, the errors, the warnings."""
        names = unit_names(self.units)
        lines = [
            f"prediction of {self.source}: {self.samples} samples at dt = {self.dt:.6g} s ({self.units})",
            f"the model is driven by {describe(self.reconstruction)}",
            f"rms of f_model - f: {self.rms:.6g} {names.force} (driven as a live loop would be: "
            f"{self.rms_causal:.6g} {names.force}; the measured force's own rms: "
            f"{math.sqrt(float(np.mean(self.f**2))):.6g} {names.force})",
        ]
        lines += [f"warning: {note}" for note in self.notes]
        return "\n".join(lines)

    def to_dict(self) -> dict[str, object]:
        """The summary of ``predict --json``."""
        return {"rms": self.rms, "rms_causal": self.rms_causal, "samples": self.samples, "units": self.units,
                "reconstruction": self.reconstruction.to_dict(), "warnings": list(self.notes)}  # fmt: skip

    def to_csv(self, path: str | PathLike[str], force: bool = False) -> Path:
        """Writes the columns ``t,f,f_model,friction`` (a header line, then the numbers in full
        precision), atomically; an existing file is refused with
        :class:`~leuven_rt.errors.OutputError` unless ``force``."""
        from ._output import check_output, text_writer, write_files

        target = check_output(path, label="prediction CSV", force=force)
        rows = np.column_stack([getattr(self, name) for name in CSV_COLUMNS]).tolist()
        # repr: the shortest text that reads back as the same float.
        text = "\n".join([",".join(CSV_COLUMNS), *(",".join(map(repr, row)) for row in rows)]) + "\n"
        return write_files([(target, text_writer(text))])[0]

    def plot(self, path: str | PathLike[str], force: bool = False) -> Path:
        """A figure of the measured force against the model's over time, and of the error."""
        from ._output import check_output
        from ._plot import figure, save

        target = check_output(path, label="figure", force=force, image=True)
        names = unit_names(self.units)
        drawing, (top, bottom) = figure(2, 1, size=(12, 7), sharex=True)
        top.plot(self.t, self.f, linewidth=0.6, label="measured f")
        top.plot(self.t, self.f_model, linewidth=0.6, label="model f_model")
        top.set(ylabel=f"force [{names.force}]", title=f"{self.source}: measured and predicted force")
        bottom.plot(self.t, self.f_model - self.f, linewidth=0.5, color="C3")
        bottom.set(xlabel="time t [s]", ylabel=f"f_model − f [{names.force}]",
                   title=f"error: rms {self.rms:.4g} {names.force}")  # fmt: skip
        for axis in (top, bottom):
            axis.grid(alpha=0.3)
        top.legend(loc="upper right")
        drawing.tight_layout()
        return save(drawing, target, dpi=110)


def effective_reconstruction(
    model: ModelFile, record: MotionData, cutoff: float | None
) -> tuple[Reconstruction, tuple[str, ...]]:
    """The reconstruction ``predict`` drives ``model`` with on ``record``: the file's (version 1:
    the position at a tenth of the Nyquist frequency), its cutoff replaced by ``cutoff`` when
    given (the file's acceleration cutoff kept), the raw position where the file wants a velocity
    the log lacks (with a note)."""
    notes: tuple[str, ...] = ()
    chosen = model.reconstruction
    if chosen is None:
        chosen = Reconstruction("position", LEGACY_CUTOFF * 0.5 / record.dt)
    if chosen.source == "velocity" and record.v is None:
        notes = ("the model was identified on a logged velocity, and this log has no `v` column: "
                 "it is driven by the raw position",)  # fmt: skip
        # The acceleration's cutoff was chosen for the velocity's one difference, not the raw
        # position's two: the default's.
        chosen = Reconstruction("position")
    if cutoff is not None:
        chosen = replace(chosen, cutoff=check_cutoff(cutoff, record.dt, record.t.size))
    return chosen, notes


def model_forces(model: ModelFile, motion: Motion) -> tuple[FloatArray, FloatArray]:
    """The friction along ``motion`` (with the level and the position force: the run a
    compensator makes over the same signal) and the model's whole force, friction plus the
    measurement terms at the motion's acceleration."""
    level, force = model.level, model.position_force
    if motion.input == "velocity":
        placed = level is not None or force is not None
        x = motion.x if placed else None
        friction = simulate(model.friction, motion.v, motion.dt, x=x, level=level, position_force=force)
    else:
        friction = simulate_position(
            model.friction, motion.drive, motion.dt, level=level, position_force=force
        )
    return friction, friction + model.measurement_force(motion.a)


def predict(
    model: ModelLike,
    data: DataLike,
    *,
    columns: Mapping[str, str] | None = None,
    units: Units | None = None,
    cutoff: float | None = None,
) -> Prediction:
    """Runs ``model`` (a :class:`ModelFile`, a :class:`~leuven_rt.Params`, or a path to either
    file) along ``data`` (anything :func:`~leuven_rt.data.as_motion_data` takes; irregular time
    stamps are resampled) and returns the :class:`Prediction` (module documentation).

    ``columns``: the log's names for ``t``, ``x``, ``f``, ``v``. ``units``: the log's kind of axis,
    which must be the model's (default: the model's). ``cutoff``: the low-pass cutoff [Hz] of the
    reconstruction, in place of the file's.
    """
    chosen = as_model_file(model)
    kind = chosen.units if units is None else check_units(units, error=DataError)
    if kind != chosen.units:
        raise DataError(
            f"`units` is {kind!r}, but the model is {chosen.units!r}: a model fits one kind of axis",
            kind="units_mismatch",
            field="units",
            value=kind,
            expected=chosen.units,
        )
    record = as_motion_data(data, columns=columns, units=kind)
    reconstruction, notes = effective_reconstruction(chosen, record, cutoff)
    motion = reconstruct(record, reconstruction)
    friction, f_model = model_forces(chosen, motion)
    rms = math.sqrt(float(np.mean((f_model - record.f) ** 2)))
    live = replace(reconstruction, cutoff=None)
    if live == reconstruction:
        rms_causal = rms
    else:
        rms_causal = math.sqrt(
            float(np.mean((model_forces(chosen, reconstruct(record, live))[1] - record.f) ** 2))
        )
    return Prediction(t=record.t, f=record.f, f_model=f_model, friction=friction, x=motion.x, v=motion.v,
                      rms=rms,
                      rms_causal=rms_causal, reconstruction=reconstruction, units=kind, source=record.source,
                      notes=record.notes + notes)  # fmt: skip


__all__ = ["CSV_COLUMNS", "Prediction", "model_forces", "predict"]
