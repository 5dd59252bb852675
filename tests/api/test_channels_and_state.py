"""Channels, chunks, steps and checkpoints of the Rust core: every way of running the same samples
gives the same forces, bit for bit (all paths run the same Rust step on the same floats)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import leuven_rt
from conftest import (
    LUGRE,
    MAXWELL,
    assert_same_state,
    log_uniform,
    params_dicts,
    state_arrays,
    velocity_signals,
)
from leuven_rt import LeuvenModel, ModelState, Params

SETTINGS = settings(
    max_examples=30,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.large_base_example],
)
DT = 1e-4
SAMPLES = 1500


def wobble(samples: int = SAMPLES, dt: float = DT, phase: float = 0.0) -> np.ndarray:
    """A velocity with reversals, a rest and a plateau; big enough to slip every element."""
    t = np.arange(samples) * dt
    v = 1e-2 * np.sin(2 * np.pi * 7 * t + phase) + 3e-3 * np.sin(2 * np.pi * 31 * t)
    v[samples // 3 : samples // 3 + 50] = 0.0
    v[samples // 2 : samples // 2 + 80] = -4e-3
    return v


def signal_rows(data: st.DataObject, rows: int, samples: int = 600) -> np.ndarray:
    scale = data.draw(log_uniform(1e-4, 5e-2), label="scale")
    return np.stack([data.draw(velocity_signals(samples, scale), label=f"v[{b}]") for b in range(rows)])


def positions(v: np.ndarray, dt: float = DT, start: float = 0.125) -> np.ndarray:
    return start + np.cumsum(v, axis=-1) * dt


# --- (B, T) against B separate runs ------------------------------------------------------------


@SETTINGS
@given(p=params_dicts(), data=st.data(), scheme=st.sampled_from(["implicit", "explicit"]))
def test_batch_equals_separate_runs(p: dict[str, Any], data: st.DataObject, scheme: str) -> None:
    """simulate and simulate_position on (B, T) give, row by row, bit-identical forces to B
    separate (T,) runs (the channels run in parallel but do not interact)."""
    rows = data.draw(st.integers(2, 5), label="rows")
    v = signal_rows(data, rows)
    if scheme == "explicit":  # keep it finite: tiny velocities for the stiff models
        v = explicit_safe(v, p)
    batch = leuven_rt.simulate(p, v, DT, scheme)
    assert batch.shape == v.shape
    for row, out in zip(v, batch, strict=True):
        np.testing.assert_array_equal(out, leuven_rt.simulate(p, row, DT, scheme))
    x = positions(v)
    batch_x = leuven_rt.simulate_position(p, x, DT, scheme)
    for row, out in zip(x, batch_x, strict=True):
        np.testing.assert_array_equal(out, leuven_rt.simulate_position(p, row, DT, scheme))


def explicit_safe(v: np.ndarray, p: dict[str, Any]) -> np.ndarray:
    """v scaled down (if needed) so that dt·|v|·stiffness/g ≤ 0.2: the explicit step stays finite."""
    stiffness = float(p["sigma0"]) if "sigma0" in p else float(np.sum(np.divide(p["W"], p["Delta"])))
    g_min = min(p["Fc"], p.get("Fc_neg", p["Fc"]))
    peak = max(float(np.abs(v).max()), 1e-300)
    return v * min(1.0, 0.2 * g_min / (DT * stiffness * peak))


def test_batch_rows_differ_when_inputs_differ() -> None:
    """Sanity for the test above: different rows give different forces (the batch is not one
    row broadcast), and a (1, T) input returns (1, T)."""
    v = np.stack([wobble(), wobble(phase=1.0), np.zeros(SAMPLES)])
    out = leuven_rt.simulate(MAXWELL, v, DT)
    assert not np.array_equal(out[0], out[1])
    np.testing.assert_array_equal(out[2], 0.0)
    assert leuven_rt.simulate(MAXWELL, v[:1], DT).shape == (1, SAMPLES)
    assert leuven_rt.simulate(MAXWELL, v[0], DT).shape == (SAMPLES,)


# --- chunked runs ------------------------------------------------------------------------------


@SETTINGS
@given(p=params_dicts(), data=st.data())
def test_run_in_chunks_equals_one_run(p: dict[str, Any], data: st.DataObject) -> None:
    """LeuvenModel.run continues from the state it left: a (B, T) signal cut at arbitrary points
    (including 1-sample and empty chunks) gives bit-identical forces and final state to one
    simulate call, and to one run on a fresh model."""
    rows = data.draw(st.integers(1, 3), label="rows")
    v = signal_rows(data, rows)
    cuts = sorted(data.draw(st.lists(st.integers(0, v.shape[1]), max_size=6), label="cuts"))
    model = LeuvenModel(p, channels=rows)
    chunks = [model.run(v[:, a:b], DT) for a, b in zip([0, *cuts], [*cuts, v.shape[1]], strict=True)]
    whole_model = LeuvenModel(p, channels=rows)
    whole = whole_model.run(v, DT)
    np.testing.assert_array_equal(np.concatenate(chunks, axis=1), whole)
    np.testing.assert_array_equal(whole, leuven_rt.simulate(p, v, DT))
    assert_same_state(model.state, whole_model.state)


@SETTINGS
@given(p=params_dicts(), data=st.data())
def test_run_position_in_chunks_continues_the_position(p: dict[str, Any], data: st.DataObject) -> None:
    """run_position remembers the last position across calls: chunked positions give the same
    forces as simulate_position on the whole signal, i.e. only the very first sample of the
    fresh model is taken as v = 0, not the first sample of each chunk."""
    v = signal_rows(data, 1)[0]
    x = positions(v)
    cuts = sorted(data.draw(st.lists(st.integers(1, x.size - 1), min_size=1, max_size=5), label="cuts"))
    model = LeuvenModel(p)
    chunks = [model.run_position(x[a:b], DT) for a, b in zip([0, *cuts], [*cuts, x.size], strict=True)]
    np.testing.assert_array_equal(np.concatenate(chunks), leuven_rt.simulate_position(p, x, DT))
    assert model.state.has_last_position.tolist() == [True]
    assert model.state.last_position.tolist() == [x[-1]]


def test_run_position_second_chunk_does_not_restart_at_rest() -> None:
    """A position chunk that starts away from where the last one ended sees the jump as a
    velocity (x_k − x_{k−1})/dt; a fresh model would see v = 0 there. So the two differ."""
    x = positions(wobble())
    model = LeuvenModel(MAXWELL)
    model.run_position(x[:700], DT)
    continued = model.run_position(x[700:], DT)
    fresh = LeuvenModel(MAXWELL).run_position(x[700:], DT)
    assert continued[0] != fresh[0]
    # and what the continuation gives is the velocity-input result for the differenced positions
    v = np.diff(x, prepend=x[0]) / DT
    np.testing.assert_array_equal(continued, leuven_rt.simulate(MAXWELL, v, DT)[700:])


# --- checkpoints -------------------------------------------------------------------------------


@pytest.mark.parametrize("model_params", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
@pytest.mark.parametrize("channels", [1, 3])
def test_set_state_restores_exactly(model_params: dict[str, Any], channels: int) -> None:
    """Take a checkpoint mid-run, run on, restore it, run the same samples again: the forces and
    the final state are bit-identical to the first time (for position input too)."""
    v = np.stack([wobble(phase=b) for b in range(channels)])
    x = positions(v)
    model = LeuvenModel(model_params, channels=channels)
    model.run_position(x[:, :600], DT)
    checkpoint = model.state
    first = model.run_position(x[:, 600:], DT)
    after_first = model.state
    assert not np.array_equal(checkpoint.z, after_first.z)  # the run moved the state
    model.set_state(checkpoint)
    assert_same_state(model.state, checkpoint)
    second = model.run_position(x[:, 600:], DT)
    np.testing.assert_array_equal(first, second)
    assert_same_state(model.state, after_first)


def test_state_moves_between_models() -> None:
    """A checkpoint of one model restored into another model with the same parameters makes it
    continue exactly as the first would."""
    v = wobble()
    a, b = LeuvenModel(MAXWELL), LeuvenModel(MAXWELL)
    a.run(v[:500], DT)
    b.set_state(a.state)
    np.testing.assert_array_equal(a.run(v[500:], DT), b.run(v[500:], DT))


@pytest.mark.parametrize("model_params", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
def test_state_is_a_copy(model_params: dict[str, Any]) -> None:
    """Arrays of a ModelState are copies: writing into them changes neither the model's state
    nor what it computes next; and a checkpoint does not follow the model as it runs on."""
    v = wobble()
    model, twin = LeuvenModel(model_params, channels=2), LeuvenModel(model_params, channels=2)
    both = np.stack([v, -v])
    model.run_position(positions(both[:, :400]), DT)
    twin.run_position(positions(both[:, :400]), DT)
    state = model.state
    kept = state_arrays(state)
    state.z[:] = 123.0
    state.zeta[...] = -7.0
    state.last_position[:] = 9.0
    state.has_last_position[:] = False
    assert_same_state(model.state, twin.state)
    np.testing.assert_array_equal(model.run(both[:, 400:], DT), twin.run(both[:, 400:], DT))
    fresh = model.state
    assert not np.array_equal(fresh.z, kept[0])  # the model ran on...
    assert model.state is not fresh and model.state.z is not fresh.z  # ...and each read is new


def test_state_shapes_and_first_position_flag() -> None:
    """state has z (B,), zeta (B, N) ((B, 0) for linear hysteresis), last_position (B,) and
    has_last_position (B,), False on a fresh model and True after a position step."""
    maxwell = LeuvenModel(MAXWELL, channels=3)
    state = maxwell.state
    assert isinstance(state, ModelState)
    assert (state.z.shape, state.zeta.shape, state.last_position.shape) == ((3,), (3, 4), (3,))
    assert state.has_last_position.dtype == np.bool_
    assert state.has_last_position.tolist() == [False] * 3
    np.testing.assert_array_equal(state.z, 0.0)
    maxwell.step_channels_position([1.0, 2.0, 3.0], DT)
    assert maxwell.state.has_last_position.tolist() == [True] * 3
    assert maxwell.state.last_position.tolist() == [1.0, 2.0, 3.0]
    assert LeuvenModel(LUGRE, channels=2).state.zeta.shape == (2, 0)


@pytest.mark.parametrize("model_params", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
def test_reset_relaxes(model_params: dict[str, Any]) -> None:
    """reset() puts every channel back to the relaxed state (z = 0, elements undeflected, no
    previous position): the state equals a fresh model's and the next run equals a fresh run."""
    v = np.stack([wobble(), wobble(phase=2.0)])
    model = LeuvenModel(model_params, channels=2)
    model.run_position(positions(v), DT)
    assert model.state.has_last_position.all() and np.any(model.state.z != 0.0)
    model.reset()
    fresh = LeuvenModel(model_params, channels=2)
    assert_same_state(model.state, fresh.state)
    np.testing.assert_array_equal(model.run_position(positions(v), DT), fresh.run_position(positions(v), DT))


