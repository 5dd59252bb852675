"""Fuzzing what comes from files: the log loaders, the parameter-file reader and the command line.

Random bytes, CSV files of every bad shape (missing columns, empty, header only, ragged rows,
text, NaN, time that does not increase), encodings (Latin-1, UTF-16, byte-order marks) and JSON
parameter files (random JSON, deep nesting, huge integers) may only raise the documented errors
(docs/errors.md). The command line, called in-process, must exit with status 2 and one line on
stderr (no traceback) and write no file. Budget: the ``fuzz`` profile of tests/conftest.py.
"""

from __future__ import annotations

import contextlib
import io
import json
import tempfile
from pathlib import Path
from typing import Any

from hypothesis import given
from hypothesis import strategies as st

from conftest import FUZZ, MAXWELL
from leuven_rt import Params
from leuven_rt.cli import main
from leuven_rt.data.records import MIN_SAMPLES, as_motion_data
from leuven_rt.errors import DataError, InputError, ParameterError

NUMBER = st.floats(allow_nan=True, allow_infinity=True).map(repr) | st.integers(-(10**30), 10**30).map(str)
FIELD = NUMBER | st.sampled_from(
    ["", " ", "nan", "inf", "-inf", "1e400", "abc", '"1"', "0x10", "1,5", "é", "\x00"]
)
HEADERS = st.sampled_from([
    ["t", "x", "f"], ["t", "x", "f", "v"], ["t", "x"], ["x", "f"], ["t", "x", "f", "f"], ["T", "X", "F"],
    [" t", "x ", "f"], ["t", "x", "f", ""], ["#t", "x", "f"], [],
])  # fmt: skip


@st.composite
def csv_texts(draw: st.DrawFn) -> str:
    """A CSV text of fewer than MIN_SAMPLES rows (so that nothing is ever fitted): any header,
    rows of numbers or junk, ragged or not, time increasing or not, any line ending."""
    header = draw(HEADERS)
    width = max(len(header), 1)
    count = draw(st.integers(0, 12))
    kind = draw(st.sampled_from(["numbers", "junk", "ragged", "decreasing"]))
    rows = []
    for index in range(count):
        if kind == "numbers":
            row = [str(index * 1e-3)] + [draw(NUMBER) for _ in range(width - 1)]
        elif kind == "decreasing":
            row = [str(-index * 1e-3)] + ["0"] * (width - 1)
        elif kind == "ragged":
            row = [draw(FIELD) for _ in range(draw(st.integers(0, width + 2)))]
        else:
            row = [draw(FIELD) for _ in range(width)]
        rows.append(",".join(row))
    ending = draw(st.sampled_from(["\n", "\r\n", "\r"]))
    text = ending.join([",".join(header), *rows]) + draw(st.sampled_from(["", ending]))
    assert text.count("\n") <= MIN_SAMPLES
    return text


ENCODINGS = st.sampled_from(["utf-8", "utf-8-sig", "latin-1", "utf-16", "utf-16-le", "utf-32", "cp1252"])


def _encode(text: str, encoding: str) -> bytes:
    return text.encode(encoding, errors="replace")


def _refused_by_the_cli(argv: list[str], folder: Path) -> None:
    """``leuven-rt argv`` exits 2 with one line on stderr and leaves ``folder`` as it was."""
    before = sorted(folder.iterdir())
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = main(argv)
    message = err.getvalue()
    assert status == 2, (argv, message)
    assert message.startswith(f"leuven-rt {argv[0]}: error: ") and message.count("\n") == 1, message
    assert "Traceback" not in message
    assert sorted(folder.iterdir()) == before


@FUZZ
@given(text=csv_texts(), encoding=ENCODINGS)
def test_csv_logs_raise_only_data_errors(text: str, encoding: str) -> None:
    """Every CSV text, in every encoding, is a DataError for the loader (never an IndexError, a
    UnicodeDecodeError or a numpy warning), and exit 2 for identify and diagnose."""
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        path = folder / "log.csv"
        path.write_bytes(_encode(text, encoding))
        try:
            as_motion_data(path)
        except DataError:
            pass
        else:  # pragma: no cover - fewer than MIN_SAMPLES rows never load
            raise AssertionError("a log of too few rows was accepted")
        _refused_by_the_cli(["identify", str(path), "-o", str(folder / "p.json"), "--quiet"], folder)
        _refused_by_the_cli(["diagnose", str(path), "--json"], folder)


