"""The candidates' parameters: θ → the model file's numbers, and their derivatives."""

from __future__ import annotations

import math

import numpy as np
import pytest

from leuven_rt.data.records import MotionData
from leuven_rt.errors import InputError
from leuven_rt.fitting import select
from leuven_rt.fitting.structure import (
    CATALOGUE,
    FRICTION,
    Scales,
    Structure,
    bounds,
    parse_effects,
    start,
    unpack,
)
from leuven_rt.modelfile import Reconstruction

SCALES = Scales(speed_low=1e-4, speed_high=0.1, force=2.0, stiff=1e-10, grid=np.geomspace(1e-7, 1e-4, 6),
                middle=0.05, half_stroke=0.05)  # fmt: skip

EVERYTHING = Structure(frozenset(CATALOGUE), form="level", periods=(0.01,), drift=True)


def theta_of(structure: Structure, rng: np.random.Generator) -> dict[str, float]:
    elements = SCALES.deltas.size
    names = structure.names() + structure.share_names(elements)
    low, high = bounds(structure, SCALES, elements)
    out = {}
    for name, lo, hi in zip(names, low, high, strict=True):
        lo, hi = max(lo, -1.0), min(hi, 3.0)
        out[name] = float(rng.uniform(lo, hi)) if lo < hi else lo
    return out


@pytest.mark.parametrize(
    ("effects", "neg_factor", "seed"),
    [
        (("coulomb", "viscous"), False, 1),
        (("coulomb", "viscous", "stribeck", "asymmetry"), False, 1),
        (CATALOGUE, False, 1),
        # The asymmetry as one factor, the −x static level above the +x one (seed 1) and below
        # it (seed 3), with the bank and with the stiff element alone.
        (("coulomb", "viscous", "stribeck", "asymmetry", "presliding_hysteresis"), True, 1),
        (("coulomb", "viscous", "stribeck", "asymmetry", "presliding_hysteresis"), True, 3),
        (("coulomb", "viscous", "stribeck", "asymmetry"), True, 1),
        (("coulomb", "viscous", "stribeck", "asymmetry"), True, 3),
    ],
)
def test_the_friction_derivatives_equal_finite_differences_of_unpack(
    effects: tuple[str, ...], neg_factor: bool, seed: int
) -> None:
    structure = Structure(frozenset(effects), form="force", periods=(0.01,), neg_factor=neg_factor)
    rng = np.random.default_rng(seed)
    theta = theta_of(structure, rng)
    values = unpack(structure, SCALES, theta)
    if neg_factor:
        factor = math.exp(theta["log_neg_factor"])
        assert values.friction["Fs_neg"] == pytest.approx(factor * values.friction["Fs"])
        assert values.friction["sigma2_neg"] == pytest.approx(factor * values.friction["sigma2"])

    def vector(t: dict[str, float]) -> np.ndarray:
        v = unpack(structure, SCALES, t)
        f = v.friction
        neg = {"Fc_neg": "Fc", "Fs_neg": "Fs", "sigma2_neg": "sigma2"}
        row = [float(f[key] if f[key] is not None else f[neg[key]]) for key in FRICTION]
        return np.array(row + list(v.W))

    names = list(theta)
    for column, name in enumerate(names):
        step = 1e-6 * max(1.0, abs(theta[name]))
        up, down = dict(theta), dict(theta)
        up[name] += step
        down[name] -= step
        numeric = (vector(up) - vector(down)) / (2 * step)
        assert np.allclose(values.jacobian[:, column], numeric, rtol=1e-6, atol=1e-8), name


def test_a_candidate_starts_where_the_model_it_extends_stands() -> None:
    base = Structure(frozenset({"coulomb", "viscous"}))
    theta = {"Fc": 1.3, "sigma2": 4.0}
    before = unpack(base, SCALES, theta)
    for effect in CATALOGUE[2:]:
        grown = base.with_effect(effect, form="level", periods=(0.02,))
        after = unpack(grown, SCALES, start(grown, SCALES, SCALES.deltas.size, theta))
        assert after.friction["Fc"] == before.friction["Fc"]
        assert after.friction["Fs"] == before.friction["Fs"], effect
        assert after.offset == 0.0 and after.inertia == 0.0
        if effect == "presliding_hysteresis":
            # The bank starts with the stiff element's weight spread evenly over its elements.
            assert after.W.sum() == pytest.approx(before.W[0])
            assert np.allclose(after.W, after.W[0])
        else:
            assert np.array_equal(after.W, before.W)
        if after.level is not None:
            trend, ripples = after.level
            assert trend == (0.0, 0.0) and all(not any(c) and not any(s) for _, c, s in ripples)


def test_a_symmetric_model_ties_the_minus_x_levels_to_the_plus_x_ones() -> None:
    structure = Structure(frozenset({"coulomb", "viscous", "stribeck"}))
    values = unpack(structure, SCALES, {"Fc": 1.0, "sigma2": 2.0, "Fs_rise": 0.5, "log_Vs": math.log(1e-3),
                                         "delta": 1.5})  # fmt: skip
    assert values.friction["Fc_neg"] is None and values.friction["sigma2_neg"] is None
    rows = {name: i for i, name in enumerate(FRICTION)}
    # d/dFc reaches both sides' levels
    column = structure.names().index("Fc")
    assert values.jacobian[rows["Fc"], column] == 1.0 and values.jacobian[rows["Fc_neg"], column] == 1.0


def test_effect_names_are_checked() -> None:
    assert parse_effects("coulomb, viscous") == ("coulomb", "viscous")
    with pytest.raises(InputError, match="unknown effects"):
        parse_effects("coulomb,magic")
    with pytest.raises(InputError, match="repeats"):
        parse_effects(["coulomb", "coulomb"])


def test_the_bank_reaches_below_the_encoder_step_only_where_a_velocity_drives_it() -> None:
    """A logged velocity resolves travel below the encoder's step, so the bank's narrowest
    element may be narrower than 3 steps; driven by the encoder, it may not."""
    dt = 1e-3
    t = np.arange(20_000) * dt
    v = 0.05 * np.cos(2 * np.pi * t / 4.0)
    step = 2 * np.pi / 2**17
    x = np.round(np.cumsum(v) * dt / step) * step
    f = np.sign(v) + np.random.default_rng(0).normal(0.0, 0.01, t.size)
    record = MotionData(t, x, f, v=v)
    by_velocity = select.prepare(record, Reconstruction("velocity"), False)[1]
    by_encoder = select.prepare(record, Reconstruction("position"), False)[1]
    assert by_velocity.grid[0] < step < 2.9 * step < by_encoder.grid[0]
