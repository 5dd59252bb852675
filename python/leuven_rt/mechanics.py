"""A simulated machine: a mass on the friction model, driven by a force, stepped in Rust.

m·ẍ = u(t) − Ff + k·(a(t) − x): a free mass (``stiffness=0``), a spring to ground
(``drive_speed=0``) or the stick-slip rig, whose spring's far end a(t) = drive_speed·t is dragged
at constant speed. How the step integrates the mechanics and why it is stable at any dt is
written in the module docs of ``crates/gms-core/src/mechanics``; :mod:`leuven_rt.reference.mechanics`
is the same discrete step in numpy.

- :class:`MassSystem`: stateful channels. ``step(u, dt) -> (friction, position, velocity)`` is the
  closed-loop path (a controller reads position and velocity and computes the next u);
  ``run(u, dt)`` continues over a whole signal; ``state``/``set_state`` checkpoint.
- :func:`simulate_mass`: a whole force signal, (T,) or (B, T), from a given start.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import _core
from ._checks import (
    as_channel_signal,
    as_channels,
    as_signal,
    as_step,
    check_channels,
    check_scheme,
    real_array,
    require_finite,
)
from ._typing import FloatArray, Scheme
from .errors import InputError, shown
from .params import Params, ParamsLike, as_params, core_params

__all__ = ["MassState", "MassSystem", "MassTrajectory", "simulate_mass"]


@dataclass(frozen=True)
class MassTrajectory:
    """Friction force over each step, position and velocity at its end; each (T,) or (B, T)."""

    friction: FloatArray
    position: FloatArray
    velocity: FloatArray


@dataclass(frozen=True, eq=False)
class MassState:
    """A checkpoint of every channel (copies)."""

    position: FloatArray
    """x of each channel [m], shape (B,)."""
    velocity: FloatArray
    """v of each channel [m/s], shape (B,)."""
    anchor: FloatArray
    """Position of the spring's far end [m], shape (B,)."""
    z: FloatArray
    """Friction deflection z [m], shape (B,)."""
    zeta: FloatArray
    """Maxwell-slip element positions ζ, shape (B, N); (B, 0) for linear hysteresis."""


