"""The closed-loop proof (leuven_rt.studies.closed_loop): on a simulated stage whose true friction
differs from the compensator's hand-set model, PID control at 1 kHz with Leuven compensation
tracks with an RMS error at least 3x smaller than without compensation and 1.5x smaller than
with Coulomb-only compensation, in both modes (feedforward and observer). The stage logged on
another trajectory and identified from that log (encoder and actuator force only) should give a
compensator at least as good as the hand-set one, in tracking RMS and in the reversal glitch:
asserted."""

from __future__ import annotations

import importlib.util
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from leuven_rt import InputError
from leuven_rt.cli import main
from leuven_rt.studies.closed_loop import (
    COMPENSATIONS,
    HAND_SET,
    Comparison,
    Scenario,
    compare,
    evaluation_trajectory,
    identification_trajectory,
    simulate,
)

LEUVEN = ("leuven_feedforward", "leuven_observer")
MODES = ("feedforward", "observer")

#: The target of the identified compensator, missed with this engine: its rounds take this log's
#: encoder for a noisy position (leuven_rt.data.reconstruction.noisy_position: the counts reverse
#: 15 times as often as their low-pass at a twentieth of the Nyquist frequency), but most of those
#: reversals are the servo's own hunting, which the true position makes too (663 reversals).
#: Driven through the low-pass at 100 Hz, the presliding candidate gains nothing (3e-12 units) and
#: the rounds name only the inertia on 6 of the seeds 0-7. With the rounds on the raw encoder, as
#: before noisy_position, every assertion below holds (and on every seed 0-7).


@pytest.fixture(scope="module")
def comparison() -> Comparison:
    return compare()


def test_the_compensator_does_not_know_the_true_friction(comparison: Comparison) -> None:
    true, model = comparison.scenario.true, comparison.scenario.model
    for key in ("Fc", "Fs", "Vs", "sigma2", "W", "Delta"):
        assert getattr(true, key) != getattr(model, key), key


@pytest.mark.parametrize("leuven", LEUVEN)
def test_leuven_cuts_the_rms_tracking_error(comparison: Comparison, leuven: str) -> None:
    assert comparison.ratio("none", leuven) >= 3.0
    assert comparison.ratio("coulomb", leuven) >= 1.5
    # The quadrant glitches, which dominate the error, shrink too.
    metrics = comparison.metrics
    assert metrics[leuven].glitch < metrics["coulomb"].glitch < metrics["none"].glitch
    assert metrics[leuven].max < metrics["coulomb"].max


def test_runs_are_what_they_claim(comparison: Comparison) -> None:
    runs = comparison.runs
    assert set(runs) == set(COMPENSATIONS)
    assert not runs["none"].compensation_force.any()
    coulomb = runs["coulomb"].compensation_force
    assert set(np.unique(np.abs(coulomb))) <= {0.0, comparison.scenario.model.Fc}
    # The stage really has friction, of the true level while sliding.
    friction = runs["none"].friction
    assert 0.9 * comparison.scenario.true.Fc < np.max(np.abs(friction)) < comparison.scenario.true.Fs
    # The encoder reads the true position to within its step and a few noise deviations.
    scenario = comparison.scenario
    reading = runs["none"].measured - runs["none"].position
    assert np.max(np.abs(reading)) < scenario.encoder_resolution + 6 * scenario.noise
    assert np.all(np.abs(np.round(runs["none"].measured / scenario.encoder_resolution)
                         - runs["none"].measured / scenario.encoder_resolution) < 1e-6)  # fmt: skip

    # Leuven feedforward predicts the true friction far better than Coulomb-only does.
    def residual(name: str) -> float:
        return float(np.sqrt(np.mean((runs[name].friction - runs[name].compensation_force) ** 2)))

    assert residual("leuven_feedforward") < 0.5 * residual("coulomb")


def test_the_identified_model_predicts_the_friction_better_than_the_hand_set_one(
    comparison: Comparison,
) -> None:
    runs = comparison.runs

    def residual(name: str) -> float:
        return float(np.sqrt(np.mean((runs[name].friction - runs[name].compensation_force) ** 2)))

    for mode in MODES:
        assert residual(f"identified_{mode}") < residual(f"leuven_{mode}"), mode


def test_the_identification_log_is_what_a_controller_logs(comparison: Comparison) -> None:
    """Another trajectory than the evaluation's, richer (presliding moves, speeds over two decades
    down to below the Stribeck velocity); the log has the encoder reading and the actuator force,
    no velocity."""
    identified = comparison.identified
    assert identified is not None
    scenario = comparison.scenario
    path, evaluation = identification_trajectory(scenario), evaluation_trajectory(scenario)
    assert path.t.size != evaluation.t.size or not np.allclose(path.x, evaluation.x)
    speeds = np.abs(np.diff(path.x)) * scenario.rate
    moving = speeds[speeds > 0]
    assert (
        moving.min() < 0.2 * scenario.true.Vs
        and moving.max() > 2.0 * np.max(np.abs(np.diff(evaluation.x))) * scenario.rate
    )
    assert len(path.reversals) >= 20
    # Presliding moves come first: reversals within the largest break deflection of the truth.
    presliding = path.t[np.argmax(np.abs(path.x - path.x[0]) > max(scenario.true.Delta or ()) * 2)]
    assert np.count_nonzero(path.reversals < presliding) >= 7
    log, run = identified.log, identified.run
    assert log.v is None
    np.testing.assert_array_equal(log.x, run.measured)
    np.testing.assert_array_equal(log.f, run.command)
    assert not run.compensation_force.any()  # logged under the PID alone


