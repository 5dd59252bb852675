"""The force-driven mass of gms-core's ``MassSystem`` in plain numpy, written as the specification.

m·ẍ = u − Ff + k·(a − x), a(t) = drive_speed·t, with the friction of :mod:`leuven_rt.reference`.
Per sample k, with (x, v, a, z, ζ) at the start of the step and u held over it:

- ``implicit`` (backward Euler on x, v and z): the new velocity w and the new deflection y solve

      m·(w − v)/dt = u + k·(a⁺ − x − dt·w) − [Fh(y) + σ1·(y − z)/dt + σ2(w)·w],
      y − z = dt·f(y, w),  f(y, w) = w − |w|·φ(Fh(y)/g(w)),

  with Fh the trial from ζ at step start and σ2(w) = sigma2_neg for w < 0, sigma2 otherwise; then
  x⁺ = x + dt·w, v⁺ = w, and the output is the friction force Fₖ = Fh(y) + σ1·(y − z)/dt + σ2(w)·w.
  The first equation gives w as an affine function of y on each side of w = 0 (σ2(w)·w is
  increasing and 0 at 0, so the side is the sign of the solution with sigma2), so the pair is one
  scalar equation in y (:func:`implicit_mass_step`), solved here with scipy's ``brentq`` (the
  Rust core uses its own bracketed search).
- ``explicit``: the friction's explicit step with v held, then v⁺ = v + dt·(u + k·(a − x) − Fₖ)/m
  and x⁺ = x + dt·v.

In both, the velocity the friction holds over the step is (x⁺ − x)/dt, the friction step's own
contract. :func:`implicit_mass_step` takes the hysteresis and the state equation as functions, so
that the original Leuven model (:mod:`leuven_rt.reference.original_leuven`) rides on the same mass.


The module's name mirrors the public :mod:`leuven_rt.mechanics` on purpose: it is that module's oracle."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from .._checks import as_signal, check_dt, check_scheme, require_finite
from .._typing import FloatArray
from ..errors import DivergenceError
from ..mechanics import MassTrajectory
from ..params import Params, ParamsLike, as_params
from .leuven import hysteresis_of, phi, step, stribeck_level, viscous_coefficient

#: Relative tolerance of the root (4 ulps, what brentq accepts and the Rust solver stops at).
RTOL = 4.0 * np.finfo(np.float64).eps


@dataclass(frozen=True)
class Mechanics:
    """Mass m [kg], spring stiffness k [N/m] and speed of the spring's far end [m/s]."""

    mass: float
    stiffness: float = 0.0
    drive_speed: float = 0.0


def implicit_mass_step(
    hysteresis: Callable[[float], float],
    rate: Callable[[float, float], float],
    z: float,
    v: float,
    dt: float,
    net: float,
    stiffness_s: float,
    sigma1: float,
    backward: tuple[float, float] | None = None,
) -> tuple[float, float]:
    """The root (y, w) of the implicit mass step, given Fh(y) = ``hysteresis(y)`` and the state
    equation dz/dt = ``rate(y, w)``.

    ``net`` = u + k·(a⁺ − x − dt·v) − σ2·v and ``stiffness_s`` = S = m/dt + k·dt + σ2, so that
    w(y) = v + (net − Fh(y) − σ1·(y − z)/dt)/S; where that w is negative and ``backward`` gives
    (net, S) with sigma2_neg in place of sigma2, w is theirs. The bracket starts from z and
    z − R(z) and is doubled until R(y) = (y − z) − dt·rate(y, w(y)) changes sign (it does: R → ±∞
    as y → ±∞).
    """

    def velocity(y: float) -> float:
        force = hysteresis(y)
        w = v + (net - force - sigma1 * (y - z) / dt) / stiffness_s
        if w < 0.0 and backward is not None:
            w = v + (backward[0] - force - sigma1 * (y - z) / dt) / backward[1]
        return w

    def residual(y: float) -> float:
        return (y - z) - dt * rate(y, velocity(y))

    r0 = residual(z)
    if not math.isfinite(r0):
        raise DivergenceError(
            "the implicit mass step overflowed: the inputs are beyond f64 range", kind="overflow"
        )
    if r0 == 0.0:
        return z, velocity(z)
    near, step_size = z, -r0
    for _ in range(64):
        far = z + step_size
        r = residual(far)
        if not math.isfinite(r):
            break
        if r == 0.0:
            return far, velocity(far)
        if (r < 0.0) != (r0 < 0.0):
            lo, hi = sorted((near, far))
            xtol = RTOL * abs(z) + 1e-300
            y = float(brentq(residual, lo, hi, xtol=xtol, rtol=RTOL, maxiter=500))
            return y, velocity(y)
        near, step_size = far, 2.0 * step_size
    raise DivergenceError(
        "the implicit mass step found no sign change: the inputs are beyond f64 range", kind="overflow"
    )


