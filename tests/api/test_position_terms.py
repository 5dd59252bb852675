"""The terms a model file can now hold, through the Python face (docs/model.md): a viscous
coefficient of its own for v < 0 (``sigma2_neg``), a force of the position alone
(:class:`PositionForce`), velocity input with positions (``simulate(..., x=...)``), and the
feedforward compensator placed at its start position (``x=``) or fed a trajectory
(``step_trajectory``). Each refusal is asserted on its class and the field it names."""

from __future__ import annotations

import json
import math
import pickle
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leuven_rt
from conftest import MAXWELL, max_relative_error
from leuven_rt import (
    Compensator,
    InputError,
    ParameterError,
    Params,
    PositionForce,
    PositionLevel,
    Ripple,
    reference,
    simulate,
    simulate_position,
)
from leuven_rt.level import MAX_HARMONICS

DT = 1e-3


def cogging() -> PositionForce:
    """A gravity-like trend and a ripple of two harmonics [N]."""
    return PositionForce(0.001, 0.02, (0.8, -0.3), (Ripple(0.0025, (0.4, 0.1), (-0.3, 0.05)),))


def screw() -> PositionLevel:
    return PositionLevel(0.002, 0.01, (0.05, -0.02), (Ripple(0.004, (0.03, 0.01), (0.0, 0.02)),))


def positions(samples: int = 1200, channels: int = 1) -> np.ndarray:
    k = np.arange(samples)
    rows = [0.003 * np.sin(0.01 * k + c) + 1e-6 * k for c in range(channels)]
    return np.array(rows) if channels > 1 else rows[0]


# --- sigma2_neg ----------------------------------------------------------------------------


@pytest.mark.parametrize("bad", [-0.1, math.nan, math.inf, -math.inf])
def test_sigma2_neg_is_refused_by_the_core_naming_it(bad: float) -> None:
    with pytest.raises(ParameterError, match=r"^`sigma2_neg` must be finite and >= 0, got"):
        Params(**MAXWELL, sigma2_neg=bad)


@pytest.mark.parametrize("bad", [True, "0.4", [0.4]])
def test_sigma2_neg_must_be_a_real_number(bad: Any) -> None:
    with pytest.raises(ParameterError, match="`sigma2_neg` must be a real number"):
        Params(**MAXWELL, sigma2_neg=bad)


def test_sigma2_neg_round_trips_and_is_written_only_when_given(tmp_path: Path) -> None:
    plain = Params(**MAXWELL)
    assert "sigma2_neg" not in plain.to_dict() and plain.sigma2_negative == plain.sigma2
    for value in (0.0, 0.4, 0.9):  # 0.4 equals sigma2, and is written: the file says what was given
        params = Params(**MAXWELL, sigma2_neg=value)
        assert params.to_dict()["sigma2_neg"] == value and params.sigma2_negative == value
        assert Params.from_dict(params.to_dict()) == params
        assert Params.from_json(params.to_json()) == params
        path = tmp_path / f"params-{value}.json"
        params.save(path)
        assert Params.load(path) == params
        assert json.loads(path.read_text())["sigma2_neg"] == value
        assert pickle.loads(pickle.dumps(params)) == params
    assert Params(**MAXWELL, sigma2_neg=3) == Params(**MAXWELL, sigma2_neg=3.0)


def test_sigma2_neg_scales_the_viscous_force_of_negative_velocity_only() -> None:
    """The state evolves as without it (σ2 is memoryless), so the outputs differ by exactly
    (sigma2_neg − sigma2)·v where v < 0, up to rounding; given equal to sigma2 it changes
    nothing, bit for bit."""
    v = 5e-3 * np.sin(np.linspace(0.0, 30.0, 2000))
    plain = simulate(MAXWELL, v, DT)
    asymmetric = simulate(dict(MAXWELL, sigma2_neg=1.3), v, DT)
    expected = np.where(v < 0, (1.3 - 0.4) * v, 0.0)
    assert np.max(np.abs(asymmetric - plain - expected)) <= 1e-13
    assert np.max(np.abs(expected)) > 1e-3
    assert np.array_equal(simulate(dict(MAXWELL, sigma2_neg=0.4), v, DT), plain)
    # The numpy reference agrees, and so does the mass system (implicit coupled solve).
    assert max_relative_error(asymmetric, reference.simulate(dict(MAXWELL, sigma2_neg=1.3), v, DT)) <= 1e-12
    u = 3.0 * np.sin(np.linspace(0.0, 12.0, 1500))
    params = dict(MAXWELL, sigma2_neg=2.5)
    rust = leuven_rt.simulate_mass(params, u, DT, mass=0.5)
    spec = reference.mechanics.simulate_mass(params, u, DT, mass=0.5)
    assert max_relative_error(rust.velocity, spec.velocity) <= 1e-9
    assert np.min(rust.velocity) < -1e-3, "the mass must move backwards"


