"""Online identification (recursive least squares in gms-core), from Python.

Stated targets, with the figures measured when they were set:
- λ = 1: the recursive estimate equals the batch least-squares estimate on the same samples to
  1e-4 of its size from sample 200 on (measured ≤ 3e-5), and lies within 2 % of the batch
  estimate of the whole 8000-sample log from sample 3000 on (measured: from sample 2929).
- λ = 0.995: after a step of Fc from 0.3 N to 0.5 N, the Fc estimate is within 0.02 N of the new
  value from 500 samples after the step on (measured: 418).
- Bad input of every kind raises ParameterError or InputError naming the argument, and a
  rejected call changes nothing.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leuven_rt as lr
from leuven_rt.reference.online import regressors

DT = 1e-3
#: A Leuven model whose sliding is Coulomb + viscous at the speeds below (Vs is small).
LEUVEN = lr.Params(
    Fc=1.0, Fs=1.2, Vs=1e-4, delta=2.0, n=2.0, sigma1=0.0, sigma2=50.0,
    W=[0.6, 0.5, 0.4, 0.3], Delta=[2e-6, 4e-6, 8e-6, 1.6e-5],
)  # fmt: skip
#: Break deflections of the identifier: equally spaced up to the presliding range.
DELTA = np.linspace(4e-6, 2e-5, 5)


def backward_velocity(x: np.ndarray) -> np.ndarray:
    """The velocity the simulator uses for position input: (xₖ − xₖ₋₁)/dt, 0 at the start."""
    v = np.zeros_like(x)
    v[1:] = np.diff(x) / DT
    return v


def leuven_log(samples: int = 8000, seed: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x, v, f: a 1-second-periodic motion (2, 5 and 11 Hz: reversals of many amplitudes) through
    the project's simulator, with 0.01 N of force noise."""
    t = np.arange(samples) * DT
    x = (
        1e-4 * np.sin(2 * np.pi * 2 * t)
        + 2e-5 * np.sin(2 * np.pi * 5 * t)
        + 4e-6 * np.sin(2 * np.pi * 11 * t)
    )
    noise = 0.01 * np.random.default_rng(seed).standard_normal(samples)
    return x, backward_velocity(x), lr.simulate_position(LEUVEN, x, DT) + noise


def test_recursive_estimate_converges_to_the_batch_least_squares_estimate() -> None:
    x, v, f = leuven_log()
    identifier = lr.OnlineIdentifier(DELTA, initial_covariance=1e9)
    estimates = identifier.run(x, v, f)
    design = regressors(DELTA, x, v)
    for samples in (200, 1000, len(x)):
        batch, *_ = np.linalg.lstsq(design[:samples], f[:samples], rcond=None)
        deviation = np.abs(estimates[samples - 1] - batch).max() / np.abs(batch).max()
        assert deviation < 1e-4, (samples, deviation)
    full, *_ = np.linalg.lstsq(design, f, rcond=None)
    deviation = np.abs(estimates - full).max(axis=1) / np.abs(full).max()
    assert (deviation[2999:] < 0.02).all(), np.nonzero(deviation >= 0.02)[0][-1]
    assert identifier.covariance_resets == 0


def test_sliding_params_are_the_leuven_sliding_level_and_viscous_coefficient() -> None:
    x, v, f = leuven_log()
    identifier = lr.OnlineIdentifier(DELTA, initial_covariance=1e9)
    identifier.run(x, v, f)
    sliding = identifier.sliding_params()
    assert set(sliding) == {"Fc", "sigma2"}
    assert sliding["Fc"] == pytest.approx(LEUVEN.Fc, rel=0.01)
    assert sliding["sigma2"] == pytest.approx(LEUVEN.sigma2, rel=0.05)
    merged = lr.Params(**{**LEUVEN.to_dict(), **sliding, "Fs": max(LEUVEN.Fs, sliding["Fc"])})
    assert merged.sigma2 == sliding["sigma2"]
    named = identifier.estimate_dict()
    assert named["Delta"] == pytest.approx(DELTA.tolist())
    assert named["Fc"] + sum(named["W"]) == pytest.approx(sliding["Fc"])


