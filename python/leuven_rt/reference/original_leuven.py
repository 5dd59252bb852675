"""The original Leuven model (Swevers et al. 2000, the paper's section II), for comparison only.

Its hysteresis force is Fh = Fb + Fd(z): Fb is the value of Fh where the current transition curve
began, Fd a point-symmetric, strictly increasing transition curve of the curve-local deflection
z, and two stacks remember the past extrema (maxima in descending order, minima in ascending
order). The rules, as the paper states them:

- velocity reversal: the current Fh is pushed on the stack of maxima (if the motion was upward)
  or minima, and becomes the new Fb; z and Fd(z) restart at 0;
- closing an internal loop (wiping out): when Fh comes back to the extremum where the loop began,
  that extremum and the one that started the current curve are popped; Fb becomes the top of
  the stack the current curve started from, and z is recalculated so that Fb + Fd(z) equals the
  former Fh;
- on a transition curve, the state equation (2) gives dz/dt = v·(1 − sgn(r)·|r|ⁿ),
  r = Fd(z)/(s(v) − Fb).

Before the first reversal Fh runs on the initial (virgin) curve V(z) = Fd(2z)/2, and a curve that
comes back past the mirror image of the first extremum re-enters it (the "extra implementation"
the paper mentions). With Fd(z) = 2·V(z/2) these are Masing's rules, which a Maxwell-slip bank
obeys exactly: :class:`MasingMaxwell` is the stack model of the same hysteresis as a given bank.

The stacks have a fixed depth; pushing onto a full stack raises :class:`StackOverflowError`
naming the sample and the depth. The paper's second modification (Maxwell slip) removes that
failure; the first (the state equation's argument Fh/s(v)) removes the force jump at loop closure
that the recalculation of z and Fb causes here.

Steps follow the contract of :mod:`leuven_rt.reference`: velocity held over the step, backward
Euler on z, output Ff = Fh(z⁺) + σ1·(z⁺ − z)/dt + σ2·v; reversals are applied at the start of a
step, loop closures at its end. :class:`OriginalLeuvenMass` puts the model under the mass of
:mod:`leuven_rt.reference.mechanics`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from typing import Any, Protocol, cast

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from .._checks import as_signal, check_dt, require_finite
from .._typing import FloatArray
from ..errors import InputError, ParameterError, StackOverflowError, shown
from ..params import ParamsLike, as_params
from .leuven import phi, stribeck_level, viscous_coefficient
from .mechanics import implicit_mass_step

__all__ = [
    "MasingMaxwell",
    "OriginalLeuven",
    "OriginalLeuvenMass",
    "StackHysteresis",
    "StackOverflowError",
    "TanhCurve",
    "TransitionCurve",
]


class TransitionCurve(Protocol):
    """Fd: odd, strictly increasing on (−limit, limit), with its inverse."""

    @property
    def limit(self) -> float: ...  # read-only: a property or a plain attribute both fit

    def __call__(self, z: float) -> float: ...

    def inverse(self, force: float) -> float: ...


@dataclass(frozen=True)
class TanhCurve:
    """A smooth transition curve: virgin V(z) = F_max·tanh(z/z_c), Fd(z) = 2·V(z/2)."""

    F_max: float
    z_c: float

    def __post_init__(self) -> None:
        for name in ("F_max", "z_c"):
            value = getattr(self, name)
            # numbers.Real declares no typed comparisons: compared as a float for the checker only.
            if not (isinstance(value, numbers.Real) and math.isfinite(value) and cast(float, value) > 0):
                raise ParameterError(
                    f"`{name}` must be finite and > 0, got {shown(value)!r}",
                    kind="not_positive",
                    field=name,
                    value=value,
                )

    @property
    def limit(self) -> float:
        return 2.0 * self.F_max

    def __call__(self, z: float) -> float:
        return 2.0 * self.F_max * math.tanh(z / (2.0 * self.z_c))

    def inverse(self, force: float) -> float:
        return 2.0 * self.z_c * math.atanh(_inside(force, self.limit))

    def virgin(self, z: float) -> float:
        return self(2.0 * z) / 2.0


def _inside(force: float, limit: float) -> float:
    """force/limit, which must lie in (−1, 1) for the curve to be inverted."""
    ratio = force / limit
    if not -1.0 < ratio < 1.0:
        raise ValueError(f"the transition curve cannot reach {force} (its range is ±{limit})")
    return ratio


class MasingMaxwell:
    """Fd(z) = 2·V(z/2) for the virgin curve V(z) = Σ Wᵢ·clip(z/Δᵢ, −1, 1) of a Maxwell-slip bank:
    the stack model of exactly the bank's hysteresis."""

    def __init__(self, W: ArrayLike, Delta: ArrayLike) -> None:
        self.W = np.asarray(W, dtype=np.float64)
        self.Delta = np.asarray(Delta, dtype=np.float64)
        if self.W.shape != self.Delta.shape or self.W.ndim != 1 or self.W.size == 0:
            raise ParameterError(
                f"`W` and `Delta` must be 1-D of the same length, got {self.W.shape} and {self.Delta.shape}",
                kind="shape",
                field="Delta",
                expected=self.W.shape,
                got=self.Delta.shape,
            )
        if not (np.all(self.W > 0) and np.all(self.Delta > 0) and np.all(np.isfinite(self.W * self.Delta))):
            raise ParameterError("`W` and `Delta` must be finite and > 0", kind="element", field="W")
        # Fd is piecewise linear with knots at ±2Δᵢ: tabulate it for the inverse.
        knots = np.unique(np.concatenate(([0.0], 2.0 * self.Delta)))
        self._knots = np.concatenate((-knots[::-1], knots[1:]))
        self._values = np.array([self(z) for z in self._knots])
        self.limit = float(2.0 * self.W.sum())

    def __call__(self, z: float) -> float:
        return float(2.0 * np.sum(self.W * np.clip(z / (2.0 * self.Delta), -1.0, 1.0)))

    def inverse(self, force: float) -> float:
        if not abs(force) <= self.limit:
            raise ValueError(f"the transition curve cannot reach {force} (its range is ±{self.limit})")
        # Fd is flat beyond ±2·max(Δ); interp returns the first point that reaches the value.
        return float(np.interp(force, self._values, self._knots))

    def virgin(self, z: float) -> float:
        return self(2.0 * z) / 2.0