def _run_channel(
    params: Params,
    mechanics: Mechanics,
    u: FloatArray,
    dt: float,
    scheme: str,
    position: float,
    velocity: float,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    hysteresis = hysteresis_of(params)
    zeta = hysteresis.relaxed()
    m, k, speed = mechanics.mass, mechanics.stiffness, mechanics.drive_speed
    x, v, anchor, z = position, velocity, 0.0, 0.0
    friction, xs, vs = (np.empty_like(u) for _ in range(3))
    for index, uk in enumerate(u.tolist()):
        anchor_next = anchor + dt * speed
        if scheme == "implicit":

            def trial(y: float) -> float:
                return hysteresis.force(zeta, y)

            def rate(y: float, w: float) -> float:
                return w - abs(w) * phi(trial(y) / stribeck_level(params, w), params.n)

            drive = uk + k * (anchor_next - x - dt * v)
            net, stiffness_s = drive - params.sigma2 * v, m / dt + k * dt + params.sigma2
            sigma2_neg = params.sigma2_negative
            backward = (drive - sigma2_neg * v, m / dt + k * dt + sigma2_neg)
            y, w = implicit_mass_step(trial, rate, z, v, dt, net, stiffness_s, params.sigma1, backward)
            force = trial(y) + params.sigma1 * (y - z) / dt + viscous_coefficient(params, w) * w
            hysteresis.commit(zeta, y)
            z, x, v = y, x + dt * w, w
        else:
            z, force = step(params, hysteresis, zeta, z, v, dt, "explicit", sample=index)
            v_next = v + dt * (uk + k * (anchor - x) - force) / m
            x, v = x + dt * v, v_next
        if not (math.isfinite(force) and math.isfinite(x) and math.isfinite(v)):
            raise DivergenceError(
                f"the {scheme} mass step diverged at sample {index}", kind="diverged", sample=index
            )
        anchor = anchor_next
        friction[index], xs[index], vs[index] = force, x, v
    return friction, xs, vs


def simulate_mass(
    params: ParamsLike,
    u: ArrayLike,
    dt: float,
    mass: float,
    stiffness: float = 0.0,
    drive_speed: float = 0.0,
    position: float = 0.0,
    velocity: float = 0.0,
    scheme: str = "implicit",
) -> MassTrajectory:
    """The mass driven by applied force ``u`` ((T,) or (B, T)), from ``position``/``velocity``
    with relaxed friction and the spring's far end at 0. Slow and plain; the same contract as
    :func:`leuven_rt.simulate_mass`, whose mechanical parameters it does not validate."""
    params = as_params(params)
    array, one_dimensional = as_signal(u, "u")
    require_finite(array, "u", one_dimensional)
    dt = check_dt(dt)
    scheme = check_scheme(scheme)
    mechanics = Mechanics(float(mass), float(stiffness), float(drive_speed))
    rows = [_run_channel(params, mechanics, row, dt, scheme, position, velocity) for row in array]
    out = [np.stack([row[i] for row in rows]) for i in range(3)]
    if one_dimensional:
        out = [a[0] for a in out]
    return MassTrajectory(*out)
