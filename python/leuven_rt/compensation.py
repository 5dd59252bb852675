"""Friction compensation for a control loop: :class:`Compensator`, stepped sample by sample.

Each sample, ``step`` takes the desired velocity (``mode="feedforward"``) or the measured
position (``mode="observer"``) and returns the friction force to add to the command. The model
is the Rust core's (gms-core ``Compensator``), stepped implicitly at the fixed ``dt`` given at
construction, with bounded work per step (at most 2N + 1 evaluations of the hysteresis force,
and with a level one sincos per ripple).
``set_params`` swaps parameters between samples without a jump in the output: the hysteresis
force carries over (see crates/gms-core/src/compensator.rs).

With a position-dependent ``level`` (:class:`~leuven_rt.level.PositionLevel`) and a
``position_force`` (:class:`~leuven_rt.level.PositionForce`), the output is
``level.factor(x)·(F − σ2(v)·v) + σ2(v)·v + position_force.force(x)``. In observer mode x is the
input. In feedforward mode ``step_trajectory(v, x)`` takes the desired position with the desired
velocity (a trajectory generator gives both), and ``step(v)`` integrates the desired velocity,
x ← x + v·dt, from the axis's start position ``x`` given at construction (or to
``set_position``): a feedforward compensator with a level or a position force and no start
position is refused, since its terms would be placed from x = 0, out of phase with the machine
(docs/model.md#position-dependent-level).

The model may be given as a model file (a :class:`~leuven_rt.ModelFile` or the path of one, as
``identify`` writes it): the compensator then runs the file's friction model with its level and
position force, exactly as ``predict`` runs the file (its ``friction`` column). The file's
measurement terms (offset, inertia) describe the force sensor, not the friction, and are not
added.
"""

from __future__ import annotations

from os import PathLike
from typing import cast

from . import _core
from ._checks import as_step
from ._typing import Mode
from .errors import InputError, shown
from .level import PositionForce, PositionLevel, core_level, core_position_force
from .modelfile import ModelFile
from .params import Params, ParamsLike, as_params, core_params

MODES: tuple[Mode, ...] = ("feedforward", "observer")


def _from_model_file(
    model: ModelFile | str | PathLike[str], level: PositionLevel | None, position_force: PositionForce | None
) -> tuple[Params, PositionLevel | None, PositionForce | None]:
    """The friction model, level and position force of a model file (or of the file at a path:
    read by the one reader, gms-file); the file holds its own terms, so none may be given too."""
    for name, given in (("level", level), ("position_force", position_force)):
        if given is not None:
            raise InputError(
                f"`{name}` must be None when the model is a model file (the file holds its own), "
                f"got a {type(given).__name__}",
                kind="not_applicable",
                field=name,
                value=given,
                expected=None,
            )
    file = model if isinstance(model, ModelFile) else ModelFile.load(model)
    return file.friction, file.level, file.position_force


class Compensator(_core.CompensatorEngine):
    """One axis of friction compensation at the fixed sample time ``dt`` [s].

    ``step(input) -> float``: the force for this sample (the fast path for a Python loop; a
    non-finite input raises :class:`InputError` and leaves state and ``output`` unchanged).
    ``set_params(params)``: new parameters of the same kind and number of elements.
    ``step_trajectory(v, x)``: the force for one sample of a planned trajectory, the velocity
    driving the model and the position placing the level and the position force.
    ``reset()``: back to rest. ``output``: the last force returned. ``level``,
    ``position_force``: the position-dependent terms or None; ``x`` (at construction),
    ``set_position(x)`` and ``position``: the axis's position, from which feedforward mode places
    them (see the module documentation; required in feedforward mode with a term, else
    :class:`InputError` naming ``x``).

    A compensator's calls hold the GIL, so threads take turns; should two ever overlap (a
    free-threaded Python), the second raises :class:`~leuven_rt.errors.ConcurrentUseError`.
    """

    _params: Params
    _level: PositionLevel | None
    _position_force: PositionForce | None

    def __new__(
        cls,
        params: ParamsLike | ModelFile | str | PathLike[str],
        dt: float,
        mode: Mode = "feedforward",
        level: PositionLevel | None = None,
        position_force: PositionForce | None = None,
        *,
        x: float | None = None,
    ) -> Compensator:
        if mode not in MODES:
            raise InputError(
                f"`mode` must be 'feedforward' or 'observer', got {shown(mode)!r}",
                kind="invalid_choice",
                field="mode",
                value=mode,
                expected=MODES,
            )
        if isinstance(params, (ModelFile, str, PathLike)):
            params, level, position_force = _from_model_file(params, level, position_force)
        given = as_params(params)
        validated_level = None if level is None else core_level(level)
        validated_force = None if position_force is None else core_position_force(position_force)
        # The engine gets the set and the terms validated when they were built, and does not
        # check them again; gms-core checks the values of dt and x, and that feedforward terms
        # have their start position.
        engine = super().__new__(
            cls,
            core_params(given),
            as_step(dt),
            cast("Mode", str(mode)),
            validated_level,
            validated_force,
            x,
        )
        engine._params = given
        engine._level = level
        engine._position_force = position_force
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

    @property
    def position_force(self) -> PositionForce | None:
        """The position force, or None."""
        return self._position_force

    def __repr__(self) -> str:
        return f"Compensator(mode={self.mode!r}, dt={self.dt!r}, elements={self.elements})"
