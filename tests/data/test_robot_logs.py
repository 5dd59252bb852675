"""Logs as users have them (docs/data-and-reports.md#measured-data): the file's own column names
(``columns=``), spaces around header names, empty trailing columns, time stamps rounded to the
millisecond (resampled, with the warning kept in ``notes``), units that look wrong (UnitsWarning),
rotary axes; and the real robot logs of ../shared when they are there."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from conftest import SMALL_LOG_SAMPLES as SAMPLES
from conftest import small_log
from leuven_rt.data import MotionData, as_motion_data
from leuven_rt.data.records import parse_column_map
from leuven_rt.errors import DataError, ResamplingWarning, UnitsWarning

SHARED = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "robots"
FRANKA = SHARED / "franka" / "case4_slow.csv"
FAIRINO = SHARED / "fairino" / "S_slow.csv"


def _write(path: Path, header: str, rows: np.ndarray, tail: str = "") -> Path:
    lines = [header] + [",".join(repr(float(value)) for value in row) + tail for row in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _table() -> np.ndarray:
    log = small_log()
    return np.column_stack((log["t"], log["x"], log["f"], np.gradient(log["x"], 1e-3)))


def test_columns_map_the_files_names(tmp_path: Path) -> None:
    table = _table()
    path = _write(tmp_path / "log.csv", "time,q7,q7_tau,dq7,other", np.column_stack((table, table[:, 0])))
    data = as_motion_data(path, columns={"t": "time", "x": "q7", "f": "q7_tau", "v": "dq7"})
    for index, name in enumerate(("t", "x", "f", "v")):
        np.testing.assert_array_equal(getattr(data, name), table[:, index])
    # Unmapped roles keep their own columns; v is optional.
    plain = _write(tmp_path / "plain.csv", "t,position,f", table[:, :3])
    data = as_motion_data(plain, columns={"x": "position"})
    assert data.v is None
    np.testing.assert_array_equal(data.x, table[:, 1])
    # A mapping of arrays is renamed the same way.
    data = as_motion_data({"time": table[:, 0], "q": table[:, 1], "tau": table[:, 2]},
                          columns={"t": "time", "x": "q", "f": "tau"})  # fmt: skip
    np.testing.assert_array_equal(data.f, table[:, 2])


def test_a_missing_column_is_named_with_what_the_file_has(tmp_path: Path) -> None:
    path = _write(tmp_path / "log.csv", "time,q7,q7_tau", _table()[:, :3])
    with pytest.raises(
        DataError,
        match=r"log\.csv: `columns` maps `x` to the column `q9`, which it does not have: "
        r"its columns are time, q7, q7_tau$",
    ):
        as_motion_data(path, columns={"t": "time", "x": "q9", "f": "q7_tau"})
    with pytest.raises(DataError, match=r"missing columns \['t', 'x'\]"):
        as_motion_data(path, columns={"f": "q7_tau"})
    with pytest.raises(DataError, match=r"`columns` maps \['y'\]: expected keys among t, x, f, v"):
        as_motion_data(path, columns={"y": "q7"})
    with pytest.raises(DataError, match=r"`columns\['x'\]` must be a column name, got 3"):
        as_motion_data(path, columns={"x": 3})  # type: ignore[dict-item]
    with pytest.raises(DataError, match=r"`columns` must be a mapping"):
        as_motion_data(path, columns="t=time")  # type: ignore[arg-type]


def test_the_command_line_form_of_columns() -> None:
    assert parse_column_map("t=time, x = q7,f=q7_tau_J_compensate,v=dq7") == {
        "t": "time", "x": "q7", "f": "q7_tau_J_compensate", "v": "dq7",
    }  # fmt: skip
    for text, match in [
        ("t=time,x", r"`--columns` must be a list like t=time,x=q7"),
        ("y=q7", r"got 'y=q7'"),
        ("x=", r"got 'x='"),
        ("x=a,x=b", r"gives `x` twice"),
    ]:
        with pytest.raises(DataError, match=match):
            parse_column_map(text)


def test_header_names_with_spaces_and_empty_trailing_columns(tmp_path: Path) -> None:
    table = _table()[:, :3]
    spaced = _write(tmp_path / "spaced.csv", " t , x ,f ", table)
    trailing = _write(tmp_path / "trailing.csv", "t,x,f,,", table, tail=",,")
    unnamed = _write(tmp_path / "unnamed.csv", "t,x,f", table, tail=",,")
    for path in (spaced, trailing, unnamed):
        data = as_motion_data(path)
        np.testing.assert_array_equal(data.f, table[:, 2])
    ragged = _write(tmp_path / "ragged.csv", "t,x,f", table, tail=",,7")
    with pytest.raises(DataError, match=r"line 2 has 5 cells, the header has 3"):
        as_motion_data(ragged)
    twice = _write(tmp_path / "twice.csv", "t,x,f,x", np.column_stack((table, table[:, 1])))
    with pytest.raises(DataError, match=r"the header names \['x'\] more than once"):
        as_motion_data(twice)


def test_time_rounded_to_the_millisecond_is_resampled_and_noted() -> None:
    """Robot logs: steps of 1 to 20 ms, stamps rounded to 1 ms."""
    rng = np.random.default_rng(3)
    steps = rng.choice([0.001, 0.004, 0.004, 0.004, 0.006, 0.02], size=1999)
    t = np.round(np.r_[0.0, np.cumsum(steps)], 3)
    x = 0.1 * np.sin(t)
    with pytest.warns(ResamplingWarning, match=r"not uniformly sampled .*more than 1% from the median"):
        data = as_motion_data({"t": t, "x": x, "f": np.cos(t)})
    assert data.dt == pytest.approx(0.004, rel=1e-9)
    np.testing.assert_allclose(np.diff(data.t), 0.004, rtol=1e-9)
    np.testing.assert_allclose(data.x, 0.1 * np.sin(data.t), atol=1e-5)  # linear between stamps
    assert len(data.notes) == 1 and data.notes[0].startswith("`t` is not uniformly sampled")
    # The notes travel with a slice.
    assert data.slice(0, 500).notes == data.notes


def test_steps_of_one_to_twenty_milliseconds_are_not_a_gap() -> None:
    """A log of mostly 1 ms steps with a few of 20 ms loads; a longer hole is still refused."""
    steps = np.full(1999, 0.001)
    steps[[100, 700, 1500]] = 0.02
    t = np.round(np.r_[0.0, np.cumsum(steps)], 3)
    with pytest.warns(ResamplingWarning, match=r"step 0\.001 s"):
        data = as_motion_data(small_log(t=t, x=0.1 * np.sin(t), f=np.cos(t)))
    assert data.dt == pytest.approx(0.001, rel=1e-9)
    steps[700] = 0.05
    t = np.round(np.r_[0.0, np.cumsum(steps)], 3)
    with pytest.raises(DataError, match=r"`t` has a gap of 0\.05 s after sample 700"):
        as_motion_data(small_log(t=t, x=0.1 * np.sin(t), f=np.cos(t)))


def test_a_wander_below_one_percent_is_uniform() -> None:
    t = np.arange(SAMPLES) * 1e-3
    t[1::2] += 4e-6  # 0.4 % of the step
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        data = as_motion_data(small_log(t=t))
    assert data.notes == ()
    np.testing.assert_array_equal(data.t, t)


def test_time_that_does_not_increase_is_still_refused() -> None:
    t = np.round(np.arange(SAMPLES) * 4e-4, 3)  # rounding makes equal stamps
    with pytest.raises(DataError, match=r"`t` must strictly increase"):
        as_motion_data(small_log(t=t))


@pytest.mark.parametrize(
    ("changes", "units", "match"),
    [
        pytest.param({"t": np.arange(SAMPLES, dtype=float)}, "linear",
                     r"column `t` steps by whole numbers \(median step 1\): this looks like time in millisec",
                     id="milliseconds"),
        pytest.param({"t": 0.9 * np.arange(100_000), "x": np.sin(np.arange(100_000)),
                      "f": np.ones(100_000)}, "linear",
                     r"column `t` spans .* s, more than a day: this looks like time in millisec",
                     id="longer-than-a-day"),
        pytest.param({"x": np.linspace(0.0, 0.05, SAMPLES) * 1e3 * 0.2}, "linear",
                     r"column `x` spans 10 m, a linear stroke beyond 5 m: this looks like millimetres; "
                     r"expected metres", id="millimetres"),
        pytest.param({"x": np.linspace(0.0, 180.0, SAMPLES)}, "rotary",
                     r"column `x` reaches 180 rad, beyond ±100 rad: this looks like degrees; expected rad",
                     id="degrees"),
    ],
)  # fmt: skip
def test_units_that_look_wrong_are_warned_and_noted(changes: dict[str, np.ndarray], units: str,
                                                    match: str) -> None:  # fmt: skip
    columns = small_log(**changes)
    with pytest.warns(UnitsWarning, match=match):
        data = as_motion_data(columns, units=units)  # type: ignore[arg-type]
    assert len(data.notes) == 1 and UnitsWarning.__mro__[1] is UserWarning
    assert data.units == units


def test_plausible_units_are_not_warned() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        as_motion_data(small_log(x=np.linspace(0.0, 4.0, SAMPLES)))  # a 4 m stroke
        as_motion_data(small_log(x=np.linspace(0.0, 90.0, SAMPLES)), units="rotary")  # 90 rad: many turns
        as_motion_data(small_log(x=np.linspace(0.0, 20.0, SAMPLES)), units="rotary")  # 20 rad: not mm


def test_the_warning_names_the_files_column(tmp_path: Path) -> None:
    table = _table()[:, :3].copy()
    table[:, 1] = np.linspace(0.0, 150.0, SAMPLES)
    path = _write(tmp_path / "log.csv", "time,q7,tau", table)
    with pytest.warns(UnitsWarning, match=r"column `x` \(`q7` in the file\) reaches 150 rad"):
        as_motion_data(path, columns={"t": "time", "x": "q7", "f": "tau"}, units="rotary")


def test_rotary_units_in_messages_and_on_the_record() -> None:
    with pytest.raises(
        DataError, match=r"column `f` reaches 1e\+12 N·m, beyond 1e\+07 N·m: expected SI units"
    ):
        as_motion_data(small_log(f=1e12 * np.ones(SAMPLES)), units="rotary")
    with pytest.raises(DataError, match=r"expected `t` \[s\], `x` \[rad\], `f` \[N·m\]"):
        as_motion_data(small_log(f=None), units="rotary")
    with pytest.raises(DataError, match=r"`units` must be 'linear' or 'rotary', got 'deg'"):
        as_motion_data(small_log(), units="deg")  # type: ignore[arg-type]
    data = as_motion_data(small_log(), units="rotary")
    assert data.units == "rotary" and data.slice(0, 300).units == "rotary"
    assert as_motion_data(data, units="rotary") is data
    with pytest.raises(DataError, match=r"`units` is 'linear', but the MotionData holds 'rotary' data"):
        as_motion_data(data, units="linear")
    with pytest.raises(DataError, match=r"`columns` applies to a file or a mapping"):
        as_motion_data(data, columns={"x": "q"})
    record = MotionData(data.t, data.x, data.f, units="rotary", notes=["kept"])  # type: ignore[arg-type]
    assert record.notes == ("kept",)
    with pytest.raises(DataError, match=r"`notes` must be a sequence of str"):
        MotionData(data.t, data.x, data.f, notes="kept")  # type: ignore[arg-type]


@pytest.mark.skipif(not FRANKA.is_file(), reason=f"the Franka log is not at {FRANKA}")
def test_the_franka_log_loads() -> None:
    """time,q7,dq7,ddq7,q7_tau_J_compensate,…: steps of 2 to 16 ms stamped to the millisecond."""
    with pytest.warns(ResamplingWarning, match=r"resampled linearly onto a uniform grid with step 0\.004 s"):
        columns = {"t": "time", "x": "q7", "f": "q7_tau_J_compensate", "v": "dq7"}
        data = as_motion_data(FRANKA, columns=columns, units="rotary")
    assert data.samples > 20_000 and data.dt == pytest.approx(0.004, rel=1e-6)
    assert data.units == "rotary" and data.v is not None
    assert len(data.notes) == 1 and "resampled" in data.notes[0]
    assert 0.5 < float(np.median(data.x)) < 1.0  # q7 near 0.785 rad


@pytest.mark.skipif(not FAIRINO.is_file(), reason=f"the Fairino log is not at {FAIRINO}")
def test_the_fairino_log_loads() -> None:
    """q3…, two empty trailing fields on every line (and two unnamed columns in the header)."""
    with pytest.warns(ResamplingWarning):
        data = as_motion_data(FAIRINO, columns={"t": "time", "x": "q3", "f": "q3_tau_J_compensate"},
                              units="rotary")  # fmt: skip
    assert data.samples > 5_000 and np.all(np.isfinite(data.f)) and data.v is None
