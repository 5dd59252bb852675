"""Nothing lost: the output-file policy of every command that writes files (docs/errors.md#output-files).

Outputs are checked before the work starts (the fit takes 40–55 s: a refusal must not come after
it); an input is never overwritten; an existing file only with --force; a folder is made when it
can be; a figure's extension must be one matplotlib writes; the files are written atomically.
The expensive work is replaced by a stand-in that records whether it ran.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt.discrepancy
from conftest import MAXWELL, small_log
from conftest import IdentifyStandIn as _Result
from leuven_rt import ModelFile, Params
from leuven_rt._output import check_outputs, image_formats, text_writer, write_files
from leuven_rt.cli import main
from leuven_rt.errors import OutputError


@pytest.fixture
def fit(monkeypatch: pytest.MonkeyPatch) -> list[Any]:
    """identify and diagnose replaced by stand-ins; the list records every call."""
    calls: list[Any] = []

    def identify(data: Any, *arguments: Any, **options: Any) -> _Result:
        calls.append(("identify", data))
        return _Result(data)

    def diagnose(data: Any, baseline: Any, **options: Any) -> Any:
        calls.append(("diagnose", data))
        raise AssertionError("diagnose ran although its outputs were refused")

    monkeypatch.setattr(leuven_rt.discrepancy, "identify", identify)
    monkeypatch.setattr(leuven_rt.discrepancy, "diagnose", diagnose)
    return calls


@pytest.fixture
def log(tmp_path: Path) -> Path:
    """A valid log: the CLI loads it before the (stand-in) fit."""
    path = tmp_path / "log.csv"
    columns = small_log()
    rows = [",".join(repr(float(columns[key][i])) for key in "txf") for i in range(len(columns["t"]))]
    path.write_text("\n".join(["t,x,f", *rows]) + "\n", encoding="utf-8")
    return path


def _refused(capsys: pytest.CaptureFixture[str], argv: list[str], message: str) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"leuven-rt {argv[0]}: error: "), err
    assert message in err, err
    assert "Traceback" not in err


def test_identify_never_overwrites_its_input(
    fit: list[Any], log: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`identify log.csv -o log.csv` replaced the measurements with the parameter file and exited
    0; now it is refused before the fit, even with --force, however the path is spelled."""
    before = log.read_bytes()
    spellings = [str(log), str(tmp_path / "." / "log.csv"), os.path.relpath(log)]
    link = tmp_path / "link.csv"
    link.symlink_to(log)
    for output in [*spellings, str(link)]:
        for force in ([], ["--force"]):
            _refused(capsys, ["identify", str(log), "-o", output, *force], "is the input file")
            _refused(capsys, ["identify", str(log), "-o", str(tmp_path / "p.json"), "--report", output,
                              *force], "is the input file")  # fmt: skip
    assert log.read_bytes() == before
    assert fit == [] and not (tmp_path / "p.json").exists()


