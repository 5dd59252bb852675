"""Measured motion data: loading (CSV of docs/data-and-reports.md#measured-data, EMPS .mat files),
validation, resampling and the zero-phase derivative estimates that every fit works from.

Bad data is refused once, here, with a :class:`DataError` naming the column; the fitting modules
can then assume uniformly sampled, finite, increasing, plausibly scaled signals.

Non-uniform sampling: time stamps that wander by more than :data:`UNIFORM_TOLERANCE` of the
median step (robot logs stamped to the millisecond) are interpolated (linearly) onto a uniform
grid at the median step, with a :class:`ResamplingWarning`; a step longer than :data:`MAX_GAP`
median steps (and than :data:`MIN_GAP`) is a gap in the log and is refused, since interpolating
across it would invent the motion in between.

Logs as users have them: ``columns`` maps the file's own column names onto ``t``, ``x``, ``f``,
``v``; header names may carry spaces, and empty trailing columns (rows ending in ``,,``) are
dropped. Values that load but look like other units (time in milliseconds, a linear stroke in
millimetres, an angle in degrees) give a :class:`UnitsWarning`. Every warning of the loader is
also kept, as text, in :attr:`MotionData.notes`, so that reports can carry it.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from os import PathLike
from pathlib import Path
from typing import Any, Union

import numpy as np
import scipy.io
from numpy.typing import ArrayLike

from .._checks import real_array
from .._typing import FloatArray
from ..errors import DataError, ResamplingWarning, UnitsWarning, data_of, shown
from ..units import Units, check_units, unit_names

#: Fewer samples than this cannot be filtered, split into training and held-out parts, and fitted.
MIN_SAMPLES = 200
#: Relative wander of the sampling step tolerated as uniform (EMPS: 4e-5; robot logs stamped to
#: the millisecond wander by far more, and are resampled).
UNIFORM_TOLERANCE = 1e-2
#: A step longer than this many median steps is a gap: refused rather than interpolated.
MAX_GAP = 10.0
#: ... unless it is no longer than this [s]: robot controllers log at steps of 1 to 20 ms, so a
#: 20 ms step in a log of mostly 1 ms steps is the controller's rhythm, not a hole in the log.
MIN_GAP = 0.02
#: Plausibility bounds of SI data; values beyond them are almost surely in other units.
MAX_FORCE = 1e7  # N
MAX_POSITION = 1e3  # m
MAX_VELOCITY = 1e3  # m/s
STEP_RANGE = (1e-7, 1.0)  # s
#: Plausibility warnings (UnitsWarning): a linear stroke beyond this looks like millimetres [m];
#: an angle beyond this looks like degrees [rad]; a record longer than this looks like time in
#: milliseconds [s] (as does a median step of at least MS_STEP with whole-number steps).
MAX_LINEAR_STROKE = 5.0
MAX_ANGLE = 100.0
MAX_DURATION = 86_400.0
MS_STEP = 0.5
#: The names of a log's columns, in order; ``v`` is optional.
ROLES = ("t", "x", "f", "v")


@dataclass(frozen=True, eq=False)
class MotionData:
    """A uniformly sampled log: time ``t`` [s], position ``x`` [m or rad], force ``f`` [N or N·m]
    to be explained and, where measured, velocity ``v`` [m/s or rad/s].

    ``units`` says which (``"linear"`` or ``"rotary"``); ``notes`` holds the text of every
    warning given when the log was loaded (resampling, units that look wrong), for reports.
    Construction validates everything (see :func:`check_columns`); use :func:`as_motion_data`
    to load files or to resample non-uniform time stamps.
    """

    t: FloatArray
    x: FloatArray
    f: FloatArray
    v: FloatArray | None = None
    source: str = "arrays"
    units: Units = "linear"
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "units", check_units(self.units, error=DataError))
        notes: Any = self.notes  # typed as a tuple, but any value may come
        if not isinstance(notes, (list, tuple)) or not all(isinstance(note, str) for note in notes):
            raise DataError(
                f"`notes` must be a sequence of str, got {shown(notes)!r:.80}",
                kind="wrong_type",
                field="notes",
                value=notes,
            )
        object.__setattr__(self, "notes", tuple(notes))
        columns = {"t": self.t, "x": self.x, "f": self.f}
        if self.v is not None:
            columns["v"] = self.v
        checked = check_columns(columns, units=self.units)
        if not is_uniform(checked["t"]):
            raise DataError(
                f"`t` must be uniformly sampled (steps within {UNIFORM_TOLERANCE:g} of the median), "
                f"got steps from {np.min(np.diff(checked['t'])):g} to {np.max(np.diff(checked['t'])):g} s; "
                "as_motion_data resamples such data",
                kind="not_uniform",
                field="t",
                bound=UNIFORM_TOLERANCE,
            )
        for name, values in checked.items():
            values.setflags(write=False)
            object.__setattr__(self, name, values)

    @classmethod
    def _from_checked(
        cls,
        checked: Mapping[str, FloatArray],
        source: str,
        units: Units = "linear",
        notes: tuple[str, ...] = (),
    ) -> MotionData:
        """A record of columns that :func:`check_columns` passed and that are uniformly sampled,
        taken as they are: a log validated on load is not validated again."""
        record = object.__new__(cls)
        object.__setattr__(record, "v", None)
        object.__setattr__(record, "source", source)
        object.__setattr__(record, "units", units)
        object.__setattr__(record, "notes", notes)
        for name, values in checked.items():
            values.setflags(write=False)
            object.__setattr__(record, name, values)
        return record

    @property
    def samples(self) -> int:
        return int(self.t.size)

    @property
    def dt(self) -> float:
        """The sampling step [s] (mean over the record)."""
        return float((self.t[-1] - self.t[0]) / (self.t.size - 1))

    def slice(self, start: int, stop: int) -> MotionData:
        """Samples ``start:stop`` as a new record."""
        v = None if self.v is None else self.v[start:stop]
        return MotionData(self.t[start:stop], self.x[start:stop], self.f[start:stop], v, self.source,
                          self.units, self.notes)  # fmt: skip


#: A log: a :class:`MotionData`, a path to a ``.csv`` or EMPS ``.mat`` file, or a mapping of
#: the columns ``t``, ``x``, ``f`` (and optionally ``v``).
DataLike = Union[MotionData, str, "PathLike[str]", Mapping[str, ArrayLike]]


def _column(name: str, values: ArrayLike) -> FloatArray:
    raw = real_array(values, name, DataError, label=f"column `{name}`")
    array = np.array(raw, dtype=np.float64)  # a copy of its own: the record is made read-only
    if array.ndim == 2 and 1 in array.shape:  # MATLAB stores vectors as (T, 1)
        array = array.ravel()
    if array.ndim != 1:
        raise DataError(
            f"column `{name}` must be one-dimensional, got shape {array.shape}",
            kind="shape",
            field=name,
            expected="(T,)",
            got=array.shape,
        )
    return array


def check_columns(columns: Mapping[str, ArrayLike], units: Units = "linear") -> dict[str, FloatArray]:
    """Checks and converts the columns ``t``, ``x``, ``f`` (and ``v`` when present); ``units``
    names the units in the messages.

    Refuses with :class:`DataError`: missing columns; columns of different lengths; fewer than
    :data:`MIN_SAMPLES` samples; NaN or infinite values (naming the first); time that does not
    strictly increase; a step outside :data:`STEP_RANGE`; forces, positions or velocities beyond
    the plausibility bounds of SI units; a position that never changes.
    """
    names = unit_names(units)
    missing = [name for name in ("t", "x", "f") if name not in columns]
    if missing:
        raise DataError(
            f"missing columns {missing}: expected `t` [s], `x` [{names.position}], `f` [{names.force}] "
            f"and optionally `v` [{names.velocity}], got columns {sorted(columns)}",
            kind="missing_column",
            field=missing[0],
            expected=["t", "x", "f"],
            got=sorted(columns),
        )
    arrays = {name: _column(name, columns[name]) for name in ("t", "x", "f", "v") if name in columns}
    lengths = {name: array.size for name, array in arrays.items()}
    if len(set(lengths.values())) != 1:
        differing = next(name for name, length in lengths.items() if length != lengths["t"])
        raise DataError(
            f"columns must have the same length, got lengths {lengths}",
            kind="input_length_mismatch",
            field=differing,
            expected=lengths["t"],
            got=lengths[differing],
        )
    samples = lengths["t"]
    if samples < MIN_SAMPLES:
        raise DataError(
            f"too few samples: need at least {MIN_SAMPLES}, got {samples}",
            kind="too_few",
            value=samples,
            bound=MIN_SAMPLES,
        )
    for name, array in arrays.items():
        finite = np.isfinite(array)
        if not finite.all():
            index = int(np.argmin(finite))
            value = float(array[index])
            raise DataError(
                f"column `{name}` must be finite, got {value} at sample {index}",
                kind="not_finite",
                field=name,
                value=value,
                sample=index,
            )
    steps = np.diff(arrays["t"])
    if not (steps > 0).all():
        index = int(np.argmin(steps > 0))
        before, after = float(arrays["t"][index]), float(arrays["t"][index + 1])
        raise DataError(
            f"`t` must strictly increase, got t[{index}] = {before!r} followed by t[{index + 1}] = {after!r}",
            kind="not_increasing",
            field="t",
            value=after,
            bound=before,
            sample=index + 1,
        )
    step = float(np.median(steps))
    if not STEP_RANGE[0] <= step <= STEP_RANGE[1]:
        raise DataError(
            f"the sampling step of `t` must be between {STEP_RANGE[0]:g} and {STEP_RANGE[1]:g} s, "
            f"got {step:g}: is `t` in seconds?",
            kind="implausible_units",
            field="t",
            value=step,
            bound=STEP_RANGE[0] if step < STEP_RANGE[0] else STEP_RANGE[1],
        )
    bounds = {"f": (MAX_FORCE, names.force), "x": (MAX_POSITION, names.position),
              "v": (MAX_VELOCITY, names.velocity)}  # fmt: skip
    for name, (bound, unit) in bounds.items():
        if name in arrays:
            largest = float(np.max(np.abs(arrays[name])))
            if largest > bound:
                raise DataError(
                    f"column `{name}` reaches {largest:g} {unit}, beyond {bound:g} {unit}: "
                    f"expected SI units ({unit})",
                    kind="implausible_units",
                    field=name,
                    value=largest,
                    bound=bound,
                )
    speed = float(np.max(np.abs(np.diff(arrays["x"]))) / step)
    if speed > MAX_VELOCITY:
        raise DataError(
            f"`x` moves at up to {speed:g} {names.velocity} between samples, beyond {MAX_VELOCITY:g} "
            f"{names.velocity}: expected `x` in {names.position} and `t` in s",
            kind="implausible_units",
            field="x",
            value=speed,
            bound=MAX_VELOCITY,
        )
    if np.ptp(arrays["x"]) == 0.0:
        raise DataError(
            "`x` never changes: there is no motion to identify friction from", kind="no_motion", field="x"
        )
    return arrays


def is_uniform(t: FloatArray) -> bool:
    """Whether every step is within :data:`UNIFORM_TOLERANCE` of the median step."""
    steps = np.diff(t)
    median = np.median(steps)
    return bool(np.max(np.abs(steps - median)) <= UNIFORM_TOLERANCE * median)


def resample_uniform(columns: Mapping[str, FloatArray]) -> tuple[dict[str, FloatArray], str]:
    """Linear interpolation of every column onto a uniform grid at the median step; returns the
    columns and the text of the :class:`ResamplingWarning` it issues. A gap longer than
    :data:`MAX_GAP` median steps (and longer than :data:`MIN_GAP`) is refused."""
    t = columns["t"]
    steps = np.diff(t)
    step = float(np.median(steps))
    longest = float(np.max(steps))
    # The stamps' own rounding (a 20 ms step of rounded stamps comes out as 0.020000000000000018)
    # must not turn the limit into a refusal.
    if longest > max(MAX_GAP * step, MIN_GAP) * (1.0 + 1e-9):
        index = int(np.argmax(steps))
        raise DataError(
            f"`t` has a gap of {longest:g} s after sample {index} ({longest / step:.1f} median steps): "
            f"expected steps within {MAX_GAP:g} median steps (or {MIN_GAP:g} s); split the log at the gap",
            kind="gap",
            field="t",
            value=longest,
            bound=max(MAX_GAP * step, MIN_GAP),
            sample=index,
        )
    grid = t[0] + step * np.arange(int(np.floor((t[-1] - t[0]) / step + 1e-9)) + 1)
    note = (
        f"`t` is not uniformly sampled (steps from {np.min(steps):g} to {longest:g} s, more than "
        f"{UNIFORM_TOLERANCE:.0%} from the median): resampled linearly onto a uniform grid with step "
        f"{step:g} s ({grid.size} samples)"
    )
    warnings.warn(note, ResamplingWarning, stacklevel=3)
    resampled = {
        name: (grid if name == "t" else np.interp(grid, t, values)) for name, values in columns.items()
    }
    return resampled, note


def plausibility_notes(
    columns: Mapping[str, FloatArray], units: Units, names: Mapping[str, str] | None = None
) -> list[str]:
    """Texts of the :class:`UnitsWarning` for checked columns that look like other units (time
    in milliseconds, a linear stroke in millimetres, an angle in degrees); ``names`` gives the
    file's name of each column, for the message. Warns with each; the data is left as it is."""
    names = names or {}

    def label(role: str) -> str:
        source = names.get(role, role)
        return f"column `{role}`" if source == role else f"column `{role}` (`{source}` in the file)"

    notes: list[str] = []
    t = columns["t"]
    steps = np.diff(t)
    step = float(np.median(steps))
    duration = float(t[-1] - t[0])
    if step >= MS_STEP and bool(np.all(steps == np.round(steps))):
        notes.append(
            f"{label('t')} steps by whole numbers (median step {step:g}): this looks like time in "
            "milliseconds; expected seconds"
        )
    elif duration > MAX_DURATION:
        notes.append(
            f"{label('t')} spans {duration:g} s, more than a day: this looks like time in milliseconds "
            "(or a clock of another unit); expected seconds"
        )
    x = columns["x"]
    if units == "linear" and float(np.ptp(x)) > MAX_LINEAR_STROKE:
        notes.append(
            f"{label('x')} spans {float(np.ptp(x)):g} m, a linear stroke beyond {MAX_LINEAR_STROKE:g} m: "
            "this looks like millimetres; expected metres (or units='rotary' for an angle in rad)"
        )
    if units == "rotary" and float(np.max(np.abs(x))) > MAX_ANGLE:
        notes.append(
            f"{label('x')} reaches {float(np.max(np.abs(x))):g} rad, beyond ±{MAX_ANGLE:g} rad: this looks "
            "like degrees; expected radians"
        )
    for note in notes:
        warnings.warn(note, UnitsWarning, stacklevel=3)
    return notes


