"""Fuzzing the stateful objects: hypothesis state machines over LeuvenModel, MassSystem,
Compensator and OnlineIdentifier that call every method with valid and invalid arguments.

After every call: a refusal is one of the documented errors (docs/errors.md) and left the state
bit for bit as it was; an accepted call left the invariants true (every Maxwell-slip element
within its break deflection of z, |z − ζᵢ| ≤ Δᵢ; forces, positions and estimates finite).
Budget: the ``fuzz`` profile of tests/conftest.py.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

import leuven_rt as lr
from conftest import FUZZ, LUGRE, MAXWELL
from leuven_rt.errors import DivergenceError, InputError, ParameterError

DOCUMENTED = (ParameterError, InputError, DivergenceError)
#: What :meth:`_Machine.attempt` returns for a refused call.
REFUSED: Any = object()
DT = 1e-4

#: Numbers as they come: ordinary, tiny, huge, non-finite, and things that are not numbers.
finite = st.floats(-1.0, 1.0) | st.sampled_from([0.0, 1e-300, -1e-12, 5e-3, 0.5])
hostile_scalar = st.sampled_from(
    [np.nan, np.inf, -np.inf, 1e308, -1e308, 10**400, True, None, "1", b"1", [1.0], np.array(1.0), 1j]
)
scalar = finite | hostile_scalar
step_size = st.sampled_from([DT, 1e-3, 1e-6]) | st.sampled_from(
    [0.0, -DT, np.nan, np.inf, 1e-310, 10**400, 1e300, "1e-4", True, None]
)


def signal(rows: int) -> st.SearchStrategy[Any]:
    """A (rows, T) block of velocities, sometimes hostile: a NaN inside, a wrong shape, text,
    booleans, a masked array."""
    good = st.integers(1, 40).flatmap(
        lambda length: st.lists(finite, min_size=rows * length, max_size=rows * length).map(
            lambda values: np.array(values).reshape(rows, length)
        )
    )

    def spoil(block: np.ndarray, how: str) -> Any:
        if how == "nan":
            block = block.copy()
            block.flat[len(block.flat) // 2] = np.nan
            return block
        if how == "shape":
            return block.reshape(1, -1, 1)
        if how == "rows":
            return np.vstack([block, block])
        if how == "text":
            return block.astype(str)
        if how == "bool":
            return block > 0
        if how == "masked":
            return np.ma.masked_array(block, mask=block > 0)
        if how == "huge":
            return block * 1e308
        return block

    how = st.sampled_from(["good"] * 6 + ["nan", "shape", "rows", "text", "bool", "masked", "huge"])
    return st.tuples(good, how).map(lambda pair: spoil(*pair))


def within_deflection(z: np.ndarray, zeta: np.ndarray, delta: np.ndarray) -> None:
    """Every element within its break deflection of z (to rounding)."""
    if zeta.size:
        gap = np.abs(np.asarray(z)[..., None] - zeta)
        assert (gap <= delta * (1 + 1e-9) + 1e-300).all(), (gap, delta)


class _Machine(RuleBasedStateMachine):
    """Calls through :meth:`attempt`: a refusal must be documented and change nothing."""

    def snapshot(self) -> tuple[Any, ...]:
        raise NotImplementedError

    def attempt(self, call: Callable[[], Any]) -> Any:
        before = self.snapshot()
        try:
            return call()
        except DOCUMENTED:
            after = self.snapshot()
            for old, new in zip(before, after, strict=True):
                np.testing.assert_array_equal(np.asarray(old), np.asarray(new), strict=True)
            return REFUSED


class ModelMachine(_Machine):
    @initialize(kind=st.sampled_from(["maxwell", "lugre"]), channels=st.integers(1, 3),
                scheme=st.sampled_from(["implicit", "explicit"]))  # fmt: skip
    def build(self, kind: str, channels: int, scheme: Any) -> None:
        self.params = MAXWELL if kind == "maxwell" else LUGRE
        self.delta = np.array(self.params.get("Delta", []))
        self.model = lr.LeuvenModel(self.params, channels=channels, scheme=scheme)
        self.checkpoints = [self.model.state]

    def snapshot(self) -> tuple[Any, ...]:
        state = self.model.state
        return (state.z, state.zeta, state.last_position, state.has_last_position)

    @rule(v=scalar, dt=step_size, position=st.booleans())
    def step(self, v: Any, dt: Any, position: bool) -> None:
        method = self.model.step_position if position else self.model.step
        force = self.attempt(lambda: method(v, dt))
        assert force is REFUSED or np.isfinite(force)

    @rule(data=st.data(), dt=step_size, position=st.booleans())
    def step_channels(self, data: st.DataObject, dt: Any, position: bool) -> None:
        block = data.draw(signal(self.model.channels))
        values = block[:, 0] if isinstance(block, np.ndarray) and block.ndim == 2 else block
        method = self.model.step_channels_position if position else self.model.step_channels
        forces = self.attempt(lambda: method(values, dt))
        assert forces is REFUSED or np.isfinite(forces).all()

    @rule(data=st.data(), dt=step_size, position=st.booleans())
    def run(self, data: st.DataObject, dt: Any, position: bool) -> None:
        block = data.draw(signal(self.model.channels))
        if self.model.channels == 1 and isinstance(block, np.ndarray) and block.ndim == 2:
            block = block[0] if data.draw(st.booleans()) else block
        method = self.model.run_position if position else self.model.run
        forces = self.attempt(lambda: method(block, dt))
        assert forces is REFUSED or np.isfinite(forces).all()

    @rule()
    def checkpoint(self) -> None:
        self.checkpoints.append(self.model.state)

    @rule(index=st.integers(0, 10), kind=st.sampled_from(["same", "nan", "shape", "type"]))
    def set_state(self, index: int, kind: str) -> None:
        state = self.checkpoints[index % len(self.checkpoints)]
        z = state.z.copy()
        if kind == "nan":
            z[0] = np.nan
        elif kind == "shape":
            z = np.append(z, 0.0)
        new: Any = lr.ModelState(z, state.zeta, state.last_position, state.has_last_position)
        if kind == "type":
            new = (z, state.zeta)
        refused = self.attempt(lambda: self.model.set_state(new)) is REFUSED
        assert refused == (kind != "same")

    @rule()
    def reset(self) -> None:
        self.model.reset()
        assert not self.model.state.has_last_position.any()

    @invariant()
    def elements_within_deflection(self) -> None:
        state = self.model.state
        assert np.isfinite(state.z).all() and np.isfinite(state.zeta).all()
        within_deflection(state.z, state.zeta, self.delta)


class MassMachine(_Machine):
    @initialize(channels=st.integers(1, 2), stiffness=st.sampled_from([0.0, 100.0]))
    def build(self, channels: int, stiffness: float) -> None:
        self.delta = np.array(MAXWELL["Delta"])
        self.system = lr.MassSystem(MAXWELL, mass=0.5, stiffness=stiffness, channels=channels)
        self.checkpoints = [self.system.state]

    def snapshot(self) -> tuple[Any, ...]:
        state = self.system.state
        return (state.position, state.velocity, state.anchor, state.z, state.zeta)

    @rule(u=scalar, dt=step_size)
    def step(self, u: Any, dt: Any) -> None:
        if self.system.channels == 1:
            out = self.attempt(lambda: self.system.step(u, dt))
            assert out is REFUSED or np.isfinite(out).all()

    @rule(data=st.data(), dt=step_size)
    def run(self, data: st.DataObject, dt: Any) -> None:
        block = data.draw(signal(self.system.channels))
        out = self.attempt(lambda: self.system.run(block, dt))
        assert out is REFUSED or np.isfinite(out.friction).all()

    @rule(position=scalar, velocity=scalar)
    def place(self, position: Any, velocity: Any) -> None:
        self.attempt(lambda: self.system.place(position, velocity))

    @rule()
    def checkpoint(self) -> None:
        self.checkpoints.append(self.system.state)

    @rule(index=st.integers(0, 10), spoil=st.booleans())
    def set_state(self, index: int, spoil: bool) -> None:
        s = self.checkpoints[index % len(self.checkpoints)]
        position = np.where(spoil, np.inf, s.position)
        self.attempt(lambda: self.system.set_state(lr.MassState(position, s.velocity, s.anchor, s.z, s.zeta)))

    @invariant()
    def finite_and_within_deflection(self) -> None:
        for value in self.snapshot():
            assert np.isfinite(value).all()
        state = self.system.state
        within_deflection(state.z, state.zeta, self.delta)


class CompensatorMachine(_Machine):
    @initialize(mode=st.sampled_from(["feedforward", "observer"]), terms=st.booleans())
    def build(self, mode: Any, terms: bool) -> None:
        self.delta = np.array(MAXWELL["Delta"])
        if terms:
            # A level, a cogging force and a viscous coefficient of its own for v < 0.
            ripple = lr.Ripple(0.004, (0.05, 0.02), (0.0, 0.03))
            level = lr.PositionLevel(0.0, 0.01, (0.05, -0.02), (ripple,))
            force = lr.PositionForce(0.0, 0.01, (0.5, 0.1), (ripple,))
            params = dict(MAXWELL, sigma2_neg=0.9)
            self.compensator = lr.Compensator(params, DT, mode, level, force, x=0.001)
        else:
            self.compensator = lr.Compensator(MAXWELL, DT, mode)

    def snapshot(self) -> tuple[Any, ...]:
        z, zeta, last = self.compensator._state()
        position = self.compensator.position
        return (z, np.array(zeta), np.nan if last is None else last, self.compensator.output,
                np.nan if position is None else position)  # fmt: skip

    @rule(value=scalar)
    def step(self, value: Any) -> None:
        force = self.attempt(lambda: self.compensator.step(value))
        assert force is REFUSED or np.isfinite(force)

    @rule(v=scalar, x=scalar)
    def step_trajectory(self, v: Any, x: Any) -> None:
        force = self.attempt(lambda: self.compensator.step_trajectory(v, x))
        assert force is REFUSED or np.isfinite(force)

    @rule(x=scalar)
    def set_position(self, x: Any) -> None:
        self.attempt(lambda: self.compensator.set_position(x))

    @rule(change=st.sampled_from([{}, {"Fc": 0.9}, {"W": [0.6] * 4}, {"Fs": 0.1}, {"W": [1.0] * 3},
                                  {"sigma0": 1e5, "W": None, "Delta": None}, {"Vs": "x"}, {"sigma2_neg": 0.0},
                                  {"sigma2_neg": -1.0}, {"sigma2_neg": "x"}]))  # fmt: skip
    def set_params(self, change: dict[str, Any]) -> None:
        given = {key: value for key, value in {**MAXWELL, **change}.items() if value is not None}
        self.attempt(lambda: self.compensator.set_params(given))

    @rule()
    def reset(self) -> None:
        self.compensator.reset()
        assert self.compensator.output == 0.0

    @invariant()
    def finite_and_within_deflection(self) -> None:
        z, zeta, _ = self.compensator._state()
        assert np.isfinite(self.compensator.output) and np.isfinite(z)
        within_deflection(np.asarray(z), np.asarray(zeta), self.delta)


class OnlineMachine(_Machine):
    @initialize(forgetting=st.sampled_from([1.0, 0.99]))
    def build(self, forgetting: float) -> None:
        self.identifier = lr.OnlineIdentifier([1e-6, 4e-6], forgetting=forgetting)

    def snapshot(self) -> tuple[Any, ...]:
        i = self.identifier
        return (i.estimate, i.covariance, i.covariance_trace, i.covariance_resets)

    @rule(x=scalar, v=scalar, f=scalar)
    def update(self, x: Any, v: Any, f: Any) -> None:
        error = self.attempt(lambda: self.identifier.update(x, v, f))
        assert error is REFUSED or np.isfinite(error)

    @rule(data=st.data())
    def run(self, data: st.DataObject) -> None:
        x, v, f = (data.draw(signal(1)) for _ in range(3))
        flat = [
            block[0] if isinstance(block, np.ndarray) and block.ndim == 2 else block for block in (x, v, f)
        ]
        self.attempt(lambda: self.identifier.run(*flat))

    @rule(x=scalar, v=scalar)
    def predict(self, x: Any, v: Any) -> None:
        before = self.snapshot()
        self.attempt(lambda: self.identifier.predict(x, v))
        for old, new in zip(before, self.snapshot(), strict=True):
            np.testing.assert_array_equal(old, new)  # predicting changes nothing

    @rule()
    def reset(self) -> None:
        self.identifier.reset()

    @invariant()
    def finite(self) -> None:
        assert np.isfinite(self.identifier.estimate).all()
        assert np.isfinite(self.identifier.covariance).all()


TestModelMachine = ModelMachine.TestCase
TestMassMachine = MassMachine.TestCase
TestCompensatorMachine = CompensatorMachine.TestCase
TestOnlineMachine = OnlineMachine.TestCase
TestModelMachine.settings = TestMassMachine.settings = FUZZ
TestCompensatorMachine.settings = TestOnlineMachine.settings = FUZZ
