"""One model: what the report says is what the loop gets.

Every number the identification reports about its model is that model file's simulation error
along the log, and ``predict`` of the written file gives the report's final rms; the file records
how it reconstructs the motion, and ``predict`` drives it that way (the logged velocity where the
fit used it)."""

from __future__ import annotations

import ctypes
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import leuven_rt as lr
from conftest import CError, built_c_library, cargo_built
from leuven_rt.data.records import MotionData
from leuven_rt.discrepancy.hidden import make_hidden
from leuven_rt.errors import DataError
from leuven_rt.studies.emps import relative_error

LOGS = {
    "with v": dict(truth=("coulomb", "viscous", "stribeck"), with_velocity=True),
    "without v": dict(truth=("coulomb", "viscous", "presliding_hysteresis"), with_velocity=False),
    "with a level": dict(truth=("coulomb", "viscous", "position_dependence", "offset"), with_velocity=True),
}


@pytest.fixture(scope="module", params=sorted(LOGS))
def identified(request: pytest.FixtureRequest) -> tuple[MotionData, lr.Identification]:
    log = make_hidden(seed=3, **LOGS[request.param]).data
    return log, lr.identify(log)


def test_the_reports_final_rms_is_the_written_files_predict_rms(
    identified: tuple[MotionData, lr.Identification],
) -> None:
    log, result = identified
    prediction = lr.predict(result.model, log)
    assert result.diagnosis.rms_after == prediction.rms
    assert result.model.report is not None
    assert result.model.report["rms_after"] == prediction.rms
    # The last step ends where the file is.
    if result.diagnosis.steps:
        assert result.diagnosis.steps[-1].rms_after == prediction.rms


def test_the_file_says_how_it_reconstructs_the_motion_and_predict_follows(
    identified: tuple[MotionData, lr.Identification],
) -> None:
    log, result = identified
    reconstruction = result.model.reconstruction
    assert reconstruction is not None
    prediction = lr.predict(result.model, log)
    assert prediction.reconstruction == reconstruction
    if log.v is not None and reconstruction.source == "velocity":
        # Driven by the logged velocity: the same velocities as the log's.
        assert np.array_equal(prediction.v, log.v)


def compensated(model: lr.ModelFile | Path, prediction: lr.Prediction) -> np.ndarray:
    """The friction of a Python compensator running ``model`` along the motion ``predict``
    drove the model with, in the mode the file's reconstruction stands for: feedforward with the
    velocity and its positions where the file is driven by a velocity, observer with the position
    otherwise."""
    reconstruction = prediction.reconstruction
    if reconstruction.source == "velocity":
        compensator = lr.Compensator(model, prediction.dt, "feedforward", x=float(prediction.x[0]))
        return np.array(
            [
                compensator.step_trajectory(float(v), float(x))
                for v, x in zip(prediction.v, prediction.x, strict=True)
            ]
        )
    compensator = lr.Compensator(model, prediction.dt, "observer")
    return np.array([compensator.step(float(x)) for x in prediction.x])


def c_compensated(text: str, prediction: lr.Prediction) -> np.ndarray:
    """The same through the C library, which reads the file's text with the same reader."""
    library = built_c_library()
    data = text.encode()
    handle, error, force = ctypes.c_void_p(), CError(), ctypes.c_double()
    velocity = prediction.reconstruction.source == "velocity"
    status = library.leuven_rt_compensator_create_from_json_at(
        data, len(data), prediction.dt, 0 if velocity else 1, float(prediction.x[0]), ctypes.byref(handle),
        ctypes.byref(error),
    )  # fmt: skip
    assert status == 0, error.message
    out = np.empty(prediction.x.size)
    try:
        for k, (v, x) in enumerate(zip(prediction.v, prediction.x, strict=True)):
            if velocity:
                status = library.leuven_rt_compensator_step_trajectory(
                    handle, float(v), float(x), ctypes.byref(force)
                )
            else:
                status = library.leuven_rt_compensator_step(handle, float(x), ctypes.byref(force))
            assert status == 0
            out[k] = force.value
    finally:
        library.leuven_rt_compensator_destroy(handle)
    return out


