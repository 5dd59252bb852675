"""Real logs as they come (docs/data-and-reports.md#measured-data): a filter cutoff the record does
not support, a logged ``v`` of the wrong sign or in other units, time exported in milliseconds,
one column in two roles, and the CSV dialects users export. Each refusal is a DataError whose
message names the cause; each warning a UnitsWarning; the shared logs of ../shared load silently.

The errors are asserted on their class and on the facts of their message (the column, the share,
the bound, the line), which are the data they will carry as attributes."""

from __future__ import annotations

import contextlib
import importlib.util
import io
import json
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conftest import MAXWELL, small_log
from leuven_rt import ModelFile, Params, predict
from leuven_rt.cli import main
from leuven_rt.data import as_motion_data, estimate_derivatives
from leuven_rt.data.records import MAX_SIGN_DISAGREEMENT, load_csv, velocity_agreement
from leuven_rt.data.signals import MIN_CUTOFF_PERIODS, check_cutoff
from leuven_rt.errors import DataError, ResamplingWarning, UnitsWarning

SHARED = Path(__file__).resolve().parents[2].parent / "shared"
HOLDOUT = SHARED / "data" / "holdout-v2"
ROBOTS = SHARED / "data" / "robots"
SCORER = SHARED / "tools" / "score_robots.py"


def _stage_log(
    rate: float = 1000.0,
    seconds: float = 20.0,
    period: float = 5.0,
    amplitude: float = 1e-3,
    encoder: float = 1e-5,
    velocity_noise: float = 1e-4,
    dwell: bool = False,
    seed: int = 0,
) -> dict[str, np.ndarray]:
    """A stage moved back and forth (a sine, or with ``dwell`` a clipped sine that rests at each
    end), its position read by an encoder of step ``encoder``, its velocity measured with white
    noise: a log with a v column, in SI units."""
    rng = np.random.default_rng(seed)
    t = np.arange(round(rate * seconds)) / rate
    true = amplitude * np.sin(2.0 * np.pi * t / period)
    if dwell:
        true = np.clip(1.3 * true, -amplitude, amplitude)
    v = np.gradient(true, t) + velocity_noise * rng.standard_normal(t.size)
    f = np.tanh(v / 1e-4) + 0.3 * v + 0.01 * rng.standard_normal(t.size)
    return {"t": t, "x": np.round(true / encoder) * encoder, "f": f, "v": v}


