"""Measured motion data: loading (CSV of docs/data-and-reports.md#measured-data, EMPS .mat files),
validation, resampling and the zero-phase derivative estimates that every fit works from.

Bad data is refused once, here, with a :class:`DataError` naming the column; the fitting modules
can then assume uniformly sampled, finite, increasing, plausibly scaled signals.

Non-uniform sampling: time stamps that wander by more than :data:`UNIFORM_TOLERANCE` of the
median step are interpolated (linearly) onto a uniform grid at the median step, with a
:class:`ResamplingWarning`; a step longer than :data:`MAX_GAP` median steps is a gap in the log
and is refused, since interpolating across it would invent the motion in between.
"""

from __future__ import annotations

import io
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from os import PathLike
from pathlib import Path
from typing import Any, Union, cast

import numpy as np
import scipy.io
from numpy.typing import ArrayLike, NDArray

from .._checks import real_array
from .._typing import FloatArray
from ..errors import DataError, ResamplingWarning

#: Fewer samples than this cannot be filtered, split into training and held-out parts, and fitted.
MIN_SAMPLES = 200
#: Relative wander of the sampling step tolerated as uniform (EMPS: 4e-5).
UNIFORM_TOLERANCE = 1e-3
#: A step longer than this many median steps is a gap: refused rather than interpolated.
MAX_GAP = 10.0
#: Plausibility bounds of SI data; values beyond them are almost surely in other units.
MAX_FORCE = 1e7  # N
MAX_POSITION = 1e3  # m
MAX_VELOCITY = 1e3  # m/s
STEP_RANGE = (1e-7, 1.0)  # s


@dataclass(frozen=True, eq=False)
class MotionData:
    """A uniformly sampled log: time ``t`` [s], position ``x`` [m], force ``f`` [N] to be
    explained and, where measured, velocity ``v`` [m/s].

    Construction validates everything (see :func:`check_columns`); use :func:`as_motion_data`
    to load files or to resample non-uniform time stamps.
    """

    t: FloatArray
    x: FloatArray
    f: FloatArray
    v: FloatArray | None = None
    source: str = "arrays"

    def __post_init__(self) -> None:
        columns = {"t": self.t, "x": self.x, "f": self.f}
        if self.v is not None:
            columns["v"] = self.v
        checked = check_columns(columns)
        if not is_uniform(checked["t"]):
            raise DataError(
                f"`t` must be uniformly sampled (steps within {UNIFORM_TOLERANCE:g} of the median), "
                f"got steps from {np.min(np.diff(checked['t'])):g} to {np.max(np.diff(checked['t'])):g} s; "
                "as_motion_data resamples such data"
            )
        for name, values in checked.items():
            values.setflags(write=False)
            object.__setattr__(self, name, values)

    @classmethod
    def _from_checked(cls, checked: Mapping[str, FloatArray], source: str) -> MotionData:
        """A record of columns that :func:`check_columns` passed and that are uniformly sampled,
        taken as they are: a log validated on load is not validated again."""
        record = object.__new__(cls)
        object.__setattr__(record, "v", None)
        object.__setattr__(record, "source", source)
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
        return MotionData(self.t[start:stop], self.x[start:stop], self.f[start:stop], v, self.source)


#: A log: a :class:`MotionData`, a path to a ``.csv`` or EMPS ``.mat`` file, or a mapping of
#: the columns ``t``, ``x``, ``f`` (and optionally ``v``).
DataLike = Union[MotionData, str, "PathLike[str]", Mapping[str, ArrayLike]]


def _column(name: str, values: ArrayLike) -> FloatArray:
    raw = real_array(values, name, DataError, label=f"column `{name}`")
    array = np.array(raw, dtype=np.float64)  # a copy of its own: the record is made read-only
    if array.ndim == 2 and 1 in array.shape:  # MATLAB stores vectors as (T, 1)
        array = array.ravel()
    if array.ndim != 1:
        raise DataError(f"column `{name}` must be one-dimensional, got shape {array.shape}")
    return array