def test_the_identification_names_what_the_stage_has(comparison: Comparison) -> None:
    """From coulomb, viscous: the Stribeck curve and the presliding hysteresis of the true
    friction, and the inertia of the actuator force (the mass, to 5 %); nothing the stage does
    not have. The model explains its own log to a tenth of the baseline's error."""
    identified = comparison.identified
    assert identified is not None
    assert sorted(identified.named) == ["inertia", "presliding_hysteresis", "stribeck"]
    model = identified.identification.model
    assert model.inertia == pytest.approx(comparison.scenario.mass, rel=0.05)
    assert model.level is None and model.position_force is None
    friction, true = model.friction, comparison.scenario.true
    for key in ("Fc", "Fs", "Vs", "sigma2"):
        assert getattr(friction, key) == pytest.approx(getattr(true, key), rel=0.15), key
    assert identified.rms < 0.1 * identified.identification.diagnosis.rms_before
    assert identified.identification.warnings == ()


@pytest.mark.parametrize("mode", MODES)
def test_the_identified_compensator_is_at_least_as_good_as_the_hand_set_one(
    comparison: Comparison, mode: str
) -> None:
    identified, hand_set = comparison.metrics[f"identified_{mode}"], comparison.metrics[f"leuven_{mode}"]
    assert identified.rms <= hand_set.rms
    assert identified.glitch <= hand_set.glitch
    assert identified.max <= hand_set.max


def test_the_identified_compensator_holds_on_a_faster_trajectory(comparison: Comparison) -> None:
    """The same identification (the log does not depend on the evaluation trajectory) at twice
    the frequency: still at least as good as the hand-set model."""
    faster = compare(replace(comparison.scenario, frequency=2.0), identified=comparison.identified)
    for mode in MODES:
        identified, hand_set = faster.metrics[f"identified_{mode}"], faster.metrics[f"leuven_{mode}"]
        assert identified.rms <= hand_set.rms and identified.glitch <= hand_set.glitch, mode


@pytest.mark.parametrize(
    "change", [dict(bandwidth=50.0), dict(frequency=2.0), dict(encoder_resolution=1e-6, noise=2e-7)]
)
def test_the_ratios_hold_beyond_the_default_scenario(change: dict[str, float]) -> None:
    """A stiffer loop, faster motion and a coarse, noisy encoder: still above the targets."""
    other = compare(replace(Scenario(), **change), HAND_SET)
    assert other.identified is None
    for leuven in LEUVEN:
        assert other.ratio("none", leuven) >= 3.0, (change, leuven)
        assert other.ratio("coulomb", leuven) >= 1.5, (change, leuven)


def test_cli_prints_the_table_and_writes_the_figure(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["control", "--out", str(tmp_path), "--quiet"]) == 0
    captured = capsys.readouterr()
    out = captured.out
    for name in COMPENSATIONS:
        assert f"| {name} |" in out, name
    assert "identify named" in out and "hand-set -> identified (feedforward)" in out
    assert captured.err == ""  # --quiet: no progress
    assert (tmp_path / "closed_loop.png").stat().st_size > 10_000


@pytest.mark.parametrize(
    ("change", "match"),
    [
        (dict(rate=0.0), r"`rate` must be a finite number > 0, got 0.0"),
        (dict(mass=float("nan")), r"`mass` must be a finite number > 0, got nan"),
        (dict(noise=-1e-9), r"`noise` must be finite and >= 0, got -1e-09"),
        (dict(plant_rate=1500.0), r"`plant_rate` must be a multiple of `rate`"),
    ],
)
def test_bad_scenarios_are_refused(change: dict[str, float], match: str) -> None:
    with pytest.raises(InputError, match=match):
        replace(Scenario(), **change)


def test_unknown_compensation_is_refused() -> None:
    with pytest.raises(InputError, match=r"`compensation` must be one of .*, got 'pid'") as caught:
        simulate(Scenario(), "pid")
    assert (caught.value.kind, caught.value.field, caught.value.value) == (
        "invalid_choice",
        "compensation",
        "pid",
    )
    assert caught.value.expected == COMPENSATIONS
    with pytest.raises(InputError, match=r"`compensations` must be among .*, got 'pid'") as caught:
        compare(compensations=("none", "pid"))
    assert (caught.value.kind, caught.value.field, caught.value.value) == (
        "invalid_choice",
        "compensations",
        "pid",
    )


def test_an_identified_compensation_needs_the_identified_model() -> None:
    with pytest.raises(InputError, match=r"`identified` must be the identified model file") as caught:
        simulate(Scenario(), "identified_observer")
    assert (caught.value.kind, caught.value.field) == ("missing", "identified")


def test_the_identification_of_another_stage_is_refused(comparison: Comparison) -> None:
    other = replace(comparison.scenario, mass=3.0, noise=0.0)
    with pytest.raises(
        InputError, match=r"identification of this scenario's stage, .* mass, noise differ"
    ) as caught:
        compare(other, identified=comparison.identified)
    assert (caught.value.kind, caught.value.field, caught.value.value) == (
        "not_applicable",
        "identified",
        ["mass", "noise"],
    )


def test_the_true_law_bench_refuses_an_unknown_plant(capsys: pytest.CaptureFixture[str]) -> None:
    """``benches/true_law.py --plant`` takes the plants it knows, and names them when given another,
    before any identification runs."""
    path = Path(__file__).resolve().parents[2] / "benches" / "true_law.py"
    spec = importlib.util.spec_from_file_location("leuven_rt_bench_true_law", path)
    assert spec is not None and spec.loader is not None
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    with pytest.raises(SystemExit) as exit_info:
        bench.main(["--plant", "mujoco"])
    assert exit_info.value.code == 2
    assert "--plant: invalid choice: 'mujoco' (choose from 'study', 'lugre_soft', 'lugre_stiff')" in (
        capsys.readouterr().err
    )
