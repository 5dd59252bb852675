"""Bad input to the discrepancy workflow: each a clear error, from Python and from the CLI."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt.cli import main
from leuven_rt.discrepancy.hidden import make_hidden


def _columns(samples: int) -> dict[str, np.ndarray]:
    t = np.arange(samples) * 1e-3
    return {"t": t, "x": 1e-3 * np.sin(2 * np.pi * 2 * t), "f": np.sign(np.cos(2 * np.pi * 2 * t))}


def test_unknown_baseline_effect_is_refused() -> None:
    with pytest.raises(lr.InputError, match=r"unknown effects \['friction'\].*expected names among"):
        lr.diagnose(_columns(2000), "coulomb,friction")


def test_repeated_baseline_effect_is_refused() -> None:
    with pytest.raises(lr.InputError, match="repeats effects"):
        lr.diagnose(_columns(2000), ["coulomb", "coulomb"])


def test_file_of_another_kind_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text("t,x,f\n0,0,0\n", encoding="utf-8")
    with pytest.raises(lr.InputError, match=r"must end in \.csv or \.mat"):
        lr.diagnose(path)
    fake = tmp_path / "log.mat"
    fake.write_bytes(b"not a MATLAB file")
    with pytest.raises(lr.InputError, match=r"cannot read .* as a MATLAB \.mat file"):
        lr.diagnose(fake)


def test_cli_reports_bad_input_with_exit_code_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data = make_hidden(("coulomb", "viscous"), dt=8e-4).data
    path = tmp_path / "log.csv"
    np.savetxt(path, np.column_stack((data.t, data.x, data.f)), delimiter=",", header="t,x,f", comments="")
    assert main(["diagnose", str(path), "--baseline", "coulomb,stiction", "--json"]) == 2
    assert "unknown effects ['stiction']" in capsys.readouterr().err


def test_cli_diagnose_writes_json_and_plot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import json

    data = make_hidden(("coulomb", "viscous", "offset"), dt=8e-4).data
    path = tmp_path / "log.csv"
    np.savetxt(path, np.column_stack((data.t, data.x, data.f)), delimiter=",", header="t,x,f", comments="")
    figure = tmp_path / "diagnose.png"
    assert main(["diagnose", str(path), "--json", "--plot", str(figure)]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["named_effects"] == ["offset"]
    assert figure.stat().st_size > 10_000


def test_cli_diagnose_reads_named_columns_of_a_rotary_axis(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """--columns maps the file's names; --units rotary names the force N·m in the story."""
    data = make_hidden(("coulomb", "viscous", "offset"), dt=8e-4).data
    path = tmp_path / "joint.csv"
    np.savetxt(path, np.column_stack((data.t, data.x, data.f)), delimiter=",", header="time, q2 ,tau_2",
               comments="")  # fmt: skip
    argv = ["diagnose", str(path), "--columns", "t=time,x=q2,f=tau_2", "--units", "rotary"]
    assert main(argv) == 0
    story = capsys.readouterr().out
    assert "force noise" in story and " N·m" in story
    assert " N " not in story and " N;" not in story and not story.rstrip().endswith(" N")