def _csv_values(cells: list[str]) -> FloatArray:
    """One column of text cells as floats: an empty or non-numeric cell becomes NaN, which the
    checks refuse naming the sample when the column is used, and which is harmless when not."""
    try:
        return np.array(cells, dtype=np.float64)
    except ValueError:  # some cell is empty or not a number: convert one by one
        values = np.empty(len(cells))
        for index, cell in enumerate(cells):
            try:
                values[index] = float(cell)
            except ValueError:
                values[index] = np.nan
        return values


def load_csv(path: Path) -> dict[str, FloatArray]:
    """Columns of a CSV file with a header line (docs/data-and-reports.md#measured-data: ``t,x,f[,v]``),
    UTF-8 (a byte-order mark is allowed), by their names in the header, spaces around them
    stripped. Unnamed columns that hold nothing (rows ending in ``,,``) are dropped; a row with
    more or fewer cells than the header otherwise is refused."""
    expected = (
        f"a CSV file in UTF-8 with a header line `t,x,f[,v]` and at least {MIN_SAMPLES} rows of numbers"
    )
    try:
        raw = path.read_bytes()
    except OSError as error:
        raise DataError(
            f"cannot read {path}: {error.strerror or error}", kind="unreadable_file", value=str(path)
        ) from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise DataError(
            f"{path} is not UTF-8 text (byte {error.start} is {raw[error.start]:#04x}): expected {expected}",
            kind="not_text",
            value=str(path),
            index=error.start,
        ) from None
    if not text.strip():
        raise DataError(f"{path} is empty: expected {expected}", kind="empty_file", value=str(path))
    if "\0" in text:
        raise DataError(
            f"{path} holds NUL characters, so it is not text: expected {expected}",
            kind="not_text",
            value=str(path),
            index=text.index("\0"),
        )
    lines = [line for line in text.splitlines() if line.strip()]
    header = [name.strip() for name in lines[0].split(",")]
    if not any(header):
        raise DataError(
            f"{path} must start with a header line naming the columns, e.g. `t,x,f`",
            kind="no_header",
            value=str(path),
        )
    named = [name for name in header if name]
    repeated = sorted({name for name in named if named.count(name) > 1})
    if repeated:
        raise DataError(
            f"cannot read {path} as {expected}: the header names {repeated} more than once",
            kind="repeated",
            field=repeated[0],
        )
    width = len(header)
    cells: list[list[str]] = []
    for number, line in enumerate(lines[1:], start=2):
        row = line.split(",")
        if len(row) > width and not "".join(row[width:]).strip():
            row = row[:width]  # empty trailing cells: nothing there to read
        if len(row) != width:
            raise DataError(
                f"cannot read {path} as {expected}: line {number} has {len(row)} cells, "
                f"the header has {width}",
                kind="ragged",
                value=str(path),
                index=number,
                expected=width,
                got=len(row),
            )
        cells.append(row)
    # Header only: empty columns, which the checks refuse as too few samples.
    columns = list(zip(*cells, strict=True)) if cells else [() for _ in header]
    return {name: _csv_values(list(column)) for name, column in zip(header, columns, strict=True) if name}


