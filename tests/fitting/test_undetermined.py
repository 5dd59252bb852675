"""Undetermined parameters: fixed at the value that adds no force, unless fixing them costs what
the log shows."""

from __future__ import annotations

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt.data.reconstruction import noisy_position
from leuven_rt.data.records import MotionData
from leuven_rt.fitting import select, undetermined
from leuven_rt.fitting.solve import Fitted, fit
from leuven_rt.fitting.structure import Structure

NOISE = 0.02


def fitted_with_offset() -> tuple[Fitted, select.Target, select.Scales]:
    dt = 1e-3
    t = np.arange(8000) * dt
    v = 0.05 * np.sin(2 * np.pi * 0.5 * t)
    x = np.cumsum(v) * dt
    truth = lr.Params(Fc=1.0, Fs=1.0, Vs=0.01, delta=2.0, n=2.0, sigma2=0.02, W=[2.0], Delta=[1e-9])
    f = lr.simulate(truth, v, dt) + 0.3 + np.random.default_rng(5).normal(0.0, NOISE, t.size)
    record = MotionData(t, x, f, v=v)
    noisy = noisy_position(record.x, record.dt)
    target, scales = select.prepare(record, select.rounds_reconstruction(record, noisy), noisy)
    structure = Structure(frozenset({"coulomb", "viscous", "offset"}))
    return fit(structure, scales, target, {"Fc": 1.0, "sigma2": 0.1, "offset": 0.0}), target, scales


def test_a_parameter_whose_neutral_value_costs_more_than_the_threshold_stays_free(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    fitted, target, scales = fitted_with_offset()
    assert fitted.theta["offset"] == pytest.approx(0.3, abs=0.01)
    # Every standard error large, as where parameters trade off nonlinearly.
    monkeypatch.setattr(undetermined, "standard_errors", lambda *_: dict.fromkeys(fitted.theta, 1e9))
    calls: list[dict[str, float]] = []

    def refit(structure: Structure, fixed: dict[str, float]) -> Fitted:
        calls.append(fixed)
        return fit(structure, scales, target, fitted.theta, fixed=fixed)

    threshold = 0.5 * NOISE**2
    settled, found = undetermined.settle(fitted, scales, target, NOISE, refit, threshold)
    # The offset (0.3 against a noise of 0.02) stays; σ2 (0.02, a thousandth of a newton at these
    # speeds) is fixed at 0; Fc has no neutral value.
    assert [item.name for item in found] == ["sigma2"]
    assert settled.theta["offset"] == pytest.approx(0.3, abs=0.01)
    assert settled.theta["sigma2"] == 0.0
    assert calls[0] == {"sigma2": 0.0, "offset": 0.0} and calls[-1] == {"sigma2": 0.0}
    # Without a threshold, as before, both are fixed.
    everything, found = undetermined.settle(fitted, scales, target, NOISE, refit)
    assert sorted(item.name for item in found) == ["offset", "sigma2"]
    assert everything.theta["offset"] == 0.0
