"""``predict``: what a model says a log's force should have been, next to what was measured.

The model is run along the log's own motion, the way a compensator in observer mode would run
it: the position is the zero-phase filtered position of the log (the derivative estimate the
identification uses, :func:`leuven_rt.data.estimate_derivatives`, with its default cutoff), and

    friction = factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x),    f_model = friction + offset + inertia·a,

where F is the plain model along x (:func:`leuven_rt.simulate_position`), v the model's own
velocity (v₀ = 0, vₖ = (xₖ − xₖ₋₁)/dt), factor(x) the position-dependent level (1 without one),
r(x) the position force (0 without one) and a the filtered acceleration. ``friction`` is what a
compensator adds to the command; ``f_model`` adds the measurement terms, to compare with the
measured force ``f``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from os import PathLike
from pathlib import Path

import numpy as np

from ._typing import FloatArray
from .data.records import DataLike, as_motion_data
from .data.signals import estimate_derivatives
from .errors import DataError
from .modelfile import ModelFile, ModelLike, as_model_file
from .simulation import simulate_position
from .units import Units, check_units, unit_names

#: The columns of the prediction CSV, in order.
CSV_COLUMNS = ("t", "f", "f_model", "friction")


@dataclass(frozen=True, eq=False)
class Prediction:
    """A model's force along a log: time ``t`` [s], the measured force ``f``, the model's whole
    force ``f_model`` (friction and measurement terms), its ``friction`` alone, and the position
    ``x`` fed to the model (a compensator in observer mode fed the same ``x`` gives ``friction``).
    ``rms`` is the RMS of ``f_model − f``; ``notes`` the warnings given when the log was loaded."""

    t: FloatArray
    f: FloatArray
    f_model: FloatArray
    friction: FloatArray
    x: FloatArray
    rms: float
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
        """A few lines: the log, the error, the warnings."""
        names = unit_names(self.units)
        lines = [
            f"prediction of {self.source}: {self.samples} samples at dt = {self.dt:.6g} s ({self.units})",
            f"rms of f_model - f: {self.rms:.6g} {names.force} "
            f"(the measured force's own rms: {float(np.sqrt(np.mean(self.f**2))):.6g} {names.force})",
        ]
        lines += [f"warning: {note}" for note in self.notes]
        return "\n".join(lines)

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


def predict(
    model: ModelLike,
    data: DataLike,
    *,
    columns: Mapping[str, str] | None = None,
    units: Units | None = None,
    cutoff: float | None = None,
) -> Prediction:
    """Runs ``model`` (a :class:`ModelFile`, a :class:`~leuven_rt.Params`, or a path to either
    file) along the motion of ``data`` (anything :func:`~leuven_rt.data.as_motion_data` takes;
    irregular time stamps are resampled) and returns the :class:`Prediction` (module
    documentation).

    ``columns``: the log's names for ``t``, ``x``, ``f``, ``v``. ``units``: the log's kind of axis,
    which must be the model's (default: the model's). ``cutoff``: the position filter's cutoff
    [Hz] (default a tenth of the Nyquist frequency, as for identification); one the record does
    not support is refused (:func:`leuven_rt.data.signals.check_cutoff`).
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
    derivatives = estimate_derivatives(record, cutoff)
    dt = record.dt
    x = derivatives.x
    friction, f_model = model_forces(chosen, x, derivatives.a, dt)
    rms = float(np.sqrt(np.mean((f_model - record.f) ** 2)))
    return Prediction(t=record.t, f=record.f, f_model=f_model, friction=friction, x=x, rms=rms, units=kind,
                      source=record.source, notes=record.notes)  # fmt: skip


def model_forces(model: ModelFile, x: FloatArray, a: FloatArray, dt: float) -> tuple[FloatArray, FloatArray]:
    """The friction along the filtered position ``x`` (with the level and the position force,
    docs/model.md#position-dependent-level: the run a compensator in observer mode makes over the
    same positions) and the model's whole force, friction plus the measurement terms at the
    acceleration ``a``."""
    friction = simulate_position(
        model.friction, x, dt, level=model.level, position_force=model.position_force
    )
    return friction, friction + model.measurement_force(a)


__all__ = ["CSV_COLUMNS", "Prediction", "model_forces", "predict"]
