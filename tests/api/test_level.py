"""The position-dependent level (docs/model.md#position-dependent-level) through the Python face:
types coerced by Python, values refused by gms-core naming the field, the factor (gms-core's)
against the oracle's numpy formula, the compensator and ``simulate_position`` against
F_level = factor(x)·(F − σ2(v)·v) + σ2(v)·v, and the numpy reference against Rust."""

from __future__ import annotations

import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import MAXWELL, max_relative_error
from leuven_rt import Compensator, InputError, ParameterError, Params, _core, reference, simulate_position
from leuven_rt.level import MAX_HARMONICS, MAX_RIPPLES, PositionLevel, Ripple, core_level

DT = 1e-3


def screw() -> PositionLevel:
    """A trend and two ripples with several harmonics."""
    return PositionLevel(
        middle=0.002,
        half_stroke=0.01,
        trend=(0.05, -0.02),
        ripples=(
            Ripple(0.004, (0.03, 0.01, 0.005), (0.0, 0.02, -0.004)),
            Ripple(0.0013, (0.01, -0.006), (0.012, 0.003)),
        ),
    )


def positions(samples: int = 1500, channels: int = 1) -> np.ndarray:
    """A swing over a few ripple periods with a slow drift, per channel."""
    k = np.arange(samples)
    rows = [0.003 * np.sin(0.01 * k + c) + 1e-5 * k for c in range(channels)]
    return np.array(rows) if channels > 1 else rows[0]


def velocities(x: np.ndarray) -> np.ndarray:
    return np.diff(x, axis=-1, prepend=x[..., :1]) / DT


def test_limits_are_the_cores() -> None:
    assert (MAX_RIPPLES, MAX_HARMONICS) == (_core.MAX_RIPPLES, _core.MAX_HARMONICS) == (2, 8)


ok_ripple = Ripple(0.004, (0.1,), (0.1,))


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        (dict(middle=math.inf), "`middle` must be finite, got inf"),
        (dict(half_stroke=0.0), "`half_stroke` must be finite and > 0, got 0.0"),
        (dict(half_stroke=-0.01), "`half_stroke` must be finite and > 0, got -0.01"),
        (dict(half_stroke=1e-310), "subnormal"),
        (dict(half_stroke=math.nan), "`half_stroke` must be finite and > 0, got nan"),
        (dict(trend=(0.1, math.nan)), r"`trend` must be finite, got nan at entry 1"),
        (dict(ripples=(ok_ripple,) * 3), "`ripples` must have at most 2 ripples, got 3"),
        (
            dict(ripples=(ok_ripple, Ripple(-1.0, (), ()))),
            r"`ripples\[1\].period` must be finite and > 0, got -1.0",
        ),
        (dict(ripples=(Ripple(1.0, (0.1, 0.1), (0.1,)),)), "must have the same length, got 2 and 1"),
        (
            dict(ripples=(Ripple(1.0, (0.01,) * 9, (0.0,) * 9),)),
            r"`ripples\[0\]` must have at most 8 harmonics, got 9",
        ),
        (
            dict(ripples=(ok_ripple, Ripple(1.0, (0.0, math.inf), (0.0, 0.0)))),
            r"`ripples\[1\].cos\[1\]` must be finite",
        ),
        (
            dict(trend=(0.5, -0.3), ripples=(ok_ripple,)),
            r"< 1 \(so that the factor stays > 0 everywhere\), got 1.0",
        ),
    ],
)
def test_bad_values_are_refused_by_the_core_naming_the_field(changes: dict[str, Any], message: str) -> None:
    with pytest.raises(ParameterError, match=message):
        PositionLevel(**changes)


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (lambda: PositionLevel(middle=True), "`middle` must be a real number, got True"),
        (lambda: PositionLevel(half_stroke="0.01"), "`half_stroke` must be a real number, got '0.01'"),
        (lambda: PositionLevel(trend=(0.1, 0.2, 0.3)), "`trend` must have 2 coefficients"),
        (lambda: PositionLevel(trend="ab"), "`trend` must be a sequence of real numbers"),
        (lambda: PositionLevel(trend=(0.1, False)), r"`trend\[1\]` must be a real number, got False"),
        (lambda: PositionLevel(ripples=ok_ripple), "`ripples` must be a sequence of Ripple"),
        (lambda: PositionLevel(ripples=(1.0,)), r"`ripples\[0\]` must be a Ripple, got 1.0"),
        (lambda: PositionLevel(ripples=({"period": 1.0, "cos": ()},)), r"`ripples\[0\]` must have the keys"),
        (lambda: Ripple(period=None, cos=(), sin=()), "`period` must be a real number, got None"),  # type: ignore[arg-type]
        (lambda: Ripple(period=1.0, cos="0.1", sin=()), "`cos` must be a sequence of real numbers"),
    ],
)
def test_bad_types_are_refused_by_python_naming_the_field(build: Any, message: str) -> None:
    with pytest.raises(ParameterError, match=message):
        build()