def load_emps(path: Path) -> dict[str, FloatArray]:
    """The EMPS benchmark's MATLAB file: f = gtau·vir [N], x = qm [m], t [s]."""
    try:
        content = scipy.io.loadmat(path)
    # scipy raises NotImplementedError for v7.3 (HDF5) files, MatReadError for broken ones, and
    # whatever its parser trips on (struct.error, zlib.error, KeyError, …) for bytes that are not
    # a MAT file at all: every one means the same to the caller.
    except Exception as error:
        message = " ".join(str(error).split())[:300]
        raise DataError(
            f"cannot read {path} as a MATLAB .mat file: {type(error).__name__}: {message}",
            kind="unreadable_file",
            value=str(path),
        ) from None
    missing = [name for name in ("t", "qm", "vir", "gtau") if name not in content]
    if missing:
        raise DataError(
            f"{path} lacks the EMPS variables {missing}: "
            "expected `t`, `qm`, `vir`, `gtau` (f = gtau·vir, x = qm)",
            kind="missing_column",
            field=missing[0],
            value=str(path),
            expected=["t", "qm", "vir", "gtau"],
            got=sorted(name for name in content if not name.startswith("__")),
        )
    gtau = (
        real_array(content["gtau"], "gtau", DataError, label=f"`gtau` in {path}").astype(np.float64).ravel()
    )
    if gtau.size != 1:
        raise DataError(
            f"`gtau` in {path} must be one number, got shape {content['gtau'].shape}",
            kind="shape",
            field="gtau",
            value=str(path),
            expected=(1,),
            got=content["gtau"].shape,
        )
    vir = _column("vir", content["vir"])
    return {"t": _column("t", content["t"]), "x": _column("qm", content["qm"]), "f": gtau[0] * vir}


