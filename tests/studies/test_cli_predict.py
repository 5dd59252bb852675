"""``leuven-rt predict`` and the log options of every command that reads a log (``--columns``,
``--units``): the prediction CSV and its JSON summary, the output checked before the work, one-line
refusals with status 2, the loader's warnings as the command's own lines, and ``identify -o``
writing a model file."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt.discrepancy
import leuven_rt.prediction
from conftest import MAXWELL
from conftest import IdentifyStandIn as _Result
from leuven_rt import ModelFile, Params, predict
from leuven_rt.cli import main
from leuven_rt.data.synthetic import SyntheticData, make_data
from leuven_rt.modelfile import VERSION

SHARED = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "robots"
FRANKA = SHARED / "franka" / "case4_slow.csv"


@pytest.fixture(scope="module")
def synthetic() -> SyntheticData:
    return make_data(seed=0)


def _csv(path: Path, header: str, columns: list[np.ndarray], jitter: bool = False) -> Path:
    rows = np.column_stack(columns).tolist()
    path.write_text("\n".join([header, *(",".join(map(repr, row)) for row in rows)]) + "\n", encoding="utf-8")
    return path


@pytest.fixture
def files(tmp_path: Path, synthetic: SyntheticData) -> dict[str, Path]:
    data = synthetic.data
    log = _csv(tmp_path / "log.csv", "t,x,f", [data.t, data.x, data.f])
    renamed = _csv(tmp_path / "robot.csv", " time , q7 ,tau, other", [data.t, data.x, data.f, data.f])
    model = tmp_path / "model.json"
    ModelFile(friction=synthetic.params).save(model)
    return {"log": log, "renamed": renamed, "model": model}


def _refused(capsys: pytest.CaptureFixture[str], argv: list[str], message: str) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"leuven-rt {argv[0]}: error: "), err
    assert message in err, err


def test_predict_writes_the_csv_and_the_json_summary(
    files: dict[str, Path], tmp_path: Path, synthetic: SyntheticData, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "pred.csv"
    assert main(["predict", str(files["model"]), str(files["log"]), "-o", str(out), "--json"]) == 0
    captured = capsys.readouterr()
    summary = json.loads(captured.out)
    expected = predict(files["model"], files["log"])
    assert summary == expected.to_dict()
    assert summary["rms"] == expected.rms and summary["warnings"] == []
    assert set(summary) == {"rms", "rms_causal", "samples", "units", "reconstruction", "warnings"}
    assert summary["rms"] < 1.05 * synthetic.noise_std
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    assert out.read_text(encoding="utf-8").startswith("t,f,f_model,friction\n")
    np.testing.assert_array_equal(table[:, 2], expected.f_model)
    # Without --json: the summary in sentences.
    assert main(["predict", str(files["model"]), str(files["log"]), "-o", str(out), "--force"]) == 0
    text = capsys.readouterr().out
    assert "rms of f_model - f" in text and f"prediction: {out}" in text


def test_predict_checks_its_output_before_the_work(
    files: dict[str, Path],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    calls: list[Any] = []
    monkeypatch.setattr(leuven_rt.prediction, "predict", lambda *args, **kwargs: calls.append(args))
    existing = tmp_path / "existing.csv"
    existing.write_text("keep me", encoding="utf-8")
    model, log = str(files["model"]), str(files["log"])
    _refused(capsys, ["predict", model, log, "-o", str(existing)], "exists: refusing to overwrite it")
    _refused(capsys, ["predict", model, log, "-o", log, "--force"], "is the input file")
    _refused(capsys, ["predict", model, log, "-o", model, "--force"], "is the input file")
    _refused(capsys, ["predict", model, log, "-o", str(tmp_path)], "is a folder")
    assert calls == [] and existing.read_text(encoding="utf-8") == "keep me"


def test_predict_refusals_are_one_line(files: dict[str, Path], tmp_path: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:  # fmt: skip
    newer = tmp_path / "newer.json"
    newer.write_text(
        json.dumps({**ModelFile(friction=Params(**MAXWELL)).to_dict(), "version": VERSION + 1}),
        encoding="utf-8",
    )
    out = str(tmp_path / "p.csv")
    model, log, renamed = str(files["model"]), str(files["log"]), str(files["renamed"])
    _refused(capsys, ["predict", str(newer), log, "-o", out], "upgrade leuven-rt")
    _refused(capsys, ["predict", model, log, "-o", out, "--units", "rotary"],
             "`--units` is 'rotary', but the model file")  # fmt: skip
    _refused(capsys, ["predict", model, renamed, "-o", out, "--columns", "t=time,x=q8,f=tau"],
             "`q8`, which it does not have: its columns are time, q7, tau, other")  # fmt: skip
    _refused(capsys, ["predict", model, renamed, "-o", out, "--columns", "t:time"],
             "`--columns` must be a list like t=time,x=q7")  # fmt: skip
    assert not Path(out).exists()


def test_predict_maps_columns_and_reports_warnings(
    files: dict[str, Path], tmp_path: Path, synthetic: SyntheticData, capsys: pytest.CaptureFixture[str]
) -> None:
    data = synthetic.data
    t = data.t.copy()
    t[1::2] += 0.2 * data.dt
    jittered = _csv(tmp_path / "jittered.csv", "time,q7,tau", [t, data.x, data.f])
    out = tmp_path / "pred.csv"
    argv = [
        "predict",
        str(files["model"]),
        str(jittered),
        "-o",
        str(out),
        "--json",
        "--columns",
        "t=time,x=q7,f=tau",
    ]
    assert main(argv) == 0
    captured = capsys.readouterr()
    summary = json.loads(captured.out)
    assert len(summary["warnings"]) == 1 and "resampled linearly" in summary["warnings"][0]
    assert captured.err == f"leuven-rt predict: warning: {summary['warnings'][0]}\n"
    assert summary["rms"] < 1.2 * synthetic.noise_std


def test_a_rotary_model_file_predicts_rotary(files: dict[str, Path], tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:  # fmt: skip
    rotary = tmp_path / "rotary.json"
    ModelFile(friction=ModelFile.load(files["model"]).friction, units="rotary").save(rotary)
    out = tmp_path / "pred.csv"
    argv = ["predict", str(rotary), str(files["renamed"]), "-o", str(out), "--columns", "t=time,x=q7,f=tau"]
    assert main([*argv, "--units", "rotary"]) == 0
    assert "N·m" in capsys.readouterr().out


@pytest.mark.skipif(not FRANKA.is_file(), reason=f"the Franka log is not at {FRANKA}")
def test_predict_on_the_franka_log(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    model = tmp_path / "joint.json"
    params = Params(Fc=0.1, Fs=0.15, Vs=0.01, delta=2.0, n=2.0, sigma1=0.0, sigma2=0.1, sigma0=100.0)
    ModelFile(friction=params, offset=-0.05, units="rotary").save(model)
    out = tmp_path / "pred.csv"
    argv = ["predict", str(model), str(FRANKA), "-o", str(out), "--json", "--units", "rotary",
            "--columns", "t=time,x=q7,f=q7_tau_J_compensate,v=dq7"]  # fmt: skip
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["units"] == "rotary" and summary["samples"] > 20_000 and np.isfinite(summary["rms"])
    assert "resampled" in summary["warnings"][0]


def test_identify_and_diagnose_take_columns_and_units(
    files: dict[str, Path],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    seen: list[Any] = []

    def identify(data: Any, *arguments: Any, **options: Any) -> _Result:
        seen.append(data)
        return _Result(data)

    class _Diagnosis:
        def story(self) -> str:
            return "story"

    def diagnose(data: Any, baseline: Any, **options: Any) -> _Diagnosis:
        seen.append(data)
        return _Diagnosis()

    monkeypatch.setattr(leuven_rt.discrepancy, "identify", identify)
    monkeypatch.setattr(leuven_rt.discrepancy, "diagnose", diagnose)
    out = tmp_path / "fitted.json"
    columns = ["--columns", "t=time,x=q7,f=tau"]
    assert main(["identify", str(files["renamed"]), "-o", str(out), "--units", "rotary", *columns]) == 0
    assert "model file (rotary)" in capsys.readouterr().out
    assert main(["diagnose", str(files["renamed"]), *columns]) == 0
    assert [record.units for record in seen] == ["rotary", "linear"]
    np.testing.assert_array_equal(seen[0].x, seen[1].x)
    written = ModelFile.load(out)
    assert written == ModelFile(friction=_Result.params, units="rotary", report={"held_out_rms": 0.1})
    _refused(capsys, ["diagnose", str(files["renamed"])], "missing columns ['t', 'x', 'f']")


def test_identify_keeps_the_loaders_warnings_in_the_model_file(
    files: dict[str, Path],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(leuven_rt.discrepancy, "identify", lambda data, *arguments, **options: _Result(data))
    log = _csv(
        tmp_path / "mm.csv", "t,x,f", [np.arange(400) * 1e-3, np.linspace(0.0, 8.0, 400), np.ones(400)]
    )
    out = tmp_path / "fitted.json"
    assert main(["identify", str(log), "-o", str(out), "--quiet"]) == 0
    err = capsys.readouterr().err
    assert err.startswith("leuven-rt identify: warning: column `x` spans 8 m") and err.count("\n") == 1
    report = ModelFile.load(out).report
    assert report is not None and report["data_notes"] == [err.split("warning: ", 1)[1].rstrip("\n")]
