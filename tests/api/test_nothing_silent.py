"""Nothing silent: values that are not real numbers are refused, not read as numbers; every failure
is one of the documented classes (docs/errors.md); inputs are not read while another thread writes
them; a second thread gets ConcurrentUseError, never PyO3's bare RuntimeError."""

from __future__ import annotations

import datetime
import json
import re
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt as lr
from conftest import MAXWELL, small_log
from leuven_rt.errors import ConcurrentUseError, DataError, InputError, ModelFileError, ParameterError

DT = 1e-4
V = 1e-3 * np.sin(np.linspace(0.0, 6.0, 200))

NOT_NUMBERS = [
    pytest.param(np.array(["0.1", "0.2"]), r"got dtype <U3", id="text-array"),
    pytest.param([b"0.1", b"0.2"], r"got dtype \|S3", id="bytes-list"),
    pytest.param(b"0123", r"got bytes", id="bytes"),
    pytest.param(bytearray(b"0123"), r"got bytearray", id="bytearray"),
    pytest.param("0.1", r"got str", id="str"),
    pytest.param(np.array([True, False, True]), r"got dtype bool", id="bool-array"),
    pytest.param([True, False], r"got dtype bool", id="bool-list"),
    pytest.param(np.array(["2024-01-01"] * 2, dtype="datetime64[D]"), r"datetime64", id="datetime64"),
    pytest.param([datetime.datetime(2024, 1, 1)] * 3, r"got dtype object", id="datetime"),
    pytest.param(np.array([(1.0, 2.0)] * 3, dtype="f8,f8"), r"structured", id="structured"),
    pytest.param(np.array([0.1, 0.2], dtype=object), r"got dtype object", id="object"),
    pytest.param(np.ma.masked_array([0.1, 0.2, 0.3], mask=[0, 1, 0]), r"masked array: fill it", id="masked"),
    pytest.param([10**400, 1], r"got dtype object", id="huge-int"),
]  # fmt: skip


@pytest.mark.parametrize(("signal", "message"), NOT_NUMBERS)
@pytest.mark.parametrize(
    "call",
    [
        pytest.param(lambda s: lr.simulate(MAXWELL, s, DT), id="simulate"),
        pytest.param(lambda s: lr.simulate_position(MAXWELL, s, DT), id="simulate_position"),
        pytest.param(lambda s: lr.LeuvenModel(MAXWELL).run(s, DT), id="LeuvenModel.run"),
        pytest.param(lambda s: lr.simulate_mass(MAXWELL, s, DT, mass=1.0), id="simulate_mass"),
        pytest.param(lambda s: lr.reference.simulate(MAXWELL, s, DT), id="reference.simulate"),
    ],
)
def test_signals_that_are_not_real_numbers_are_refused(
    call: Callable[[Any], object], signal: Any, message: str
) -> None:
    """Text, bytes, bytearray, booleans, dates, structured records, objects and masked arrays are
    refused with InputError naming the argument and the dtype that came; before, they were
    simulated as numbers (a masked array lost its mask)."""
    with pytest.raises(InputError, match=message) as refused:
        call(signal)
    error = refused.value
    assert error.kind == "not_real" and error.field in ("v", "x", "u") and error.value is signal
    assert str(error).startswith(f"`{error.field}` ")


@pytest.mark.parametrize(
    ("W", "message"),
    [
        pytest.param(bytearray(b"\x01\x01\x01\x01"), r"`W` must be a sequence of real numbers, got bytearray",
                     id="bytearray"),
        pytest.param(np.array(2.0), r"`W` must be a flat sequence of real numbers, got shape \(\)", id="0-d"),
        pytest.param(np.array([True] * 4), r"`W` must hold real numbers .*got dtype bool", id="bool-array"),
        pytest.param(np.array(["1"] * 4), r"`W` must hold real numbers .*got dtype <U1", id="text-array"),
        pytest.param(np.ma.masked_array([1.0] * 4, mask=[0, 0, 1, 0]), r"`W` .*masked array", id="masked"),
        pytest.param([1.0, 10**400, 1.0, 1.0], r"`W\[1\]` must be finite, got an integer of 401 digits",
                     id="huge-int"),
    ],
)  # fmt: skip
def test_parameter_sequences_that_are_not_real_numbers_are_refused(W: Any, message: str) -> None:
    """W given as a bytearray (was read as bytes 1, 1, 1, 1), a 0-d array (was a TypeError), booleans,
    text, a masked array or a huge integer (was an OverflowError) raise ParameterError naming W."""
    with pytest.raises(ParameterError, match=message) as refused:
        lr.Params(**{**MAXWELL, "W": W})
    assert refused.value.field in ("W", "W[1]")
    assert refused.value.kind in ("not_real", "shape", "not_finite_value")