def test_types_are_coerced() -> None:
    level = PositionLevel(
        middle=1,
        half_stroke=np.float32(0.5),
        trend=[0, 0.1],
        ripples=[{"period": 2, "cos": np.array([0.1, 0.0]), "sin": [0, 0]}],
    )
    assert level == PositionLevel(0.0 + 1.0, 0.5, (0.0, 0.1), (Ripple(2.0, (0.1, 0.0), (0.0, 0.0)),))
    assert all(type(value) is float for value in (level.middle, level.half_stroke, *level.trend))
    assert isinstance(level.ripples, tuple) and type(level.ripples[0].cos[0]) is float
    # The validated core level travels with the object, and is rebuilt by pickle.
    restored = pickle.loads(pickle.dumps(level))
    assert restored == level and core_level(restored).ripples == 1


@settings(max_examples=200, deadline=None)
@given(
    middle=st.floats(-0.1, 0.1),
    half_stroke=st.floats(1e-3, 1.0),
    coefficients=st.lists(
        st.floats(-1.0, 1.0), min_size=2 + 4 * MAX_HARMONICS, max_size=2 + 4 * MAX_HARMONICS
    ),
    harmonics=st.tuples(st.integers(0, MAX_HARMONICS), st.integers(0, MAX_HARMONICS)),
    periods=st.tuples(st.floats(1e-3, 0.1), st.floats(1e-3, 0.1)),
    depth=st.floats(0.0, 0.99),
    cycles=st.floats(-20.0, 20.0),
)
def test_rust_factor_is_numpys_formula(
    middle: float,
    half_stroke: float,
    coefficients: list[float],
    harmonics: tuple[int, int],
    periods: tuple[float, float],
    depth: float,
    cycles: float,
) -> None:
    """To 1e-12 relative for |x/P| up to 20 for every ripple: numpy's unreduced phase k·2π·x/P
    rounds by up to about 3·k·2π·|x/P|·1.1e-16 rad, 3e-13 there with k = 8 (larger |x/P| is the
    next test's, against the reduced phase); and positive, since the amplitudes add up to below 1."""
    total = sum(abs(c) for c in coefficients)
    c = [value * depth / total for value in coefficients] if total > 0 else coefficients
    m = MAX_HARMONICS
    level = PositionLevel(
        middle,
        half_stroke,
        (c[0], c[1]),
        (
            Ripple(periods[0], tuple(c[2 : 2 + harmonics[0]]), tuple(c[2 + m : 2 + m + harmonics[0]])),
            Ripple(
                periods[1],
                tuple(c[2 + 2 * m : 2 + 2 * m + harmonics[1]]),
                tuple(c[2 + 3 * m : 2 + 3 * m + harmonics[1]]),
            ),
        ),
    )
    x = cycles * min(periods)
    rust, numpy = float(level.factor(x)), 1.0 + float(reference.position_series(level, x))
    assert rust > 0.0
    assert abs(rust - numpy) <= 1e-12 * abs(numpy)


def test_far_positions_agree_with_the_reduced_phase() -> None:
    """At any |x/P| (here up to 1e12), Rust's factor is the formula with the phase reduced to one
    period, as Rust reduces it: the harmonics' recurrence adds no more than a few ulps."""
    level = PositionLevel(
        ripples=(Ripple(0.004, (0.06,) * 8, (0.0,) * 8), Ripple(0.0013, (0.0,) * 8, (0.05,) * 8))
    )
    worst = 0.0
    for x in np.geomspace(1.0, 1e10, 400):
        for position in (float(x), -float(x)):
            want = 1.0
            for ripple in level.ripples:
                cycles = position / ripple.period
                angle = 2.0 * np.pi * (cycles - round(cycles))
                for k, (c, s) in enumerate(zip(ripple.cos, ripple.sin, strict=True), start=1):
                    want += c * math.cos(k * angle) + s * math.sin(k * angle)
            worst = max(worst, abs(float(level.factor(position)) - want) / want)
    assert worst <= 1e-14


