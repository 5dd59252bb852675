"""The analysis runs of the Rust core: ``LeuvenModel.trace_position`` (forces and the deflection z)
and ``element_deflections`` (Maxwell-slip responses along a path), against the per-sample calls
and the numpy reference's slip rule."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import MAXWELL, params_dicts
from leuven_rt import InputError, LeuvenModel, Trace
from leuven_rt.data import element_deflections
from leuven_rt.reference import MaxwellSlip

SETTINGS = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
DT = 1e-4


def path(samples: int = 2000, seed: int = 0) -> np.ndarray:
    """Positions with reversals of every size, from below the elements' deflections to sliding."""
    rng = np.random.default_rng(seed)
    t = np.arange(samples) * DT
    return (
        2e-5 * np.sin(2 * np.pi * 3 * t)
        + 3e-6 * np.sin(2 * np.pi * 41 * t)
        + 1e-7 * rng.standard_normal(samples)
    )


def numpy_slip(x: np.ndarray, Delta: np.ndarray) -> np.ndarray:
    """The numpy reference's slip rule (``leuven_rt.reference.MaxwellSlip``), one sample at a time."""
    bank = MaxwellSlip(tuple(np.ones(Delta.size)), tuple(Delta))
    zeta = np.full(Delta.size, x[0])
    out = np.empty((x.size, Delta.size))
    for k, position in enumerate(x):
        bank.commit(zeta, position)
        out[k] = (position - zeta) / Delta
    return out


@SETTINGS
@given(params=params_dicts(linear=False), seed=st.integers(0, 1000))
def test_trace_equals_stepping(params: dict, seed: int) -> None:
    x = path(600, seed)
    stepped = LeuvenModel(params)
    forces, z = [], []
    for position in x:
        forces.append(stepped.step_position(float(position), DT))
        z.append(stepped.state.z[0])
    trace = LeuvenModel(params).trace_position(x, DT)
    assert isinstance(trace, Trace)
    np.testing.assert_array_equal(trace.force, forces)
    np.testing.assert_array_equal(trace.z, z)


def test_trace_continues_the_state_like_run_position() -> None:
    x = path()
    traced, run = LeuvenModel(MAXWELL), LeuvenModel(MAXWELL)
    first = traced.trace_position(x[:700], DT)
    second = traced.trace_position(x[700:], DT)
    np.testing.assert_array_equal(np.concatenate((first.force, second.force)), run.run_position(x, DT))
    np.testing.assert_array_equal(traced.state.zeta, run.state.zeta)


def test_trace_refuses_what_it_cannot_run() -> None:
    with pytest.raises(InputError, match="runs one channel, this model has 2"):
        LeuvenModel(MAXWELL, channels=2).trace_position(path(), DT)
    with pytest.raises(InputError, match=r"shape \(T,\)"):
        LeuvenModel(MAXWELL).trace_position(path().reshape(1, -1), DT)
    model = LeuvenModel(MAXWELL)
    x = path()
    x[5] = np.nan
    with pytest.raises(InputError, match="`x` must be finite, got nan at sample 5"):
        model.trace_position(x, DT)
    assert model.state.z[0] == 0.0  # nothing was run
    with pytest.raises(InputError, match="`dt` must be finite and > 0"):
        model.trace_position(path(), -1.0)


@pytest.mark.parametrize("elements", [1, 12, 32, 45])
def test_element_deflections_follow_the_slip_rule(elements: int) -> None:
    x = path()
    Delta = np.geomspace(1e-7, 3e-5, elements)
    responses = element_deflections(x, Delta)
    assert responses.shape == (x.size, elements)
    np.testing.assert_allclose(responses, numpy_slip(x, Delta), rtol=0, atol=1e-9)
    assert np.all(np.abs(responses) <= 1.0)


def test_element_deflections_refuse_bad_input() -> None:
    x = path()
    with pytest.raises(
        InputError, match=r"`Delta\[1\]` must be finite and > 0 \(and 1/Delta finite\), got 0.0"
    ):
        element_deflections(x, np.array([1e-6, 0.0]))
    with pytest.raises(InputError, match=r"`Delta\[35\]` must be finite and > 0 .*, got -1.0"):
        element_deflections(x, np.r_[np.full(35, 1e-6), -1.0])
    with pytest.raises(InputError, match=r"`Delta\[0\]` .*, got 1e-310"):
        element_deflections(x, np.array([1e-310]))
    with pytest.raises(InputError, match=r"`x` must be one-dimensional, got shape \(1, 2000\)"):
        element_deflections(x.reshape(1, -1), np.array([1e-6]))
    with pytest.raises(InputError, match=r"`Delta` must be one-dimensional, got shape \(1, 1\)"):
        element_deflections(x, np.array([[1e-6]]))
    x[3] = np.inf
    with pytest.raises(InputError, match="`x` must be finite, got inf at sample 3"):
        element_deflections(x, np.array([1e-6]))