def test_huge_integers_are_parameter_and_input_errors() -> None:
    """An integer beyond the float range is refused with the package's errors, not OverflowError."""
    with pytest.raises(ParameterError, match=r"`Fc` must be finite, got an integer of 401 digits") as refused:
        lr.Params(**{**MAXWELL, "Fc": 10**400})
    assert (refused.value.kind, refused.value.field, refused.value.value) == (
        "not_finite_value",
        "Fc",
        10**400,
    )
    with pytest.raises(
        InputError, match=r"`dt` must be finite and > 0, got an integer of 401 digits"
    ) as refused:
        lr.simulate(MAXWELL, V, 10**400)
    assert (refused.value.kind, refused.value.field) == ("not_positive", "dt")
    with pytest.raises(InputError) as refused:
        lr.LeuvenModel(MAXWELL).step(1e-3, 10**400)
    assert (refused.value.kind, refused.value.field) == ("not_real", "dt")
    with pytest.raises(InputError, match=r"`cutoff` must be finite") as refused:
        lr.predict(lr.Params(**MAXWELL), small_log(), cutoff=10**400)
    assert (refused.value.kind, refused.value.field) == ("not_finite_value", "cutoff")


@pytest.mark.parametrize(
    ("text", "kind", "key"),
    [
        pytest.param("[" * 100_000 + "]" * 100_000, "not_json", None, id="nested"),
        pytest.param(json.dumps({**MAXWELL, "Fc": 10**400}), "out_of_range", "Fc", id="huge-int"),
        pytest.param(json.dumps({**MAXWELL, "W": [10**400] * 4}), "out_of_range", "W[0]", id="huge-W"),
        pytest.param('{"Fc": ' + "9" * 5000 + "}", "out_of_range", "Fc", id="too-many-digits"),
        pytest.param("[1, 2]", "wrong_type", None, id="list"),
        pytest.param(json.dumps({**MAXWELL, "Fc": "1"}), "wrong_type", "Fc", id="text-value"),
    ],
)
def test_parameter_json_failures_are_parameter_errors(text: str, kind: str, key: str | None) -> None:
    """Deep nesting (was RecursionError), huge integers (was OverflowError), numbers of more digits
    than Python converts (was ValueError) raise ModelFileError, a ParameterError naming the key."""
    with pytest.raises(ModelFileError) as caught:
        lr.Params.from_json(text)
    assert isinstance(caught.value, ParameterError)
    assert (caught.value.kind, caught.value.field) == (kind, key), str(caught.value)


def test_a_parameter_file_that_is_not_utf8_is_a_parameter_error(tmp_path: Path) -> None:
    """A parameter file in UTF-16 or Latin-1 (was UnicodeDecodeError) or missing (was
    FileNotFoundError) raises ParameterError naming the file."""
    path = tmp_path / "p.json"
    path.write_text('{"Fc": 1.0}', encoding="utf-16")
    with pytest.raises(ParameterError, match=rf"parameter file {path} is not UTF-8 text") as refused:
        lr.Params.load(path)
    assert (refused.value.kind, refused.value.value) == ("not_text", str(path))
    path.write_bytes('{"Fc": 1.0, "note": "Müller"}'.encode("latin-1"))
    with pytest.raises(ParameterError, match=r"is not UTF-8 text") as refused:
        lr.Params.load(path)
    assert refused.value.kind == "not_text"
    with pytest.raises(ParameterError, match=r"cannot read parameter file .*missing\.json") as refused:
        lr.Params.load(tmp_path / "missing.json")
    assert refused.value.kind == "unreadable_file"


def test_predict_refuses_a_cutoff_that_is_not_a_number() -> None:
    """A cutoff of '10' was accepted (read as 10 Hz)."""
    for cutoff in ("10", True):
        with pytest.raises(InputError, match=rf"`cutoff` must be a real number, got {cutoff!r}") as refused:
            lr.predict(lr.Params(**MAXWELL), small_log(), cutoff=cutoff)  # type: ignore[arg-type]
        assert (refused.value.kind, refused.value.field, refused.value.value) == (
            "not_real",
            "cutoff",
            cutoff,
        )


@pytest.mark.parametrize("baseline", [None, 3, b"coulomb", {"coulomb": 1}])
def test_diagnose_refuses_a_baseline_that_is_not_names(baseline: Any) -> None:
    """diagnose(baseline=None) was a TypeError."""
    with pytest.raises(InputError, match=r"`baseline` must be effect names") as refused:
        lr.diagnose(small_log(), baseline)
    assert (refused.value.kind, refused.value.field) == ("wrong_type", "baseline")


