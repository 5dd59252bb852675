"""The force-driven mass: Rust (`leuven_rt.simulate_mass`, `MassSystem`) against the numpy
reference (`leuven_rt.reference.mechanics`), consistency with the velocity-driven friction,
channels and checkpoints, and every bad input."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import leuven_rt as lr
from conftest import MAXWELL, log_uniform, max_relative_error, params_dicts
from leuven_rt.reference import mechanics as reference

#: Rust and the reference solve the same equations to a few ulps each; chained over a run the
#: difference stays far below this (observed ≤ 1e-12).
TOLERANCE = 1e-9


def steepest_stribeck_slope(p: dict[str, Any]) -> float:
    """max |g'(v)| over both directions, on a dense log grid (infinite at v → 0 when δ < 1)."""
    x = np.logspace(-6, 2, 4001)
    shape = p["delta"] * x ** (p["delta"] - 1.0) * np.exp(-(x ** p["delta"])) / p["Vs"]
    drop = max(p["Fs"] - p["Fc"], p.get("Fs_neg", p["Fs"]) - p.get("Fc_neg", p["Fc"]))
    return float(drop * shape.max())


@st.composite
def mass_cases(draw: st.DrawFn) -> dict[str, Any]:
    """A friction model, a machine and a force signal. The mass is at least 4·dt·max|g'|, the
    condition under which the implicit step has a single root in sliding (crates/gms-core/src/
    mechanics), so that both implementations must find the same one."""
    p = draw(params_dicts(linear=False).filter(lambda p: len(p["W"]) <= 8))
    dt = draw(st.sampled_from([1e-4, 1e-3]))
    mass = max(draw(log_uniform(0.05, 5.0)), 4.0 * dt * steepest_stribeck_slope(p))
    samples = 150
    t = np.arange(samples) * dt
    amplitude = 2.0 * max(p["Fs"], p.get("Fs_neg", p["Fs"])) * draw(st.floats(0.05, 1.0))
    frequency = draw(st.floats(0.5, 20.0)) / (samples * dt)
    u = amplitude * np.sin(2 * np.pi * frequency * t + draw(st.floats(0.0, 2 * np.pi)))
    return dict(
        params=p,
        u=u,
        dt=dt,
        mass=mass,
        stiffness=draw(st.sampled_from([0.0]) | log_uniform(10.0, 1e5)),
        drive_speed=draw(st.sampled_from([0.0]) | log_uniform(1e-4, 1e-2)),
        position=draw(st.sampled_from([0.0]) | st.floats(-1e-3, 1e-3)),
    )


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(case=mass_cases())
def test_implicit_rust_matches_reference(case: dict[str, Any]) -> None:
    rust = lr.simulate_mass(**case)
    spec = reference.simulate_mass(**case)
    for name in ("friction", "position", "velocity"):
        error = max_relative_error(getattr(rust, name), getattr(spec, name))
        assert error < TOLERANCE, (name, error)


@pytest.mark.parametrize("stiffness, drive_speed", [(0.0, 0.0), (500.0, 0.0), (500.0, 0.01)])
def test_explicit_rust_matches_reference_where_it_is_stable(stiffness: float, drive_speed: float) -> None:
    # Explicit is compared where it is stable (dt²·K/m ≈ 0.01): where it chatters, it is chaotic
    # and rounding differences grow without bound.
    t = np.arange(2000) * 1e-5
    case = dict(params=MAXWELL, u=1.5 * np.sin(2 * np.pi * 50 * t), dt=1e-5, mass=1.0,
                stiffness=stiffness, drive_speed=drive_speed, scheme="explicit")  # fmt: skip
    rust, spec = lr.simulate_mass(**case), reference.simulate_mass(**case)
    for name in ("friction", "position", "velocity"):
        assert max_relative_error(getattr(rust, name), getattr(spec, name)) < TOLERANCE, name


def test_the_friction_is_the_velocity_driven_model_at_the_mass_velocity() -> None:
    # Same dt contract: over step k the friction holds the velocity (x⁺ − x)/dt = v⁺.
    t = np.arange(5000) * 1e-4
    run = lr.simulate_mass(MAXWELL, 2.0 * np.sin(2 * np.pi * 2 * t), 1e-4, mass=0.3, stiffness=100.0)
    np.testing.assert_allclose(np.diff(run.position, prepend=0.0) / 1e-4, run.velocity, rtol=0, atol=1e-12)
    friction = lr.simulate(MAXWELL, run.velocity, 1e-4)
    assert max_relative_error(friction, run.friction) < 1e-9


def test_momentum_balance_of_backward_euler() -> None:
    t = np.arange(3000) * 1e-3
    u = 3.0 * np.sin(2 * np.pi * t)
    m, k, speed, dt = 0.7, 200.0, 3e-3, 1e-3
    run = lr.simulate_mass(MAXWELL, u, dt, mass=m, stiffness=k, drive_speed=speed)
    anchor = speed * dt * np.arange(1, t.size + 1)
    velocity_before = np.concatenate(([0.0], run.velocity[:-1]))
    imbalance = m * (run.velocity - velocity_before) / dt - (u + k * (anchor - run.position) - run.friction)
    assert np.max(np.abs(imbalance)) < 1e-9


