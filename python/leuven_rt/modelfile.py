"""The versioned model file: a friction model with what a fit found beside it, in one JSON file.

A :class:`ModelFile` holds the friction model (:class:`~leuven_rt.Params`), its optional
position-dependent level (:class:`~leuven_rt.PositionLevel`), an optional force that depends on
the position alone (:class:`~leuven_rt.PositionForce`: cogging, gear mesh), the measurement terms
of the log it was fitted to (a constant force ``offset`` and an ``inertia`` times the
acceleration: they explain the measured force but are not friction, so a compensator ignores
them), the kind of axis (``units``), how the model's motion signal is made from a log
(:class:`Reconstruction`) and a free-form ``report`` of the fit, which loaders of the model
ignore.

Its JSON form is docs/data-and-reports.md#model-file. The file is read and written by the Rust
crate gms-file, the same reader the C library uses, so that Python and C accept and refuse
exactly the same texts; a refusal raises :class:`~leuven_rt.errors.ModelFileError` (a
:class:`~leuven_rt.errors.ParameterError`) naming the key path (``level.ripples[0].period``). A
plain parameter file (docs/parameters.md, no ``"format"`` key) loads as a model file with every
other key at its default, and version 1 files load as they are.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from os import PathLike, fspath
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._typing import FloatArray
from .errors import ParameterError, shown
from .level import PositionForce, PositionLevel
from .params import Params, _real
from .units import Units

#: The value of the ``"format"`` key that marks a model file (gms-file's).
FORMAT: str = _core.MODEL_FILE_FORMAT
#: The version this leuven-rt writes (it reads every version from 1 to this; gms-file's).
VERSION: int = _core.MODEL_FILE_VERSION
#: The columns a motion signal can be made from (:class:`Reconstruction`).
SOURCES = ("velocity", "position")

Source = Literal["velocity", "position"]


@dataclass(frozen=True)
class Reconstruction:
    """How the model's motion signal is made from a log, as identify chose it: the log's
    ``source`` column (``"velocity"``: ``v``; ``"position"``: ``x``) through a zero-phase
    4th-order Butterworth low-pass at ``cutoff`` Hz, or as logged (``cutoff=None``: the velocity
    as logged, the position's raw differences). The acceleration of the inertia term comes from
    the same column through a low-pass at ``acceleration_cutoff`` Hz (a key of version 3), or
    without one at the lower of ``cutoff`` and a tenth of the Nyquist frequency. A model file
    without a reconstruction uses the position through a low-pass at a tenth of the Nyquist
    frequency (version 1's way).

    The types are checked here; the cutoffs' rule (finite, > 0) when a :class:`ModelFile` holds
    them."""

    source: Source
    cutoff: float | None = None
    acceleration_cutoff: float | None = None

    def __post_init__(self) -> None:
        if self.source not in SOURCES:
            raise ParameterError(
                f"`reconstruction.source` must be one of {list(SOURCES)}, got {shown(self.source)!r:.80}",
                kind="invalid_choice",
                field="reconstruction.source",
                value=self.source,
                expected=list(SOURCES),
            )
        if self.cutoff is not None:
            object.__setattr__(self, "cutoff", _real("reconstruction.cutoff", self.cutoff))
        if self.acceleration_cutoff is not None:
            value = _real("reconstruction.acceleration_cutoff", self.acceleration_cutoff)
            object.__setattr__(self, "acceleration_cutoff", value)

    def to_dict(self) -> dict[str, Any]:
        """The file's ``reconstruction`` object (``acceleration_cutoff`` only where there is one,
        as gms-file writes it)."""
        out: dict[str, Any] = {"source": self.source, "cutoff": self.cutoff}
        if self.acceleration_cutoff is not None:
            out["acceleration_cutoff"] = self.acceleration_cutoff
        return out


def _object(value: Any, kind: type) -> Any:
    """``value`` as its JSON object when it is an instance of ``kind``, as given otherwise (a
    mapping, None, or something the reader refuses naming the key)."""
    if isinstance(value, kind) and isinstance(value, (PositionLevel, PositionForce, Reconstruction, Params)):
        return value.to_dict()
    return value


def _plain(value: Any, key: str) -> Any:
    """A copy of ``value`` made of JSON types only (dict with str keys, list, str, bool, None,
    int, float), refused naming ``key`` otherwise. Non-finite floats become ``None``, so that the
    file stays standard JSON that every parser reads."""
    if value is None or isinstance(value, (str, bool)):
        return value
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, Mapping):
        out: dict[str, Any] = {}
        for name, item in value.items():
            if isinstance(name, (int, np.integer)) and not isinstance(name, bool):
                name = str(int(name))  # as JSON writes it (e.g. the report's elements → RMS)
            if not isinstance(name, str):
                raise ParameterError(
                    f"`{key}` keys must be text, got {shown(name)!r:.80}",
                    kind="wrong_type",
                    field=key,
                    value=name,
                )
            out[name] = _plain(item, f"{key}.{name}")
        return out
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(item, f"{key}[{index}]") for index, item in enumerate(value)]
    raise ParameterError(
        f"`{key}` must hold JSON values only, got {type(value).__name__}: {shown(value)!r:.80}",
        kind="wrong_type",
        field=key,
        value=value,
    )


@dataclass(frozen=True, kw_only=True)
class ModelFile:
    """A friction model as a file holds it (module documentation): ``friction`` (a
    :class:`Params` or a mapping of its keys), ``level`` (a :class:`PositionLevel`, its JSON
    object, or ``None``), ``position_force`` (a :class:`~leuven_rt.PositionForce`, its JSON
    object, or ``None``), the measurement terms ``offset`` [N or N·m] and ``inertia`` [kg or kg·m²],
    ``units`` (``"linear"`` or ``"rotary"``), ``reconstruction`` (a :class:`Reconstruction`, its
    JSON object, or ``None``) and ``report`` (a JSON object, or ``None``; numpy values become
    Python ones, integer keys text, non-finite numbers ``None``).

    Everything is checked by the file's reader (gms-file), so that a ModelFile holds exactly
    what a file can: a refusal raises :class:`~leuven_rt.errors.ModelFileError` naming the key.
    """

    friction: Params
    level: PositionLevel | None = None
    position_force: PositionForce | None = None
    offset: float = 0.0
    inertia: float = 0.0
    units: Units = "linear"
    reconstruction: Reconstruction | None = None
    # A report is a free-form mapping: compared, but not hashed (a dict is not hashable).
    report: Mapping[str, Any] | None = field(default=None, hash=False)

    def __post_init__(self) -> None:
        if not isinstance(self.friction, (Params, Mapping)):
            raise ParameterError(
                "`friction` must be a leuven_rt.Params or a mapping of its keys, "
                f"got {type(self.friction).__name__}",
                kind="wrong_type",
                field="friction",
                value=self.friction,
            )
        if self.report is not None and not isinstance(self.report, Mapping):
            raise ParameterError(
                f"`report` must be a JSON object or None, got {shown(self.report)!r:.80}",
                kind="wrong_type",
                field="report",
                value=self.report,
            )
        given = {
            "format": FORMAT,
            "version": VERSION,
            "units": self.units,
            "friction": _object(self.friction, Params),
            "level": _object(self.level, PositionLevel),
            "position_force": _object(self.position_force, PositionForce),
            "measurement": {"offset": self.offset, "inertia": self.inertia},
            "reconstruction": _object(self.reconstruction, Reconstruction),
            "report": None if self.report is None else _plain(self.report, "report"),
        }
        # gms-file reads the whole object as it would a file, and checks every value.
        checked = _core.model_file_from_object(given)
        for name, value in _fields(checked, self.friction).items():
            object.__setattr__(self, name, value)

    def measurement_force(self, a: ArrayLike) -> FloatArray:
        """The measurement terms for the acceleration ``a`` [m/s² or rad/s²]: offset + inertia·a,
        in N (linear) or N·m (rotary). Not friction: a compensator leaves it out."""
        acceleration = np.asarray(a, dtype=np.float64)
        out: FloatArray = self.offset + self.inertia * acceleration
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of the file (docs/data-and-reports.md#model-file), as plain Python
        values, in the current version."""
        return {
            "format": FORMAT,
            "version": VERSION,
            "units": self.units,
            "friction": self.friction.to_dict(),
            "level": None if self.level is None else self.level.to_dict(),
            "position_force": None if self.position_force is None else self.position_force.to_dict(),
            "measurement": {"offset": self.offset, "inertia": self.inertia},
            "reconstruction": _object(self.reconstruction, Reconstruction),
            "report": None if self.report is None else dict(self.report),
        }

    @classmethod
    def from_dict(cls, mapping: Mapping[str, Any]) -> ModelFile:
        """Reads a model file's object (version 1 to 3), or a plain parameter file's (no
        ``"format"`` key), with exactly the rules of :meth:`from_json`: what JSON cannot hold (a
        NaN, a key that is not text, an object of another type) is refused too."""
        return cls._from_checked(_core.model_file_from_object(mapping))

    def to_json(self) -> str:
        """The file's text (indented JSON, without the final newline), written by gms-file."""
        return _core.model_file_to_json(self.to_dict())

    @classmethod
    def from_json(cls, text: str) -> ModelFile:
        """Parses the text of a model file (version 1 to 3) or a plain parameter file."""
        if not isinstance(text, str):
            raise ParameterError(
                f"a model file's text must be a str, got {type(text).__name__}",
                kind="wrong_type",
                field="text",
                value=text,
            )
        return cls._from_checked(_core.model_file_from_json(text))

    @classmethod
    def load(cls, path: str | PathLike[str]) -> ModelFile:
        """Reads a model file or a plain parameter file (a regular file of at most 1 MiB, UTF-8
        JSON); errors name the file."""
        return cls._from_checked(_core.model_file_load(fspath(path)))

    @classmethod
    def _from_checked(cls, checked: Mapping[str, Any]) -> ModelFile:
        """A ModelFile of the plain values gms-file returned."""
        return cls(**_fields(checked, None))

    def save(
        self,
        path: str | PathLike[str],
        *,
        force: bool = False,
        inputs: Iterable[str | PathLike[str]] = (),
    ) -> None:
        """Writes the file atomically (docs/errors.md#output-files): an existing file is refused
        with :class:`~leuven_rt.errors.OutputError` unless ``force``, and one of ``inputs`` (the
        files the model came from) even then."""
        from ._output import check_output, write_text

        target = check_output(path, label="model file", inputs=inputs, force=force)
        write_text(target, self.to_json() + "\n")


def _fields(checked: Mapping[str, Any], friction: Params | Mapping[str, Any] | None) -> dict[str, Any]:
    """The fields of a :class:`ModelFile` from the plain values gms-file returned; ``friction``
    is kept when it is already the :class:`Params` of those values."""
    parameters = dict(checked["friction"])
    if not (isinstance(friction, Params) and friction.to_dict() == parameters):
        friction = Params(**parameters)
    level, position_force = checked["level"], checked["position_force"]
    reconstruction = checked["reconstruction"]
    return {
        "friction": friction,
        "level": None if level is None else PositionLevel.from_dict(level),
        "position_force": None if position_force is None else PositionForce.from_dict(position_force),
        "offset": float(checked["measurement"]["offset"]),
        "inertia": float(checked["measurement"]["inertia"]),
        "units": checked["units"],
        "reconstruction": None if reconstruction is None else Reconstruction(**reconstruction),
        "report": checked["report"],
    }


#: A model: a :class:`ModelFile`, a :class:`Params` or a mapping of a file's object, or a path to
#: a model file or a parameter file.
ModelLike = ModelFile | Params | Mapping[str, Any] | str | PathLike[str]


def as_model_file(model: ModelLike) -> ModelFile:
    """Accepts a :class:`ModelFile`, a :class:`Params`, a mapping (a model file's or a parameter
    file's object) or a path to either file."""
    if isinstance(model, ModelFile):
        return model
    if isinstance(model, Params):
        return ModelFile(friction=model)
    if isinstance(model, Mapping):
        return ModelFile.from_dict(model)
    if isinstance(model, (str, PathLike)):
        return ModelFile.load(model)
    raise ParameterError(
        "`model` must be a ModelFile, a Params, a mapping or a path to a model file, "
        f"got {type(model).__name__}",
        kind="wrong_type",
        field="model",
        value=model,
    )


__all__ = [
    "FORMAT",
    "SOURCES",
    "VERSION",
    "ModelFile",
    "ModelLike",
    "Reconstruction",
    "as_model_file",
]