@pytest.mark.parametrize("column", ["t", "x", "f"])
def test_columns_that_are_not_numbers_are_data_errors(column: str) -> None:
    """A column of booleans or text is refused, not read as numbers."""
    log = small_log()
    for spoilt, dtype in ((log[column] > 0, "bool"), (log[column].astype(str), "<U")):
        with pytest.raises(
            DataError, match=rf"column `{column}` must hold real numbers .*got dtype {dtype}"
        ) as refused:
            lr.identify({**log, column: spoilt})
        assert (refused.value.kind, refused.value.field) == ("not_real", column)


def test_a_signal_written_by_another_thread_does_not_change_the_result() -> None:
    """simulate reads its input with the GIL released; a thread that writes the caller's array
    while the simulation runs must not change the result (the input is copied first). The writer
    starts 0.2 s into a call of about a second, long after the copy (milliseconds)."""
    v = np.tile(1e-2 * np.sin(np.linspace(0.0, 800.0, 200_000)), (16, 1))
    expected = lr.simulate(MAXWELL, v, DT)
    started, stop = threading.Event(), threading.Event()

    def scribble() -> None:
        started.wait()
        stop.wait(0.2)
        while not stop.is_set():
            v[:] = 1.0
            v[:] = -1.0

    writer = threading.Thread(target=scribble)
    writer.start()
    try:
        started.set()
        got = lr.simulate(MAXWELL, v, DT)
    finally:
        stop.set()
        writer.join()
    np.testing.assert_array_equal(got, expected)


def test_simulate_never_reads_the_callers_memory() -> None:
    """The array the engine reads is a copy of its own, for float64 input as for any other."""
    from leuven_rt._checks import as_signal

    for values in (V, V.reshape(1, -1), np.tile(V, (3, 1)), np.asfortranarray(np.tile(V, (3, 1))), V[::2]):
        array, _ = as_signal(values, "v")
        assert not np.may_share_memory(array, values)
        np.testing.assert_array_equal(array.reshape(np.shape(values)), values)


def _busy_calls(owner: Any, start: Callable[[], object], calls: list[Callable[[], object]]) -> set[str]:
    """Runs ``start`` in a thread and the ``calls`` from this one while it runs; the names of the
    exceptions the calls raised."""

    def begin() -> None:
        while True:  # this thread may itself find the object held by one of the calls below
            try:
                start()
                return
            except ConcurrentUseError:
                continue

    running = threading.Thread(target=begin)
    raised: set[str] = set()
    running.start()
    try:
        while running.is_alive():
            for call in calls:
                try:
                    call()
                except ConcurrentUseError as error:
                    assert type(owner).__name__ in str(error)
                    raised.add(type(error).__name__)
                except RuntimeError as error:  # pragma: no cover - the bug this test is about
                    raised.add(f"RuntimeError: {error}")
    finally:
        running.join()
    return raised


LONG = 1e-3 * np.sin(np.linspace(0.0, 500.0, 2_000_000))


def test_a_second_thread_gets_concurrent_use_error() -> None:
    """A model, mass system or online identifier inside ``run`` (GIL released) refuses calls from
    another thread with ConcurrentUseError (a documented RuntimeError subclass), not PyO3's bare
    'Already borrowed' RuntimeError; the objects stay usable afterwards."""
    model = lr.LeuvenModel(MAXWELL)
    found = _busy_calls(
        model,
        lambda: model.run(LONG, DT),
        [lambda: model.step(1e-3, DT), lambda: model.state, lambda: model.reset(), lambda: model.run(V, DT)],
    )
    assert found <= {"ConcurrentUseError"}
    model.reset()
    system = lr.MassSystem(MAXWELL, mass=1.0)
    found |= _busy_calls(
        system, lambda: system.run(LONG[:400_000], DT), [lambda: system.step(0.0, DT), lambda: system.state]
    )
    identifier = lr.OnlineIdentifier([1e-6, 2e-6])
    found |= _busy_calls(
        identifier,
        lambda: identifier.run(LONG, LONG, LONG),
        [lambda: identifier.update(0.0, 0.0, 0.0), lambda: identifier.estimate],
    )
    assert found == {"ConcurrentUseError"}, found
    system.step(0.0, DT)
    identifier.update(0.0, 0.0, 0.0)