def test_existing_outputs_need_force(
    fit: list[Any], log: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`-o existing.json` and `diagnose --plot existing.png` overwrote silently; now they are
    refused before the work unless --force."""
    existing = tmp_path / "existing.json"
    existing.write_text("keep me", encoding="utf-8")
    _refused(capsys, ["identify", str(log), "-o", str(existing)], "exists: refusing to overwrite it")
    figure = tmp_path / "existing.png"
    figure.write_text("keep me", encoding="utf-8")
    _refused(capsys, ["diagnose", str(log), "--plot", str(figure)], "exists: refusing to overwrite it")
    assert existing.read_text(encoding="utf-8") == figure.read_text(encoding="utf-8") == "keep me"
    assert fit == []
    assert main(["identify", str(log), "-o", str(existing), "--quiet", "--force"]) == 0
    assert ModelFile.load(existing) == ModelFile(friction=_Result.params, report={"held_out_rms": 0.1})


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        pytest.param(["-o", "{blocker}/sub/p.json"], "cannot be made, {blocker} is a file", id="file"),
        pytest.param(["-o", "{blocker}/p.json"], "{blocker} is a file, not a folder", id="file-as-parent"),
        pytest.param(["-o", "{tmp}"], "is a folder: expected a file name", id="folder-as-file"),
        pytest.param(["-o", "{tmp}/p.json", "--report", "{blocker}/r.json"], "is a file", id="report"),
        pytest.param(["-o", "{tmp}/p.json", "--report", "{tmp}/p.json"], "are the same file", id="twice"),
    ],
)  # fmt: skip
def test_identify_checks_outputs_before_the_fit(
    fit: list[Any], log: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], arguments: list[str],
    message: str,
) -> None:  # fmt: skip
    """A file where a folder should be, a folder as the output file or an output given twice
    failed after the whole fit with a traceback (and --report could fail after -o was written);
    now they are refused before the fit, and nothing is written."""
    blocker = tmp_path / "blocker"
    blocker.write_text("", encoding="utf-8")
    names = {"tmp": str(tmp_path), "blocker": str(blocker)}
    argv = ["identify", str(log), *[argument.format(**names) for argument in arguments]]
    _refused(capsys, argv, message.format(**names))
    assert fit == []
    assert sorted(path.name for path in tmp_path.iterdir()) == ["blocker", "log.csv"]


def test_missing_folders_are_made(fit: list[Any], log: Path, tmp_path: Path) -> None:
    """`--report` into a missing folder left -o's file written and exited 1; now both folders are
    made, and both files written."""
    output, report = tmp_path / "a" / "b" / "p.json", tmp_path / "c" / "r.json"
    assert main(["identify", str(log), "-o", str(output), "--report", str(report), "--quiet"]) == 0
    assert ModelFile.load(output).friction == _Result.params
    assert json.loads(report.read_text(encoding="utf-8")) == {"named_effects": []}


@pytest.mark.parametrize("name", ["figure.txt", "figure", "figure.json", "figure.PNG.bak"])
def test_diagnose_plot_needs_an_image_extension(
    fit: list[Any], log: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    """A --plot path with a non-image extension failed after the whole diagnosis; now it is
    refused first, with the formats matplotlib writes."""
    _refused(capsys, ["diagnose", str(log), "--plot", str(tmp_path / name)], "expected an image format")
    assert fit == []


def test_image_formats_are_matplotlibs() -> None:
    """The formats accepted for figures are those matplotlib's savefig writes."""
    assert {"png", "pdf", "svg"} <= set(image_formats())
    assert "txt" not in image_formats()


@pytest.mark.parametrize(
    ("command", "names"),
    [
        ("figures", ["fig1_loop_closure.png"]),
        ("demo", ["diagnose.png"]),
        ("control", ["closed_loop.png"]),
    ],
)
def test_folder_commands_refuse_existing_figures(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str, names: list[str]
) -> None:
    """figures, demo and control refuse (before their work) to replace figures in --out unless
    --force, and refuse an --out that is a file."""
    for name in names:
        (tmp_path / name).write_text("keep me", encoding="utf-8")
    _refused(capsys, [command, "--out", str(tmp_path)], "exists: refusing to overwrite it (pass --force")
    assert (tmp_path / names[0]).read_text(encoding="utf-8") == "keep me"
    _refused(capsys, [command, "--out", str(tmp_path / names[0])], "is a file, not a folder")


def test_writes_are_atomic_and_all_or_nothing(tmp_path: Path) -> None:
    """A writer that fails leaves neither its file nor the others of the call, nor temporary files;
    an existing target is left as it was."""
    first, second = tmp_path / "p.json", tmp_path / "r.json"
    second.write_text("old", encoding="utf-8")

    def broken(path: Path) -> None:
        path.write_text("half", encoding="utf-8")
        raise OSError(28, "No space left on device")

    with pytest.raises(OutputError, match=r"cannot write .*r\.json: No space left on device"):
        write_files([(first, text_writer("new")), (second, broken)])
    assert sorted(path.name for path in tmp_path.iterdir()) == ["r.json"]
    assert second.read_text(encoding="utf-8") == "old"
    write_files([(first, text_writer("new")), (second, text_writer("newer"))])
    assert (first.read_text(encoding="utf-8"), second.read_text(encoding="utf-8")) == ("new", "newer")
    assert sorted(path.name for path in tmp_path.iterdir()) == ["p.json", "r.json"]


def test_check_outputs_creates_nothing(tmp_path: Path) -> None:
    """Checking is free of side effects: a missing folder is found makeable, not made."""
    check_outputs([("out", tmp_path / "x" / "y" / "f.png", True)])
    assert list(tmp_path.iterdir()) == []


def test_params_save_is_atomic(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A failing Params.save leaves the file it would have replaced untouched."""
    path = tmp_path / "p.json"
    path.write_text("old", encoding="utf-8")

    def fail(*args: Any, **kwargs: Any) -> None:
        raise OSError(5, "Input/output error")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OutputError, match="Input/output error"):
        Params(**MAXWELL).save(path)
    assert path.read_text(encoding="utf-8") == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["p.json"]
    assert np.isfinite(Params(**MAXWELL).Fc)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        pytest.param(b"", r"is empty: expected a CSV file in UTF-8 with a header line", id="empty"),
        pytest.param(b"\n\n", r"is empty", id="blank-lines"),
        pytest.param(b"t,x,f\n", r"too few samples: need at least 200, got 0", id="header-only"),
        pytest.param("t,x,f\n0,1,2\n".encode("utf-16"), r"is not UTF-8 text \(byte 0 is 0xff\)", id="utf-16"),
        pytest.param("t,x,f\n0,1,é\n".encode("latin-1"), r"is not UTF-8 text", id="latin-1"),
        pytest.param(b"t,x,f\n0,1\n", r"line 2 has 2 cells, the header has 3", id="ragged"),
    ],
)  # fmt: skip
@pytest.mark.parametrize("command", ["identify", "diagnose"])
def test_unreadable_csv_is_a_data_error_naming_the_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str, content: bytes, message: str
) -> None:
    """An empty CSV raised IndexError from the loader (and non-UTF-8 text UnicodeDecodeError); now
    identify and diagnose say which file and what was expected, exit 2, and write nothing."""
    path = tmp_path / "log.csv"
    path.write_bytes(content)
    argv = [command, str(path)] + (["-o", str(tmp_path / "p.json")] if command == "identify" else [])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"leuven-rt {command}: error: ") and str(path) in err and err.count("\n") == 1, err
    assert re.search(message, err), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["log.csv"]
