"""The closed-loop proof (leuven_rt.studies.closed_loop): on a simulated stage whose true friction
differs from the compensator's model, PID control at 1 kHz with Leuven compensation tracks with
an RMS error at least 3x smaller than without compensation and 1.5x smaller than with
Coulomb-only compensation, in both modes (feedforward and observer)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from leuven_rt import InputError
from leuven_rt.cli import main
from leuven_rt.studies.closed_loop import COMPENSATIONS, Comparison, Scenario, compare, simulate

LEUVEN = ("leuven_feedforward", "leuven_observer")


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

    # Leuven feedforward predicts the true friction far better than Coulomb-only does.
    def residual(name: str) -> float:
        return float(np.sqrt(np.mean((runs[name].friction - runs[name].compensation_force) ** 2)))

    assert residual("leuven_feedforward") < 0.5 * residual("coulomb")


@pytest.mark.parametrize(
    "change", [dict(bandwidth=50.0), dict(frequency=2.0), dict(encoder_resolution=1e-6, noise=2e-7)]
)
def test_the_ratios_hold_beyond_the_default_scenario(change: dict[str, float]) -> None:
    """A stiffer loop, faster motion and a coarse, noisy encoder: still above the targets."""
    other = compare(replace(Scenario(), **change))
    for leuven in LEUVEN:
        assert other.ratio("none", leuven) >= 3.0, (change, leuven)
        assert other.ratio("coulomb", leuven) >= 1.5, (change, leuven)


def test_cli_prints_the_table_and_writes_the_figure(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["control", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "| leuven_feedforward |" in out and "| coulomb |" in out
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
    with pytest.raises(InputError, match=r"`compensation` must be one of .*, got 'pid'"):
        simulate(Scenario(), "pid")