def _silently(call: Any) -> Any:
    """``call()``, which must give no warning at all (a UnitsWarning would be an error here)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return call()


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def _rows(log: dict[str, np.ndarray], keys: str = "txf") -> list[list[str]]:
    return [[repr(float(log[key][i])) for key in keys] for i in range(log["t"].size)]


def _cli(argv: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(argv)
    return status, out.getvalue(), err.getvalue()


# Item 2: a cutoff the record does not support -------------------------------------------------


@pytest.mark.parametrize("cutoff", [1e-6, 1e-5, 19.9])
def test_a_cutoff_below_what_the_record_supports_is_refused_with_the_bound(cutoff: float) -> None:
    """400 samples at 1 kHz hold 8 periods of 20 Hz: lower cutoffs ended in a LinAlgError (1e-6)
    or filtered all motion away (1e-5) without a word."""
    log = small_log()
    with pytest.raises(DataError) as raised:
        predict(Params(**MAXWELL), log, cutoff=cutoff)
    message = str(raised.value)
    assert f"got {cutoff!r} Hz" in message
    assert "`cutoff` must be at least 20 Hz for a record of 0.4 s (400 samples)" in message
    assert f"{MIN_CUTOFF_PERIODS} periods of the cutoff" in message
    with pytest.raises(DataError, match=r"`cutoff` must be at least 20 Hz"):
        estimate_derivatives(as_motion_data(log), cutoff)
    # The bound itself is supported.
    assert estimate_derivatives(as_motion_data(log), 20.0).cutoff == 20.0


@pytest.mark.parametrize("cutoff", [500.0, 600.0, float("inf"), float("nan"), -1.0, 0.0])
def test_a_cutoff_at_or_above_nyquist_or_not_positive_is_refused(cutoff: float) -> None:
    log = as_motion_data(small_log())
    with pytest.raises(DataError, match=r"^`cutoff` must be (below 500 Hz|at least 20 Hz)") as raised:
        estimate_derivatives(log, cutoff)
    assert f"got {cutoff!r} Hz" in str(raised.value)
    assert check_cutoff(499.0, log.dt, log.samples) == 499.0
    with pytest.raises(DataError, match=r"`cutoff` must be a real number, got 'fast'"):
        check_cutoff("fast", log.dt, log.samples)


@pytest.mark.parametrize("cutoff", ["1e-6", "1e-5", "500"])
def test_predict_cutoff_on_the_command_line_is_one_line(tmp_path: Path, cutoff: str) -> None:
    """`leuven-rt predict --cutoff 1e-6` ended in a LinAlgError traceback."""
    model = tmp_path / "model.json"
    ModelFile(friction=Params(**MAXWELL)).save(model)
    log = _write(tmp_path / "log.csv", "\n".join(["t,x,f", *map(",".join, _rows(small_log()))]) + "\n")
    out = tmp_path / "p.csv"
    status, _, err = _cli(["predict", str(model), str(log), "-o", str(out), "--cutoff", cutoff])
    assert status == 2 and err.count("\n") == 1, err
    assert err.startswith("leuven-rt predict: error: ") and "`cutoff` must be" in err
    assert not out.exists()


# Item 3: v of the wrong sign, v in other units ---------------------------------------------------


@pytest.mark.parametrize(
    "options",
    [
        {},
        {"dwell": True},
        {"encoder": 1e-4, "period": 2.0, "velocity_noise": 1e-4},  # ±10 counts of a coarse encoder
        {"amplitude": 2e-4, "period": 10.0, "seconds": 30.0},  # ±20 counts
        {"rate": 500.0, "encoder": 2 * np.pi / 4096, "amplitude": 0.05, "period": 4.0},  # a 12-bit joint
        {"velocity_noise": 3e-3},  # v noise above the peak speed (1.3 mm/s)
    ],
    ids=["sine", "dwell", "ten-counts", "twenty-counts", "12-bit-joint", "noisy-v"],
)
def test_v_of_the_wrong_sign_is_refused_and_the_right_one_passes_silently(options: dict[str, Any]) -> None:
    log = _stage_log(**options)
    record = _silently(lambda: as_motion_data(log))
    assert record.v is not None and record.notes == ()
    with pytest.raises(DataError) as raised:
        as_motion_data({**log, "v": -log["v"]})
    message = str(raised.value)
    share = re.search(r"on (\d+)% of the moving samples", message)
    assert message.startswith("column `v` has the opposite sign of the motion of `x`"), message
    assert share is not None and int(share.group(1)) > 100 * MAX_SIGN_DISAGREEMENT
    assert "expected v = dx/dt" in message


def test_the_wrong_sign_names_the_files_column(tmp_path: Path) -> None:
    log = _stage_log()
    log["v"] = -log["v"]
    path = _write(tmp_path / "robot.csv", "\n".join(["time,q7,tau,dq7", *map(",".join, _rows(log, "txfv"))]))
    with pytest.raises(
        DataError, match=r"robot\.csv: column `v` \(`dq7` in the file\) has the opposite sign"
    ):
        as_motion_data(path, columns={"t": "time", "x": "q7", "f": "tau", "v": "dq7"})
    status, _, err = _cli(["diagnose", str(path), "--columns", "t=time,x=q7,f=tau,v=dq7"])
    assert status == 2 and "column `v` (`dq7` in the file) has the opposite sign" in err


@pytest.mark.parametrize(
    "scale",
    [1e3, 1e-3, 180 / np.pi, 2 * np.pi, 60 / (2 * np.pi)],
    ids=["mm/s", "km/s", "deg/s", "rev/s", "rpm"],
)
def test_v_in_other_units_than_x_per_t_is_warned(scale: float) -> None:
    """v in mm/s with x in m was taken as it was, and every velocity term was 1000x off."""
    log = _stage_log()
    with pytest.warns(UnitsWarning) as caught:
        record = as_motion_data({**log, "v": scale * log["v"]})
    message = str(caught[0].message)
    ratio = re.match(r"column `v` is ([0-9.e+-]+) times the velocity of `x` over `t`", message)
    assert ratio is not None, message
    assert float(ratio.group(1)) == pytest.approx(scale, rel=0.05)
    assert len(record.notes) == 1 and "other units than `x` per `t`" in record.notes[0]
    np.testing.assert_array_equal(record.v, scale * log["v"])  # warned, never rescaled


def test_a_v_within_a_factor_of_the_motion_passes() -> None:
    """A factor of 2 is no unit conversion (the Franka logs' dq7 is 2x the differences of q7)."""
    log = _stage_log()
    for factor in (0.5, 2.0):
        _silently(lambda factor=factor: as_motion_data({**log, "v": factor * log["v"]}))


def test_too_little_motion_to_judge_v_is_not_judged() -> None:
    """An x that moves by a few encoder steps cannot say v's sign: v is taken as it is."""
    log = _stage_log(amplitude=2e-5, encoder=1e-5)  # ±2 counts
    assert velocity_agreement(log["t"], log["x"], -log["v"]) is None
    _silently(lambda: as_motion_data({**log, "v": -log["v"]}))


@pytest.mark.skipif(not HOLDOUT.is_dir(), reason=f"the shared logs are not at {HOLDOUT}")
def test_every_holdout_log_loads_without_a_warning() -> None:
    """Those with a v column pass the sign and unit checks silently, in their units and as linear."""
    manifest = {entry["name"]: entry for entry in json.loads((HOLDOUT / "manifest.json").read_text())}
    with_v = 0
    for path in sorted(HOLDOUT.glob("*.csv")):
        for units in {manifest[path.stem]["scale"], "linear"}:
            record = _silently(lambda path=path, units=units: as_motion_data(path, units=units))
            assert record.notes == ()
            with_v += record.v is not None
            if record.v is not None:
                with pytest.raises(DataError, match=r"has the opposite sign of the motion of `x` on 100%"):
                    as_motion_data({"t": record.t, "x": record.x, "f": record.f, "v": -record.v})
    assert with_v >= 9


@pytest.mark.skipif(not ROBOTS.is_dir(), reason=f"the robot logs are not at {ROBOTS}")
@pytest.mark.parametrize(
    "name", ["franka/case4_slow", "franka/case4_high", "fairino/S_slow", "fairino/yuanhu_slow"]
)
def test_the_robot_logs_dq_columns_pass_and_negated_are_refused(name: str) -> None:
    path = ROBOTS / f"{name}.csv"
    joint = path.read_text(encoding="utf-8").split("\n", 1)[0].split(",")[1].strip()
    columns = {"t": "time", "x": joint, "f": f"{joint}_tau_J_compensate", "v": f"d{joint}"}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", ResamplingWarning)  # stamped to the millisecond
        record = as_motion_data(path, columns=columns, units="rotary")
    assert record.v is not None and not [note for note in record.notes if "resampled" not in note]
    raw = load_csv(path)
    negated = {"t": raw["time"], "x": raw[joint], "f": raw[columns["f"]], "v": -raw[columns["v"]]}
    opposite = r"column `v` has the opposite sign of the motion of `x` on (9\d|100)%"
    with pytest.raises(DataError, match=opposite):
        as_motion_data(negated, units="rotary")


# Item 4: time in milliseconds ------------------------------------------------------------------


@pytest.mark.parametrize(
    ("rate", "shown"), [(2000.0, "0.5"), (5000.0, "0.2"), (10_000.0, "0.1"), (20_000.0, "0.05")]
)
def test_a_fast_log_exported_in_milliseconds_is_warned(rate: float, shown: str) -> None:
    """A 5 kHz log in ms steps by 0.2: not whole numbers, so it passed without a word and every
    velocity term came out 1000x off."""
    log = _stage_log(rate=rate, seconds=4.0, period=1.0, encoder=1e-6)
    log.pop("v")
    milliseconds = {**log, "t": 1e3 * log["t"]}
    with pytest.warns(UnitsWarning) as caught:
        record = as_motion_data(milliseconds)
    message = str(caught[0].message)
    assert message.startswith(f"column `t` steps by {shown} s"), message
    assert "this looks like time in milliseconds; expected seconds" in message
    assert f"in milliseconds it is a {rate:.3g} Hz log" in message
    np.testing.assert_array_equal(record.t, milliseconds["t"])  # warned, never rescaled
    _silently(lambda: as_motion_data(log))  # the same log in seconds


def test_a_slow_logger_of_a_motion_it_resolves_is_not_warned() -> None:
    """20 Hz and 10 Hz loggers whose motion turns within seconds are plausible in seconds."""
    for rate, period in ((20.0, 30.0), (10.0, 1.0), (25.0, 4.0)):
        log = _stage_log(rate=rate, seconds=600.0, period=period, encoder=1e-6)
        _silently(lambda log=log: as_motion_data(log))


def test_a_log_in_milliseconds_with_a_v_in_metres_per_second_is_warned_twice() -> None:
    log = _stage_log(rate=5000.0, seconds=4.0, period=1.0, encoder=1e-6)
    with pytest.warns(UnitsWarning) as caught:
        as_motion_data({**log, "t": 1e3 * log["t"]})
    messages = [str(warning.message) for warning in caught]
    assert len(messages) == 2 and "time in milliseconds" in messages[0]
    ratio = re.match(r"column `v` is ([0-9.e+-]+) times the velocity of `x`", messages[1])
    assert ratio is not None and float(ratio.group(1)) == pytest.approx(1e3, rel=0.05)


@pytest.mark.skipif(not (ROBOTS.is_dir() and SCORER.is_file()), reason=f"the robot logs are not at {ROBOTS}")
def test_robot_records_as_the_scorer_writes_them_load_without_a_units_warning(tmp_path: Path) -> None:
    """The robot scorer resamples each record, writes t,x,f with x in rad, and reads it without
    --units rotary: neither the time rule nor the stroke rule may trip."""
    spec = importlib.util.spec_from_file_location("score_robots", SCORER)
    assert spec is not None and spec.loader is not None
    scorer = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(scorer)
    for record in sorted(ROBOTS.glob("*/*.csv")):
        t, x, f, _ = scorer.load(record)
        split = int(0.75 * t.size)
        for part in (slice(0, split), slice(split, None)):
            path = tmp_path / f"{record.stem}.csv"
            scorer.write(path, t[part], x[part], f[part])
            assert _silently(lambda path=path: as_motion_data(path)).notes == ()


# Item 8: one column in two roles -----------------------------------------------------------------


def test_one_column_in_two_roles_is_refused(tmp_path: Path) -> None:
    log = _stage_log()
    path = _write(
        tmp_path / "robot.csv", "\n".join(["time,q7,q7_tau,dq7", *map(",".join, _rows(log, "txfv"))])
    )
    with pytest.raises(DataError) as raised:
        as_motion_data(path, columns={"t": "time", "x": "q7", "f": "q7"})
    assert "`columns` maps `x` and `f` to the same column `q7`" in str(raised.value)
    with pytest.raises(DataError, match=r"maps `x` and `v` to the same column `q7`"):
        as_motion_data(path, columns={"t": "time", "x": "q7", "f": "q7_tau", "v": " q7 "})
    # A role left to the column of its own name that another role took.
    renamed = _write(tmp_path / "named.csv", "\n".join(["t,x,f", *map(",".join, _rows(log))]))
    with pytest.raises(DataError, match=r"`columns` maps `x` to the column `f`, which `f` would take too"):
        as_motion_data(renamed, columns={"x": "f"})
    status, _, err = _cli(["diagnose", str(path), "--columns", "t=time,x=q7,f=q7"])
    assert status == 2 and err.count("\n") == 1
    assert "maps `x` and `f` to the same column `q7`" in err


# Item 10: CSV dialects ---------------------------------------------------------------------------


def _dialect_text(log: dict[str, np.ndarray], dialect: str) -> str:
    rows = _rows(log)
    if dialect == "quoted-names":
        return "\n".join(['"t","x","f"', *map(",".join, rows)]) + "\n"
    if dialect == "quoted-everything":
        return "\n".join(['"t","x","f"', *(",".join(f'"{cell}"' for cell in row) for row in rows)]) + "\n"
    if dialect == "semicolon-decimal-comma":
        return (
            "\n".join(["t;x;f", *(";".join(cell.replace(".", ",") for cell in row) for row in rows)]) + "\n"
        )
    if dialect == "semicolon-decimal-point":
        return "\r\n".join(["t;x;f", *map(";".join, rows)]) + "\r\n"
    if dialect == "tab":
        return "\n".join(["t\tx\tf", *map("\t".join, rows)]) + "\n"
    if dialect == "tab-quoted-names":
        return "\n".join(['"t"\t"x"\t"f"', *map("\t".join, rows)]) + "\n"
    raise AssertionError(dialect)


@pytest.mark.parametrize(
    "dialect",
    ["quoted-names", "quoted-everything", "semicolon-decimal-comma", "semicolon-decimal-point", "tab",
     "tab-quoted-names"],
)  # fmt: skip
def test_csv_dialects_load_to_the_same_numbers(tmp_path: Path, dialect: str) -> None:
    """Quoted names were refused, `;` with decimal commas gave "line 2 has 2 cells, the header has
    1", tabs gave "got columns ['t\\tx\\tf']"."""
    log = small_log()
    plain = load_csv(_write(tmp_path / "plain.csv", "\n".join(["t,x,f", *map(",".join, _rows(log))]) + "\n"))
    columns = load_csv(_write(tmp_path / f"{dialect}.csv", _dialect_text(log, dialect)))
    assert sorted(columns) == ["f", "t", "x"]
    for key in "txf":
        np.testing.assert_array_equal(columns[key], plain[key], strict=True)
        np.testing.assert_array_equal(columns[key], log[key])


def test_a_missing_header_line_is_refused_naming_the_cause(tmp_path: Path) -> None:
    """It was "the header names ['0'] more than once"."""
    path = _write(tmp_path / "bare.csv", "\n".join(map(",".join, _rows(small_log()))) + "\n")
    with pytest.raises(DataError) as raised:
        as_motion_data(path)
    message = str(raised.value)
    assert message.startswith(f"cannot read {path} as a CSV file")
    assert "line 1 holds numbers ('0.0,0.0,1.0'), not column names: the header line is missing" in message


@pytest.mark.parametrize(
    ("units_row", "separator"),
    [("s,m,N", ","), ("[s];[m];[N]", ";"), ("s\t\tN", "\t")],
    ids=["plain", "semicolon", "tab-gap"],
)
def test_a_units_row_under_the_header_is_refused_naming_the_cause(
    tmp_path: Path, units_row: str, separator: str
) -> None:
    """It was "`t` must be finite, got nan at sample 0"."""
    rows = [separator.join(row) for row in _rows(small_log())]
    if separator == ";":
        rows = [row.replace(".", ",") for row in rows]
    path = _write(tmp_path / "units.csv", "\n".join([separator.join("txf"), units_row, *rows]) + "\n")
    with pytest.raises(DataError) as raised:
        as_motion_data(path)
    message = str(raised.value)
    assert f"line 2 holds text, not numbers ({units_row!r})" in message
    assert "a units row under the header" in message


def test_a_header_repeated_among_the_rows_is_refused_naming_the_line(tmp_path: Path) -> None:
    rows = list(map(",".join, _rows(small_log())))
    path = _write(tmp_path / "joined.csv", "\n".join(["t,x,f", *rows[:200], "", "t,x,f", *rows[200:]]) + "\n")
    with pytest.raises(DataError, match=r"line 203 holds text, not numbers \('t,x,f'\): a header repeated"):
        as_motion_data(path)


def test_a_ragged_line_is_named_by_its_line_in_the_file(tmp_path: Path) -> None:
    rows = list(map(",".join, _rows(small_log())))
    rows[9] += ",7"
    path = _write(tmp_path / "ragged.csv", "\n".join(["", "t,x,f", *rows[:5], "", *rows[5:]]) + "\n")
    with pytest.raises(DataError, match=r"line 13 has 4 cells, the header has 3"):
        as_motion_data(path)


def test_a_comma_inside_quotes_is_one_cell_and_text_cells_of_unused_columns_are_harmless(
    tmp_path: Path,
) -> None:
    log = small_log()
    rows = [",".join([*row, '"note, with a comma"']) for row in _rows(log)]
    path = _write(tmp_path / "notes.csv", "\n".join(["t,x,f,comment", *rows]) + "\n")
    record = _silently(lambda: as_motion_data(path))
    np.testing.assert_array_equal(record.f, log["f"])
    assert np.isnan(load_csv(path)["comment"]).all()
