"""Identification on data made by the project's own simulator: the truth is known.

Two records (leuven_rt.data.synthetic.make_data: presliding loops, a sliding sine, constant-velocity
plateaus from 0.3 to 100 Vs in both directions), each measured with white force noise and an
encoder quantization:

- symmetric truth (scenarios.standard_params: N = 10, Δ up to 10 µm), noise 0.02 N, 10 nm;
  N chosen by the identification;
- asymmetric truth (Fc_neg, Fs_neg; N = 8; σ2 = 2 N·s/m, so that viscous friction stands out of
  the noise at the top speed), noise 0.05 N, 50 nm; N = 6 given.

Stated tolerances, relative to the truth: Fc, Fs (and Fc_neg, Fs_neg) 1 %; Vs 3 %; δ 5 %; n 10 %;
σ2 15 %; σ1 within a factor 2 (it acts only through dz/dt in the transitions, so the data pins
it down loosely). Break deflections are pre-assigned, so W and Δ are not compared one by one:
the model's noise-free force is, over the whole record (RMS below 0.6 noise levels). The
held-out force error (the last quarter of the record, never fitted) is within 1.2× the noise.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt.cli
from leuven_rt import ModelFile, Params, simulate_position
from leuven_rt.data.scenarios import standard_params
from leuven_rt.data.synthetic import SyntheticData, make_data
from leuven_rt.identification import IdentificationResult, MotionData
from leuven_rt.identification import identify_staged as identify

TOLERANCES = {"Fc": 0.01, "Fs": 0.01, "Fc_neg": 0.01, "Fs_neg": 0.01, "Vs": 0.03, "delta": 0.05, "n": 0.10,
              "sigma2": 0.15}  # fmt: skip
HELD_OUT_LIMIT = 1.2
MODEL_ERROR_LIMIT = 0.6


def asymmetric_truth() -> Params:
    values = standard_params(elements=8).to_dict()
    values.update(Fc_neg=0.8, Fs_neg=1.3, sigma2=2.0)
    return Params.from_dict(values)


@pytest.fixture(scope="module")
def symmetric() -> tuple[SyntheticData, IdentificationResult]:
    synthetic = make_data(noise_std=0.02, quantization=1e-8, seed=0)
    return synthetic, identify(synthetic.data)


@pytest.fixture(scope="module")
def asymmetric() -> tuple[SyntheticData, IdentificationResult]:
    synthetic = make_data(asymmetric_truth(), noise_std=0.05, quantization=5e-8, seed=1)
    return synthetic, identify(synthetic.data, asymmetric=True, elements=6)


CASES = ["symmetric", "asymmetric"]


def case(request: pytest.FixtureRequest, name: str) -> tuple[SyntheticData, IdentificationResult]:
    value: Any = request.getfixturevalue(name)
    return value


@pytest.mark.parametrize("name", CASES)
def test_held_out_error_is_within_the_noise_level(request: pytest.FixtureRequest, name: str) -> None:
    synthetic, result = case(request, name)
    report = result.report
    assert report.held_out_samples == synthetic.data.samples - report.training_samples > 0
    assert report.held_out_rms <= HELD_OUT_LIMIT * synthetic.noise_std


@pytest.mark.parametrize("name", CASES)
def test_parameters_are_within_the_stated_tolerances(request: pytest.FixtureRequest, name: str) -> None:
    synthetic, result = case(request, name)
    truth, found = synthetic.params.to_dict(), result.params.to_dict()
    for key, tolerance in TOLERANCES.items():
        if key in truth:
            assert found[key] == pytest.approx(truth[key], rel=tolerance), key
    assert 0.5 * truth["sigma1"] <= found["sigma1"] <= 2.0 * truth["sigma1"]


@pytest.mark.parametrize("name", CASES)
def test_the_model_reproduces_the_noise_free_force(request: pytest.FixtureRequest, name: str) -> None:
    synthetic, result = case(request, name)
    model = simulate_position(result.params, synthetic.x_true, synthetic.data.dt)
    error = float(np.sqrt(np.mean((model - synthetic.force_true) ** 2)))
    assert error <= MODEL_ERROR_LIMIT * synthetic.noise_std


def test_the_number_of_elements_is_chosen_or_given(
    symmetric: tuple[SyntheticData, IdentificationResult],
    asymmetric: tuple[SyntheticData, IdentificationResult],
) -> None:
    presliding = next(stage for stage in symmetric[1].report.stages if stage.name == "presliding")
    errors = presliding.details["held_out_rms_by_elements"]
    assert sorted(errors) == list(range(1, 13))
    chosen = symmetric[1].params.elements
    assert errors[chosen] <= 1.02 * min(errors.values())
    assert asymmetric[1].params.elements == 6
    # Δ is pre-assigned equally spaced up to the presliding range estimated from the data.
    Delta = np.asarray(asymmetric[1].params.Delta)
    np.testing.assert_allclose(Delta, asymmetric[1].report.presliding_range * np.arange(1, 7) / 6)


def test_the_report_says_what_each_stage_did(symmetric: tuple[SyntheticData, IdentificationResult]) -> None:
    synthetic, result = symmetric
    report = result.report
    assert [stage.name for stage in report.stages] == ["sliding", "presliding", "transition", "joint"]
    assert report.reversals >= 20
    assert report.noise_std == pytest.approx(synthetic.noise_std, rel=0.1)
    assert all(np.isfinite(stage.condition) and stage.rms > 0 for stage in report.stages)
    # The joint fit is the best of the stages over the whole training part.
    assert report.stages[-1].rms <= report.stages[-2].rms
    assert report.warnings == []
    text = report.to_json()
    assert '"held_out_rms"' in text and "joint" in report.summary()


def test_synthetic_data_is_quantized_noisy_and_true_to_the_simulator() -> None:
    synthetic = make_data(noise_std=0.03, quantization=5e-8, seed=4)
    data = synthetic.data
    steps = data.x / 5e-8
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-6)
    assert np.max(np.abs(data.x - synthetic.x_true)) <= 2.5e-8 * (1 + 1e-9)
    np.testing.assert_array_equal(
        synthetic.force_true, simulate_position(synthetic.params, synthetic.x_true, data.dt)
    )
    assert np.std(data.f - synthetic.force_true) == pytest.approx(0.03, rel=0.05)
    v = np.diff(synthetic.x_true) / data.dt
    assert np.count_nonzero(np.diff(np.sign(v[v != 0]))) >= 20  # reversals
    assert np.max(np.abs(v)) >= 50 * synthetic.params.Vs  # sliding well past the Stribeck velocity


def short_move() -> MotionData:
    """One move from rest in one direction at 5 mm/s: no reversal."""
    dt, samples = 2e-4, 2500
    speed = 5e-3 * np.minimum(np.arange(samples) / 1000.0, 1.0)  # ramps up from rest in 0.2 s
    x = np.cumsum(speed) * dt
    force = simulate_position(standard_params(), x, dt) + np.random.default_rng(5).normal(0.0, 0.01, samples)
    return MotionData(np.arange(samples) * dt, np.round(x / 1e-8) * 1e-8, force)


def test_no_reversals_is_reported() -> None:
    result = identify(short_move(), elements=3, held_out=0.0)
    assert result.report.reversals == 0
    assert any(
        "no reversals in the data: presliding not identifiable" in text for text in result.report.warnings
    )
    assert np.isnan(result.report.held_out_rms)


def test_command_line_writes_the_model_file_of_identify(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    data = short_move()
    csv = tmp_path / "log.csv"
    np.savetxt(csv, np.column_stack((data.t, data.x, data.f)), delimiter=",", header="t,x,f", comments="",
               fmt="%.17g")  # fmt: skip
    out, report = tmp_path / "model.json", tmp_path / "report.json"
    assert leuven_rt.cli.main(["identify", str(csv), "-o", str(out), "--report", str(report), "--quiet"]) == 0
    assert capsys.readouterr().out == ""
    expected = leuven_rt.identify(csv)
    assert ModelFile.load(out).to_dict() == ModelFile.from_json(expected.model.to_json()).to_dict()
    assert '"named_effects"' in report.read_text(encoding="utf-8")