def load_columns(path: str | PathLike[str]) -> dict[str, FloatArray]:
    """The raw columns of a ``.csv`` or EMPS ``.mat`` file (not yet validated)."""
    path = Path(path)
    if not path.is_file():
        raise DataError(f"data file {path} does not exist", kind="no_such_file", value=str(path))
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return load_csv(path)
    if suffix == ".mat":
        return load_emps(path)
    raise DataError(
        f"data file must end in .csv or .mat, got {path.name!r}",
        kind="invalid_choice",
        value=str(path),
        expected=(".csv", ".mat"),
        got=suffix,
    )


def check_column_map(columns: Any) -> dict[str, str]:
    """A ``columns`` mapping (``{"t": "time", "x": "q7", ...}``: the log's column for each of
    ``t``, ``x``, ``f``, ``v``) checked, as a plain dict."""
    if not isinstance(columns, Mapping):
        raise DataError(
            "`columns` must be a mapping from t, x, f, v to the log's column names, "
            f"got {shown(columns)!r:.80}",
            kind="wrong_type",
            field="columns",
            value=columns,
        )
    unknown = [key for key in columns if key not in ROLES]
    if unknown:
        raise DataError(
            f"`columns` maps {unknown!r:.80}: expected keys among t, x, f, v",
            kind="unknown_key",
            field=f"columns[{unknown[0]!r}]",
            value=unknown[0],
            expected=list(ROLES),
        )
    for key, name in columns.items():
        if not isinstance(name, str) or not name.strip():
            raise DataError(
                f"`columns[{key!r}]` must be a column name, got {shown(name)!r:.80}",
                kind="wrong_type",
                field=f"columns[{key!r}]",
                value=name,
            )
    return {key: name.strip() for key, name in columns.items()}


