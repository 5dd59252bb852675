"""The original Leuven model (stacks of extrema): its hysteresis equals Maxwell slip under
Masing's rules, its stacks overflow with a clear error, its force jumps at loop closure where the
modified model's does not, and its steady state is the modified model's."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leuven_rt as lr
from conftest import MAXWELL
from leuven_rt.reference import MaxwellSlip
from leuven_rt.reference.original_leuven import (
    MasingMaxwell,
    OriginalLeuven,
    OriginalLeuvenMass,
    StackHysteresis,
    StackOverflowError,
    TanhCurve,
    run_velocity,
)
from leuven_rt.studies.figures import loop_closure


def maxwell_forces(w: list[float], delta: list[float], z: np.ndarray) -> np.ndarray:
    bank = MaxwellSlip(tuple(w), tuple(delta))
    zeta = bank.relaxed()
    out = np.empty_like(z)
    for k, value in enumerate(z.tolist()):
        out[k] = bank.force(zeta, value)
        bank.commit(zeta, value)
    return out


@settings(max_examples=60, deadline=None)
@given(
    count=st.integers(1, 8),
    data=st.data(),
    steps=st.lists(st.floats(-3.0, 3.0), min_size=1, max_size=300),
)
def test_stack_model_with_masing_curve_is_maxwell_slip(
    count: int, data: st.DataObject, steps: list[float]
) -> None:
    # Nested reversals of any size, closures of any depth: the two memories agree to rounding.
    w = data.draw(st.lists(st.floats(0.05, 1.0), min_size=count, max_size=count))
    delta = data.draw(st.lists(st.floats(0.2, 4.0), min_size=count, max_size=count))
    z = np.concatenate(([0.0], np.cumsum(steps))) * 1e-6
    delta = [d * 1e-6 for d in delta]
    stack = StackHysteresis(MasingMaxwell(w, delta), depth=len(steps) + 1).run(z)
    np.testing.assert_allclose(stack, maxwell_forces(w, delta, z), rtol=0, atol=1e-12 * sum(w))


def test_a_decaying_oscillation_fills_the_stacks_and_the_bank_does_not_care() -> None:
    w, delta = [0.5, 0.4, 0.3], [2e-6, 5e-6, 1e-5]
    k = np.arange(2000)
    z = 2e-5 * np.exp(-k / 600) * np.sin(2 * np.pi * k / 50)
    model = StackHysteresis(MasingMaxwell(w, delta), depth=100)
    sizes = []
    forces = []
    for value in z.tolist():
        forces.append(model.update(value))
        sizes.append(model.stacks.size)
    assert max(sizes) >= 60  # one extremum per reversal, no loop ever closes
    np.testing.assert_allclose(forces, maxwell_forces(w, delta, z), rtol=0, atol=1e-13)
    with pytest.raises(StackOverflowError) as caught:
        StackHysteresis(MasingMaxwell(w, delta), depth=5).run(z)
    assert (caught.value.depth, caught.value.stack) == (5, "maxima")
    sample = caught.value.sample
    assert f"overflowed at sample {sample}: it holds depth = 5" in str(caught.value)
    # The sample named is the reversal that found the stack full: one sample earlier it fits.
    fits = StackHysteresis(MasingMaxwell(w, delta), depth=5)
    fits.run(z[:sample])
    assert fits.stacks.size == 10 and np.sign(z[sample] - z[sample - 1]) != fits.stacks.direction


def test_overflow_in_the_dynamic_model_names_sample_and_depth() -> None:
    p = dict(MAXWELL, Fc_neg=None, Fs_neg=None)
    model = OriginalLeuven(p, depth=2)
    v = 1e-4 * np.cos(2 * np.pi * np.arange(400) / 40) * np.exp(-np.arange(400) / 300)
    with pytest.raises(StackOverflowError, match=r"overflowed at sample 91: it holds depth = 2") as caught:
        run_velocity(model, v, 1e-3)
    # v changes sign at samples 11, 31, 51, 71, 91: maxima at 11, 51 fill the stack, 91 overflows.
    assert caught.value.sample == 91


@pytest.mark.parametrize("depth", [0, -3, 1.5, True, "4", None])
def test_depth_below_one_or_not_an_integer_is_rejected(depth: Any) -> None:
    with pytest.raises(lr.ParameterError, match=r"`depth` \(stack depth\) must be an integer >= 1, got"):
        OriginalLeuven(MAXWELL, depth=depth)
    with pytest.raises(lr.ParameterError, match=r"`depth`"):
        StackHysteresis(TanhCurve(1.0, 1e-6), depth=depth)


@pytest.mark.parametrize(
    "kwargs", [dict(F_max=0.0, z_c=1e-6), dict(F_max=1.0, z_c=-1e-6), dict(F_max=math.inf, z_c=1e-6)]
)
def test_bad_curves_are_parameter_errors(kwargs: dict[str, float]) -> None:
    with pytest.raises(lr.ParameterError, match=r"must be finite and > 0"):
        TanhCurve(**kwargs)


def test_bad_inputs_of_the_original_models() -> None:
    with pytest.raises(lr.ParameterError, match=r"give a `curve`"):
        OriginalLeuven(dict(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=1.0, sigma0=1e5), depth=4)
    model = OriginalLeuven(MAXWELL, depth=4)
    with pytest.raises(lr.InputError, match=r"`dt` must be finite and > 0, got 0.0"):
        model.step(1e-3, 0.0)
    with pytest.raises(lr.ParameterError, match=r"`mass` must be finite and > 0, got -1"):
        OriginalLeuvenMass(model, mass=-1.0)
    with pytest.raises(lr.InputError, match=r"`u` must be finite, got nan"):
        OriginalLeuvenMass(model, mass=1.0).step(math.nan, 1e-3)


def test_the_original_force_jumps_at_loop_closure_and_the_modified_one_does_not() -> None:
    # The paper's Fig. 1, measured: the largest step-to-step change within 10 ms of the closure.
    # A continuous force changes by O(dt) per step; a jump J keeps the largest change near J.
    coarse, fine = loop_closure(4e-4), loop_closure(1e-4)
    original = [run.largest_change(run.friction_original) for run in (coarse, fine)]
    modified = [run.largest_change(run.friction_modified) for run in (coarse, fine)]
    assert original[1] > 0.8 * original[0] and original[1] > 5e-3  # measured 8.3e-3, 7.5e-3 N
    assert modified[1] < 0.3 * modified[0]  # measured 7.5e-3, 1.9e-3 N: ÷4 with dt
    # The jump is the micro-viscous term's, at the sample where the stacks are popped.
    k = fine.closure
    jump = abs(fine.microviscous_original[k + 1] - fine.microviscous_original[k])
    before = abs(fine.microviscous_original[k] - fine.microviscous_original[k - 1])
    assert jump > 5e-3 and before < 1e-4


def test_steady_sliding_is_the_same_as_the_modified_model() -> None:
    # The paper: the modification does not change the steady state Ff = s(v) + sigma2·v.
    p = dict(MAXWELL, Fc_neg=None, Fs_neg=None)
    v = np.full(3000, 2e-3)
    original = run_velocity(OriginalLeuven(p, depth=4), v, 1e-4)
    modified = lr.simulate(p, v, 1e-4)
    expected = 1.0 + 0.5 * math.exp(-4.0) + 0.4 * 2e-3
    assert abs(original[-1] - expected) < 1e-9 and abs(modified[-1] - expected) < 1e-9
