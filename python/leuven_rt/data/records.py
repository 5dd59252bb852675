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
``v`` (one column per role); the separator (``,``, ``;`` or tab) is sniffed, names and numbers
may be quoted, a ``;`` file may write decimal commas, header names may carry spaces, and empty
trailing columns (rows ending in ``,,``) are dropped; a missing header line and a units row under
the header are refused, naming the cause. A logged ``v`` whose sign is the opposite of the
position's own motion is refused. Values that load but look like other units (time in
milliseconds, a linear stroke in millimetres, an angle in degrees, a ``v`` in other units than
``x`` per ``t``) give a :class:`UnitsWarning`. Every warning of the loader is also kept, as text,
in :attr:`MotionData.notes`, so that reports can carry it.
"""

from __future__ import annotations

import csv
import io
import warnings
from collections.abc import Mapping, Sequence
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
#: milliseconds [s].
MAX_LINEAR_STROKE = 5.0
MAX_ANGLE = 100.0
MAX_DURATION = 86_400.0
#: Time in milliseconds read as seconds (docs/data-and-reports.md#time-unit) makes the sampling
#: and the motion 1000 times slower. Friction is logged at 50 Hz or faster (robot controllers: 1
#: to 20 ms), so a median step of at least MS_STEP [s] (25 Hz) is a slow sampling; it is taken
#: for milliseconds when the motion is slow at that rate too: whole-number steps (a millisecond
#: clock), or a position that takes MS_TRAVEL [s] or more to travel its range (duration x range
#: / total travel: half the period of a sine; noise and quantisation only shorten it). Neither
#: depends on the units of x, so a rotary log read as linear is judged the same.
MS_STEP = 0.04
MS_TRAVEL = 20.0
#: A logged ``v`` against the position's own motion (docs/data-and-reports.md#measured-data): the
#: displacement of ``x`` over windows of the record against the integral of ``v`` over the same
#: windows, on the windows where ``x`` moves by at least MOVING times its resolution (its
#: smallest step, or its noise when larger), so that encoder quantisation and noise do not count.
#: The windows are the record split in VELOCITY_WINDOWS, made longer (doubled) until at least
#: MIN_MOVING_WINDOWS of them move. More than MAX_SIGN_DISAGREEMENT of the moving windows of the
#: opposite sign is refused (v = -dx/dt); a median ratio of the two beyond VELOCITY_RATIO (either
#: way) is warned of: another unit (mm/s against m, deg/s against rad, rev/s: 2π, time in ms).
VELOCITY_WINDOWS = 1000
NOISE_SAMPLES = 100_000
MOVING = 4.0
MIN_MOVING_WINDOWS = 20
MAX_SIGN_DISAGREEMENT = 0.5
VELOCITY_RATIO = 4.0
#: The separators a CSV log may use, sniffed (csv.Sniffer) from its header and the lines after it;
#: a ``;`` file may write decimal commas.
SEPARATORS = ",;\t"
SNIFFED_LINES = 20
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


def check_columns(
    columns: Mapping[str, ArrayLike], units: Units = "linear", names: Mapping[str, str] | None = None
) -> dict[str, FloatArray]:
    """Checks and converts the columns ``t``, ``x``, ``f`` (and ``v`` when present); ``units``
    names the units in the messages, ``names`` the file's name of each column.

    Refuses with :class:`DataError`: missing columns; columns of different lengths; fewer than
    :data:`MIN_SAMPLES` samples; NaN or infinite values (naming the first); time that does not
    strictly increase; a step outside :data:`STEP_RANGE`; forces, positions or velocities beyond
    the plausibility bounds of SI units; a position that never changes; a ``v`` whose sign is the
    opposite of the position's motion (:func:`velocity_agreement`).
    """
    si = unit_names(units)
    missing = [name for name in ("t", "x", "f") if name not in columns]
    if missing:
        raise DataError(
            f"missing columns {missing}: expected `t` [s], `x` [{si.position}], `f` [{si.force}] "
            f"and optionally `v` [{si.velocity}], got columns {sorted(columns)}",
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
    bounds = {"f": (MAX_FORCE, si.force), "x": (MAX_POSITION, si.position),
              "v": (MAX_VELOCITY, si.velocity)}  # fmt: skip
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
            f"`x` moves at up to {speed:g} {si.velocity} between samples, beyond {MAX_VELOCITY:g} "
            f"{si.velocity}: expected `x` in {si.position} and `t` in s",
            kind="implausible_units",
            field="x",
            value=speed,
            bound=MAX_VELOCITY,
        )
    if np.ptp(arrays["x"]) == 0.0:
        raise DataError(
            "`x` never changes: there is no motion to identify friction from", kind="no_motion", field="x"
        )
    if "v" in arrays:
        agreement = velocity_agreement(arrays["t"], arrays["x"], arrays["v"])
        if agreement is not None and agreement.opposite > MAX_SIGN_DISAGREEMENT:
            raise DataError(
                f"{_label('v', names)} has the opposite sign of the motion of `x` on "
                f"{agreement.opposite:.0%} of the moving samples ({agreement.moving} windows of "
                f"{agreement.window} samples): expected v = dx/dt; is it -dx/dt? "
                "(negate it, or leave it out)",
                kind="wrong_sign",
                field="v",
                value=agreement.opposite,
                bound=MAX_SIGN_DISAGREEMENT,
            )
    return arrays


def _label(role: str, names: Mapping[str, str] | None) -> str:
    """``column `role```, with the file's name of the column when it has another."""
    source = (names or {}).get(role, role)
    return f"column `{role}`" if source == role else f"column `{role}` (`{source}` in the file)"


