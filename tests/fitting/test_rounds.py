"""The rounds' candidates: where a candidate starts decides whether its fit finds the effect."""

from __future__ import annotations

import numpy as np

import leuven_rt as lr
from leuven_rt.data.reconstruction import noisy_position
from leuven_rt.data.records import MotionData
from leuven_rt.fitting import select
from leuven_rt.fitting.solve import fit
from leuven_rt.fitting.structure import Structure

NOISE = 0.2


def slowly_sampled_bank() -> MotionData:
    """A geared joint's friction that flips over about ten samples after each reversal (a bank
    whose widest element is several samples of travel wide), sampled at 65 Hz by a fine encoder."""
    dt = 0.0155
    t = np.arange(6000) * dt
    x = 0.01 * np.sin(2 * np.pi * t / 12.0) + 0.002 * np.sin(2 * np.pi * t / 2.9)
    x = np.round(x / 1e-7) * 1e-7
    v = np.diff(x, prepend=x[0]) / dt
    truth = lr.Params(Fc=5.0, Fs=5.0, Vs=0.001, delta=2.0, n=2.0, sigma2=100.0,
                      W=[4.0, 3.0, 3.0], Delta=[2e-6, 3e-5, 2e-4])  # fmt: skip
    f = lr.simulate(truth, v, dt) + np.random.default_rng(3).normal(0.0, NOISE, t.size)
    return MotionData(t, x, f)


def test_a_bank_found_only_from_a_spread_start_is_found() -> None:
    record = slowly_sampled_bank()
    noisy = noisy_position(record.x, record.dt)
    target, scales = select.prepare(record, select.rounds_reconstruction(record, noisy), noisy)
    structure = Structure(frozenset({"coulomb", "viscous"}))
    base = fit(structure, scales, target, {"Fc": 4.0, "sigma2": 50.0})
    # From all its weight on the stiff element the fit has no direction: the samples where the
    # other elements' weights change the force are the ones the rounds weigh out.
    stiff = {f"share_{i}": float(i == 0) for i in range(scales.deltas.size)}
    bank = structure.with_effect("presliding_hysteresis")
    flat = fit(bank, scales, target, {**base.theta, **stiff}, select.SCREEN)
    assert flat.mse > 0.9 * base.mse
    # The candidate starts with the weight spread evenly over the bank (structure.start).
    found = select._extend(base, "presliding_hysteresis", scales, target, select.SCREEN)
    assert found.mse < 1.1 * NOISE**2 < 0.7 * base.mse