def rust_compensated(path: Path, prediction: lr.Prediction) -> np.ndarray:
    """The same through Rust alone: gms-file's ``compensate`` example, which loads the file with
    the same reader and steps gms-dyn's compensator."""
    [program] = cargo_built(["-p", "gms-file", "--example", "compensate"], "compensate", "the Rust example")
    velocity = prediction.reconstruction.source == "velocity"
    arguments = ["feedforward", repr(float(prediction.x[0]))] if velocity else ["observer"]
    columns = (prediction.v, prediction.x) if velocity else (prediction.x,)
    signal = "".join(
        ",".join(repr(float(value)) for value in row) + "\n" for row in zip(*columns, strict=True)
    )
    done = subprocess.run([program, str(path), repr(prediction.dt), *arguments], input=signal,
                          capture_output=True, text=True, timeout=600, check=False)  # fmt: skip
    assert done.returncode == 0, done.stderr
    return np.array([float(line) for line in done.stdout.splitlines()])


def test_the_rust_example_refuses_what_it_cannot_run(
    identified: tuple[MotionData, lr.Identification], tmp_path: Path
) -> None:
    """A mode it does not know, a line of the wrong width or not a number, a DT that is no
    number, a file that is no model: one line on stderr that says what was expected and what it
    got (or names the file's key), and exit status 1."""
    [program] = cargo_built(["-p", "gms-file", "--example", "compensate"], "compensate", "the Rust example")
    _, result = identified
    path = tmp_path / "model.json"
    result.model.save(path)
    broken = tmp_path / "broken.json"
    broken.write_text(path.read_text().replace('"Fc"', '"Fk"', 1))

    def run(*arguments: str, signal: str = "0.0\n") -> subprocess.CompletedProcess[str]:
        return subprocess.run([program, *arguments], input=signal, capture_output=True, text=True,
                              timeout=120, check=False)  # fmt: skip

    refusals = {
        'mode must be observer or feedforward, got "backwards"': run(str(path), "1e-3", "backwards"),
        'line 1 of the signal must hold 1 number(s), got "0.0,1.0"': run(
            str(path), "1e-3", "observer", signal="0.0,1.0\n"
        ),
        'line 2 of the signal must be a number, got "x"': run(
            str(path), "1e-3", "observer", signal="0.0\nx\n"
        ),
        'DT must be a number, got "fast"': run(str(path), "fast", "observer"),
        "`friction.Fk`: unknown key": run(str(broken), "1e-3", "observer"),
    }
    for message, done in refusals.items():
        assert done.returncode == 1 and done.stderr.startswith(f"compensate: {message}"), done.stderr


def test_the_compensator_running_the_written_file_gives_predicts_friction(
    identified: tuple[MotionData, lr.Identification], tmp_path: Path
) -> None:
    log, result = identified
    prediction = lr.predict(result.model, log)
    scale = float(np.max(np.abs(prediction.friction)))
    path = tmp_path / "model.json"
    result.model.save(path)
    for model in (result.model, path):
        np.testing.assert_allclose(
            compensated(model, prediction), prediction.friction, rtol=0.0, atol=1e-9 * scale
        )
    from_c = c_compensated(path.read_text(), prediction)
    np.testing.assert_allclose(from_c, prediction.friction, rtol=0.0, atol=1e-9 * scale)
    from_rust = rust_compensated(path, prediction)
    np.testing.assert_allclose(from_rust, prediction.friction, rtol=0.0, atol=1e-9 * scale)


def test_a_round_trip_through_the_file_predicts_the_same(
    identified: tuple[MotionData, lr.Identification], tmp_path: Path
) -> None:
    log, result = identified
    path = tmp_path / "model.json"
    result.model.save(path)
    assert lr.predict(path, log).rms == lr.predict(result.model, log).rms


def test_a_log_with_no_sliding_motion_is_refused_saying_what_it_lacks() -> None:
    t = np.arange(5000) * 1e-3
    x = np.where(t > 1.0, 1e-8, 0.0)  # one 10 nm step
    f = np.random.default_rng(0).normal(0.0, 0.01, t.size)
    with pytest.raises(DataError) as caught:
        lr.identify(MotionData(t, x, f))
    assert caught.value.kind == "no_sliding_motion"
    assert "no sliding motion" in str(caught.value)
    dither = 1e-7 * (np.arange(t.size) % 2)  # an axis holding still, one count of encoder dither
    with pytest.raises(DataError) as caught:
        lr.identify(MotionData(t, dither, f))
    assert caught.value.kind == "no_sliding_motion"


def test_what_is_named_does_not_depend_on_the_forces_scale() -> None:
    log = make_hidden(("coulomb", "viscous", "stribeck"), seed=1, with_velocity=True).data
    scaled = MotionData(log.t, log.x, log.f * 1e-9, v=log.v)
    assert lr.diagnose(scaled).named_effects == lr.diagnose(log).named_effects