@dataclass(frozen=True)
class VelocityAgreement:
    """How a logged ``v`` agrees with the motion of ``x`` (:func:`velocity_agreement`)."""

    opposite: float
    """The share of the moving windows on which the integral of ``v`` has the opposite sign of
    the displacement of ``x``."""
    ratio: float
    """The median of (integral of ``v``) / (displacement of ``x``) over the other moving windows:
    1 for v = dx/dt (NaN when every one is of the opposite sign)."""
    moving: int
    """The windows on which ``x`` moves (by at least :data:`MOVING` resolutions)."""
    window: int
    """Samples per window."""


def velocity_agreement(t: FloatArray, x: FloatArray, v: FloatArray) -> VelocityAgreement | None:
    """``v`` compared with the position's own motion over windows of the record (the constants'
    documentation: :data:`VELOCITY_WINDOWS`), or None when too few windows move to tell. The
    displacement ``v`` gives over a window is its integral (trapezoidal, at the stamps ``t``), so
    that the comparison holds across reversals and non-uniform stamps alike."""
    dx = np.diff(x)
    steps = np.abs(dx)
    smallest = float(np.min(steps[steps > 0]))  # the caller has refused a position that never changes
    # The noise of x from its second differences (a smooth motion's are tiny): 1.4826·MAD/√6, read
    # on at most NOISE_SAMPLES of them, spread over the record (a statistic needs no more).
    at = np.arange(0, dx.size - 1, max(1, (dx.size - 1) // NOISE_SAMPLES))
    second = dx[at + 1] - dx[at]
    noise = 1.4826 * float(np.median(np.abs(second - np.median(second)))) / np.sqrt(6.0)
    resolution = max(smallest, noise)
    integral = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))))
    window = max(1, x.size // VELOCITY_WINDOWS)
    while x.size // window >= 2:
        ends = np.arange(0, x.size, window)
        displacement, said = np.diff(x[ends]), np.diff(integral[ends])
        moving = np.abs(displacement) >= MOVING * resolution
        count = int(np.count_nonzero(moving))
        if count >= MIN_MOVING_WINDOWS:
            displacement, said = displacement[moving], said[moving]
            opposite = said * displacement < 0
            ratios = said[~opposite] / displacement[~opposite]
            return VelocityAgreement(
                opposite=float(np.mean(opposite)),
                ratio=float(np.median(ratios)) if ratios.size else float("nan"),
                moving=count,
                window=window,
            )
        window *= 2
    return None


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
    in milliseconds, a linear stroke in millimetres, an angle in degrees, a ``v`` in other units
    than ``x`` per ``t``); ``names`` gives the file's name of each column, for the message. Warns
    with each; the data is left as it is."""
    notes: list[str] = []
    t, x = columns["t"], columns["x"]
    steps = np.diff(t)
    step = float(np.median(steps))
    duration = float(t[-1] - t[0])
    if step >= MS_STEP:  # a slow sampling: milliseconds when the motion is slow at this rate too
        travel = duration * float(np.ptp(x)) / float(np.sum(np.abs(np.diff(x))))
        if bool(np.all(steps == np.round(steps))):
            notes.append(
                f"{_label('t', names)} steps by whole numbers (median step {step:g}): this looks like "
                "time in milliseconds; expected seconds"
            )
        elif travel >= MS_TRAVEL:
            notes.append(
                f"{_label('t', names)} steps by {step:g} s ({1.0 / step:.3g} Hz) and `x` takes "
                f"{travel:.3g} s to travel its range: both slow for a friction log in seconds, while in "
                f"milliseconds it is a {1e3 / step:.3g} Hz log whose travel takes {travel / 1e3:.3g} s: "
                "this looks like time in milliseconds; expected seconds"
            )
    if not notes and duration > MAX_DURATION:
        notes.append(
            f"{_label('t', names)} spans {duration:g} s, more than a day: this looks like time in "
            "milliseconds (or a clock of another unit); expected seconds"
        )
    unit = unit_names(units)
    if units == "linear" and float(np.ptp(x)) > MAX_LINEAR_STROKE:
        notes.append(
            f"{_label('x', names)} spans {float(np.ptp(x)):g} m, a linear stroke beyond "
            f"{MAX_LINEAR_STROKE:g} m: this looks like millimetres; expected metres (or units='rotary' "
            "for an angle in rad)"
        )
    if units == "rotary" and float(np.max(np.abs(x))) > MAX_ANGLE:
        notes.append(
            f"{_label('x', names)} reaches {float(np.max(np.abs(x))):g} rad, beyond ±{MAX_ANGLE:g} rad: this "
            "looks like degrees; expected radians"
        )
    v = columns.get("v")
    agreement = None if v is None else velocity_agreement(t, x, v)
    if (
        agreement is not None
        and agreement.opposite <= MAX_SIGN_DISAGREEMENT
        and not (1.0 / VELOCITY_RATIO <= agreement.ratio <= VELOCITY_RATIO)
    ):
        notes.append(
            f"{_label('v', names)} is {agreement.ratio:.3g} times the velocity of `x` over `t` (the median "
            f"over {agreement.moving} moving windows of {agreement.window} samples): this looks like other "
            f"units than `x` per `t` (mm/s with x in m, deg/s with x in rad, or t in ms); expected "
            f"{unit.velocity} with x in {unit.position} and t in s"
        )
    for note in notes:
        warnings.warn(note, UnitsWarning, stacklevel=3)
    return notes


def _csv_values(cells: Sequence[str]) -> FloatArray:
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


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _dialect(lines: list[str]) -> tuple[str, str]:
    """The separator and quote character of a CSV log, sniffed from its header and the lines after
    it, or from the header alone when no separator fits every one of those (a ragged line among
    them); ``,`` when nothing fits (a file of one column). Tab and ``;`` are tried before ``,``:
    the decimal commas of a ``;`` file are as regular as its separators once a header line is
    missing, and the sniffer would prefer the comma."""
    for sample in (lines, lines[:1]):
        for separator in SEPARATORS[::-1]:
            try:
                sniffed = csv.Sniffer().sniff("\n".join(sample), delimiters=separator)
            except csv.Error:  # this separator does not fit every line
                continue
            return sniffed.delimiter, sniffed.quotechar or '"'
    return ",", '"'


def load_csv(path: Path) -> dict[str, FloatArray]:
    """Columns of a CSV file with a header line (docs/data-and-reports.md#measured-data: ``t,x,f[,v]``),
    UTF-8 (a byte-order mark is allowed), by their names in the header, spaces around them
    stripped. The separator (``,``, ``;`` or tab) is sniffed; names and numbers may be quoted; in
    a ``;`` file a decimal comma is read as a decimal point. Unnamed columns that hold nothing
    (rows ending in ``,,``) are dropped; a row with more or fewer cells than the header otherwise
    is refused, and so are a first line of numbers (no header) and a line of text among the
    numbers (a units row under the header), each naming the line."""
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
    lines = text.splitlines()
    first = next(index for index, line in enumerate(lines) if line.strip())
    sample = [line for line in lines[first : first + 4 * SNIFFED_LINES] if line.strip()][: SNIFFED_LINES + 1]
    separator, quote = _dialect(sample)
    header = [name.strip() for name in next(csv.reader(sample[:1], delimiter=separator, quotechar=quote,
                                                        skipinitialspace=True))]  # fmt: skip
    if not any(header):
        raise DataError(
            f"{path} must start with a header line naming the columns, e.g. `t,x,f`",
            kind="no_header",
            value=str(path),
        )
    named = [name for name in header if name]
    if all(_is_number(name.replace(",", ".") if separator == ";" else name) for name in named):
        raise DataError(
            f"cannot read {path} as {expected}: line {first + 1} holds numbers "
            f"({lines[first].strip()!r:.60}), not column names: the header line is missing (add one, "
            "e.g. `t,x,f`)",
            kind="no_header",
            value=str(path),
            index=first + 1,
        )
    repeated = sorted({name for name in named if named.count(name) > 1})
    if repeated:
        raise DataError(
            f"cannot read {path} as {expected}: the header names {repeated} more than once",
            kind="repeated",
            field=repeated[0],
        )
    body = text[text.index(lines[first]) + len(lines[first]) :]
    if separator == ";":  # the separator of locales that write a decimal comma
        body = body.replace(",", ".")
    if not body.strip():  # header only: empty columns, which the checks refuse as too few samples
        return {name: np.empty(0) for name in named}
    table = _numbers(body, separator, quote, header)
    if table is None:
        return _cells(path, expected, lines[first + 1 :], first + 2, header, separator, quote)
    return {name: np.ascontiguousarray(table[:, index]) for index, name in enumerate(named)}


def _numbers(body: str, separator: str, quote: str, header: list[str]) -> FloatArray | None:
    """The named columns of the rows of ``body`` as a (rows, named) array by numpy's C reader, or
    None when some cell is not a number or a row has another width than the header
    (:func:`_cells` then reads it cell by cell, and says which)."""
    used = [index for index, name in enumerate(header) if name]
    every = len(used) == len(header)  # then numpy checks that each row has as many cells as the first
    try:
        table = np.loadtxt(
            io.StringIO(body, newline=None), delimiter=separator, quotechar=quote, comments=None,
            dtype=np.float64, ndmin=2, usecols=None if every else used,
        )  # fmt: skip
    except ValueError:
        return None
    if every:
        return table if table.shape[1] == len(header) else None
    # Unnamed columns (rows ending in ",,") are not read, and numpy checks no width then.
    cells = np.fromiter(
        (line.count(separator) + 1 for line in body.splitlines() if line.strip()), dtype=np.int64
    )
    return table if bool(np.all(cells == len(header))) else None


def _cells(
    path: Path, expected: str, lines: list[str], start: int, header: list[str], separator: str, quote: str
) -> dict[str, FloatArray]:
    """The columns of the rows ``lines`` (the first is line ``start`` of the file) read cell by cell
    (csv's reader): empty trailing cells dropped, a row of another width refused, a row of text
    refused, a cell that is not a number NaN."""
    numbered = [(number, line) for number, line in enumerate(lines, start=start) if line.strip()]
    if separator == ";":
        numbered = [(number, line.replace(",", ".")) for number, line in numbered]
    width = len(header)
    rows: list[list[str]] = []
    reader = csv.reader((line for _, line in numbered), delimiter=separator, quotechar=quote,
                        skipinitialspace=True)  # fmt: skip
    for (number, _), row in zip(numbered, reader, strict=True):
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
        rows.append(row)
    used = [index for index, name in enumerate(header) if name]
    transposed = list(zip(*rows, strict=True))
    columns = {header[index]: _csv_values(transposed[index]) for index in used}
    # A row with text in every named cell is no row of numbers: a units row under the header, or a
    # header repeated where two logs were joined. Rows of NaN are left to the checks.
    unread = np.flatnonzero(np.all([np.isnan(values) for values in columns.values()], axis=0))
    for index in unread:
        cells = [rows[index][column].strip() for column in used]
        if any(cells) and not any(_is_number(cell) for cell in cells if cell):
            number, line = numbered[index]
            cause = (
                "a units row under the header, it seems; remove it (units are not read from the file: "
                "t must be in s, the others in SI units)"
                if index == 0
                else "a header repeated among the rows (logs joined?), it seems; remove it"
            )
            raise DataError(
                f"cannot read {path} as {expected}: line {number} holds text, not numbers "
                f"({line.strip()!r:.60}): {cause}",
                kind="not_real",
                value=str(path),
                index=number,
            )
    return columns


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
    mapping = {key: name.strip() for key, name in columns.items()}
    roles: dict[str, list[str]] = {}
    for key, name in mapping.items():
        roles.setdefault(name, []).append(key)
    for name, keys in roles.items():
        if len(keys) > 1:
            both = " and ".join(f"`{key}`" for key in keys)
            raise DataError(
                f"`columns` maps {both} to the same column `{name}`: each of t, x, f, v needs a column "
                "of its own",
                kind="repeated",
                field="columns",
                value=name,
            )
    return mapping


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
    taken = {name: key for key, name in columns.items()}
    selected = {key: raw[name] for key, name in columns.items()}
    for role in ROLES:
        if role not in selected and role in raw:
            if role in taken and role != "v":  # v is optional: the column stays with its mapped role
                raise DataError(
                    f"`columns` maps `{taken[role]}` to the column `{role}`, which `{role}` would take too: "
                    f"each of t, x, f, v needs a column of its own (map `{role}` to another column)",
                    kind="repeated",
                    field="columns",
                    value=role,
                )
            if role not in taken:
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
        checked: dict[str, Any] = check_columns(selected, units=kind, names=mapping)
        if not is_uniform(checked["t"]):
            checked, note = resample_uniform(checked)
            notes.append(note)
            checked = check_columns(
                checked, units=kind, names=mapping
            )  # new samples on a new grid: checked once
        notes += plausibility_notes(checked, kind, mapping)
    except DataError as error:
        if source == "arrays":
            raise
        raise DataError(f"{source}: {error}", **data_of(error)) from None  # which file, when it came from one
    return MotionData._from_checked(checked, source, kind, tuple(notes))