def test_tracks_a_step_change_of_coulomb_friction() -> None:
    samples = 8000
    t = np.arange(samples) * DT
    x = 3e-5 * np.sin(2 * np.pi * 3 * t) + 1.5e-5 * np.sin(2 * np.pi * 7.3 * t)
    v = np.gradient(x, DT)
    delta = np.array([5e-6, 1e-5, 2e-5, 4e-5])
    design = regressors(delta, x, v)
    truth = np.array([0.3, 0.3, 0.2, 0.2, 0.3, 20.0, 0.02])
    step = samples // 2
    coulomb = np.where(np.arange(samples) < step, 0.3, 0.5)
    noise = 0.005 * np.random.default_rng(3).standard_normal(samples)
    f = design @ truth + (coulomb - truth[4]) * design[:, 4] + noise
    identifier = lr.OnlineIdentifier(delta, forgetting=0.995, initial_covariance=1e3)
    estimate = identifier.run(x, v, f)[:, identifier.names.index("Fc")]
    assert np.abs(estimate[step - 1000 : step] - 0.3).max() < 0.02
    late = np.nonzero(np.abs(estimate[step:] - 0.5) >= 0.02)[0]
    assert late.size == 0 or late[-1] < 500, late[-1]


def test_step_by_step_updates_equal_one_run() -> None:
    x, v, f = leuven_log(samples=600)
    stepped = lr.OnlineIdentifier(DELTA, forgetting=0.99)
    run = lr.OnlineIdentifier(DELTA, forgetting=0.99)
    errors = []
    rows = []
    for k in range(len(x)):
        errors.append(stepped.update(x[k], v[k], f[k]))
        rows.append(stepped.estimate)
    np.testing.assert_array_equal(run.run(x, v, f), np.array(rows))
    np.testing.assert_array_equal(run.covariance, stepped.covariance)
    # The returned error is the a priori one: f minus the prediction before the update.
    fresh = lr.OnlineIdentifier(DELTA, forgetting=0.99)
    fresh.run(x[:-1], v[:-1], f[:-1])
    assert errors[-1] == pytest.approx(f[-1] - fresh.predict(x[-1], v[-1]), abs=1e-12)
    run.reset()
    np.testing.assert_array_equal(run.estimate, np.zeros(len(DELTA) + 3))
    assert run.covariance_trace == pytest.approx((len(DELTA) + 3) * 1e4)


@settings(max_examples=25, deadline=None)
@given(
    delta=st.lists(st.floats(1e-7, 1e-4), min_size=1, max_size=6),
    steps=st.lists(st.floats(-3e-5, 3e-5), min_size=2, max_size=300),
)
def test_rust_regressors_match_the_numpy_definition(delta: list[float], steps: list[float]) -> None:
    """On noiseless data built from the numpy regressors, the Rust estimator (λ = 1, huge prior)
    finds the batch solution of those same regressors: the two build the same regressors."""
    x = np.cumsum(steps)
    v = backward_velocity(x)
    design = regressors(delta, x, v)
    theta = np.linspace(0.2, 1.0, len(delta) + 3)
    f = design @ theta
    identifier = lr.OnlineIdentifier(delta, initial_covariance=1e12)
    identifier.run(x, v, f)
    # Whatever the rank of the data, the fit reproduces them.
    prediction = regressors(delta, x, v) @ identifier.estimate
    assert np.abs(prediction - f).max() < 1e-6 * max(1.0, np.abs(f).max())


