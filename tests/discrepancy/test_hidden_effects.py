"""The workflow on generated logs with hidden effects (leuven_rt.discrepancy.hidden): every
catalogue effect alone, pairs, a null case and an effect outside the catalogue (a drift), with and
without a logged velocity. What is named, and the error of the written file where the log allows
the noise (a logged velocity: the floor is the noise itself)."""

from __future__ import annotations

import dataclasses
import importlib
import json
from typing import Any

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt.discrepancy import CATALOGUE
from leuven_rt.discrepancy.hidden import make_hidden
from leuven_rt.discrepancy.report import Diagnosis
from leuven_rt.fitting.select import Selection, StandIn

BASE = ("coulomb", "viscous")
#: The module, which ``leuven_rt.discrepancy.identify`` (the function) hides.
identify_module = importlib.import_module("leuven_rt.discrepancy.identify")
DT = 8e-4
SINGLE = [(*BASE, effect) for effect in CATALOGUE if effect not in BASE]
PAIRS = [
    (*BASE, "inertia", "offset"),
    (*BASE, "presliding_hysteresis", "position_dependence"),
    (*BASE, "stribeck", "asymmetry"),
]


@pytest.mark.parametrize("with_velocity", [False, True], ids=["x", "x,v"])
@pytest.mark.parametrize("truth", SINGLE + PAIRS, ids="+".join)
def test_hidden_effects_are_named_exactly(truth: tuple[str, ...], with_velocity: bool) -> None:
    hidden = make_hidden(truth, dt=DT, with_velocity=with_velocity, seed=len(truth))
    identification = lr.identify(hidden.data, BASE)
    diagnosis = identification.diagnosis
    assert sorted(diagnosis.named_effects) == sorted(set(truth) - set(BASE)), diagnosis.story()
    assert diagnosis.rms_after < diagnosis.rms_before
    if with_velocity:
        # The log gives the model what it needs: the written file ends at the noise.
        assert lr.predict(identification.model, hidden.data).rms <= 1.2 * hidden.noise_std, diagnosis.story()


def offset_log() -> lr.MotionData:
    return make_hidden((*BASE, "offset"), dt=DT, with_velocity=True).data


@pytest.fixture(scope="module")
def offset_named() -> Diagnosis:
    return lr.identify(offset_log(), BASE).diagnosis


def test_the_report_says_where_a_named_effect_and_its_stand_in_are_not_told_apart(
    offset_named: Diagnosis,
) -> None:
    """An offset smaller than both levels is held as well by levels of their own for −x: the
    report gives what the asymmetry gains in the offset's place, and the story says the log does
    not tell the two apart by their fit, and what the asymmetry as one factor on every −x level
    gains over the offset (it scales the −x viscous slope, which the offset leaves alone)."""
    diagnosis = offset_named
    assert diagnosis.named_effects == ["offset"]
    [pair] = json.loads(diagnosis.to_json())["stand_ins"]
    assert set(pair) == {"named", "stand_in", "gain", "factor", "stops"}
    assert pair["stops"] is None  # its friction holds at a stop
    assert (pair["named"], pair["stand_in"]) == ("offset", "asymmetry")
    assert abs(pair["gain"]) < 0.01
    assert pair["factor"] < -0.01
    told = "`asymmetry` in place of `offset`: gains 0.00 units of max(σ², floor²), an effect counts above 0.5"
    one = "the asymmetry as one factor on every -x level"
    factor = f"the offset fits {-pair['factor']:.2f} units better than {one}"
    assert (
        f"{told}: this log does not tell the two apart by their fit; {factor}"
        in diagnosis.story().splitlines()
    )

    def told(gain: float, factor: float | None = None, stops: float | None = None) -> str:
        changed = {**pair, "gain": gain, "factor": factor, "stops": stops}
        return dataclasses.replace(diagnosis, stand_ins=[changed]).story()

    assert (
        "does not tell the two apart by their fit; the asymmetry as one factor on every -x level fits "
        "0.25 units better than the offset" in told(0.0, 0.25)
    )
    assert "does not tell the two apart\n" in told(0.0) + "\n"
    # On a log whose friction lets go at its stops, the force there decides before the factor.
    stops = "by their fit; with the stops where friction lets go counted, it gains -1.29 units"
    assert any(
        line.endswith(f"does not tell the two apart {stops}") for line in told(0.0, None, -1.29).splitlines()
    )

    assert "in place of `offset`: gains 0.00 units" in told(-0.001)  # never "-0.00"
    assert (
        "gains -3.00 units of max(σ², floor²), an effect counts above 0.5: it does worse in its place"
        in told(-3.0)
    )
    assert "does not tell the two apart" not in told(-0.51) and "does not tell the two apart" in told(-0.5)
    assert ": it gains more, but not one-sidedly over the record" in told(0.6)


