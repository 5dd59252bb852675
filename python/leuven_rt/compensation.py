"""Friction compensation for a control loop: :class:`Compensator`, stepped sample by sample.

Each sample, ``step`` takes the desired velocity (``mode="feedforward"``) or the measured
position (``mode="observer"``) and returns the friction force to add to the command. The model
is the Rust core's (gms-core ``Compensator``), stepped implicitly at the fixed ``dt`` given at
construction, with bounded work per step (at most 2N + 1 evaluations of the hysteresis force,
and with a level one sincos per ripple).
``set_params`` swaps parameters between samples without a jump in the output: the hysteresis
force carries over (see crates/gms-core/src/compensator.rs).

With a position-dependent ``level`` (:class:`~leuven_rt.level.PositionLevel`), the output is
``level.factor(x)·(F − sigma2·v) + sigma2·v``. In observer mode x is the input; in feedforward
mode the compensator integrates the desired velocity, x ← x + v·dt, from the position given to
``set_position`` (0 until then), so a feedforward compensator with a level needs the axis's
start position (docs/model.md#position-dependent-level).
"""

from __future__ import annotations

from typing import cast

from . import _core
from ._checks import as_step
from ._typing import Mode
from .errors import InputError, shown
from .level import PositionLevel, core_level
from .params import Params, ParamsLike, as_params, core_params

MODES: tuple[Mode, ...] = ("feedforward", "observer")


class Compensator(_core.CompensatorEngine):
    """One axis of friction compensation at the fixed sample time ``dt`` [s].

    ``step(input) -> float``: the force for this sample (the fast path for a Python loop; a
    non-finite input raises :class:`InputError` and leaves state and ``output`` unchanged).
    ``set_params(params)``: new parameters of the same kind and number of elements.
    ``reset()``: back to rest. ``output``: the last force returned. ``level``: the
    position-dependent level or None; ``set_position(x)`` and ``position``: the position that
    feedforward mode integrates the desired velocity from (see the module documentation).

    A compensator's calls hold the GIL, so threads take turns; should two ever overlap (a
    free-threaded Python), the second raises :class:`~leuven_rt.errors.ConcurrentUseError`.
    """

    _params: Params
    _level: PositionLevel | None

    def __new__(
        cls,
        params: ParamsLike,
        dt: float,
        mode: Mode = "feedforward",
        level: PositionLevel | None = None,
    ) -> Compensator:
        if mode not in MODES:
            raise InputError(
                f"`mode` must be 'feedforward' or 'observer', got {shown(mode)!r}",
                kind="invalid_choice",
                field="mode",
                value=mode,
                expected=MODES,
            )
        given = as_params(params)
        validated_level = None if level is None else core_level(level)
        # The engine gets the set and the level validated when they were built, and does not
        # check them again; gms-core checks the value of dt.
        engine = super().__new__(
            cls, core_params(given), as_step(dt), cast("Mode", str(mode)), validated_level
        )
        engine._params = given
        engine._level = level
        return engine

    # Narrower than the engine's on purpose: a Params or a mapping of its keys.
    def set_params(self, params: ParamsLike) -> None:  # type: ignore[override]
        """Swaps in new parameters between two samples; the hysteresis force carries over."""
        given = as_params(params)
        super().set_params(core_params(given))
        self._params = given

    @property
    def params(self) -> Params:
        """The parameters in use."""
        return self._params

    @property
    def level(self) -> PositionLevel | None:
        """The position-dependent level, or None."""
        return self._level

    def __repr__(self) -> str:
        return f"Compensator(mode={self.mode!r}, dt={self.dt!r}, elements={self.elements})"