def check_columns(columns: Mapping[str, ArrayLike]) -> dict[str, FloatArray]:
    """Checks and converts the columns ``t``, ``x``, ``f`` (and ``v`` when present).

    Refuses with :class:`DataError`: missing columns; columns of different lengths; fewer than
    :data:`MIN_SAMPLES` samples; NaN or infinite values (naming the first); time that does not
    strictly increase; a step outside :data:`STEP_RANGE`; forces, positions or velocities beyond
    the plausibility bounds of SI units; a position that never changes.
    """
    missing = [name for name in ("t", "x", "f") if name not in columns]
    if missing:
        raise DataError(
            f"missing columns {missing}: expected `t` [s], `x` [m], `f` [N] and optionally `v` [m/s], "
            f"got columns {sorted(columns)}"
        )
    arrays = {name: _column(name, columns[name]) for name in ("t", "x", "f", "v") if name in columns}
    lengths = {name: array.size for name, array in arrays.items()}
    if len(set(lengths.values())) != 1:
        raise DataError(f"columns must have the same length, got lengths {lengths}")
    samples = lengths["t"]
    if samples < MIN_SAMPLES:
        raise DataError(f"too few samples: need at least {MIN_SAMPLES}, got {samples}")
    for name, array in arrays.items():
        finite = np.isfinite(array)
        if not finite.all():
            index = int(np.argmin(finite))
            raise DataError(f"column `{name}` must be finite, got {array[index]} at sample {index}")
    steps = np.diff(arrays["t"])
    if not (steps > 0).all():
        index = int(np.argmin(steps > 0))
        raise DataError(
            f"`t` must strictly increase, got t[{index}] = {arrays['t'][index]!r} followed by "
            f"t[{index + 1}] = {arrays['t'][index + 1]!r}"
        )
    step = float(np.median(steps))
    if not STEP_RANGE[0] <= step <= STEP_RANGE[1]:
        raise DataError(
            f"the sampling step of `t` must be between {STEP_RANGE[0]:g} and {STEP_RANGE[1]:g} s, "
            f"got {step:g}: is `t` in seconds?"
        )
    bounds = {"f": (MAX_FORCE, "N"), "x": (MAX_POSITION, "m"), "v": (MAX_VELOCITY, "m/s")}
    for name, (bound, unit) in bounds.items():
        if name in arrays:
            largest = float(np.max(np.abs(arrays[name])))
            if largest > bound:
                raise DataError(
                    f"column `{name}` reaches {largest:g} {unit}, beyond {bound:g} {unit}: "
                    f"expected SI units ({unit})"
                )
    speed = float(np.max(np.abs(np.diff(arrays["x"]))) / step)
    if speed > MAX_VELOCITY:
        raise DataError(
            f"`x` moves at up to {speed:g} m/s between samples, beyond {MAX_VELOCITY:g} m/s: "
            "expected `x` in m and `t` in s"
        )
    if np.ptp(arrays["x"]) == 0.0:
        raise DataError("`x` never changes: there is no motion to identify friction from")
    return arrays


def is_uniform(t: FloatArray) -> bool:
    """Whether every step is within :data:`UNIFORM_TOLERANCE` of the median step."""
    steps = np.diff(t)
    median = np.median(steps)
    return bool(np.max(np.abs(steps - median)) <= UNIFORM_TOLERANCE * median)


def resample_uniform(columns: Mapping[str, FloatArray]) -> dict[str, FloatArray]:
    """Linear interpolation of every column onto a uniform grid at the median step, with a
    :class:`ResamplingWarning`; a gap longer than :data:`MAX_GAP` median steps is refused."""
    t = columns["t"]
    steps = np.diff(t)
    step = float(np.median(steps))
    longest = float(np.max(steps))
    if longest > MAX_GAP * step:
        index = int(np.argmax(steps))
        raise DataError(
            f"`t` has a gap of {longest:g} s after sample {index} ({longest / step:.1f} median steps): "
            f"expected steps within {MAX_GAP:g} median steps; split the log at the gap"
        )
    grid = t[0] + step * np.arange(int(np.floor((t[-1] - t[0]) / step + 1e-9)) + 1)
    warnings.warn(
        f"`t` is not uniformly sampled (steps from {np.min(steps):g} to {longest:g} s): "
        f"resampled linearly onto a uniform grid with step {step:g} s ({grid.size} samples)",
        ResamplingWarning,
        stacklevel=3,
    )
    return {name: (grid if name == "t" else np.interp(grid, t, values)) for name, values in columns.items()}