# --- the position force ---------------------------------------------------------------------


def test_position_force_has_the_levels_shape_without_its_depth_rule() -> None:
    force = cogging()
    x = np.linspace(-0.05, 0.05, 400)
    # Rust's force against the oracle's formula; amplitudes far beyond a level's sum of 1.
    assert np.max(np.abs(force.force(x) - reference.position_series(force, x))) <= 1e-13
    with pytest.raises(ParameterError, match=r"< 1 \(so that the factor stays > 0"):
        PositionLevel(**vars_of(force))
    # Any shape in, the same shape out; NaN where x is not finite.
    grid = x.reshape(20, -1)
    assert np.array_equal(force.force(grid), force.force(x).reshape(20, -1))
    assert math.isnan(float(force.force(math.inf)))
    assert force.force(0.01).shape == ()


def vars_of(series: PositionForce | PositionLevel) -> dict[str, Any]:
    return dict(
        middle=series.middle, half_stroke=series.half_stroke, trend=series.trend, ripples=series.ripples
    )


def test_position_force_json_form_round_trips() -> None:
    force = cogging()
    text = json.dumps(force.to_dict())
    assert PositionForce.from_dict(json.loads(text)) == force
    assert pickle.loads(pickle.dumps(force)) == force
    assert PositionForce.from_dict({}) == PositionForce()
    level = screw()
    assert PositionLevel.from_dict(json.loads(json.dumps(level.to_dict()))) == level
    # A level and a force of the same values are different things.
    assert PositionForce(**vars_of(level)) != level
    with pytest.raises(ParameterError, match=r"unknown keys \['amplitude'\]"):
        PositionForce.from_dict({"middle": 0.0, "amplitude": 1.0})
    with pytest.raises(ParameterError, match="must be a mapping, got list"):
        PositionForce.from_dict([0.0])  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        (dict(middle=math.nan), "`middle` must be finite"),
        (dict(half_stroke=0.0), "`half_stroke` must be finite and > 0"),
        (dict(trend=(math.inf, 0.0)), r"`trend` must be finite, got inf at entry 0"),
        (dict(ripples=(Ripple(0.01, (math.nan,), (0.0,)),)), r"`ripples\[0\].cos\[0\]` must be finite"),
        (dict(ripples=(Ripple(0.01, (0.1,) * 9, (0.0,) * 9),)), r"`ripples\[0\]` must have at most 8"),
        (dict(trend=(0.1,)), "`trend` must have 2 coefficients"),
    ],
)
def test_position_force_refusals_name_the_field(changes: dict[str, Any], field: str) -> None:
    with pytest.raises(ParameterError, match=field):
        PositionForce(**changes)


# --- phases that cannot be resolved -----------------------------------------------------------


@pytest.mark.parametrize("kind", [PositionLevel, PositionForce])
@pytest.mark.parametrize(
    ("changes", "message"),
    [
        (
            dict(ripples=(Ripple(1e-12, (0.1,), (0.0,)),)),
            r"^`ripples\[0\].period` must be at least 2\^20 ulps",
        ),
        (
            dict(ripples=(Ripple(1e-300, (0.1,), (0.0,)),)),
            r"^`ripples\[0\].period` must be at least 2\^20 ulps",
        ),
        (
            dict(ripples=(Ripple(0.5, (0.1,), (0.0,)), Ripple(1e-11, (0.1,), (0.0,)))),
            r"^`ripples\[1\].period` .* = 1.0, i.e. >= 2.3283064365386963e-10, got 1e-11",
        ),
        (dict(half_stroke=1e-300), r"^`half_stroke` must be at least 2\^20 ulps .* got 1e-300"),
        (
            dict(middle=1e308),
            r"^`middle` must leave `half_stroke` at least 2\^20 ulps .* got middle = 1e\+?308",
        ),
        (dict(middle=1e6, half_stroke=1e-6), r"^`middle` must leave `half_stroke`"),
        (dict(middle=1e6, ripples=(Ripple(1e-6, (0.1,), (0.0,)),)), r"^`ripples\[0\].period`"),
    ],
)
def test_unresolvable_phases_are_refused(kind: type, changes: dict[str, Any], message: str) -> None:
    """Periods of 1e-12 or 1e-300 m were accepted, and Rust and Python's own formula then
    disagreed at the first digit; gms-core now refuses them, and Python evaluates
    with gms-core, so there is one answer."""
    with pytest.raises(ParameterError, match=message):
        kind(**changes)


