"""The discrepancy workflow on generated logs with hidden effects (leuven_rt.discrepancy.hidden):
every catalogue effect alone, pairs, a null case and an effect outside the catalogue.

Single effects use dt = 0.8 ms (about 7 800 samples) to keep the suite fast, pairs dt = 0.4 ms
(15 600 samples: at 0.8 ms the second effect of a pair is not always significant in every
block); the benchmark benches/diagnose.py runs the workflow on 30 000 samples.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt.discrepancy import CATALOGUE
from leuven_rt.discrepancy.hidden import make_hidden

DT = 8e-4
BASE = ("coulomb", "viscous")

SINGLE = [(BASE, ("viscous",)), (BASE, ("coulomb",))] + [
    (BASE + (effect,), BASE) for effect in CATALOGUE if effect not in BASE
]
PAIRS = [
    (BASE + ("inertia", "offset"), BASE),
    (BASE + ("presliding_hysteresis", "position_dependence"), BASE),
    (BASE + ("stribeck", "inertia"), BASE),
]
PAIR_DT = 4e-4


@pytest.mark.parametrize(("truth", "baseline"), SINGLE + PAIRS, ids=lambda value: "+".join(value))
def test_hidden_effects_are_named_exactly(truth: tuple[str, ...], baseline: tuple[str, ...]) -> None:
    dt = PAIR_DT if len(set(truth) - set(baseline)) > 1 else DT
    data = make_hidden(truth, dt=dt, with_velocity="offset" in truth).data  # some cases give v, most only x
    diagnosis = lr.diagnose(data, baseline)
    assert sorted(diagnosis.named_effects) == sorted(set(truth) - set(baseline)), diagnosis.story()
    assert diagnosis.rms_after < diagnosis.rms_before


@pytest.mark.xfail(strict=True, reason="target not met: the final rms is 1.9-3.9x the noise floor; without the 2 samples either side "
                   "of each direction flip (2.4 % of the samples) it is 0.97x (measured, inertia case)")
@pytest.mark.parametrize("hidden", ["inertia", "offset"])
def test_final_rms_within_1_2_noise_floors(hidden: str) -> None:
    diagnosis = lr.diagnose(make_hidden(BASE + (hidden,), dt=DT).data, BASE)
    assert diagnosis.named_effects == [hidden]
    assert diagnosis.rms_after <= 1.2 * diagnosis.noise_std


def test_null_case_names_nothing() -> None:
    diagnosis = lr.diagnose(make_hidden(BASE, dt=DT, seed=3).data, BASE)
    assert diagnosis.named_effects == []
    assert diagnosis.rms_after == diagnosis.rms_before


def test_drift_outside_the_catalogue_names_nothing_wrong_and_stays_unexplained() -> None:
    diagnosis = lr.diagnose(make_hidden(BASE, dt=DT, drift=True).data, BASE)
    assert diagnosis.named_effects == [], diagnosis.story()
    assert diagnosis.unexplained_significant
    assert diagnosis.rms_after > 2.0 * diagnosis.noise_std


def test_report_follows_design_section_4() -> None:
    diagnosis = lr.diagnose(make_hidden(BASE + ("inertia",), dt=DT).data, "coulomb,viscous")
    report = json.loads(diagnosis.to_json())
    assert list(report) == ["samples", "noise_std", "baseline", "rms_before", "rms_after", "named_effects",
                            "steps", "unexplained", "final_model"]  # fmt: skip
    assert report["samples"] == diagnosis.samples and report["baseline"] == list(BASE)
    assert report["named_effects"] == ["inertia"]
    (step,) = report["steps"]
    assert set(step) == {"effect", "where", "rms_before", "rms_after", "params"}
    assert step["rms_after"] < step["rms_before"]
    assert step["params"]["M"] == pytest.approx(0.05, rel=0.1)  # the generator's MASS (the filtered ẍ is a little low)
    assert not step["where"].startswith("everywhere")  # localised, with its numbers
    assert "rms" in step["where"]
    assert set(report["unexplained"]) == {"significant", "where"}
    assert report["final_model"]["effects"] == list(BASE) + ["inertia"]
    assert np.isfinite(report["noise_std"]) and report["noise_std"] > 0