@dataclass
class _Stacks:
    """The two stacks of extrema, of fixed depth, and the current transition curve."""

    depth: int
    maxima: list[float] = field(default_factory=list)
    minima: list[float] = field(default_factory=list)
    initial: bool = True
    """On the initial (virgin) curve, where z is the total deflection and Fb = 0."""
    Fb: float = 0.0
    direction: int = 0
    """+1 or −1: the direction of motion on the current curve; 0 before the first motion."""

    def push(self, force: float, sample: int) -> None:
        """A reversal at Fh = ``force``: the end of an upward curve is a maximum."""
        stack, name = (self.maxima, "maxima") if self.direction > 0 else (self.minima, "minima")
        if len(stack) >= self.depth:
            raise StackOverflowError(name, sample, self.depth)
        stack.append(force)
        self.Fb, self.initial = force, False
        self.direction = -self.direction

    def threshold(self) -> float | None:
        """The Fh at which the current curve closes a loop, or None on the initial curve."""
        if self.initial:
            return None
        # An upward curve started at the top minimum; it closes at the maximum before it, or at
        # the mirror of that minimum when the history began with it (the initial curve's bound).
        ahead, start = (self.maxima, self.minima) if self.direction > 0 else (self.minima, self.maxima)
        return ahead[-1] if ahead else -start[-1]

    def closes(self, force: float) -> bool:
        limit = self.threshold()
        return limit is not None and (force - limit) * self.direction >= 0.0

    def pop(self) -> None:
        """Wipes out the closed loop: the curve continues the one that was interrupted."""
        ahead, start = (self.maxima, self.minima) if self.direction > 0 else (self.minima, self.maxima)
        start.pop()
        if ahead:
            ahead.pop()
        if start:
            self.Fb = start[-1]
        else:
            self.Fb, self.initial = 0.0, True

    @property
    def size(self) -> int:
        return len(self.maxima) + len(self.minima)