def test_channels_steps_chunks_and_checkpoints_agree() -> None:
    t = np.arange(400) * 1e-3
    u = np.stack([2.0 * np.sin(2 * np.pi * f * t) for f in (1.0, 3.0, 7.0)])
    kwargs = dict(mass=0.5, stiffness=300.0, drive_speed=1e-3)
    block = lr.simulate_mass(MAXWELL, u, 1e-3, **kwargs)
    for b in range(3):
        one = lr.simulate_mass(MAXWELL, u[b], 1e-3, **kwargs)
        np.testing.assert_array_equal(one.position, block.position[b])
    system = lr.MassSystem(MAXWELL, **kwargs)
    stepped = np.array([system.step(float(value), 1e-3) for value in u[0, :200]])
    checkpoint = system.state
    rest = system.run(u[0, 200:], 1e-3)
    np.testing.assert_array_equal(stepped[:, 0], block.friction[0, :200])
    np.testing.assert_array_equal(stepped[:, 1], block.position[0, :200])
    np.testing.assert_array_equal(rest.velocity, block.velocity[0, 200:])
    system.set_state(checkpoint)
    np.testing.assert_array_equal(system.run(u[0, 200:], 1e-3).position, rest.position)
    many = lr.MassSystem(MAXWELL, channels=3, **kwargs)
    first = many.step_channels(u[:, 0], 1e-3)
    np.testing.assert_array_equal(first.friction, block.friction[:, 0])


def test_start_from_a_position_and_velocity() -> None:
    run = lr.simulate_mass(MAXWELL, np.zeros(3), 1e-3, mass=1.0, stiffness=1e3, position=1e-3, velocity=0.02)
    spec = reference.simulate_mass(MAXWELL, np.zeros(3), 1e-3, mass=1.0, stiffness=1e3, position=1e-3,
                                   velocity=0.02)  # fmt: skip
    assert max_relative_error(run.position, spec.position) < TOLERANCE
    assert run.position[0] > 1e-3  # moving on at about 20 mm/s


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(mass=0.0), r"`mass` must be finite and > 0, got 0.0$"),
        (dict(mass=-1.0), r"`mass` must be finite and > 0, got -1.0$"),
        (dict(mass=math.nan), r"`mass` must be finite and > 0, got nan"),
        (dict(mass="1"), r"`mass` must be a real number, got '1'"),
        (dict(mass=1.0, stiffness=-5.0), r"`stiffness` must be finite and >= 0, got -5.0$"),
        (dict(mass=1.0, stiffness=math.inf), r"`stiffness` must be finite and >= 0, got inf"),
        (dict(mass=1.0, drive_speed=math.nan), r"`drive_speed` must be finite, got nan"),
    ],
)
def test_bad_mechanical_parameters_are_parameter_errors(kwargs: dict[str, Any], match: str) -> None:
    with pytest.raises(lr.ParameterError, match=match):
        lr.MassSystem(MAXWELL, **kwargs)
    with pytest.raises(lr.ParameterError, match=match):
        lr.simulate_mass(MAXWELL, np.zeros(3), 1e-3, **kwargs)


def test_bad_friction_parameters_keep_their_messages() -> None:
    with pytest.raises(lr.ParameterError, match=r"`Fs` must be >= `Fc`"):
        lr.MassSystem(dict(MAXWELL, Fs=0.5), mass=1.0)


def test_bad_inputs_are_input_errors_and_leave_the_state_untouched() -> None:
    system = lr.MassSystem(MAXWELL, mass=1.0, stiffness=100.0)
    system.run(np.full(10, 0.7), 1e-3)
    before = system.state
    for dt in (0.0, -1e-3, math.nan, math.inf):
        with pytest.raises(lr.InputError, match=r"`dt` must be finite and > 0"):
            system.step(0.1, dt)
        with pytest.raises(lr.InputError, match=r"`dt` must be finite and > 0"):
            system.run(np.zeros(4), dt)
    with pytest.raises(lr.InputError, match=r"`u` must be finite, got nan at sample 0"):
        system.step(math.nan, 1e-3)
    with pytest.raises(lr.InputError, match=r"`u` must be finite, got inf at sample 2"):
        system.run([0.1, 0.2, math.inf], 1e-3)
    with pytest.raises(lr.InputError, match=r"`u` must be a real number"):
        system.step("1", 1e-3)  # type: ignore[arg-type]
    with pytest.raises(lr.InputError, match=r"`u` must have shape \(T,\) or \(1, T\), got shape \(2, 3\)"):
        system.run(np.zeros((2, 3)), 1e-3)
    with pytest.raises(lr.InputError, match=r"`scheme` must be 'implicit' or 'explicit', got 'rk4'"):
        lr.MassSystem(MAXWELL, mass=1.0, scheme="rk4")
    with pytest.raises(lr.InputError, match=r"`channels` must be an integer from 1"):
        lr.MassSystem(MAXWELL, mass=1.0, channels=0)
    with pytest.raises(lr.InputError, match=r"`state.zeta` must have shape \(1, 4\)"):
        system.set_state(lr.MassState(*(np.zeros(1),) * 4, np.zeros((1, 3))))
    with pytest.raises(lr.InputError, match=r"`position` must be finite, got nan at sample 0"):
        system.place(math.nan)
    with pytest.raises(
        lr.InputError, match=r"`velocity` must be a real number or have shape \(1,\), got \[1.0, 2.0\]"
    ):
        system.place(0.0, [1.0, 2.0])
    after = system.state
    for name in ("position", "velocity", "anchor", "z", "zeta"):
        np.testing.assert_array_equal(getattr(before, name), getattr(after, name), err_msg=name)


def test_explicit_divergence_is_reported_with_the_sample() -> None:
    # A LuGre spring of 1e12 N/m stepped explicitly at 1 kHz overflows within a few samples.
    stiff = dict(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=1.0, sigma0=1e12, sigma1=0.0, sigma2=0.0)
    with pytest.raises(lr.DivergenceError, match=r"diverged at sample \d+"):
        lr.simulate_mass(stiff, np.full(2000, 5.0), 1e-3, mass=1e-3, scheme="explicit")