# --- step, step_channels -----------------------------------------------------------------------


@SETTINGS
@given(p=params_dicts(), data=st.data(), scheme=st.sampled_from(["implicit", "explicit"]))
def test_step_loop_equals_run(p: dict[str, Any], data: st.DataObject, scheme: str) -> None:
    """Calling step(v, dt) sample by sample gives bit-identical forces and state to run; the same
    for step_position against run_position."""
    v = signal_rows(data, 1, samples=300)[0]
    if scheme == "explicit":
        v = explicit_safe(v, p)
    stepped, ran = LeuvenModel(p, scheme=scheme), LeuvenModel(p, scheme=scheme)
    forces = [stepped.step(float(vk), DT) for vk in v]
    assert all(type(f) is float for f in forces)
    np.testing.assert_array_equal(np.array(forces), ran.run(v, DT))
    assert_same_state(stepped.state, ran.state)
    x = positions(v)
    forces_x = [stepped.step_position(float(xk), DT) for xk in x]
    np.testing.assert_array_equal(np.array(forces_x), ran.run_position(x, DT))
    assert_same_state(stepped.state, ran.state)


@SETTINGS
@given(p=params_dicts(), data=st.data())
def test_step_channels_equals_per_channel(p: dict[str, Any], data: st.DataObject) -> None:
    """step_channels(v[:, k], dt) for k = 0..T−1 on a B-channel model equals, channel by
    channel, single-channel models stepped alone, and equals run on the (B, T) signal; the same
    for step_channels_position."""
    rows = data.draw(st.integers(2, 4), label="rows")
    v = signal_rows(data, rows, samples=200)
    x = positions(v)
    model = LeuvenModel(p, channels=rows)
    out = np.stack([model.step_channels(v[:, k], DT) for k in range(v.shape[1])], axis=1)
    out_x = np.stack([model.step_channels_position(x[:, k], DT) for k in range(x.shape[1])], axis=1)
    for b in range(rows):
        single = LeuvenModel(p)
        np.testing.assert_array_equal(out[b], [single.step(float(vk), DT) for vk in v[b]])
        np.testing.assert_array_equal(out_x[b], [single.step_position(float(xk), DT) for xk in x[b]])
    ran = LeuvenModel(p, channels=rows)
    np.testing.assert_array_equal(out, ran.run(v, DT))
    np.testing.assert_array_equal(out_x, ran.run_position(x, DT))
    assert_same_state(model.state, ran.state)