@pytest.mark.parametrize("spoil", [lambda a: a.astype(str), lambda a: a > 0], ids=["text", "bool"])
def test_checkpoints_of_text_or_booleans_are_refused(spoil: Callable[[np.ndarray], Any]) -> None:
    """A checkpoint whose positions are text or booleans was read as numbers by set_state."""
    model = lr.LeuvenModel(MAXWELL)
    model.run(V, DT)
    state = model.state
    with pytest.raises(InputError, match=r"`state.z` must hold real numbers") as refused:
        s = state
        model.set_state(lr.ModelState(spoil(s.z), s.zeta, s.last_position, s.has_last_position))
    assert (refused.value.kind, refused.value.field) == ("not_real", "state.z")
    system = lr.MassSystem(MAXWELL, mass=1.0)
    c = system.state
    with pytest.raises(InputError, match=r"`state.position` must hold real numbers") as refused:
        system.set_state(lr.MassState(spoil(c.position + 1.0), c.velocity, c.anchor, c.z, c.zeta))
    assert (refused.value.kind, refused.value.field) == ("not_real", "state.position")


@pytest.mark.parametrize(
    ("ending", "mark"),
    [("\n", ""), ("\r\n", ""), ("\r", ""), ("\n", "\ufeff")],
    ids=["lf", "crlf", "cr", "bom"],
)
def test_csv_line_endings_and_a_byte_order_mark_load_the_same(tmp_path: Path, ending: str, mark: str) -> None:
    """The loader reads the file's bytes itself (to name the file when they are not UTF-8): every
    line ending, and a UTF-8 byte-order mark, give the same columns, bit for bit."""
    from leuven_rt.data.records import load_csv

    log = small_log()
    rows = ["t,x,f"] + [",".join(repr(float(log[k][i])) for k in "txf") for i in range(len(log["t"]))]
    path = tmp_path / "log.csv"
    path.write_bytes((mark + ending.join(rows) + ending).encode("utf-8"))
    columns = load_csv(path)
    assert sorted(columns) == ["f", "t", "x"]
    for key in "txf":
        np.testing.assert_array_equal(columns[key], log[key])


def _non_increasing_log() -> dict[str, Any]:
    log = small_log()
    t = log["t"].copy()
    t[6] = t[5]
    return {**log, "t": t}


NUMPY_SCALARS = [
    pytest.param(lambda: lr.identify(_non_increasing_log()), id="t-not-increasing"),
    pytest.param(lambda: lr.predict(lr.Params(**MAXWELL), small_log(), cutoff=np.float64(1e9)), id="cutoff"),
    pytest.param(lambda: lr.simulate(MAXWELL, V, DT, np.str_("rk4")), id="scheme"),  # type: ignore[arg-type]
    pytest.param(lambda: lr.LeuvenModel(MAXWELL, channels=np.float64(2.0)), id="channels"),  # type: ignore[arg-type]
    pytest.param(lambda: lr.discrepancy.Settings(chunks=np.int64(1)), id="settings"),
    pytest.param(lambda: lr.Params(**{**MAXWELL, "W": [np.float64(0.5), [0.5], 0.5, 0.5]}), id="W-nested"),
    pytest.param(lambda: lr.Params(**{**MAXWELL, "Fc": np.str_("1")}), id="Fc-text"),
    pytest.param(
        lambda: lr.ModelFile.from_dict(
            {"format": "leuven-rt model", "version": np.int64(2), "friction": MAXWELL}
        ),
        id="version",
    ),
    pytest.param(lambda: lr.Compensator(MAXWELL, DT, np.str_("both")), id="mode"),  # type: ignore[arg-type]
]


@pytest.mark.parametrize("call", NUMPY_SCALARS)
def test_messages_show_numpy_scalars_as_python_numbers(call: Callable[[], object]) -> None:
    """A numpy scalar in a message is shown as the Python number or text it holds (shortest
    round-trip digits): "t[5] = 0.005", never "t[5] = np.float64(0.005)" (numpy 2's repr)."""
    with pytest.raises(ValueError) as refused:
        call()
    message = str(refused.value)
    assert "np." not in message and "float64(" not in message and "int64(" not in message, message


def test_the_command_line_help_is_plain_text(capsys: pytest.CaptureFixture[str]) -> None:
    """`leuven-rt --help` printed the module docstring's reStructuredText (":mod:`leuven_rt._output`",
    "``--force``")."""
    from leuven_rt.cli import main

    with pytest.raises(SystemExit) as done:
        main(["--help"])
    assert done.value.code == 0
    text = capsys.readouterr().out
    assert "leuven_rt._output" in text and "--force" in text
    assert ":mod:" not in text and "``" not in text and not re.search(r":[a-z]+:`", text)


@pytest.mark.parametrize("command", ["identify", "diagnose"])
def test_the_baseline_help_lists_the_effect_names(command: str, capsys: pytest.CaptureFixture[str]) -> None:
    """`--baseline` took effect names without saying which; its help lists the catalogue's."""
    from leuven_rt.cli import main
    from leuven_rt.discrepancy import CATALOGUE

    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for name in CATALOGUE:
        assert name in text, name
