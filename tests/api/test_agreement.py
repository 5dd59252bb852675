"""The Rust core (`leuven_rt.simulate`, `simulate_position`) against the numpy reference.

Agreement is measured as the max relative error over the run, max|a − b| / max|b| (a: Rust,
b: reference), and must be ≤ 1e-12, for random valid parameter sets (a viscous coefficient of
their own for v < 0 included) and for velocity signals with reversals, plateaus and exact zeros,
with and without the position-dependent terms (a level and a position force).
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import leuven_rt
from conftest import LUGRE, MAXWELL, log_uniform, max_relative_error, params_dicts, velocity_signals
from leuven_rt import DivergenceError, PositionForce, PositionLevel, Ripple, reference

TOLERANCE = 1e-12
SETTINGS = settings(
    max_examples=40,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.large_base_example],
)


def stiffness(p: dict[str, Any]) -> float:
    """The largest dFh/dz of the hysteresis: σ0, or Σ Wᵢ/Δᵢ with every element sticking."""
    if "sigma0" in p:
        return float(p["sigma0"])
    return float(np.sum(np.asarray(p["W"]) / np.asarray(p["Delta"])))


def diverged_at(error: Exception) -> int:
    """The sample a DivergenceError names."""
    found = re.search(r"diverged at (?:channel \d+, )?sample (\d+)", str(error))
    assert found, str(error)
    return int(found.group(1))


def signals(data: st.DataObject, p: dict[str, Any], scale: float) -> np.ndarray:
    """(T,) or (B, T) velocities: B = 1 is drawn as a 1-D array half of the time."""
    samples = data.draw(st.integers(200, 500), label="samples")
    channels = data.draw(st.integers(1, 2), label="channels")
    rows = [data.draw(velocity_signals(samples, scale), label=f"v[{b}]") for b in range(channels)]
    if channels == 1 and data.draw(st.booleans(), label="one-dimensional"):
        return rows[0]
    return np.stack(rows)


def compare(p: dict[str, Any], v: np.ndarray, dt: float, scheme: str, kind: str, data: st.DataObject) -> None:
    """Runs both implementations on the same input and checks shape and relative error."""
    if kind == "velocity":
        signal, rust, spec = v, leuven_rt.simulate, reference.simulate
    else:
        offset = data.draw(st.sampled_from([0.0, 0.25, -3.0]), label="x0")
        signal = offset + np.cumsum(v, axis=-1) * dt
        rust, spec = leuven_rt.simulate_position, reference.simulate_position
    try:
        expected = spec(p, signal, dt, scheme)
    except DivergenceError as error:
        # Then the Rust core must diverge too, at the same sample.
        with pytest.raises(DivergenceError) as caught:
            rust(p, signal, dt, scheme)
        assert diverged_at(caught.value) == diverged_at(error)
        assume(False)
    got = rust(p, signal, dt, scheme)
    assert got.shape == signal.shape
    assert got.dtype == np.float64
    error = max_relative_error(got, expected)
    assert error <= TOLERANCE, f"max relative error {error:.3g}"


@SETTINGS
@given(p=params_dicts(), data=st.data())
@pytest.mark.parametrize("kind", ["velocity", "position"])
def test_implicit_rust_matches_reference(p: dict[str, Any], data: st.DataObject, kind: str) -> None:
    """Implicit scheme, any valid parameters (Maxwell slip with 1..32 elements or linear σ0,
    symmetric or not, n in (0.5, 4) with 1 and 2 exactly), velocity or position input, one or
    two channels: Rust and the reference agree to max|a − b| / max|b| ≤ 1e-12."""
    dt = data.draw(log_uniform(1e-5, 1e-3), label="dt")
    scale = data.draw(log_uniform(1e-4, 1e-1), label="scale")
    compare(p, signals(data, p, scale), dt, "implicit", kind, data)


@st.composite
def terms(draw: st.DrawFn) -> tuple[PositionLevel | None, PositionForce | None]:
    """A level, a position force, or both: a trend and up to two ripples of up to eight harmonics,
    periods of 0.2–1 (so that |x/P| stays below 20 at the positions below, where the oracle's
    unreduced phase agrees with gms-core's to 1e-12), the level's amplitudes adding up to < 1 and
    the force's to up to 5 N."""

    def shape(total: float) -> dict[str, Any]:
        count = draw(st.integers(0, 2))
        harmonics = [draw(st.integers(1, 8)) for _ in range(count)]
        raw = draw(
            st.lists(st.floats(-1.0, 1.0), min_size=2 + 2 * sum(harmonics), max_size=2 + 2 * sum(harmonics))
        )
        magnitude = sum(abs(c) for c in raw)
        c = [value * total / magnitude for value in raw] if magnitude > 0 else raw
        ripples, at = [], 2
        for k in harmonics:
            period = draw(st.floats(0.2, 1.0))
            ripples.append(Ripple(period, tuple(c[at : at + k]), tuple(c[at + k : at + 2 * k])))
            at += 2 * k
        middle, half_stroke = draw(st.floats(-1.0, 1.0)), draw(st.floats(0.01, 2.0))
        return dict(middle=middle, half_stroke=half_stroke, trend=(c[0], c[1]), ripples=tuple(ripples))

    which = draw(st.sampled_from(["level", "force", "both"]))
    level = PositionLevel(**shape(draw(st.floats(0.0, 0.99)))) if which != "force" else None
    force = PositionForce(**shape(draw(st.floats(0.0, 5.0)))) if which != "level" else None
    return level, force


@SETTINGS
@given(p=params_dicts(), data=st.data(), placed=terms())
@pytest.mark.parametrize("kind", ["velocity", "position"])
def test_rust_matches_reference_with_the_position_terms(
    p: dict[str, Any],
    data: st.DataObject,
    placed: tuple[PositionLevel | None, PositionForce | None],
    kind: str,
) -> None:
    """Implicit scheme, any valid parameters, with a level, a position force or both: position
    input, and velocity input with the positions ``x`` placing the terms (a log with a measured
    velocity). Rust and the reference agree to max|a − b| / max(|b| + Σ|terms of r(x)|) ≤ 1e-12."""
    level, force = placed
    dt = data.draw(log_uniform(1e-5, 1e-3), label="dt")
    v = signals(data, p, data.draw(log_uniform(1e-4, 1e-1), label="scale"))
    x = data.draw(st.sampled_from([0.0, 0.25, -3.0]), label="x0") + np.cumsum(v, axis=-1) * dt
    if kind == "position":
        got = leuven_rt.simulate_position(p, x, dt, level=level, position_force=force)
        expected = reference.simulate_position(p, x, dt, level=level, position_force=force)
    else:
        # The velocity need not be the positions' difference: the two are separate inputs.
        v = 1.3 * v
        got = leuven_rt.simulate(p, v, dt, x=x, level=level, position_force=force)
        expected = reference.simulate(p, v, dt, x=x, level=level, position_force=force)
    assert got.shape == x.shape
    # Rounding is relative to what is summed: where the position force's terms cancel each other
    # (and the friction is tiny), the two sums differ by an ulp of the terms, not of the total.
    error = max_relative_error(got, expected, term_magnitude(force, x))
    assert error <= TOLERANCE, f"max relative error {error:.3g}"


def term_magnitude(force: PositionForce | None, x: np.ndarray) -> np.ndarray:
    """Σ |each term of r(x)| on every sample (0 without a position force): each Legendre and
    Fourier coefficient evaluated on its own, through gms-core."""
    if force is None:
        return np.zeros_like(x)
    t1, t2 = force.trend
    trend = [(t1, 0.0), (0.0, t2)]
    parts = [PositionForce(force.middle, force.half_stroke, trend=t) for t in trend]
    for ripple in force.ripples:
        coefficients = np.concatenate([ripple.cos, ripple.sin])
        for alone in np.diag(coefficients):
            cos, sin = np.split(alone, 2)
            ripples = (Ripple(ripple.period, tuple(cos), tuple(sin)),)
            parts.append(PositionForce(force.middle, force.half_stroke, ripples=ripples))
    return sum((np.abs(part.force(x)) for part in parts), np.zeros_like(x))


@SETTINGS
@given(p=params_dicts(), data=st.data())
@pytest.mark.parametrize("kind", ["velocity", "position"])
def test_explicit_rust_matches_reference(p: dict[str, Any], data: st.DataObject, kind: str) -> None:
    """Explicit scheme where it stays finite (velocities scaled so that dt·|v|·stiffness/g ≤ 0.5):
    Rust and the reference agree to max|a − b| / max|b| ≤ 1e-12."""
    dt = data.draw(log_uniform(1e-5, 1e-3), label="dt")
    g_min = min(p["Fc"], p.get("Fc_neg", p["Fc"]))
    scale = 0.5 * g_min / (dt * stiffness(p)) * data.draw(st.floats(0.05, 1.0), label="fraction")
    compare(p, signals(data, p, scale), dt, "explicit", kind, data)


@SETTINGS
@given(p=params_dicts(linear=True), data=st.data())
@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_linear_hysteresis_rust_matches_reference(
    p: dict[str, Any], data: st.DataObject, scheme: str
) -> None:
    """The linear (σ0, LuGre-like) hysteresis on its own, both schemes, velocity input:
    max|a − b| / max|b| ≤ 1e-12. (Explicit: velocities scaled to stay stable.)"""
    dt = data.draw(log_uniform(1e-5, 1e-3), label="dt")
    if scheme == "explicit":
        scale = 0.5 * min(p["Fc"], p.get("Fc_neg", p["Fc"])) / (dt * p["sigma0"])
    else:
        scale = data.draw(log_uniform(1e-4, 1e-1), label="scale")
    compare(p, signals(data, p, scale), dt, scheme, "velocity", data)


@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
@pytest.mark.parametrize("model", [MAXWELL, LUGRE, dict(MAXWELL, n=0.6), dict(LUGRE, n=2.5)],
                         ids=["maxwell", "lugre", "maxwell-n0.6", "linear-n2.5"])  # fmt: skip
def test_fixed_models_agree_on_a_signal_with_reversals_and_rests(model: dict[str, Any], scheme: str) -> None:
    """A hand-built signal (sine, exact zeros, plateau, sign flip) on the fixed models: Rust and
    reference agree to max|a − b| / max|b| ≤ 1e-12, and the force is not trivially zero."""
    dt = 1e-5 if scheme == "explicit" else 1e-4  # explicit: dt·|v|·stiffness/g stays below 0.5
    t = np.arange(400) * dt
    sine = 1e-2 * np.sin(2 * np.pi * 2.0 * t / t[-1])  # two full cycles
    v = np.concatenate([sine, np.zeros(50), np.full(100, 3e-3), -sine, np.zeros(30)])
    got = leuven_rt.simulate(model, v, dt, scheme)
    expected = reference.simulate(model, v, dt, scheme)
    assert np.max(np.abs(expected)) > 0.1
    assert max_relative_error(got, expected) <= TOLERANCE


@pytest.mark.parametrize("two_dimensional", [False, True])
def test_explicit_divergence_is_reported_alike(two_dimensional: bool) -> None:
    """A stiff linear spring stepped explicitly at a large dt diverges; Rust and reference both
    raise DivergenceError naming the same sample (and, for (B, T) input, Rust names the channel);
    for (T,) input the two messages are identical."""
    v = 1e-2 * np.sin(np.linspace(0.0, 20.0, 2000))
    signal = np.stack([np.zeros_like(v), v]) if two_dimensional else v
    with pytest.raises(DivergenceError, match=r"diverged at .*sample (\d+)") as spec:
        reference.simulate(LUGRE, signal, 1e-2, "explicit")
    sample = re.search(r"sample (\d+)", str(spec.value)).group(1)  # type: ignore[union-attr]
    where = f"channel 1, sample {sample}" if two_dimensional else f"sample {sample}"
    with pytest.raises(DivergenceError, match=f"diverged at {where}:") as rust:
        leuven_rt.simulate(LUGRE, signal, 1e-2, "explicit")
    assert int(sample) > 0
    if not two_dimensional:
        assert str(rust.value) == str(spec.value)


def test_relative_error_definition() -> None:
    """The agreement measure is max|a − b| / max|b| over the run (and 0 for two zero runs)."""
    b = np.array([0.0, 2.0, -4.0])
    assert max_relative_error(b + np.array([0.0, 1e-3, 0.0]), b) == pytest.approx(1e-3 / 4)
    assert max_relative_error(np.zeros(3), np.zeros(3)) == 0.0
    assert max_relative_error(np.array([1e-300]), np.zeros(1)) == np.inf


@pytest.mark.parametrize(
    ("model", "first"),
    [(dict(MAXWELL, n=0.51, Fc_neg=1.0, Fs_neg=1.5), 1e-40), (dict(LUGRE, n=0.75, sigma0=1e3), 1e-100)],
    ids=["maxwell-n0.51", "linear-n0.75"],
)
def test_implicit_step_after_a_tiny_deflection_finds_the_root(model: dict[str, Any], first: float) -> None:
    """A first sample with a tiny velocity leaves a tiny but nonzero z; with n < 1 the slope
    dz/dy of |u|^n is then huge at the step start, yet the next implicit steps must still find
    the root and agree with the reference to 1e-12 (max|a − b| / max|b|) as they do when the
    first sample is exactly 0."""
    v = np.array([first, 3e-3, 6e-3, 1e-2])
    got = leuven_rt.simulate(model, v, 1e-4)
    expected = reference.simulate(model, v, 1e-4)
    assert max_relative_error(got, expected) <= TOLERANCE