def test_the_resolution_bound_itself_is_accepted() -> None:
    finest = 2.0**20 * math.ulp(1.0)
    PositionLevel(ripples=(Ripple(finest, (0.1,), (0.0,)),))
    with pytest.raises(ParameterError):
        PositionLevel(ripples=(Ripple(finest * (1 - 2**-52), (0.1,), (0.0,)),))
    PositionForce(middle=0.0, half_stroke=finest, trend=(1.0, 0.0))


def test_python_evaluates_with_gms_core() -> None:
    """One implementation: the factor Python returns is the one the runs apply (the observer
    run's level part, recovered from its forces)."""
    params, level = Params(**MAXWELL), screw()
    x = positions()
    plain = simulate_position(params, x, DT)
    leveled = simulate_position(params, x, DT, level=level)
    v = np.diff(x, prepend=x[0]) / DT
    viscous = np.where(v < 0, params.sigma2_negative, params.sigma2) * v
    moving = np.abs(plain - viscous) > 1e-3
    recovered = (leveled - viscous)[moving] / (plain - viscous)[moving]
    assert np.max(np.abs(recovered - level.factor(x)[moving])) <= 1e-12


# --- runs with the terms ----------------------------------------------------------------------


def test_position_run_with_the_terms_is_the_observer() -> None:
    params, level, force = Params(**MAXWELL, sigma2_neg=0.9), screw(), cogging()
    x = positions()
    out = simulate_position(params, x, DT, level=level, position_force=force)
    observer = Compensator(params, DT, "observer", level=level, position_force=force)
    assert np.array_equal(out, [observer.step(float(xk)) for xk in x])
    assert observer.position_force is force and observer.level is level
    only_force = simulate_position(params, x, DT, position_force=force)
    assert np.max(np.abs(only_force - simulate_position(params, x, DT) - force.force(x))) <= 1e-13
    assert (
        max_relative_error(out, reference.simulate_position(params, x, DT, level=level, position_force=force))
        <= 1e-12
    )


def test_velocity_run_at_positions_is_the_trajectory_step() -> None:
    """A log with a measured velocity column drives the model by its velocity; its positions
    place the terms. The (B, T) run is the feedforward compensator's trajectory steps."""
    params, level, force = Params(**MAXWELL, sigma2_neg=0.9), screw(), cogging()
    x = positions(800, channels=3)
    v = 6e-3 * np.cos(0.02 * np.arange(800) + np.arange(3)[:, None])
    out = simulate(params, v, DT, x=x, level=level, position_force=force)
    for row in range(3):
        compensator = Compensator(params, DT, level=level, position_force=force, x=float(x[row, 0]))
        steps = [
            compensator.step_trajectory(float(vk), float(xk)) for vk, xk in zip(v[row], x[row], strict=True)
        ]
        assert np.array_equal(out[row], steps)
    assert np.array_equal(simulate(params, v[0], DT, x=x[0], level=level, position_force=force), out[0])
    assert (
        max_relative_error(out, reference.simulate(params, v, DT, x=x, level=level, position_force=force))
        <= 1e-12
    )


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: simulate(MAXWELL, np.zeros(10), DT, level=screw()),
            r"`level` is placed by the positions `x`",
        ),
        (
            lambda: simulate(MAXWELL, np.zeros(10), DT, position_force=cogging()),
            r"`position_force` is placed",
        ),
        (
            lambda: simulate(MAXWELL, np.zeros(10), DT, x=np.zeros(10)),
            r"`x` places a `level` or a `position_force`",
        ),
        (
            lambda: simulate(MAXWELL, np.zeros(10), DT, x=np.zeros(9), level=screw()),
            r"`x` must have the shape of `v`, \(10,\), got \(9,\)",
        ),
        (
            lambda: simulate(MAXWELL, np.zeros((2, 5)), DT, x=np.full((2, 5), np.nan), level=screw()),
            r"`x` must be finite, got nan at channel 0, sample 0",
        ),
        (lambda: simulate(MAXWELL, np.zeros(10), DT, x=["a"] * 10, level=screw()), r"`x` must"),
    ],
)
def test_velocity_runs_refuse_misplaced_terms(call: Any, message: str) -> None:
    with pytest.raises(InputError, match=message):
        call()