class StackHysteresis:
    """The stack implementation of Fh as a static map of the total deflection (Figs. 4 and 5).

    ``update(Z)`` moves the input to ``Z`` and returns Fh. A loop that closes inside a move
    continues on the outer curve for the rest of the move.
    """

    def __init__(self, curve: TransitionCurve, depth: int) -> None:
        self.curve = curve
        self.stacks = _Stacks(_depth(depth))
        self.position = 0.0
        self.z = 0.0
        self.samples = 0

    @property
    def force(self) -> float:
        return self._force(self.z)

    def _force(self, z: float) -> float:
        if self.stacks.initial:
            return self.curve(2.0 * z) / 2.0
        return self.stacks.Fb + self.curve(z)

    def _local(self, force: float) -> float:
        """The z at which the current curve has Fh = ``force``."""
        if self.stacks.initial:
            return self.curve.inverse(2.0 * force) / 2.0
        return self.curve.inverse(force - self.stacks.Fb)

    def update(self, position: float) -> float:
        move = position - self.position
        stacks = self.stacks
        if move != 0.0:
            sign = 1 if move > 0 else -1
            if stacks.direction == 0:
                stacks.direction = sign
            elif sign != stacks.direction:
                stacks.push(self.force, self.samples)
                self.z = 0.0
            remaining = move
            while True:
                limit = stacks.threshold()
                if limit is not None:
                    reach = self._local(limit) - self.z  # the move that closes the loop
                    if abs(remaining) >= abs(reach):
                        stacks.pop()
                        self.z = self._local(limit)
                        remaining -= reach
                        continue
                self.z += remaining
                break
            self.position = position
        self.samples += 1
        return self.force

    def run(self, positions: ArrayLike) -> FloatArray:
        return np.array([self.update(p) for p in np.asarray(positions, dtype=np.float64).tolist()])


def _depth(depth: Any) -> int:
    if isinstance(depth, bool) or not isinstance(depth, numbers.Integral) or depth < 1:
        integer = isinstance(depth, numbers.Integral) and not isinstance(depth, bool)
        raise ParameterError(
            f"`depth` (stack depth) must be an integer >= 1, got {shown(depth)!r}",
            kind="out_of_range" if integer else "not_integer",
            field="depth",
            value=depth,
            bound=1 if integer else None,
        )
    return int(depth)


@dataclass(frozen=True)
class OriginalSample:
    """One step: friction force over the step, and the memory size at its end."""

    friction: float
    hysteresis: float
    stack_size: int