# --- construction ------------------------------------------------------------------------------


@pytest.mark.parametrize("model_params", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
@pytest.mark.parametrize("scheme", ["implicit", "explicit"])
def test_model_from_dict_equals_model_from_params(model_params: dict[str, Any], scheme: str) -> None:
    """A LeuvenModel (and simulate) built from the parameter dict gives bit-identical forces to
    one built from the equivalent Params; the model reports its channels, elements, scheme."""
    v = wobble(dt=1e-5)[:800] * 0.05  # small enough for the explicit scheme
    from_dict = LeuvenModel(model_params, channels=2, scheme=scheme)
    from_params = LeuvenModel(Params(**model_params), channels=2, scheme=scheme)
    both = np.stack([v, -v])
    np.testing.assert_array_equal(from_dict.run(both, 1e-5), from_params.run(both, 1e-5))
    np.testing.assert_array_equal(
        leuven_rt.simulate(model_params, v, 1e-5, scheme),
        leuven_rt.simulate(Params(**model_params), v, 1e-5, scheme),
    )
    elements = len(model_params.get("W", []))
    assert (from_dict.channels, from_dict.elements, from_dict.scheme) == (2, elements, scheme)
    assert from_dict.params == Params(**model_params)
    assert repr(from_dict) == f"LeuvenModel(channels=2, elements={elements}, scheme={scheme!r})"


def test_schemes_differ() -> None:
    """The scheme argument is honoured: on the same stable signal the explicit model's forces
    differ from the implicit model's, and each equals simulate with that scheme."""
    v = wobble() * 0.01
    implicit = LeuvenModel(MAXWELL, scheme="implicit").run(v, DT)
    explicit = LeuvenModel(MAXWELL, scheme="explicit").run(v, DT)
    assert not np.array_equal(implicit, explicit)
    np.testing.assert_array_equal(implicit, leuven_rt.simulate(MAXWELL, v, DT, "implicit"))
    np.testing.assert_array_equal(explicit, leuven_rt.simulate(MAXWELL, v, DT, "explicit"))