@FUZZ
@given(content=st.binary(max_size=400), suffix=st.sampled_from([".csv", ".mat"]))
def test_random_bytes_raise_only_data_errors(content: bytes, suffix: str) -> None:
    """Random bytes named .csv or .mat are a DataError naming the file, and exit 2 for the CLI."""
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        path = folder / f"log{suffix}"
        path.write_bytes(content)
        try:
            as_motion_data(path)
        except DataError as error:
            assert str(path) in str(error)
        _refused_by_the_cli(["identify", str(path), "-o", str(folder / "p.json"), "--quiet"], folder)


JSON_LEAVES = (
    st.none()
    | st.booleans()
    | st.integers()
    | st.integers(10**300, 10**400)
    | st.floats()
    | st.text(max_size=5)
)
JSON_VALUES = st.recursive(
    JSON_LEAVES,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=4),
)


@st.composite
def parameter_texts(draw: st.DrawFn) -> str:
    """Parameter-file text: random JSON, a valid set with one key spoiled, deep nesting, or junk."""
    kind = draw(st.sampled_from(["random", "spoiled", "nested", "junk"]))
    if kind == "random":
        return json.dumps(draw(JSON_VALUES))
    if kind == "spoiled":
        key = draw(st.sampled_from([*sorted(MAXWELL), "sigma0", "unknown"]))
        return json.dumps({**MAXWELL, key: draw(JSON_VALUES)})
    if kind == "nested":
        depth = draw(st.integers(1, 200_000))
        return "[" * depth + "]" * depth if draw(st.booleans()) else '{"a":' * depth + "1" + "}" * depth
    return draw(st.text(max_size=60))


@FUZZ
@given(text=parameter_texts(), encoding=ENCODINGS)
def test_parameter_files_raise_only_parameter_errors(text: str, encoding: str) -> None:
    """Params.from_json and Params.load raise ParameterError and nothing else (no OverflowError,
    RecursionError, UnicodeDecodeError, TypeError)."""
    for call in (lambda: Params.from_json(text), lambda: _load(_encode(text, encoding))):
        try:
            params = call()
        except ParameterError:
            continue
        assert isinstance(params, Params)


def _load(content: bytes) -> Any:
    with tempfile.TemporaryDirectory() as name:
        path = Path(name) / "p.json"
        path.write_bytes(content)
        return Params.load(path)


@FUZZ
@given(
    output=st.sampled_from(
        ["{log}", "{folder}", "{blocker}/p.json", "{folder}/p.txt/x.json", "{folder}/p.json"]
    ),
    report=st.sampled_from([None, "{log}", "{output}", "{blocker}/r.json", "{folder}/new/r.json"]),
    plot=st.sampled_from(["{log}", "{folder}/a.txt", "{folder}/a", "{blocker}/a.png", "{folder}/exists.png"]),
)
def test_refused_outputs_never_start_the_work(output: str, report: str | None, plot: str) -> None:
    """Bad output paths (the input, a folder, a path through a file, an existing file, a
    non-image figure) are refused with status 2 before the data is even read."""
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        log = folder / "log.csv"
        log.write_text("not even a CSV", encoding="utf-8")
        (folder / "blocker").write_text("", encoding="utf-8")
        (folder / "exists.png").write_text("", encoding="utf-8")
        names = {"log": str(log), "folder": str(folder), "blocker": str(folder / "blocker")}
        target = output.format(**names)
        argv = ["identify", str(log), "-o", target]
        if report is not None:
            argv += ["--report", report.format(output=target, **names)]
        try:
            _refused_by_the_cli(argv, folder)
        except AssertionError:
            # Every output acceptable: then the data is read, and refused as data.
            err = io.StringIO()
            with contextlib.redirect_stderr(err):
                assert main(argv) == 2
            refusals = ("cannot read", "must start with a header", "missing columns")
            assert any(text in err.getvalue() for text in refusals), err.getvalue()
        _refused_by_the_cli(["diagnose", str(log), "--plot", plot.format(**names)], folder)


def test_the_documented_errors_are_value_errors() -> None:
    """DataError is an InputError, and the families are ValueError (docs/errors.md)."""
    assert issubclass(DataError, InputError) and issubclass(InputError, ValueError)