class OriginalLeuven:
    """The original Leuven model with friction parameters ``params`` (Fc, Fs, Vs, delta, n,
    sigma1, sigma2 are used; Fc_neg/Fs_neg/sigma2_neg too), transition curve ``curve`` (default: the
    Masing curve of the params' Maxwell-slip bank) and stacks of ``depth`` extrema each."""

    def __init__(self, params: ParamsLike, depth: int, curve: TransitionCurve | None = None) -> None:
        self.params = as_params(params)
        if curve is None:
            if self.params.W is None or self.params.Delta is None:
                raise ParameterError(
                    "give a `curve`, or params with Maxwell-slip `W` and `Delta`",
                    kind="missing_key",
                    field="curve",
                )
            curve = MasingMaxwell(self.params.W, self.params.Delta)
        self.hysteresis = StackHysteresis(curve, depth)

    @property
    def stacks(self) -> _Stacks:
        return self.hysteresis.stacks

    @property
    def z(self) -> float:
        return self.hysteresis.z

    def _reverse_if(self, w: float) -> None:
        """Applies the reversal rule for a step with held velocity ``w``."""
        stacks = self.stacks
        sign = (w > 0) - (w < 0)
        if sign == 0:
            return
        if stacks.direction == 0:
            stacks.direction = sign
        elif sign != stacks.direction:
            stacks.push(self.hysteresis.force, self.hysteresis.samples)
            self.hysteresis.z = 0.0

    def _denominator(self, w: float) -> float:
        """s(v) − Fb of eq. (2) on the current curve."""
        return math.copysign(stribeck_level(self.params, w), w) - self.stacks.Fb

    def rate(self, y: float, w: float) -> float:
        """dz/dt of eq. (2) at curve-local deflection ``y``, velocity ``w``, on the current curve."""
        if w == 0.0:
            return 0.0
        numerator, denominator = self.hysteresis._force(y) - self.stacks.Fb, self._denominator(w)
        # s(v) = Fb only where eq. (2) is undefined (checked on the solution); the limit keeps
        # the root search going through it.
        r = numerator / denominator if denominator != 0.0 else math.copysign(math.inf, numerator)
        return w * (1.0 - phi(r, self.params.n))

    def _check_defined(self, w: float) -> None:
        """Eq. (2) needs s(v) − Fb to have the sign of v: a curve that started above the sliding
        level s(v) is outside the model."""
        denominator = self._denominator(w) if w != 0.0 else math.nan
        if w != 0.0 and not (denominator != 0.0 and (denominator > 0) == (w > 0)):
            raise ValueError(
                f"the original Leuven model is undefined at sample {self.hysteresis.samples}: "
                f"s(v) - Fb = {denominator} does not have the sign of v = {w}"
            )

    def _commit(self, y: float) -> float:
        """Moves to ``y`` on the current curve, then applies the wiping-out rule; returns Fh."""
        hysteresis, stacks = self.hysteresis, self.stacks
        hysteresis.z = y
        force = hysteresis.force
        # The paper's rule: Fb becomes the outer curve's, and z is recalculated to keep Fh.
        while stacks.closes(force):
            stacks.pop()
            hysteresis.z = hysteresis._local(force)
        hysteresis.samples += 1
        return force

    def step(self, v: float, dt: float) -> OriginalSample:
        """One step with velocity ``v`` held over ``dt`` (backward Euler on z)."""
        dt = check_dt(dt)
        self._reverse_if(v)
        self._check_defined(v)
        z = self.z
        r0 = 0.0 if v == 0.0 else -dt * self.rate(z, v)
        if z - r0 == z:  # no representable move: z is the root to rounding (includes v = 0)
            y = z
        else:

            def residual(y: float) -> float:
                return (y - z) - dt * self.rate(y, v)

            lo, hi = sorted((z, z - r0))
            r_lo, r_hi = residual(lo), residual(hi)
            if r_lo * r_hi > 0.0:
                # R has slope ≥ 1, so z and z − R(z) bracket the root in exact arithmetic; when
                # they are a few ulps apart, rounding in R can hide it: either end is the root.
                y = lo if abs(r_lo) <= abs(r_hi) else hi
            else:
                y = float(brentq(residual, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps))
        force_h = self.hysteresis._force(y)
        viscous = viscous_coefficient(self.params, v) * v
        friction = force_h + self.params.sigma1 * (y - z) / dt + viscous
        force_h = self._commit(y)
        return OriginalSample(friction, force_h, self.stacks.size)