class MassSystem(_core.MassEngine):
    """``channels`` masses on the friction model ``params``, with optional (dragged) spring.

    ``mass`` > 0 [kg], ``stiffness`` ≥ 0 [N/m], ``drive_speed`` [m/s] (any sign), all finite:
    otherwise :class:`ParameterError`. Every channel starts at rest at x = 0 (see :meth:`place`).
    Calling it from a second thread while one is inside ``run`` (which releases the GIL) raises
    :class:`~leuven_rt.errors.ConcurrentUseError` and changes nothing.
    """

    _params: Params
    _fixed: tuple[float, float, float, int, int, Scheme]

    def __new__(
        cls,
        params: ParamsLike,
        mass: float,
        stiffness: float = 0.0,
        drive_speed: float = 0.0,
        channels: int = 1,
        scheme: Scheme = "implicit",
    ) -> MassSystem:
        given = as_params(params)
        # The engine gets the set validated when `given` was built, and does not check it again.
        engine = super().__new__(
            cls,
            core_params(given),
            mass,
            stiffness,
            drive_speed,
            check_channels(channels),
            check_scheme(scheme),
        )
        engine._params = given
        # Fixed for the system's life, and readable while another thread runs it.
        core: Any = super(MassSystem, engine)
        engine._fixed = (core.mass, core.stiffness, core.drive_speed, core.channels, core.elements,
                         core.scheme)  # fmt: skip
        return engine

    @property
    def mass(self) -> float:
        """The mass m [kg]."""
        return self._fixed[0]

    @property
    def stiffness(self) -> float:
        """The spring's stiffness k [N/m]."""
        return self._fixed[1]

    @property
    def drive_speed(self) -> float:
        """The speed of the spring's far end [m/s]."""
        return self._fixed[2]

    @property
    def channels(self) -> int:
        """Number of channels B."""
        return self._fixed[3]

    @property
    def elements(self) -> int:
        """Number of Maxwell-slip elements N (0 for linear hysteresis)."""
        return self._fixed[4]

    @property
    def scheme(self) -> Scheme:
        """The integration scheme, 'implicit' or 'explicit'."""
        return self._fixed[5]

    @property
    def params(self) -> Params:
        """The parameters this system was built from."""
        return self._params

    def __repr__(self) -> str:
        return (
            f"MassSystem(mass={self.mass}, stiffness={self.stiffness}, drive_speed={self.drive_speed}, "
            f"channels={self.channels}, elements={self.elements}, scheme={self.scheme!r})"
        )

    def place(self, position: ArrayLike = 0.0, velocity: ArrayLike = 0.0) -> None:
        """Restarts every channel at ``position``/``velocity`` (scalars or (B,)), with relaxed
        friction and the spring's far end at 0."""
        b = self.channels
        arrays = []
        for name, value in (("position", position), ("velocity", velocity)):
            try:
                array = np.broadcast_to(real_array(value, name), (b,))
            except ValueError as error:
                if isinstance(error, InputError):
                    raise
                raise InputError(
                    f"`{name}` must be a real number or have shape ({b},), got {shown(value)!r}",
                    kind="shape",
                    field=name,
                    expected=(b,),
                    got=np.shape(value),
                ) from None
            row = as_channels(array, name, b)
            require_finite(row, name, True)  # _place takes the values as they are
            arrays.append(np.ascontiguousarray(row))
        self._place(*arrays)

    def step_channels(self, u: ArrayLike, dt: float) -> MassTrajectory:
        """One step of every channel with forces ``u`` of shape (B,); arrays of shape (B,)."""
        array = as_channels(u, "u", self.channels)
        out = self._run(np.ascontiguousarray(array[:, None]), as_step(dt))
        return MassTrajectory(out[0, :, 0], out[1, :, 0], out[2, :, 0])

    def run(self, u: ArrayLike, dt: float) -> MassTrajectory:
        """Continues every channel over forces ``u``: (T,) for one channel or (B, T)."""
        array, one_dimensional = as_channel_signal(u, "u", self.channels)
        out = self._run(array, as_step(dt))
        if one_dimensional:
            return MassTrajectory(out[0, 0], out[1, 0], out[2, 0])
        return MassTrajectory(out[0], out[1], out[2])

    @property
    def state(self) -> MassState:
        """A checkpoint of every channel."""
        return MassState(*self._get_state())

    def set_state(self, state: MassState) -> None:
        """Restores a checkpoint taken from a system with the same channels and elements."""
        if not isinstance(state, MassState):
            raise InputError(
                f"`state` must be a MassState, got {type(state).__name__}",
                kind="wrong_type",
                field="state",
                value=state,
            )
        b, n = self.channels, self.elements
        arrays = []
        for name in ("position", "velocity", "anchor", "z", "zeta"):
            shape = (b, n) if name == "zeta" else (b,)
            array = np.asarray(real_array(getattr(state, name), f"state.{name}"), dtype=np.float64)
            if array.shape != shape:
                raise InputError(
                    f"`state.{name}` must have shape {shape}, got shape {array.shape}",
                    kind="shape",
                    field=f"state.{name}",
                    expected=shape,
                    got=array.shape,
                )
            if not np.isfinite(array).all():
                raise InputError(f"`state.{name}` must be finite", kind="not_finite", field=f"state.{name}")
            arrays.append(np.ascontiguousarray(array))
        self._set_state(*arrays)


def simulate_mass(
    params: ParamsLike,
    u: ArrayLike,
    dt: float,
    mass: float,
    stiffness: float = 0.0,
    drive_speed: float = 0.0,
    position: float = 0.0,
    velocity: float = 0.0,
    scheme: Scheme = "implicit",
) -> MassTrajectory:
    """The mass driven by applied force ``u`` [N], (T,) or (B, T) for B independent channels.

    Each channel starts at ``position``/``velocity`` with relaxed friction and the spring's far
    end at 0. Returns the friction force over each step and the position and velocity at its
    end, each with the shape of ``u``. Runs in Rust with the GIL released.
    """
    array, one_dimensional = as_signal(u, "u")
    system = MassSystem(params, mass, stiffness, drive_speed, array.shape[0], scheme)
    system.place(position, velocity)
    return system.run(array[0] if one_dimensional else array, dt)