def test_a_noise_free_coulomb_log_names_nothing_at_any_scale() -> None:
    dt = 1e-3
    t = np.arange(20_000) * dt
    v = 0.01 * np.sin(2 * np.pi * 0.5 * t)
    x = np.cumsum(v) * dt
    for scale in (1.0, 1e-9):
        f = scale * lr.simulate(
            lr.Params(Fc=1.0, Fs=1.0, Vs=1.0, delta=2.0, n=2.0, W=[2.0], Delta=[1e-10]), v, dt
        )
        diagnosis = lr.diagnose(MotionData(t, x, f, v=v), "coulomb")
        assert diagnosis.named_effects == [], (scale, diagnosis.story())


def test_a_one_way_ramp_keeps_no_viscous_slope_it_cannot_see() -> None:
    dt = 1e-3
    t = np.arange(10_000) * dt
    v = np.full(t.size, 0.05)
    x = np.cumsum(v) * dt
    f = 3.0 + np.random.default_rng(2).normal(0.0, 0.05, t.size)
    result = lr.identify(MotionData(t, x, f, v=v))
    assert result.params.sigma2 == 0.0
    assert any("sigma2" in warning and "not determined" in warning for warning in result.warnings)
    # What the compensator would add at 0.1 m/s stays what the log shows.
    assert float(lr.predict(result.model, MotionData(t, x, f, v=v)).friction[-1]) == pytest.approx(
        3.0, rel=0.05
    )


def test_every_term_a_one_way_ramp_cannot_tell_is_written_neutral() -> None:
    """Moving at one speed in +x only: a viscous slope, the −x levels, an offset split off the
    Coulomb level and an inertia are all undetermined; the file keeps each at the value that adds
    no force, and a warning names each."""
    dt = 1e-3
    t = np.arange(10_000) * dt
    v = np.full(t.size, 0.05)
    x = np.cumsum(v) * dt
    f = 3.0 + np.random.default_rng(4).normal(0.0, 0.05, t.size)
    result = lr.identify(MotionData(t, x, f, v=v), "coulomb,viscous,asymmetry,offset,inertia")
    model = result.model
    params = model.friction
    assert params.sigma2 == 0.0 and model.offset == 0.0 and model.inertia == 0.0
    assert params.Fc_neg in (None, params.Fc) and params.sigma2_neg in (None, 0.0)
    warned = " ".join(result.warnings)
    for name in ("sigma2", "offset", "inertia", "Fc_neg"):
        assert f"`{name}`" in warned, result.warnings
    assert params.Fc == pytest.approx(3.0, rel=0.01)


def test_emps_figure_of_merit_is_the_relative_error_of_decimated_signals() -> None:
    t = np.arange(4000) * 1e-3
    x = 0.01 * np.sin(2 * np.pi * t)
    f = np.sin(2 * np.pi * 3 * t)
    model = lr.ModelFile(
        friction=lr.Params(Fc=1e-9, Fs=1e-9, Vs=1.0, delta=2.0, n=2.0, W=[1.0], Delta=[1e-12])
    )
    prediction = lr.predict(model, MotionData(t, x, f))
    assert relative_error(prediction) == pytest.approx(100.0, rel=1e-3)


def test_the_cli_identify_then_predict_prints_the_same_rms(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from leuven_rt.cli import main

    log = make_hidden(("coulomb", "viscous", "offset"), seed=2, with_velocity=True).data
    path = tmp_path / "log.csv"
    np.savetxt(
        path, np.column_stack([log.t, log.x, log.f, log.v]), delimiter=",", header="t,x,f,v", comments=""
    )
    assert main(["identify", str(path), "-o", str(tmp_path / "m.json"), "--report", str(tmp_path / "r.json"),
                 "--quiet"]) == 0  # fmt: skip
    capsys.readouterr()
    assert main(["predict", str(tmp_path / "m.json"), str(path), "-o", str(tmp_path / "p.csv"), "--json",
                 "--plot", str(tmp_path / "p.png")]) == 0  # fmt: skip
    printed = json.loads(capsys.readouterr().out)
    report = json.loads((tmp_path / "r.json").read_text())
    assert printed["rms"] == report["rms_after"]
    assert printed["reconstruction"] == {
        key: value for key, value in report["reconstruction"].items() if key != "description"
    }
    assert (tmp_path / "p.png").stat().st_size > 0