class OriginalLeuvenMass:
    """A mass m on the original Leuven model, with a spring k to a far end dragged at
    ``drive_speed``: the same discrete mechanics as :mod:`leuven_rt.reference.mechanics`."""

    def __init__(
        self,
        model: OriginalLeuven,
        mass: float,
        stiffness: float = 0.0,
        drive_speed: float = 0.0,
        position: float = 0.0,
        velocity: float = 0.0,
    ) -> None:
        for name, value, low in (("mass", mass, "> 0"), ("stiffness", stiffness, ">= 0")):
            ok = math.isfinite(value) and (value > 0 if low == "> 0" else value >= 0)
            if not ok:
                raise ParameterError(
                    f"`{name}` must be finite and {low}, got {value}",
                    kind="not_positive" if low == "> 0" else "negative",
                    field=name,
                    value=value,
                )
        if not math.isfinite(drive_speed):
            raise ParameterError(
                f"`drive_speed` must be finite, got {drive_speed}",
                kind="not_finite_value",
                field="drive_speed",
                value=drive_speed,
            )
        self.model = model
        self.mass, self.stiffness, self.drive_speed = float(mass), float(stiffness), float(drive_speed)
        self.x, self.v, self.anchor = float(position), float(velocity), 0.0

    def step(self, u: float, dt: float) -> OriginalSample:
        """One implicit step with applied force ``u``; returns the friction sample."""
        if not math.isfinite(u):
            raise InputError(f"`u` must be finite, got {u}", kind="not_finite", field="u", value=u, sample=0)
        dt = check_dt(dt)
        model, p = self.model, self.model.params
        m, k = self.mass, self.stiffness
        anchor = self.anchor + dt * self.drive_speed
        drive = u + k * (anchor - self.x - dt * self.v)
        net, stiffness_s = drive - p.sigma2 * self.v, m / dt + k * dt + p.sigma2
        backward = (drive - p.sigma2_negative * self.v, m / dt + k * dt + p.sigma2_negative)
        # The curve depends on the sign of the new velocity (a reversal starts a new one): solve
        # on the current curve, and on the reversed one if the root says the motion reverses.
        saved = _snapshot(model)
        y, w = implicit_mass_step(model.hysteresis._force, model.rate, model.z, self.v, dt, net,
                                  stiffness_s, p.sigma1, backward)  # fmt: skip
        direction = model.stacks.direction
        if direction != 0 and w * direction < 0:
            model._reverse_if(w)
            y, w = implicit_mass_step(model.hysteresis._force, model.rate, model.z, self.v, dt, net,
                                      stiffness_s, p.sigma1, backward)  # fmt: skip
            if w * direction > 0:
                _restore(model, saved)
                raise ValueError(f"no consistent direction for the mass step at sample {saved[-1]}")
        model._reverse_if(w)  # the first motion from rest sets the direction
        try:
            model._check_defined(w)
        except ValueError:
            _restore(model, saved)
            raise
        z = model.z
        force_h = model.hysteresis._force(y)
        friction = force_h + p.sigma1 * (y - z) / dt + viscous_coefficient(p, w) * w
        force_h = model._commit(y)
        self.x, self.v, self.anchor = self.x + dt * w, w, anchor
        return OriginalSample(friction, force_h, model.stacks.size)


def _snapshot(model: OriginalLeuven) -> tuple[Any, ...]:
    s = model.stacks
    return (list(s.maxima), list(s.minima), s.initial, s.Fb, s.direction, model.hysteresis.z,
            model.hysteresis.samples)  # fmt: skip


def _restore(model: OriginalLeuven, saved: tuple[Any, ...]) -> None:
    s = model.stacks
    s.maxima, s.minima, s.initial, s.Fb, s.direction, model.hysteresis.z, model.hysteresis.samples = saved


def run_velocity(model: OriginalLeuven, v: ArrayLike, dt: float) -> FloatArray:
    """Friction force of ``model`` for the velocity signal ``v`` (T,)."""
    array, one_dimensional = as_signal(v, "v")
    if not one_dimensional:
        raise InputError(
            f"`v` must have shape (T,), got shape {np.shape(v)}",
            kind="shape",
            field="v",
            expected="(T,)",
            got=np.shape(v),
        )
    require_finite(array, "v", one_dimensional)
    return np.array([model.step(value, dt).friction for value in array[0].tolist()])
