"""Stateful channels of one model, stepped sample by sample, with checkpoints."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _core
from ._checks import (
    as_channel_signal,
    as_channels,
    as_step,
    check_channels,
    check_scheme,
    real_array,
)
from ._typing import FloatArray, Scheme
from .errors import InputError, shown
from .params import Params, ParamsLike, as_params, core_params


@dataclass(frozen=True, eq=False)
class ModelState:
    """A checkpoint of every channel: copies, safe to keep while the model runs on."""

    z: FloatArray
    """Deflection z of each channel, shape (B,)."""
    zeta: FloatArray
    """Position ζ of each Maxwell-slip element, shape (B, N); (B, 0) for linear hysteresis."""
    last_position: FloatArray
    """Position of the previous position-input step, shape (B,); meaningful where has_last_position."""
    has_last_position: NDArray[np.bool_]
    """Whether a channel has seen a position-input step since it was relaxed, shape (B,)."""


@dataclass(frozen=True, eq=False)
class Trace:
    """A run of one channel over positions, with the state the elements are driven by."""

    force: FloatArray
    """Friction force after every sample [N]."""
    z: FloatArray
    """Deflection z of the state equation after every sample [m]."""


class LeuvenModel(_core.Engine):
    """``channels`` channels of the model with parameters ``params``, stepped in Rust.

    ``step(v, dt) -> float`` and ``step_position(x, dt) -> float`` advance a single-channel model
    by one sample (the fast path for control loops); ``step_channels`` advances B channels at
    once; ``run`` continues from the current state over a whole signal. ``state`` and
    ``set_state`` take and restore checkpoints; ``reset`` relaxes every channel.

    A model is one object of state: calling it from a second thread while one is inside ``run``
    (which releases the GIL) raises :class:`~leuven_rt.errors.ConcurrentUseError` and changes
    nothing. ``step``, ``step_position`` and ``reset`` are the engine's own (Rust, no Python frame
    in between).
    """

    _params: Params
    _shape: tuple[int, int, Scheme]

    def __new__(cls, params: ParamsLike, channels: int = 1, scheme: Scheme = "implicit") -> LeuvenModel:
        given = as_params(params)
        # The engine gets the set validated when `given` was built, and does not check it again.
        engine = super().__new__(cls, core_params(given), check_channels(channels), check_scheme(scheme))
        engine._params = given
        # Fixed for the model's life, and readable while another thread runs it.
        engine._shape = (super(LeuvenModel, engine).channels, super(LeuvenModel, engine).elements,
                         super(LeuvenModel, engine).scheme)  # fmt: skip
        return engine

    @property
    def channels(self) -> int:
        """Number of channels B."""
        return self._shape[0]

    @property
    def elements(self) -> int:
        """Number of Maxwell-slip elements N (0 for linear hysteresis)."""
        return self._shape[1]

    @property
    def scheme(self) -> Scheme:
        """The integration scheme, 'implicit' or 'explicit'."""
        return self._shape[2]

    @property
    def params(self) -> Params:
        """The parameters this model was built from."""
        return self._params

    def __repr__(self) -> str:
        return f"LeuvenModel(channels={self.channels}, elements={self.elements}, scheme={self.scheme!r})"

    def step_channels(self, v: ArrayLike, dt: float) -> FloatArray:
        """One step of every channel with velocities ``v`` of shape (B,); returns (B,) forces."""
        return self._step_channels(as_channels(v, "v", self.channels), as_step(dt), False)

    def step_channels_position(self, x: ArrayLike, dt: float) -> FloatArray:
        """One step of every channel with positions ``x`` of shape (B,); returns (B,) forces."""
        return self._step_channels(as_channels(x, "x", self.channels), as_step(dt), True)

    def run(self, v: ArrayLike, dt: float) -> FloatArray:
        """Continues every channel over velocities ``v``: (T,) for one channel or (B, T)."""
        return self._run_signal(v, "v", dt)

    def run_position(self, x: ArrayLike, dt: float) -> FloatArray:
        """Continues every channel over positions ``x``: (T,) for one channel or (B, T)."""
        return self._run_signal(x, "x", dt)

    def trace_position(self, x: ArrayLike, dt: float) -> Trace:
        """Continues the single channel over positions ``x`` of shape (T,), recording the
        deflection z after every sample as well as the force."""
        if self.channels != 1:
            raise InputError(
                f"`trace_position` runs one channel, this model has {self.channels}",
                kind="channel_mismatch",
                expected=1,
                got=self.channels,
            )
        array, one_dimensional = as_channel_signal(x, "x", 1)
        if not one_dimensional:
            raise InputError(
                f"`x` must have shape (T,) for `trace_position`, got {np.shape(x)}",
                kind="shape",
                field="x",
                expected="(T,)",
                got=np.shape(x),
            )
        force, z = self._run_position_deflection(np.ascontiguousarray(array[0]), as_step(dt))
        return Trace(force, z)

    def _run_signal(self, signal: ArrayLike, name: str, dt: float) -> FloatArray:
        array, one_dimensional = as_channel_signal(signal, name, self.channels)
        out = np.empty_like(array)
        self._run(array, as_step(dt), name == "x", out)
        return out[0] if one_dimensional else out

    @property
    def state(self) -> ModelState:
        """A checkpoint of every channel."""
        return ModelState(*self._get_state())

    def set_state(self, state: ModelState) -> None:
        """Restores a checkpoint taken from a model with the same channels and elements."""
        if not isinstance(state, ModelState):
            raise InputError(
                f"`state` must be a ModelState, got {type(state).__name__}",
                kind="wrong_type",
                field="state",
                value=state,
            )
        b, n = self.channels, self.elements
        expected = {"z": (b,), "zeta": (b, n), "last_position": (b,), "has_last_position": (b,)}
        arrays: dict[str, Any] = {}
        for name, shape in expected.items():
            value = getattr(state, name)
            boolean = name == "has_last_position"
            array: NDArray[Any]
            try:
                if boolean:
                    array = np.asarray(value, dtype=np.bool_)
                else:  # numbers only: text or booleans are not positions
                    array = np.asarray(real_array(value, f"state.{name}"), dtype=np.float64)
            except (TypeError, ValueError) as error:
                if isinstance(error, InputError):
                    raise
                raise InputError(
                    f"`state.{name}` must hold {'booleans' if boolean else 'real numbers'}, "
                    f"got {shown(value)!r}",
                    kind="wrong_type" if boolean else "not_real",
                    field=f"state.{name}",
                    value=value,
                ) from None
            if boolean and np.asarray(value).dtype != np.bool_:
                raise InputError(
                    f"`state.{name}` must be a boolean array, got dtype {np.asarray(value).dtype}",
                    kind="wrong_type",
                    field=f"state.{name}",
                    value=value,
                )
            if array.shape != shape:
                raise InputError(
                    f"`state.{name}` must have shape {shape}, got shape {array.shape}",
                    kind="shape",
                    field=f"state.{name}",
                    expected=shape,
                    got=array.shape,
                )
            if not boolean and not np.isfinite(array).all():
                raise InputError(f"`state.{name}` must be finite", kind="not_finite", field=f"state.{name}")
            arrays[name] = np.ascontiguousarray(array)
        self._set_state(arrays["z"], arrays["zeta"], arrays["last_position"], arrays["has_last_position"])
