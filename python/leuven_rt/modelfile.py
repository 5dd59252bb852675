"""The versioned model file: a friction model with what a fit found beside it, in one JSON file.

A :class:`ModelFile` holds the friction model (:class:`~leuven_rt.Params`), its optional
position-dependent level (:class:`~leuven_rt.level.PositionLevel`), the measurement terms of the
log it was fitted to (a constant force ``offset`` and an ``inertia`` times the acceleration: they
explain the measured force but are not friction, so a compensator ignores them), the kind of
axis (``units``) and a free-form ``report`` of the fit, which loaders of the model ignore.

Its JSON form (docs/data-and-reports.md#model-file)::

    {"format": "leuven-rt model", "version": 1, "units": "linear",
     "friction": {...the parameter file...},
     "level": null | {"middle": ..., "half_stroke": ..., "trend": [t1, t2],
                      "ripples": [{"period": ..., "cos": [...], "sin": [...]}]},
     "measurement": {"offset": ..., "inertia": ...},
     "report": {...} | null}

A plain parameter file (docs/parameters.md, no ``"format"`` key) loads as a model file with no
level and no measurement terms, so every file written before the model file keeps working.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from os import PathLike, fspath
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ._typing import FloatArray
from .errors import ParameterError, data_of, shown
from .level import MAX_HARMONICS, MAX_RIPPLES, PositionLevel, Ripple
from .params import Params, _real
from .units import Units, check_units

#: The value of the ``"format"`` key that marks a model file.
FORMAT = "leuven-rt model"
#: The version this leuven-rt writes and reads.
VERSION = 1
#: The keys of a model file; ``format``, ``version`` and ``friction`` are required.
KEYS = ("format", "version", "units", "friction", "level", "measurement", "report")
LEVEL_KEYS = ("middle", "half_stroke", "trend", "ripples")
RIPPLE_KEYS = ("period", "cos", "sin")
MEASUREMENT_KEYS = ("offset", "inertia")


def _finite(key: str, value: Any) -> float:
    number = _real(key, value)
    if not math.isfinite(number):
        raise ParameterError(
            f"`{key}` must be finite, got {number!r}", kind="not_finite_value", field=key, value=number
        )
    return number


def _mapping(key: str, value: Any, keys: Sequence[str], required: Sequence[str] = ()) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise ParameterError(
            f"`{key}` must be an object with keys among {list(keys)}, got {shown(value)!r:.80}",
            kind="wrong_type",
            field=key,
            value=value,
        )
    unknown = sorted((name for name in value if name not in keys), key=repr)
    if unknown:
        raise ParameterError(
            f"unknown keys {unknown} in `{key}`: expected keys among {list(keys)}",
            kind="unknown_key",
            field=f"{key}.{unknown[0]}",
            expected=list(keys),
            got=sorted(value, key=repr),
        )
    missing = [name for name in required if name not in value]
    if missing:
        raise ParameterError(
            f"`{key}` lacks the keys {missing}",
            kind="missing_key",
            field=f"{key}.{missing[0]}",
            expected=list(required),
            got=sorted(value, key=repr),
        )
    return value


def _finite_list(key: str, values: Any) -> tuple[float, ...]:
    if isinstance(values, (str, bytes, Mapping)) or not isinstance(values, (Sequence, np.ndarray)):
        raise ParameterError(
            f"`{key}` must be a list of real numbers, got {shown(values)!r:.80}",
            kind="not_real",
            field=key,
            value=values,
        )
    return tuple(_finite(f"{key}[{index}]", value) for index, value in enumerate(values))


def _ripple(key: str, value: Any) -> Ripple:
    if isinstance(value, Ripple):
        value = {"period": value.period, "cos": value.cos, "sin": value.sin}
    given = _mapping(key, value, RIPPLE_KEYS, RIPPLE_KEYS)
    period = _finite(f"{key}.period", given["period"])
    if period <= 0.0:
        raise ParameterError(
            f"`{key}.period` must be > 0, got {period!r}",
            kind="ripple_period",
            field=f"{key}.period",
            value=period,
        )
    cos, sin = _finite_list(f"{key}.cos", given["cos"]), _finite_list(f"{key}.sin", given["sin"])
    if not 1 <= len(cos) <= MAX_HARMONICS or len(sin) != len(cos):
        raise ParameterError(
            f"`{key}.cos` and `{key}.sin` must have the same length, 1 to {MAX_HARMONICS} harmonics, "
            f"got {len(cos)} and {len(sin)}",
            kind="harmonic_lengths",
            field=f"{key}.sin",
            expected=len(cos),
            got=len(sin),
        )
    return Ripple(period=period, cos=cos, sin=sin)


def as_level(value: Any, key: str = "level") -> PositionLevel | None:
    """A :class:`PositionLevel` (or ``None``) from itself or from its JSON object; the types and
    the shape are checked here, naming the key (``level.ripples[0].period``, …)."""
    if value is None:
        return None
    if isinstance(value, PositionLevel):
        value = {"middle": value.middle, "half_stroke": value.half_stroke, "trend": value.trend,
                 "ripples": value.ripples}  # fmt: skip
    given = _mapping(key, value, LEVEL_KEYS)
    middle = _finite(f"{key}.middle", given.get("middle", 0.0))
    half_stroke = _finite(f"{key}.half_stroke", given.get("half_stroke", 1.0))
    if half_stroke <= 0.0:
        raise ParameterError(
            f"`{key}.half_stroke` must be > 0, got {half_stroke!r}",
            kind="not_positive",
            field=f"{key}.half_stroke",
            value=half_stroke,
        )
    trend = _finite_list(f"{key}.trend", given.get("trend", (0.0, 0.0)))
    if len(trend) != 2:
        raise ParameterError(
            f"`{key}.trend` must hold 2 numbers (t1, t2), got {len(trend)}",
            kind="wrong_length",
            field=f"{key}.trend",
            expected=2,
            got=len(trend),
        )
    ripples = given.get("ripples", ())
    if isinstance(ripples, (str, bytes, Mapping)) or not isinstance(ripples, Sequence):
        raise ParameterError(
            f"`{key}.ripples` must be a list of ripples, got {shown(ripples)!r:.80}",
            kind="wrong_type",
            field=f"{key}.ripples",
            value=ripples,
        )
    if len(ripples) > MAX_RIPPLES:
        raise ParameterError(
            f"`{key}.ripples` must hold at most {MAX_RIPPLES} ripples, got {len(ripples)}",
            kind="too_many_ripples",
            field=f"{key}.ripples",
            value=len(ripples),
            bound=MAX_RIPPLES,
        )
    return PositionLevel(
        middle=middle,
        half_stroke=half_stroke,
        trend=(trend[0], trend[1]),
        ripples=tuple(_ripple(f"{key}.ripples[{index}]", ripple) for index, ripple in enumerate(ripples)),
    )


def _level_dict(level: PositionLevel) -> dict[str, Any]:
    return {
        "middle": level.middle,
        "half_stroke": level.half_stroke,
        "trend": list(level.trend),
        "ripples": [
            {"period": ripple.period, "cos": list(ripple.cos), "sin": list(ripple.sin)}
            for ripple in level.ripples
        ],
    }


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
    object, or ``None``), the measurement terms ``offset`` [N or N·m] and ``inertia`` [kg or
    kg·m²], ``units`` (``"linear"`` or ``"rotary"``) and ``report`` (a JSON object, or ``None``).

    Bad values raise :class:`ParameterError` naming the key.
    """

    friction: Params
    level: PositionLevel | None = None
    offset: float = 0.0
    inertia: float = 0.0
    units: Units = "linear"
    # A report is a free-form mapping: compared, but not hashed (a dict is not hashable).
    report: Mapping[str, Any] | None = field(default=None, hash=False)

    def __post_init__(self) -> None:
        friction = self.friction
        if isinstance(friction, Mapping):
            friction = _friction(friction)
        elif not isinstance(friction, Params):
            raise ParameterError(
                "`friction` must be a leuven_rt.Params or a mapping of its keys, "
                f"got {type(friction).__name__}",
                kind="wrong_type",
                field="friction",
                value=friction,
            )
        object.__setattr__(self, "friction", friction)
        object.__setattr__(self, "level", as_level(self.level))
        object.__setattr__(self, "offset", _finite("measurement.offset", self.offset))
        object.__setattr__(self, "inertia", _finite("measurement.inertia", self.inertia))
        object.__setattr__(self, "units", check_units(self.units, error=ParameterError))
        if self.report is not None:
            if not isinstance(self.report, Mapping):
                raise ParameterError(
                    f"`report` must be a JSON object or None, got {shown(self.report)!r:.80}",
                    kind="wrong_type",
                    field="report",
                    value=self.report,
                )
            object.__setattr__(self, "report", _plain(self.report, "report"))

    def measurement_force(self, a: ArrayLike) -> FloatArray:
        """The measurement terms for the acceleration ``a`` [m/s² or rad/s²]: offset + inertia·a,
        in N (linear) or N·m (rotary). Not friction: a compensator leaves it out."""
        acceleration = np.asarray(a, dtype=np.float64)
        out: FloatArray = self.offset + self.inertia * acceleration
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of the file (module documentation), as plain Python values."""
        return {
            "format": FORMAT,
            "version": VERSION,
            "units": self.units,
            "friction": self.friction.to_dict(),
            "level": None if self.level is None else _level_dict(self.level),
            "measurement": {"offset": self.offset, "inertia": self.inertia},
            "report": None if self.report is None else _plain(self.report, "report"),
        }

    @classmethod
    def from_dict(cls, mapping: Mapping[str, Any]) -> ModelFile:
        """Builds from a model file's object, or from a plain parameter file's (no ``"format"``
        key: no level, no measurement terms). A wrong format, another version, an unknown or
        missing key, or a bad value raises :class:`ParameterError` naming the key."""
        if not isinstance(mapping, Mapping):
            raise ParameterError(
                f"a model file must be a JSON object, got {type(mapping).__name__}",
                kind="wrong_type",
                value=mapping,
            )
        if "format" not in mapping:  # a parameter file of before the model file
            return cls(friction=_friction(mapping))
        if mapping["format"] != FORMAT:
            raise ParameterError(
                f"`format` must be {FORMAT!r}, got {shown(mapping['format'])!r:.80}",
                kind="invalid_choice",
                field="format",
                value=mapping["format"],
                expected=FORMAT,
            )
        if "version" not in mapping:
            raise ParameterError(
                f"missing key `version`: expected {VERSION}",
                kind="missing_key",
                field="version",
                expected=VERSION,
            )
        version = mapping["version"]
        if isinstance(version, int) and not isinstance(version, bool) and version > VERSION:
            raise ParameterError(
                f"`version` must be {VERSION}, got {version}: the file was written by a newer leuven-rt; "
                "upgrade leuven-rt to read it",
                kind="invalid_choice",
                field="version",
                value=version,
                expected=VERSION,
            )
        if isinstance(version, bool) or version != VERSION or not isinstance(version, int):
            raise ParameterError(
                f"`version` must be {VERSION}, got {shown(version)!r:.80}",
                kind="invalid_choice",
                field="version",
                value=version,
                expected=VERSION,
            )
        unknown = sorted((key for key in mapping if key not in KEYS), key=repr)
        if unknown:
            raise ParameterError(
                f"unknown keys {unknown} in the model file: expected keys among {list(KEYS)}",
                kind="unknown_key",
                field=str(unknown[0]),
                expected=list(KEYS),
                got=sorted(mapping, key=repr),
            )
        if "friction" not in mapping:
            raise ParameterError(
                "missing key `friction`: a model file must hold the friction parameters",
                kind="missing_key",
                field="friction",
            )
        measurement = _mapping("measurement", mapping.get("measurement", {}), MEASUREMENT_KEYS)
        report = mapping.get("report")
        if report is not None and not isinstance(report, Mapping):
            raise ParameterError(
                f"`report` must be a JSON object or null, got {shown(report)!r:.80}",
                kind="wrong_type",
                field="report",
                value=report,
            )
        return cls(
            friction=_friction(mapping["friction"]),
            level=as_level(mapping.get("level")),
            offset=measurement.get("offset", 0.0),
            inertia=measurement.get("inertia", 0.0),
            units=check_units(mapping.get("units", "linear"), error=ParameterError),
            report=report,
        )

    def to_json(self) -> str:
        """The file's text (indented JSON, without the final newline)."""
        import json  # here, not at the top: `import leuven_rt` stays light

        return json.dumps(self.to_dict(), indent=2, allow_nan=False)

    @classmethod
    def from_json(cls, text: str) -> ModelFile:
        """Parses the text of a model file or a plain parameter file."""
        import json

        try:
            mapping = json.loads(text)
        except (TypeError, json.JSONDecodeError, UnicodeDecodeError) as error:
            raise ParameterError(
                f"a model file must be JSON text of an object: {error}", kind="not_json"
            ) from None
        except RecursionError:
            raise ParameterError(
                "a model file must be JSON text of an object: nested too deeply", kind="not_json"
            ) from None
        except ValueError as error:  # e.g. an integer of more digits than Python converts
            raise ParameterError(
                f"a model file must be JSON text of an object: {error}", kind="not_json"
            ) from None
        return cls.from_dict(mapping)

    @classmethod
    def load(cls, path: str | PathLike[str]) -> ModelFile:
        """Reads a model file, or a plain parameter file (UTF-8 JSON); errors name the file."""
        try:
            with open(path, encoding="utf-8") as file:
                text = file.read()
        except UnicodeDecodeError as error:
            raise ParameterError(
                f"model file {path} is not UTF-8 text: {error}", kind="not_text", value=fspath(path)
            ) from None
        except OSError as error:
            raise ParameterError(
                f"cannot read model file {path}: {error.strerror or error}",
                kind="unreadable_file",
                value=fspath(path),
            ) from None
        try:
            return cls.from_json(text)
        except ParameterError as error:
            raise ParameterError(f"{path}: {error}", **data_of(error)) from None

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


def _friction(mapping: Any) -> Params:
    """The friction parameters of a model file, with ``friction`` in the message of a refusal."""
    if not isinstance(mapping, Mapping):
        raise ParameterError(
            f"`friction` must be an object of parameters, got {shown(mapping)!r:.80}",
            kind="wrong_type",
            field="friction",
            value=mapping,
        )
    try:
        return Params.from_dict(mapping)
    except ParameterError as error:
        located = {"field": f"friction.{error.field}"} if error.field is not None else {}
        raise ParameterError(f"friction: {error}", **{**data_of(error), **located}) from None


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


__all__ = ["FORMAT", "VERSION", "ModelFile", "ModelLike", "as_level", "as_model_file"]