def parse_column_map(text: str) -> dict[str, str]:
    """The command line's ``--columns t=time,x=q7,f=tau[,v=dq7]`` as a ``columns`` mapping."""
    mapping: dict[str, str] = {}
    for item in text.split(","):
        key, equals, name = item.partition("=")
        key = key.strip()
        if not equals or not name.strip() or key not in ROLES:
            raise DataError(
                f"`--columns` must be a list like t=time,x=q7,f=tau[,v=dq7] (keys among t, x, f, v), "
                f"got {item.strip()!r} in {text!r:.120}",
                kind="malformed",
                field="--columns",
                value=item.strip(),
            )
        if key in mapping:
            raise DataError(
                f"`--columns` gives `{key}` twice in {text!r:.120}",
                kind="repeated",
                field="--columns",
                value=key,
            )
        mapping[key] = name.strip()
    return mapping


def select_columns(raw: Mapping[str, Any], columns: Mapping[str, str], source: str) -> dict[str, Any]:
    """The log's columns renamed to ``t``, ``x``, ``f`` (and ``v``) by ``columns``; a role not
    mapped keeps a column of its own name. A mapped name the log lacks is refused, listing the
    log's columns."""
    missing = {key: name for key, name in columns.items() if name not in raw}
    if missing:
        key, name = next(iter(missing.items()))
        have = ", ".join(str(column) for column in raw)
        raise DataError(
            f"`columns` maps `{key}` to the column `{name}`, which {source} does not have: "
            f"its columns are {have}",
            kind="missing_column",
            field=name,
            expected=sorted(columns.values()),
            got=[str(column) for column in raw],
        )
    taken = {name for name in columns.values()}
    selected = {key: raw[name] for key, name in columns.items()}
    for role in ROLES:
        if role not in selected and role in raw and role not in taken:
            selected[role] = raw[role]
    return selected