def test_observer_with_a_level_is_the_formula() -> None:
    params, level = Params(**MAXWELL, sigma2_neg=0.9), screw()
    x = positions()
    plain = simulate_position(params, x, DT)
    v = velocities(x)
    sigma2 = np.where(v < 0, 0.9, 0.4)
    assert (v < 0).sum() > 100
    want = level.factor(x) * (plain - sigma2 * v) + sigma2 * v
    compensator = Compensator(params, DT, "observer", level=level)
    got = np.array([compensator.step(float(xk)) for xk in x])
    assert np.max(np.abs(got - want)) <= 1e-9 * np.max(np.abs(want))
    assert np.max(np.abs(got - plain)) > 1e-3, "the level must change the output"
    assert compensator.level is level
    # The block run with a level is the same.
    assert np.array_equal(simulate_position(params, x, DT, level=level), got)


def test_feedforward_integrates_from_the_start_position() -> None:
    params, level = Params(**MAXWELL), screw()
    start = -0.0042
    v = 8e-3 * np.cos(0.01 * np.arange(1500))
    compensator = Compensator(params, DT, "feedforward", level=level, x=start)
    assert compensator.position == start
    plain = Compensator(params, DT, "feedforward")
    x = start
    for vk in v.tolist():
        x += vk * DT
        force = plain.step(vk)
        sigma2 = params.sigma2_negative if vk < 0 else params.sigma2
        want = float(level.factor(x)) * (force - sigma2 * vk) + sigma2 * vk
        assert abs(compensator.step(vk) - want) <= 1e-9 * max(abs(want), 1.0)
    assert compensator.position == x


def test_set_position_refusals_change_nothing() -> None:
    compensator = Compensator(Params(**MAXWELL), DT, level=screw(), x=0.0)
    compensator.set_position(0.001)
    for bad in (math.nan, math.inf):
        with pytest.raises(InputError, match="`x` must be finite"):
            compensator.set_position(bad)
    with pytest.raises(InputError, match="`x` must be a real number"):
        compensator.set_position(True)
    assert compensator.position == 0.001


def test_no_level_is_todays_output() -> None:
    params = Params(**MAXWELL)
    x = positions()
    for mode in ("feedforward", "observer"):
        a, b = Compensator(params, DT, mode), Compensator(params, DT, mode, level=None)
        assert [a.step(float(xk)) for xk in x] == [b.step(float(xk)) for xk in x]
    assert np.array_equal(simulate_position(params, x, DT, level=None), simulate_position(params, x, DT))
    # A flat level (zeros, no ripples) is the plain output, bit for bit.
    assert np.array_equal(
        simulate_position(params, x, DT, level=PositionLevel()), simulate_position(params, x, DT)
    )


def test_level_must_be_a_position_level() -> None:
    with pytest.raises(
        ParameterError, match=r"`level` must be a leuven_rt\.level\.PositionLevel or None, got dict"
    ):
        Compensator(Params(**MAXWELL), DT, level={"middle": 0.0})  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match="`level` must be"):
        simulate_position(Params(**MAXWELL), positions(10), DT, level=0.5)  # type: ignore[arg-type]


def test_channels_and_refusals_with_a_level() -> None:
    params, level = Params(**MAXWELL), screw()
    x = positions(400, channels=3)
    out = simulate_position(params, x, DT, level=level)
    for row, forces in zip(x, out, strict=True):
        assert np.array_equal(simulate_position(params, row, DT, level=level), forces)
    bad = x.copy()
    bad[2, 7] = np.nan
    with pytest.raises(InputError, match="channel 2, sample 7"):
        simulate_position(params, bad, DT, level=level)


@pytest.mark.parametrize(
    "params", [MAXWELL, dict(MAXWELL, n=1.5, W=[0.7, 0.5, 0.4], Delta=[1e-6, 3e-6, 7e-6])]
)
def test_reference_agrees_with_rust_with_a_level(params: dict[str, Any]) -> None:
    level = screw()
    x = positions(600, channels=2)
    rust = simulate_position(params, x, DT, level=level)
    oracle = reference.simulate_position(params, x, DT, level=level)
    assert max_relative_error(rust, oracle) <= 1e-12
    # Without a level the reference is unchanged: its plain run, and Rust's.
    plain = reference.simulate_position(params, x, DT)
    assert np.array_equal(reference.simulate_position(params, x, DT, level=None), plain)
    assert max_relative_error(simulate_position(params, x, DT), plain) <= 1e-12
    assert max_relative_error(rust, plain) > 1e-3