def test_terms_must_be_their_classes() -> None:
    with pytest.raises(ParameterError, match=r"`position_force` must be a leuven_rt\.level\.PositionForce"):
        simulate_position(MAXWELL, positions(10), DT, position_force=screw())  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match=r"`position_force` must be"):
        Compensator(MAXWELL, DT, "observer", position_force={"middle": 0.0})  # type: ignore[arg-type]


# --- the feedforward compensator's position ---------------------------------------------------


@pytest.mark.parametrize("terms", [dict(level=screw()), dict(position_force=cogging())])
def test_feedforward_terms_need_the_start_position(terms: dict[str, Any]) -> None:
    """A feedforward compensator with a level started at x = 0 without a word, out of phase with
    the machine; now it is refused, naming `x`, unless the start position is given."""
    with pytest.raises(InputError, match=r"^`x`, the axis's start position, must be given"):
        Compensator(MAXWELL, DT, "feedforward", **terms)
    placed = Compensator(MAXWELL, DT, "feedforward", **terms, x=0.012)
    assert placed.position == 0.012
    Compensator(MAXWELL, DT, "observer", **terms)  # the observer's input is the position
    assert Compensator(MAXWELL, DT).position is None
    for bad in (math.nan, math.inf):
        with pytest.raises(InputError, match="`x` must be finite"):
            Compensator(MAXWELL, DT, **terms, x=bad)
    with pytest.raises(InputError, match="`x` must be a real number"):
        Compensator(MAXWELL, DT, **terms, x="0")  # type: ignore[arg-type]


def test_step_trajectory_places_the_terms_and_refuses_bad_samples() -> None:
    params, level, force = Params(**MAXWELL, sigma2_neg=0.9), screw(), cogging()
    compensator = Compensator(params, DT, level=level, position_force=force, x=0.0)
    plain = Compensator(params, DT)
    for k in range(300):
        v, x = 4e-3 * math.cos(0.03 * k), 0.004 * math.sin(0.02 * k)
        base = plain.step(v)
        sigma2 = 0.9 if v < 0 else 0.4
        want = float(level.factor(x)) * (base - sigma2 * v) + sigma2 * v + float(force.force(x))
        assert abs(compensator.step_trajectory(v, x) - want) <= 1e-12 * max(abs(want), 1.0)
        assert compensator.position == x
    before = (compensator.output, compensator._state())
    for v, x, name in ((math.nan, 0.0, "v"), (1e-3, math.inf, "x")):
        with pytest.raises(InputError, match=f"`{name}` must be finite.*the state and output are unchanged"):
            compensator.step_trajectory(v, x)
    with pytest.raises(InputError, match="`x` must be a real number"):
        compensator.step_trajectory(0.0, None)  # type: ignore[arg-type]
    assert (compensator.output, compensator._state()) == before


@settings(max_examples=100, deadline=None)
@given(
    middle=st.floats(-1.0, 1.0),
    half_stroke=st.floats(1e-3, 2.0),
    trend=st.tuples(st.floats(-50.0, 50.0), st.floats(-50.0, 50.0)),
    amplitudes=st.lists(st.floats(-50.0, 50.0), min_size=2 * MAX_HARMONICS, max_size=2 * MAX_HARMONICS),
    harmonics=st.integers(0, MAX_HARMONICS),
    period=st.floats(1e-3, 1.0),
    cycles=st.lists(st.floats(-20.0, 20.0), min_size=1, max_size=20),
)
def test_position_force_is_the_oracles_formula(
    middle: float,
    half_stroke: float,
    trend: tuple[float, float],
    amplitudes: list[float],
    harmonics: int,
    period: float,
    cycles: list[float],
) -> None:
    """Any finite amplitudes (no rule on their sum): gms-core's r(x) and the oracle's unreduced
    formula agree to 1e-12 of the sum of the amplitudes for |x/P| up to 20."""
    ripple = Ripple(
        period, tuple(amplitudes[:harmonics]), tuple(amplitudes[MAX_HARMONICS : MAX_HARMONICS + harmonics])
    )
    force = PositionForce(middle, half_stroke, trend, (ripple,))
    x = np.array(cycles) * period
    scale = abs(trend[0]) + abs(trend[1]) + sum(abs(c) for c in ripple.cos + ripple.sin)
    assert np.max(np.abs(force.force(x) - reference.position_series(force, x))) <= 1e-12 * max(scale, 1e-300)