def as_motion_data(
    data: DataLike, *, columns: Mapping[str, str] | None = None, units: Units | None = None
) -> MotionData:
    """Accepts a :class:`MotionData` (returned as it is: it was validated when built), a path to a
    ``.csv``/``.mat`` file, or a mapping with the columns ``t``, ``x``, ``f`` (and optionally
    ``v``); validates once, and resamples non-uniform time stamps with a
    :class:`ResamplingWarning`.

    ``columns``: the log's own name for each of ``t``, ``x``, ``f``, ``v`` (a ``.csv`` or a
    mapping; e.g. ``{"t": "time", "x": "q7", "f": "q7_tau_J_compensate"}``). ``units``:
    ``"linear"`` (default) or ``"rotary"``; a :class:`MotionData` of other units is refused.
    Columns that look like other units give a :class:`UnitsWarning`. Every warning's text is
    kept in the record's ``notes``.
    """
    chosen = None if units is None else check_units(units, error=DataError)
    mapping = None if columns is None else check_column_map(columns)
    if isinstance(data, MotionData):
        if mapping:
            raise DataError(
                "`columns` applies to a file or a mapping of columns, not to a MotionData",
                kind="not_applicable",
                field="columns",
            )
        if chosen is not None and chosen != data.units:
            raise DataError(
                f"`units` is {chosen!r}, but the MotionData holds {data.units!r} data",
                kind="units_mismatch",
                field="units",
                value=chosen,
                expected=data.units,
            )
        return data
    raw: Mapping[str, ArrayLike]
    if isinstance(data, (str, PathLike)):
        raw, source = load_columns(data), str(data)
        if mapping and Path(data).suffix.lower() == ".mat":
            raise DataError(
                f"{source}: `columns` applies to .csv files and mappings, not to EMPS .mat files",
                kind="not_applicable",
                field="columns",
            )
    elif isinstance(data, Mapping):
        raw, source = dict(data), "arrays"
    else:
        raise DataError(
            f"`data` must be a MotionData, a path to a .csv or .mat file, or a mapping of columns "
            f"t, x, f[, v]; got {type(data).__name__}",
            kind="wrong_type",
            field="data",
            value=data,
        )
    kind: Units = chosen or "linear"
    notes: list[str] = []
    try:
        selected = (
            raw
            if mapping is None
            else select_columns(raw, mapping, "the log" if source == "arrays" else "it")
        )
        checked: dict[str, Any] = check_columns(selected, units=kind)
        if not is_uniform(checked["t"]):
            checked, note = resample_uniform(checked)
            notes.append(note)
            checked = check_columns(checked, units=kind)  # new samples on a new grid: checked once
        notes += plausibility_notes(checked, kind, mapping)
    except DataError as error:
        if source == "arrays":
            raise
        raise DataError(f"{source}: {error}", **data_of(error)) from None  # which file, when it came from one
    return MotionData._from_checked(checked, source, kind, tuple(notes))
