"""leuven_rt.Compensator: the model stepped at a fixed dt in two modes, parameter swaps without a
jump, and a clear error (with state and output untouched) for every bad input."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import LUGRE, MAXWELL, params_dicts
from leuven_rt import Compensator, InputError, LeuvenModel, ParameterError

DT = 1e-3
V = 5e-3 * np.sin(2 * np.pi * np.arange(1500) * DT)
X = np.cumsum(V) * DT


def busy(mode: str = "observer", params: dict[str, Any] = MAXWELL) -> Compensator:
    """A compensator away from rest (deflected elements, a last position)."""
    compensator = Compensator(params, DT, mode)
    for value in (X if mode == "observer" else V)[:700]:
        compensator.step(float(value))
    return compensator


@settings(max_examples=30, deadline=None)
@given(params=params_dicts(), observer=st.booleans())
def test_modes_are_the_model_stepped_at_the_fixed_dt(params: dict[str, Any], observer: bool) -> None:
    compensator = Compensator(params, DT, "observer" if observer else "feedforward")
    model = LeuvenModel(params)
    step = model.step_position if observer else model.step
    for value in (X if observer else V)[:400].tolist():
        force = compensator.step(value)
        assert force == step(value, DT)
        assert compensator.output == force
    assert compensator.elements == (0 if "sigma0" in params else len(params["W"]))


def test_attributes_and_reset() -> None:
    compensator = busy("feedforward")
    assert (compensator.mode, compensator.dt, compensator.elements) == ("feedforward", DT, 4)
    assert compensator.params.Fc == MAXWELL["Fc"]
    assert compensator.output != 0.0
    compensator.reset()
    assert compensator.output == 0.0
    assert compensator._state() == Compensator(MAXWELL, DT, "feedforward")._state()
    assert repr(compensator) == "Compensator(mode='feedforward', dt=0.001, elements=4)"


def test_swapping_in_the_same_parameters_changes_nothing() -> None:
    compensator, twin = busy(), busy()
    compensator.set_params(MAXWELL)
    assert compensator._state() == twin._state()
    assert [compensator.step(float(x)) for x in X[700:]] == [twin.step(float(x)) for x in X[700:]]


@pytest.mark.parametrize("at", [300, 500])  # 300: sliding at 4.8 mm/s; 500: 0 ms after a reversal
def test_a_swap_has_no_jump(at: int) -> None:
    """With σ1 = σ2 = 0 (the terms without memory, which follow the new parameters at once),
    the output over the sample of the swap changes by a few mN at dt = 10 µs, though the new
    model's levels and elements differ by 20–50 %; the naive swap (new parameters on the old
    state) jumps by a large part of the friction level. That the change is O(dt), i.e. no jump,
    is shown in crates/gms-core/tests/compensator.rs (it shrinks with dt)."""
    old = dict(MAXWELL, sigma1=0.0, sigma2=0.0, Fc_neg=None, Fs_neg=None)
    new = dict(old, Fc=1.2, Fs=1.6, Vs=1.5e-3, W=[0.3, 0.5, 0.6, 0.7], Delta=[3e-6, 5e-6, 1.2e-5, 2.4e-5])
    dt = 1e-5
    v = 5e-3 * np.sin(2 * np.pi * np.arange(100 * at + 1) * dt)
    compensator = Compensator(old, dt)
    forces = [compensator.step(float(value)) for value in v[: 100 * at]]
    compensator.set_params(new)
    jump = abs(compensator.step(float(v[100 * at])) - forces[-1])
    naive_state = LeuvenModel(old)
    naive_state.run(v[: 100 * at], dt)
    naive = LeuvenModel(new)
    naive.set_state(naive_state.state)
    naive_jump = abs(naive.step(float(v[100 * at]), dt) - forces[-1])
    assert jump < 0.005, (jump, naive_jump)
    assert naive_jump > 0.1, (jump, naive_jump)


def test_lugre_compensator_swaps_too() -> None:
    compensator = busy("feedforward", LUGRE)
    before = compensator.output
    compensator.set_params(dict(LUGRE, sigma0=2e5))
    assert math.isfinite(compensator.step(float(V[700])))
    assert abs(compensator.output - before) < 0.1


# --- bad input --------------------------------------------------------------------------------


def rejects(compensator: Compensator, call: Any, error: type[Exception], match: str) -> None:
    """``call`` raises ``error`` matching ``match``; state and output are untouched."""
    state, output = compensator._state(), compensator.output
    with pytest.raises(error, match=match):
        call()
    assert compensator._state() == state
    assert compensator.output == output
    assert math.isfinite(compensator.output)


@pytest.mark.parametrize("mode", ["feedforward", "observer"])
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_input_is_an_error_and_changes_nothing(mode: str, bad: float) -> None:
    compensator = busy(mode)
    name = "x" if mode == "observer" else "v"
    rejects(compensator, lambda: compensator.step(bad), InputError, rf"`{name}` must be finite, got")
    twin = busy(mode)
    values = (X if mode == "observer" else V)[700:720].tolist()
    assert [compensator.step(value) for value in values] == [twin.step(value) for value in values]


def test_position_jump_that_overflows_the_velocity() -> None:
    compensator = busy("observer")
    rejects(compensator, lambda: compensator.step(1e306), InputError, r"`x` = 1e306 after .* not finite")


@pytest.mark.parametrize("bad", [True, "0.1", None, [0.1], 1j])
def test_input_that_is_not_a_real_number(bad: Any) -> None:
    compensator = busy()
    rejects(compensator, lambda: compensator.step(bad), InputError, r"`x` must be a real number, got")


@pytest.mark.parametrize("dt", [0.0, -1e-3, math.nan, math.inf])
def test_dt_must_be_finite_and_positive(dt: float) -> None:
    with pytest.raises(InputError, match=r"`dt` must be finite and > 0, got"):
        Compensator(MAXWELL, dt)


@pytest.mark.parametrize("dt", [True, "0.001", None])
def test_dt_must_be_a_number(dt: Any) -> None:
    with pytest.raises(InputError, match=r"`dt` must be a real number, got"):
        Compensator(MAXWELL, dt)


def test_mode_must_be_known() -> None:
    with pytest.raises(InputError, match=r"`mode` must be 'feedforward' or 'observer', got 'velocity'"):
        Compensator(MAXWELL, DT, "velocity")


@pytest.mark.parametrize(
    ("change", "match"),
    [
        (dict(Fs=0.5), r"`Fs` must be >= `Fc` = 1(\.0)?, got 0.5"),
        (dict(Vs=-1.0), r"`Vs` must be finite and > 0, got -1"),
        (dict(W=[0.5, -0.5, 0.5, 0.5]), r"`W\[1\]` must be finite and > 0, got -0.5"),
        (dict(W=[0.1] * 4), r"`sum\(W\)` must be > max\(`Fs`, `Fs_neg`\)"),
    ],
)
def test_parameters_that_break_the_rules(change: dict[str, Any], match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        Compensator(dict(MAXWELL, **change), DT)
    compensator = busy()
    rejects(compensator, lambda: compensator.set_params(dict(MAXWELL, **change)), ParameterError, match)


def test_new_parameters_must_have_the_same_kind_and_size() -> None:
    compensator = busy()
    smaller = dict(MAXWELL, W=[1.0, 1.0], Delta=[1e-6, 2e-6])
    rejects(compensator, lambda: compensator.set_params(smaller), ParameterError,
            r"must have 4 Maxwell-slip elements like the compensator's, "
            r"got 2 Maxwell-slip elements")  # fmt: skip
    rejects(compensator, lambda: compensator.set_params(LUGRE), ParameterError,
            r"must have 4 Maxwell-slip elements like the compensator's, got linear hysteresis")  # fmt: skip
    lugre = busy("observer", LUGRE)
    rejects(lugre, lambda: lugre.set_params(MAXWELL), ParameterError,
            r"must have linear hysteresis `sigma0` like the compensator's, got 4 Maxwell-slip")  # fmt: skip
    rejects(
        compensator,
        lambda: compensator.set_params(42),
        ParameterError,
        r"must be a leuven_rt.Params or a mapping",
    )


def test_a_model_file_or_its_path_runs_its_friction_and_its_own_terms(tmp_path: Any) -> None:
    from leuven_rt import ModelFile, Params, PositionLevel

    level = PositionLevel(middle=0.0, half_stroke=1e-2, trend=(0.2, 0.0))
    model = ModelFile(friction=Params(**MAXWELL), level=level, offset=0.5, inertia=2.0)
    path = tmp_path / "model.json"
    model.save(path)
    x = 1e-3 * np.sin(np.linspace(0.0, 6.0, 300))
    direct = Compensator(Params(**MAXWELL), 1e-3, "observer", level=level)
    expected = [direct.step(float(value)) for value in x]
    for source in (model, path, str(path)):
        compensator = Compensator(source, 1e-3, "observer")
        assert compensator.level == level
        # The measurement terms (offset, inertia) are the sensor's, not the friction's.
        assert [compensator.step(float(value)) for value in x] == expected


def test_a_model_file_with_terms_given_beside_it_is_refused(tmp_path: Any) -> None:
    from leuven_rt import ModelFile, Params, PositionLevel
    from leuven_rt.errors import ModelFileError

    model = ModelFile(friction=Params(**MAXWELL))
    level = PositionLevel(middle=0.0, half_stroke=1e-2, trend=(0.2, 0.0))
    with pytest.raises(InputError, match=r"^`level` must be None when the model is a model file") as caught:
        Compensator(model, 1e-3, "observer", level=level)
    assert (caught.value.kind, caught.value.field) == ("not_applicable", "level")
    with pytest.raises(ModelFileError) as missing:
        Compensator(tmp_path / "missing.json", 1e-3, "observer")
    assert missing.value.kind == "unreadable_file"
