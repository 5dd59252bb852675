"""The drift beside an effect: a friction level that drifts over the record makes an effect's
gain uneven in time, so that neither counts alone; fitted together they do. And the drift in
the place of a position dependence that stands in for it."""

from __future__ import annotations

import numpy as np
from scipy.signal import lfilter
from threadpoolctl import threadpool_limits

import leuven_rt as lr
from conftest import family
from leuven_rt.data.records import MotionData
from leuven_rt.fitting import select
from leuven_rt.fitting.settings import Settings

NOISE = 0.4


def drifting_asymmetry() -> MotionData:
    """Velocity plateaus over two decades back and forth over one stroke (1 kHz, the velocity
    logged), the −x levels 1.23 times the +x ones, the contact level rising by 34 % over the
    record, and coloured force noise (whose one-sample differences read below its spread)."""
    rng = np.random.default_rng(7)
    dt = 1e-3
    stroke = 0.005
    plateaus = []
    for leg in range(24):
        speed = float(np.exp(rng.uniform(np.log(2e-4), np.log(2e-2))))
        steps = max(int(min(stroke / speed, 1.5) / dt), 50)
        plateaus.append(np.full(steps, (-1.0) ** leg * stroke / (steps * dt)))
    v = np.convolve(np.concatenate(plateaus), np.ones(40) / 40, mode="same")
    t = np.arange(v.size) * dt
    x = np.cumsum(v) * dt
    truth = lr.Params(Fc=39.0, Fs=39.0, Vs=6e-4, delta=1.0, n=2.0, sigma2=0.0, Fc_neg=48.0, Fs_neg=48.0,
                      W=[55.0], Delta=[1e-9])  # fmt: skip
    contact = lr.simulate(truth, v, dt)
    level = 1.0 + 0.34 * t / t[-1]
    viscous = np.where(v >= 0, 374.0, 462.0) * v
    pole = np.exp(-2.0 * np.pi * 78.0 * dt)
    coloured = lfilter([1.0 - pole], [1.0, -pole], rng.normal(0.0, 1.0, t.size))
    noise = NOISE * (coloured / np.std(coloured) + 0.3 * rng.normal(0.0, 1.0, t.size))
    return MotionData(t, np.round(x / 2e-9) * 2e-9, level * contact + viscous + noise, v=v)


def test_a_drift_that_hides_an_asymmetry_is_found_beside_it() -> None:
    with threadpool_limits(1):
        selection = select.select(drifting_asymmetry(), ("coulomb", "viscous"), Settings())
    assert selection.drift
    assert selection.final.structure.has("asymmetry")
    assert not selection.written.structure.drift


def test_a_drift_that_a_position_dependence_stands_in_for_is_found_in_its_place() -> None:
    """The family's held_04 of seed base 12000 (the contact level rising by a quarter over the
    record, Stribeck, reversal legs, no `v`): named first, a position dependence took the drift's
    place and the drift gained too little beside it; in its place the drift gains more, so the
    rounds run again with the drift alongside, and Stribeck is named alone."""
    generator = family()
    log = generator.make_log(generator.draw_case("held-out", 3, seed_base=12000))
    assert log.case.recipe.extra == "drift" and log.v is None
    said: list[str] = []
    with threadpool_limits(1):
        selection = select.select(
            MotionData(log.t, log.x, log.f), ("coulomb", "viscous"), Settings(), said.append
        )
    assert selection.drift
    assert selection.final.structure.effects == frozenset({"coulomb", "viscous", "stribeck"})
    # The progress says how the drift counted.
    assert any(
        line.startswith("a drift of the level (in the place of position_dependence: it gains")
        for line in said
    )
    assert not selection.written.structure.drift