def test_no_stand_in_is_reported_for_an_effect_the_file_lacks(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """An effect whose parameter the excitation leaves undetermined can be gone from the file
    (:mod:`leuven_rt.fitting.undetermined`): the report gives no stand-in for it."""
    chosen = identify_module.select

    def with_a_stray_pair(*arguments: Any) -> Selection:
        run = chosen(*arguments)
        return dataclasses.replace(run, stand_ins=[*run.stand_ins, StandIn("asymmetry", "offset", 0.0)])

    monkeypatch.setattr(identify_module, "select", with_a_stray_pair)
    diagnosis = lr.identify(offset_log(), BASE).diagnosis
    assert [pair["named"] for pair in diagnosis.stand_ins] == ["offset"]


def test_the_verdict_on_what_remains_sets_the_gross_errors_aside(offset_named: Diagnosis) -> None:
    diagnosis = offset_named
    assert diagnosis.gross_errors == 0 and not diagnosis.unexplained_significant
    last = diagnosis.story().splitlines()[-1]
    assert "what remains is no more than noise and the floor: " in last
    gross = dataclasses.replace(diagnosis, gross_errors=1324).story().splitlines()[-1]
    assert "what remains is no more than noise and the floor, the 1324 gross errors aside: " in gross
    assert "1324 samples (" in dataclasses.replace(diagnosis, gross_errors=1324).story()
    one = dataclasses.replace(diagnosis, gross_errors=1).story()
    assert "what remains is no more than noise and the floor, 1 gross error aside: " in one
    assert "1 sample (" in one and ") is a gross error the model cannot explain" in one
    significant = dataclasses.replace(diagnosis, gross_errors=1324, unexplained_significant=True)
    assert "what remains is significant: " in significant.story().splitlines()[-1]


def test_presliding_is_the_modified_leuven_bank() -> None:
    hidden = make_hidden((*BASE, "presliding_hysteresis"), dt=DT, with_velocity=True)
    identification = lr.identify(hidden.data, BASE)
    (step,) = identification.diagnosis.steps
    assert step.effect == "presliding_hysteresis"
    params = identification.params
    assert params.W is not None and all(w >= 0.0 for w in params.W)
    # What the log determines is the force along a presliding loop, not each element: the virgin
    # curve from rest and the curve back after 20 µm, as the generator's bank gives them (six
    # elements up to 10 µm holding 1.02·Fc, n = 2).
    index = np.arange(1, 7)
    truth = lr.Params(Fc=1.0, Fs=1.0, Vs=1e-3, delta=2.0, n=2.0, sigma2=10.0,
                      W=tuple((7 - index) / 21 * 1.02),
                      Delta=tuple(1e-5 * index / 6))  # fmt: skip
    dt = 1e-3
    x = np.concatenate([np.linspace(0.0, 2e-5, 400), np.linspace(2e-5, -2e-5, 800)])
    np.testing.assert_allclose(
        lr.simulate_position(params, x, dt), lr.simulate_position(truth, x, dt), rtol=0.0, atol=0.05
    )


def test_the_null_case_names_nothing_and_leaves_nothing_unexplained() -> None:
    diagnosis = lr.diagnose(make_hidden(BASE, dt=DT, seed=3).data, BASE)
    assert diagnosis.named_effects == [], diagnosis.story()
    assert diagnosis.rms_after == diagnosis.rms_before
    assert not diagnosis.unexplained_significant, diagnosis.story()


def test_a_drift_names_nothing_stays_unexplained_and_is_not_written() -> None:
    identification = lr.identify(make_hidden(BASE, drift=True).data, BASE)
    diagnosis = identification.diagnosis
    assert diagnosis.named_effects == [], diagnosis.story()
    assert diagnosis.drift and diagnosis.unexplained_significant, diagnosis.story()
    assert "drift" in diagnosis.unexplained_where
    assert any("drift" in warning for warning in identification.warnings)
    assert "drift" not in json.dumps(identification.model.to_dict()["friction"])


def test_the_report_follows_the_documented_layout() -> None:
    hidden = make_hidden((*BASE, "inertia"), dt=DT, with_velocity=True)
    identification = lr.identify(hidden.data, "coulomb,viscous")
    diagnosis = identification.diagnosis
    report = json.loads(diagnosis.to_json())
    assert list(report) == [
        "samples", "noise_std", "floor_estimate", "reconstruction", "named_under", "gross_errors", "baseline",
        "rms_before", "rms_after", "named_effects", "steps", "stand_ins", "unexplained", "settings",
        "final_model",
    ]  # fmt: skip
    assert report["stand_ins"] == []  # neither an offset nor an asymmetry named
    # a logged velocity: the effects are named under what the written file is driven by (the
    # file may take an acceleration cutoff of its own for the inertia term)
    assert report["named_under"] == {
        "source": "velocity", "cutoff": None, "description": report["named_under"]["description"]
    }  # fmt: skip
    driven = {key: report["reconstruction"][key] for key in ("source", "cutoff")}
    assert driven == {"source": "velocity", "cutoff": None}
    assert "named with it" not in diagnosis.story()
    assert report["samples"] == diagnosis.samples and report["baseline"] == list(BASE)
    assert report["named_effects"] == ["inertia"]
    (step,) = report["steps"]
    assert set(step) == {"effect", "where", "rms_before", "rms_after", "robust_before", "robust_after",
                         "params"}  # fmt: skip
    assert step["robust_after"] < step["robust_before"]
    assert step["rms_after"] < step["rms_before"]
    assert step["params"]["inertia"] == pytest.approx(0.05, rel=0.1)  # the generator's mass
    # The step's numbers are the file's.
    assert step["params"]["inertia"] == identification.model.to_dict()["measurement"]["inertia"]
    assert set(report["unexplained"]) == {"significant", "where", "drift"}
    assert report["settings"] == lr.discrepancy.Settings().to_dict()
    # The final model is the file, as written.
    assert report["final_model"] == {
        key: value for key, value in identification.model.to_dict().items() if key != "report"
    }
    assert np.isfinite(report["noise_std"]) and report["noise_std"] > 0
    assert report["floor_estimate"] >= 0.0
