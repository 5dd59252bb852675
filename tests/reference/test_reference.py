"""The numpy reference (`leuven_rt.reference`) on its own: the properties
docs/model.md#discrete-step promises.

No comparison with the Rust core here; that lives in its own test file.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from leuven_rt import DivergenceError, InputError, Params, PositionForce, PositionLevel, Ripple, reference

EPS = np.finfo(np.float64).eps

#: Asymmetric Maxwell-slip model; sum(W) = 2 N can balance both static levels.
MAXWELL = dict(
    Fc=1.0, Fs=1.5, Fc_neg=0.7, Fs_neg=1.2, Vs=1e-3, delta=2.0, n=2.0,
    sigma1=30.0, sigma2=0.4, W=[0.5, 0.5, 0.5, 0.5], Delta=[2e-6, 4e-6, 8e-6, 1.6e-5],
)  # fmt: skip
LUGRE = dict(
    Fc=1.0, Fs=1.5, Fc_neg=0.7, Fs_neg=1.2, Vs=1e-3, delta=2.0, n=1.0,
    sigma0=1e5, sigma1=30.0, sigma2=0.4,
)  # fmt: skip


def s_of_v(p: dict, v: float) -> float:
    """s(v) = sgn(v)·g(v), written out again so that the test does not trust the module."""
    fc, fs = (p.get("Fc_neg", p["Fc"]), p.get("Fs_neg", p["Fs"])) if v < 0 else (p["Fc"], p["Fs"])
    return math.copysign(fc + (fs - fc) * math.exp(-(abs(v / p["Vs"]) ** p["delta"])), v)


def wobbly_velocity(samples: int, dt: float) -> np.ndarray:
    t = np.arange(samples) * dt
    return 1e-2 * np.sin(2 * np.pi * 5 * t) + 3e-3 * np.sin(2 * np.pi * 23 * t)


# --- v = 0 changes nothing -------------------------------------------------------------------


@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
@pytest.mark.parametrize("model", [MAXWELL, LUGRE, dict(MAXWELL, n=0.6)], ids=["n2", "lugre", "n06"])
def test_rest_holds_the_state_and_outputs_the_hysteresis_force(model: dict, scheme: str) -> None:
    dt = 1e-4
    moving = wobbly_velocity(737, dt)  # ends mid-motion, with elements partly slipped
    later = wobbly_velocity(400, dt)[::-1]
    rest = np.zeros(50)
    with_rest = reference.simulate(model, np.concatenate([moving, rest, later]), dt, scheme)
    without = reference.simulate(model, np.concatenate([moving, later]), dt, scheme)
    # σ1 and σ2 do not enter the state equation, so without them the last moving force is Fh(z).
    bare = reference.simulate(dict(model, sigma1=0.0, sigma2=0.0), moving, dt, scheme)
    hysteresis_force = bare[-1]
    assert hysteresis_force != 0.0
    np.testing.assert_array_equal(with_rest[moving.size : -later.size], hysteresis_force)
    # Nothing moved during the rest: what follows is bit-for-bit what follows without it.
    np.testing.assert_array_equal(with_rest[-later.size :], without[-later.size :])


def test_a_relaxed_channel_at_rest_has_no_force() -> None:
    np.testing.assert_array_equal(reference.simulate(MAXWELL, np.zeros(5), 1e-3), 0.0)


# --- steady sliding -------------------------------------------------------------------------


@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
@pytest.mark.parametrize(
    "model", [MAXWELL, dict(MAXWELL, n=1.0), dict(MAXWELL, n=0.6), LUGRE], ids=["n2", "n1", "n06", "lugre"]
)
@pytest.mark.parametrize("v", [1e-2, 3e-4, -3e-4, -1e-2])
def test_constant_velocity_settles_on_the_stribeck_curve(model: dict, scheme: str, v: float) -> None:
    """F → s(v) + σ2·v, with the negative-direction levels for v < 0.

    The state moves by dt·v per step, so dt is chosen for a fixed 0.5 µm per step (well inside
    the explicit scheme's stability limit) and 3000 steps travel 1.5 mm, about 100 × the largest
    Δ; the approach to the fixed point is exponential in distance and is down to rounding after
    about 1100 steps for the slowest case (n = 0.6, 0.3 mm/s), so a 1e-12 relative tolerance
    holds with margin.
    """
    dt = 5e-7 / abs(v)
    force = reference.simulate(model, np.full(3000, v), dt, scheme)
    expected = s_of_v(model, v) + model["sigma2"] * v
    assert force[-1] == pytest.approx(expected, rel=1e-12)
    assert force[-1000] == pytest.approx(expected, rel=1e-12)  # settled, not passing through


def test_steady_levels_differ_by_direction() -> None:
    """Written-out numbers: at 1 mm/s, g = 1 + 0.5/e in the forward direction, 0.7 + 0.5/e back."""
    dt, v = 5e-4, 1e-3
    forward = reference.simulate(MAXWELL, np.full(3000, v), dt)[-1]
    backward = reference.simulate(MAXWELL, np.full(3000, -v), dt)[-1]
    assert forward == pytest.approx(1.0 + 0.5 / math.e + 0.4 * v, rel=1e-12)
    assert backward == pytest.approx(-(0.7 + 0.5 / math.e) - 0.4 * v, rel=1e-12)
    # With a viscous coefficient of its own for v < 0, only the backward level changes.
    asymmetric = dict(MAXWELL, sigma2_neg=2.5)
    assert reference.simulate(asymmetric, np.full(3000, v), dt)[-1] == forward
    backward = reference.simulate(asymmetric, np.full(3000, -v), dt)[-1]
    assert backward == pytest.approx(-(0.7 + 0.5 / math.e) - 2.5 * v, rel=1e-12)


def test_the_position_terms_are_written_out() -> None:
    """The oracle's r(x), factor and position force, in numbers: at the middle of the stroke
    p = 0, P2 = −0.5; at a quarter period the ripple's cos is 0 and its sin 1."""
    level = PositionLevel(0.0, 0.01, (0.1, 0.04), (Ripple(0.004, (0.03,), (0.02,)),))
    force = PositionForce(0.0, 0.01, (2.0, 0.4), (Ripple(0.004, (0.3,), (0.2,)),))
    assert reference.position_series(level, 0.0) == pytest.approx(-0.02 + 0.03, abs=1e-15)
    assert reference.position_series(level, 0.001) == pytest.approx(
        0.1 * 0.1 + 0.04 * (1.5 * 0.01 - 0.5) + 0.02, abs=1e-15
    )
    assert reference.position_series(force, 0.02) == pytest.approx(2.0 + 0.4 + 0.3, abs=1e-14)
    # A run: the level scales the contact part, sigma2(v)·v stays, the force is added.
    x = 0.003 * np.sin(np.linspace(0.0, 9.0, 900))
    params = dict(MAXWELL, sigma2_neg=1.1)
    plain = reference.simulate_position(params, x, 1e-3)
    v = np.diff(x, prepend=x[0]) / 1e-3
    viscous = np.where(v < 0, 1.1, 0.4) * v
    want = (1.0 + reference.position_series(level, x)) * (plain - viscous) + viscous
    want = want + reference.position_series(force, x)
    got = reference.simulate_position(params, x, 1e-3, level=level, position_force=force)
    assert np.max(np.abs(got - want)) <= 1e-14
    with pytest.raises(InputError, match="`x` places a `level` or a `position_force`"):
        reference.simulate(params, v, 1e-3, x=x)


# --- the state: elements stay within their break deflection ---------------------------------

element_banks = st.integers(1, 6).flatmap(
    lambda count: st.tuples(
        st.lists(st.floats(0.1, 2.0), min_size=count, max_size=count),
        st.lists(st.floats(1e-7, 1e-4), min_size=count, max_size=count),
    )
)


@settings(max_examples=60, deadline=None)
@given(
    bank=element_banks,
    n=st.sampled_from([0.5, 1.0, 1.7, 3.0]),
    velocities=st.lists(st.floats(-5e-2, 5e-2), min_size=1, max_size=60),
    dt=st.sampled_from([1e-5, 1e-4, 1e-3]),
)
def test_elements_never_exceed_their_break_deflection(
    bank: tuple[list[float], list[float]], n: float, velocities: list[float], dt: float
) -> None:
    """|z − ζᵢ| ≤ Δᵢ after every commit, up to the rounding of z − (z ∓ Δᵢ) (a few ulps)."""
    W, Delta = bank
    params = Params(Fc=0.05, Fs=0.08, Vs=1e-3, delta=2.0, n=n, W=W, Delta=Delta)
    hysteresis = reference.hysteresis_of(params)
    z, zeta = 0.0, hysteresis.relaxed()
    limit = np.asarray(Delta)
    for k, v in enumerate(velocities):
        z, _ = reference.step(params, hysteresis, zeta, z, v, dt, "implicit", sample=k)
        slack = 4 * EPS * np.maximum(limit, abs(z))
        assert np.all(np.abs(z - zeta) <= limit + slack)


def test_commit_moves_only_slipping_elements() -> None:
    hysteresis = reference.MaxwellSlip((1.0, 2.0, 3.0), (1e-6, 2e-6, 4e-6))
    zeta = np.array([0.3e-6, -0.1e-6, 0.7e-6])
    before = zeta.copy()
    hysteresis.commit(zeta, 1.5e-6)
    assert zeta[0] == 1.5e-6 - 1e-6  # slipped to its break deflection
    assert zeta[1:].tolist() == before[1:].tolist()  # stuck: bit-for-bit unchanged


def test_maxwell_force_is_the_sum_of_clipped_springs() -> None:
    hysteresis = reference.MaxwellSlip((1.0, 2.0, 3.0), (1e-6, 2e-6, 4e-6))
    zeta = hysteresis.relaxed()
    assert hysteresis.force(zeta, 1.5e-6) == pytest.approx(1.0 + 1.5 + 1.125, rel=1e-15)
    assert hysteresis.force(zeta, -1.0) == -6.0
    assert hysteresis.stiffness(zeta, 1.5e-6) == pytest.approx(1e6 + 0.75e6, rel=1e-15)


# --- the implicit root ----------------------------------------------------------------------


@settings(max_examples=300, deadline=None)
@given(
    bank=element_banks,
    n=st.sampled_from([0.3, 0.5, 1.0, 2.0, 4.0]),
    offsets=st.lists(st.floats(-2.0, 2.0), min_size=6, max_size=6),
    z_scale=st.floats(-3.0, 3.0),
    v=st.floats(-1.0, 1.0).filter(lambda v: v != 0.0),
    dt=st.sampled_from([1e-6, 1e-4, 1e-2]),
)
def test_implicit_root_brackets_the_zero_of_the_residual(
    bank: tuple[list[float], list[float]],
    n: float,
    offsets: list[float],
    z_scale: float,
    v: float,
    dt: float,
) -> None:
    """R changes sign within a few ulps of the returned z⁺, for arbitrary element memories."""
    W, Delta = bank
    hysteresis = reference.MaxwellSlip(tuple(W), tuple(Delta))
    d = np.asarray(Delta)
    zeta = np.asarray(offsets[: d.size]) * d  # any memory: elements anywhere around z = 0
    z = z_scale * float(d.max())
    g = 0.3 + 0.2 * math.exp(-abs(v / 1e-3))
    root = reference.implicit_root(hysteresis, zeta, z, v, dt, g, n)

    def residual(y: float) -> float:
        return (y - z) - dt * v + dt * abs(v) * reference.phi(hysteresis.force(zeta, y) / g, n)

    # R is evaluated with rounding of order ulps of its largest term, so step out a little more.
    scale = max(abs(z), abs(root), dt * abs(v) * (1.0 + (sum(W) / g) ** n))
    step = 16 * EPS * scale
    assert residual(root - step) <= 0.0 <= residual(root + step)


def test_v_zero_root_is_the_start_point() -> None:
    hysteresis = reference.MaxwellSlip((1.0,), (1e-6,))
    assert reference.implicit_root(hysteresis, np.array([3e-7]), 2e-7, 0.0, 1e-3, 1.2, 0.5) == 2e-7


# --- the entry points -----------------------------------------------------------------------


def test_channels_are_independent_rows() -> None:
    dt = 1e-4
    v = np.stack([wobbly_velocity(300, dt), -wobbly_velocity(300, dt), np.zeros(300)])
    together = reference.simulate(MAXWELL, v, dt)
    assert together.shape == v.shape
    for row, alone in zip(together, v, strict=True):
        np.testing.assert_array_equal(row, reference.simulate(MAXWELL, alone, dt))


def test_position_input_is_differenced_with_a_still_first_sample() -> None:
    dt = 1e-4
    x = np.cumsum(wobbly_velocity(400, dt)) * dt + 0.25  # an offset stroke
    v = np.concatenate([[0.0], np.diff(x) / dt])
    np.testing.assert_array_equal(
        reference.simulate_position(MAXWELL, np.stack([x, x]), dt),
        np.stack([reference.simulate(MAXWELL, v, dt)] * 2),
    )


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: reference.simulate(MAXWELL, [0.0, np.nan], 1e-3), "`v` must be finite"),
        (lambda: reference.simulate(MAXWELL, np.zeros((2, 2, 2)), 1e-3), "shape"),
        (lambda: reference.simulate(MAXWELL, [0.0], 0.0), "`dt`"),
        (lambda: reference.simulate(MAXWELL, [0.0], 1e-3, "rk4"), "`scheme`"),
        (lambda: reference.simulate_position(MAXWELL, [0.0, np.inf], 1e-3), "`x` must be finite"),
        (lambda: reference.simulate_position(MAXWELL, [-1e308, 1e308], 1e-3), "`v` must be finite"),
    ],
)
def test_bad_inputs_raise_input_error(call: Callable[[], object], message: str) -> None:
    with pytest.raises(InputError, match=message):
        call()


def test_explicit_divergence_is_reported() -> None:
    """A stiff spring at 1 kHz and 0.1 m/s: dt·|v|·σ0/g ≈ 10, far beyond forward Euler's 2."""
    v = 0.1 * np.sin(2 * np.pi * 5 * np.arange(2000) * 1e-3)
    params = dict(LUGRE, sigma0=1e5)
    with pytest.raises(DivergenceError, match="diverged at sample"):
        reference.simulate(params, v, 1e-3, "explicit")
    assert np.all(np.isfinite(reference.simulate(params, v, 1e-3)))  # implicit is fine