def load_csv(path: Path) -> dict[str, FloatArray]:
    """Columns of a CSV file with a header line (docs/data-and-reports.md#measured-data: ``t,x,f[,v]``),
    UTF-8 (a byte-order mark is allowed)."""
    expected = (
        f"a CSV file in UTF-8 with a header line `t,x,f[,v]` and at least {MIN_SAMPLES} rows of numbers"
    )
    try:
        raw = path.read_bytes()
    except OSError as error:
        raise DataError(f"cannot read {path}: {error.strerror or error}") from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise DataError(
            f"{path} is not UTF-8 text (byte {error.start} is {raw[error.start]:#04x}): expected {expected}"
        ) from None
    if not text.strip():
        raise DataError(f"{path} is empty: expected {expected}")
    if "\0" in text:
        raise DataError(f"{path} holds NUL characters, so it is not text: expected {expected}")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # numpy warns of odd files: refuse them instead
            table = np.genfromtxt(
                io.StringIO(text, newline=None), delimiter=",", names=True, dtype=np.float64, encoding=None
            )
    except (ValueError, IndexError, TypeError, Warning) as error:
        message = " ".join(str(error).split())[:300]
        raise DataError(f"cannot read {path} as {expected}: {message}") from None
    names = table.dtype.names
    if names is None:
        raise DataError(f"{path} must start with a header line naming the columns, e.g. `t,x,f`")
    # With names=True the table is a structured array (one field per column), not float64 as typed.
    records = cast("NDArray[np.void]", np.atleast_1d(table))
    return {name: np.asarray(records[name], dtype=np.float64) for name in names}


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
            f"cannot read {path} as a MATLAB .mat file: {type(error).__name__}: {message}"
        ) from None
    missing = [name for name in ("t", "qm", "vir", "gtau") if name not in content]
    if missing:
        raise DataError(
            f"{path} lacks the EMPS variables {missing}: "
            "expected `t`, `qm`, `vir`, `gtau` (f = gtau·vir, x = qm)"
        )
    gtau = (
        real_array(content["gtau"], "gtau", DataError, label=f"`gtau` in {path}").astype(np.float64).ravel()
    )
    if gtau.size != 1:
        raise DataError(f"`gtau` in {path} must be one number, got shape {content['gtau'].shape}")
    vir = _column("vir", content["vir"])
    return {"t": _column("t", content["t"]), "x": _column("qm", content["qm"]), "f": gtau[0] * vir}


def load_columns(path: str | PathLike[str]) -> dict[str, FloatArray]:
    """The raw columns of a ``.csv`` or EMPS ``.mat`` file (not yet validated)."""
    path = Path(path)
    if not path.is_file():
        raise DataError(f"data file {path} does not exist")
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return load_csv(path)
    if suffix == ".mat":
        return load_emps(path)
    raise DataError(f"data file must end in .csv or .mat, got {path.name!r}")


def as_motion_data(data: DataLike) -> MotionData:
    """Accepts a :class:`MotionData` (returned as it is: it was validated when built), a path to a
    ``.csv``/``.mat`` file, or a mapping with the columns ``t``, ``x``, ``f`` (and optionally
    ``v``); validates once, and resamples non-uniform time stamps with a
    :class:`ResamplingWarning`."""
    if isinstance(data, MotionData):
        return data
    columns: Mapping[str, ArrayLike]
    if isinstance(data, (str, PathLike)):
        columns, source = load_columns(data), str(data)
    elif isinstance(data, Mapping):
        columns, source = dict(data), "arrays"
    else:
        raise DataError(
            f"`data` must be a MotionData, a path to a .csv or .mat file, or a mapping of columns "
            f"t, x, f[, v]; got {type(data).__name__}"
        )
    try:
        checked: dict[str, Any] = check_columns(columns)
        if not is_uniform(checked["t"]):
            # New samples on a new grid: MotionData validates them, once.
            resampled = resample_uniform(checked)
            return MotionData(resampled["t"], resampled["x"], resampled["f"], resampled.get("v"), source)
    except DataError as error:
        if source == "arrays":
            raise
        raise DataError(f"{source}: {error}") from None  # which file, when it came from one
    return MotionData._from_checked(checked, source)