# --- bad input ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        (dict(Delta=[]), r"`Delta` must have 1 to 32 elements, got 0"),
        (dict(Delta=[1e-6] * 33), r"`Delta` must have 1 to 32 elements, got 33"),
        (dict(Delta=[1e-6, -1e-6]), r"`Delta\[1\]` must be finite and > 0, got -1e-6"),
        (dict(Delta=[1e-6, float("nan")]), r"`Delta\[1\]` must be finite and > 0, got nan"),
        (dict(Delta=[[1e-6]]), r"`Delta` must be a flat sequence"),
        (dict(Delta="abc"), r"`Delta` must be a sequence of real numbers"),
        (dict(Delta=[1e-6], forgetting=0.0), r"`forgetting` must be in \(0, 1\], got 0.0"),
        (dict(Delta=[1e-6], forgetting=1.5), r"`forgetting` must be in \(0, 1\], got 1.5"),
        (dict(Delta=[1e-6], forgetting=True), r"`forgetting` must be a real number, got True"),
        (dict(Delta=[1e-6], initial_covariance=-1.0),
         r"`initial_covariance` must be finite and > 0, got -1.0"),
        (dict(Delta=[1e-6], initial_covariance=1.0, max_trace=3.0),
         r"`max_trace` must be >= the trace of the initial covariance, "
         r"4 × initial_covariance = 4.0, got 3.0"),
        (dict(Delta=[1e-6], initial=[0.0, 0.0]), r"`initial` must have 4 values, got 2"),
        (dict(Delta=[1e-6], initial=[0.0, 0.0, float("inf"), 0.0]), r"`initial` must be finite"),
    ],
)  # fmt: skip
def test_bad_settings_raise_a_parameter_error(kwargs: dict[str, Any], match: str) -> None:
    with pytest.raises(lr.ParameterError, match=match):
        lr.OnlineIdentifier(**kwargs)


def trained() -> lr.OnlineIdentifier:
    x, v, f = leuven_log(samples=300)
    identifier = lr.OnlineIdentifier(DELTA, forgetting=0.99)
    identifier.run(x, v, f)
    return identifier


def assert_unchanged(identifier: lr.OnlineIdentifier, reference: lr.OnlineIdentifier) -> None:
    np.testing.assert_array_equal(identifier.estimate, reference.estimate)
    np.testing.assert_array_equal(identifier.covariance, reference.covariance)
    # The element memory too: the next prediction is the same.
    assert identifier.predict(1e-5, 1e-3) == reference.predict(1e-5, 1e-3)


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((float("nan"), 0.0, 0.0), r"`x` must be finite, got nan at sample 0"),
        ((0.0, float("inf"), 0.0), r"`v` must be finite, got inf at sample 0"),
        ((0.0, 0.0, float("-inf")), r"`f` must be finite, got -inf at sample 0"),
        ((0.0, "fast", 0.0), r"`v` must be a real number, got 'fast'"),
        ((0.0, 0.0, True), r"`f` must be a real number, got True"),
        ((0.0, 1e300, 1.0), r"overflowed at sample 0: x = 0.0, v = 1e300, f = 1.0 are too large"),
    ],
)
def test_bad_samples_raise_an_input_error_and_change_nothing(args: tuple[Any, ...], match: str) -> None:
    identifier, reference = trained(), trained()
    with pytest.raises(lr.InputError, match=match):
        identifier.update(*args)
    assert_unchanged(identifier, reference)


@pytest.mark.parametrize(
    ("log", "match"),
    [
        (([0.0, 1e-6, 2e-6], [0.0, 1e-3, np.nan], [0.0, 0.1, 0.2]),
         r"`v` must be finite, got nan at sample 2"),
        (([0.0, 1e-6, 2e-6], [0.0, 1e-3], [0.0, 0.1, 0.2]), r"`v` must have the length of `x`, 3, got 2"),
        (([0.0, 1e-6], [0.0, 1e-3], [[0.0, 0.1]]), r"`f` must have shape \(T,\), got shape \(1, 2\)"),
        (([0.0, 1e-6], [0.0, 1e-3], ["a", "b"]), r"`f` must hold real numbers .*got dtype <U1"),
        (([0.0, 1e-6, 2e-6], [0.0, 1e-3, 1e300], [0.0, 0.1, 0.2]), r"overflowed at sample 2"),
    ],
)  # fmt: skip
def test_bad_logs_raise_an_input_error_and_change_nothing(log: tuple[Any, ...], match: str) -> None:
    identifier, reference = trained(), trained()
    with pytest.raises(lr.InputError, match=match):
        identifier.run(*log)
    assert_unchanged(identifier, reference)


def test_bad_prediction_input_raises_an_input_error() -> None:
    identifier = trained()
    with pytest.raises(lr.InputError, match=r"`x` must be finite, got nan"):
        identifier.predict(float("nan"), 0.0)
    with pytest.raises(lr.InputError, match=r"`v` must be a real number, got None"):
        identifier.predict(0.0, None)  # type: ignore[arg-type]
