"""The discrete step of the modified Leuven model in plain numpy, written as the specification.

This is docs/model.md#discrete-step spelled out one sample at a time, with nothing traded for
speed. The Rust core (`leuven_rt.simulate`) must agree with it; the tests compare the two, so the
implicit step's root is found here by a method independent of the Rust solver (see
:func:`implicit_root`).

Notation, per channel and sample k, with the state (z, ζ) at the start of the step and the
velocity vₖ held over the step of length dt:

- g(v) = Fc + (Fs − Fc)·exp(−|v/Vs|^δ), with (Fc_neg, Fs_neg) when v < 0;
- φ(u) = sgn(u)·|u|ⁿ;
- Fh(y): the hysteresis force at a candidate deflection y, computed from the ζ of the step start
  (the *trial*); Maxwell slip Fh(y) = Σᵢ Wᵢ·clip(y − ζᵢ, −Δᵢ, Δᵢ)/Δᵢ, or linear Fh(y) = σ0·y;
- f(y, v) = v − |v|·φ(Fh(y)/g(v)), the state equation dz/dt;
- implicit: z⁺ is the root of R(y) = (y − z) − dt·v + dt·|v|·φ(Fh(y)/g(v));
  explicit: z⁺ = z + dt·f(z, v);
- output Fₖ = Fh(z⁺) + σ1·(z⁺ − z)/dt + σ2(vₖ)·vₖ, with σ2(v) = sigma2_neg for v < 0 and sigma2
  otherwise, then the elements are committed at z⁺.

The position-dependent terms (docs/model.md#position-dependent-level) are written here too, as
the equations write them (:func:`position_series`, with the phase 2πk·x/P unreduced): this
module is the oracle, so it keeps its own formula rather than calling gms-core's, which reduces
the phase to one period and builds the harmonics by recurrence. The two agree to 1e-12 of the
amplitudes while |x/P| stays below about 20 (docs/model.md#position-dependent-level).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from .._checks import as_signal, check_dt, check_scheme, require_finite
from .._typing import FloatArray
from ..errors import DivergenceError, InputError
from ..level import PositionForce, PositionLevel
from ..params import Params, ParamsLike, as_params

#: Relative tolerance of the root: the smallest that ``brentq`` accepts (4 ulps), which is also
#: what the Rust solver stops at.
RTOL = 4.0 * np.finfo(np.float64).eps


def _power(a: float, p: float) -> float:
    """aᵖ for a ≥ 0, infinite on overflow (Python floats raise instead; Rust gives inf)."""
    try:
        power: float = a**p  # a ≥ 0: never complex
        return power
    except OverflowError:
        return math.inf


def phi(u: float, n: float) -> float:
    """φ(u) = sgn(u)·|u|ⁿ."""
    return math.copysign(_power(abs(u), n), u)


def viscous_coefficient(params: Params, v: float) -> float:
    """σ2(v): ``sigma2_neg`` (``sigma2`` when not given) for v < 0, ``sigma2`` otherwise."""
    return params.sigma2_negative if v < 0 else params.sigma2


def stribeck_level(params: Params, v: float) -> float:
    """g(v) > 0, the steady sliding friction magnitude at velocity v (eq. 3)."""
    fc, fs = (params.Fc_negative, params.Fs_negative) if v < 0 else (params.Fc, params.Fs)
    return fc + (fs - fc) * math.exp(-_power(abs(v / params.Vs), params.delta))


class MaxwellSlip:
    """N elasto-slide elements in parallel (eq. 5); the memory is the array ζ of their positions."""

    def __init__(self, W: Sequence[float], Delta: Sequence[float]) -> None:
        self.W = np.asarray(W, dtype=np.float64)
        self.Delta = np.asarray(Delta, dtype=np.float64)

    def relaxed(self) -> FloatArray:
        return np.zeros_like(self.W)

    def force(self, zeta: FloatArray, y: float) -> float:
        """Trial Fh(y): each element's deflection y − ζᵢ clipped to [−Δᵢ, Δᵢ]."""
        return float(np.sum(self.W * np.clip(y - zeta, -self.Delta, self.Delta) / self.Delta))

    def forces(self, zeta: FloatArray, ys: FloatArray) -> FloatArray:
        """Trial Fh at many points at once (rows: points, columns: elements)."""
        deflection = np.clip(ys[:, None] - zeta, -self.Delta, self.Delta)
        forces: FloatArray = np.sum(self.W * deflection / self.Delta, axis=1)
        return forces

    def breakpoints(self, zeta: FloatArray) -> FloatArray:
        """Where the trial Fh changes slope: each element starts or stops slipping at ζᵢ ± Δᵢ."""
        return np.concatenate((zeta - self.Delta, zeta + self.Delta))

    def stiffness(self, zeta: FloatArray, y: float) -> float:
        """dFh/dy at a y that is not a breakpoint: the stiffness Wᵢ/Δᵢ of the sticking elements."""
        sticking = np.abs(y - zeta) < self.Delta
        return float(np.sum(self.W[sticking] / self.Delta[sticking]))

    def commit(self, zeta: FloatArray, y: float) -> None:
        """Moves ζ to y in place: only over-stretched elements slip, to deflection ±Δᵢ.

        Sticking elements are left alone: rewriting their ζ as y − (y − ζ) could round.
        """
        deflection = y - zeta
        slipping = np.abs(deflection) > self.Delta
        zeta[slipping] = y - np.sign(deflection[slipping]) * self.Delta[slipping]


class LinearSpring:
    """Fh = σ0·y, a spring that never slips (LuGre when n = 1); it has no memory."""

    def __init__(self, sigma0: float) -> None:
        self.sigma0 = sigma0

    def relaxed(self) -> FloatArray:
        return np.zeros(0)

    def force(self, zeta: FloatArray, y: float) -> float:
        return self.sigma0 * y

    def forces(self, zeta: FloatArray, ys: FloatArray) -> FloatArray:
        return self.sigma0 * ys

    def breakpoints(self, zeta: FloatArray) -> FloatArray:
        return np.zeros(0)

    def stiffness(self, zeta: FloatArray, y: float) -> float:
        return self.sigma0

    def commit(self, zeta: FloatArray, y: float) -> None:
        pass


Hysteresis = MaxwellSlip | LinearSpring


def hysteresis_of(params: Params) -> Hysteresis:
    """The hysteresis force that the parameters select (`sigma0`, or `W` + `Delta`)."""
    if params.W is None or params.Delta is None:
        assert params.sigma0 is not None  # Params validation guarantees one of the two
        return LinearSpring(params.sigma0)
    return MaxwellSlip(params.W, params.Delta)


def implicit_root(
    hysteresis: Hysteresis, zeta: FloatArray, z: float, v: float, dt: float, g: float, n: float
) -> float:
    """The unique root z⁺ of R(y) = (y − z) − dt·v + dt·|v|·φ(Fh(y)/g), to machine precision.

    Why this converges, step by step:

    1. Fh is non-decreasing in y, so R is strictly increasing with slope ≥ 1: one root.
    2. Bracket. With r = R(z) and the explicit Euler point y_e = z − r, slope ≥ 1 gives
       R(y_e) ≥ 0 when r < 0 (and ≤ 0 when r > 0): the root lies between z and y_e.
    3. Piece. Fh is piecewise linear with breakpoints ζᵢ ± Δᵢ. Evaluating R at the breakpoints
       inside the bracket (all at once) and taking the first one where R ≥ 0 narrows the
       bracket to [a, b] on which Fh(y) = Fh(a) + K·(y − a) is affine.
    4. Solve on the piece. If n = 1 (or K = 0) R is affine there, so the root is
       a − R(a)/R', R' = 1 + dt·|v|·K/g (R' = 1 when K = 0): one division, no iteration.
       Otherwise R is continuous and monotone on [a, b] (smooth except where Fh = 0 with
       n < 1), and Brent's method — bracketing, falling back to bisection, so it cannot
       fail — converges to |error| ≤ 4 ulps·|y| + xtol, xtol = 4 ulps of the bracket scale.
    """
    c = dt * abs(v)  # the weight of φ in R

    def residual(y: float) -> float:
        return (y - z) - dt * v + c * phi(hysteresis.force(zeta, y) / g, n)

    r0 = residual(z)
    if r0 == 0.0:  # includes v = 0: nothing moves
        return z
    lo, hi = sorted((z, z - r0))

    # Narrow [lo, hi] to the linear piece of Fh that holds the root.
    a, b = lo, hi
    inside = hysteresis.breakpoints(zeta)
    inside = np.sort(inside[(inside > lo) & (inside < hi)])
    if inside.size:
        u = hysteresis.forces(zeta, inside) / g
        r = (inside - z) - dt * v + c * np.sign(u) * np.abs(u) ** n
        # The first breakpoint with R ≥ 0 (R increases, so the root is between it and the one
        # before; none means the root is past the last breakpoint).
        nonnegative = r >= 0.0
        above = int(np.argmax(nonnegative)) if nonnegative.any() else inside.size
        if above < inside.size and r[above] == 0.0:
            return float(inside[above])
        if above > 0:
            a = float(inside[above - 1])
        if above < inside.size:
            b = float(inside[above])

    K = hysteresis.stiffness(zeta, 0.5 * (a + b))
    if n == 1.0 or K == 0.0:
        slope = 1.0 + c * K / g if n == 1.0 else 1.0
        # Rounding in R(a) may put the affine root a hair outside the piece.
        return min(max(a - residual(a) / slope, a), b)

    ra, rb = residual(a), residual(b)
    if ra >= 0.0:
        return a
    if rb <= 0.0:
        return b
    xtol = RTOL * max(abs(lo), abs(hi))
    return float(brentq(residual, a, b, xtol=xtol, rtol=RTOL, maxiter=200))


def explicit_point(
    hysteresis: Hysteresis, zeta: FloatArray, z: float, v: float, dt: float, g: float, n: float
) -> float:
    """Forward Euler: z + dt·f(z, v)."""
    return z + dt * (v - abs(v) * phi(hysteresis.force(zeta, z) / g, n))


def step(
    params: Params,
    hysteresis: Hysteresis,
    zeta: FloatArray,
    z: float,
    v: float,
    dt: float,
    scheme: str,
    sample: int = 0,
) -> tuple[float, float]:
    """One sample with velocity v held over dt: returns (z⁺, Fₖ) and commits ζ at z⁺ in place.

    A non-finite z⁺ or force (only the explicit scheme gets there, with a linear spring stepped
    too coarsely) raises :class:`DivergenceError` naming ``sample`` and leaves ζ untouched, with
    the Rust core's message.
    """
    g = stribeck_level(params, v)
    next_z = implicit_root if scheme == "implicit" else explicit_point
    z_next = next_z(hysteresis, zeta, z, v, dt, g, params.n)
    viscous = viscous_coefficient(params, v) * v
    force = hysteresis.force(zeta, z_next) + params.sigma1 * (z_next - z) / dt + viscous
    if not (math.isfinite(z_next) and math.isfinite(force)):
        raise DivergenceError(
            f"the explicit step diverged at sample {sample}: dt is too large for the stiffness; "
            "use the implicit scheme",
            kind="diverged",
            sample=sample,
        )
    hysteresis.commit(zeta, z_next)
    return z_next, force


def _run_channel(params: Params, v: FloatArray, dt: float, scheme: str) -> FloatArray:
    """One channel from the relaxed state z = 0, ζ = 0; returns the force of every sample."""
    hysteresis = hysteresis_of(params)
    z, zeta = 0.0, hysteresis.relaxed()
    out = np.empty_like(v)
    for k, vk in enumerate(v.tolist()):
        z, out[k] = step(params, hysteresis, zeta, z, vk, dt, scheme, sample=k)
    return out


def position_series(series: PositionLevel | PositionForce, x: ArrayLike) -> FloatArray:
    """r(x) of ``series`` (a level's departure from 1, or a position force) at every sample of
    ``x``, as docs/model.md#position-dependent-level writes it:
    t1·p + t2·(1.5·p² − 0.5) + Σ_r Σ_k (c_rk·cos(k·2π·x/P_r) + s_rk·sin(k·2π·x/P_r)),
    p = clip((x − middle)/half_stroke, −1, 1)."""
    position = np.asarray(x, dtype=float)
    p = np.clip((position - series.middle) / series.half_stroke, -1.0, 1.0)
    out: FloatArray = series.trend[0] * p + series.trend[1] * (1.5 * p * p - 0.5)
    for ripple in series.ripples:
        phase = 2.0 * np.pi * position / ripple.period
        for k, (c, s) in enumerate(zip(ripple.cos, ripple.sin, strict=True), start=1):
            out = out + c * np.cos(k * phase) + s * np.sin(k * phase)
    return out


def _with_terms(
    params: Params,
    plain: FloatArray,
    x: FloatArray,
    v: FloatArray,
    level: PositionLevel | None,
    position_force: PositionForce | None,
) -> FloatArray:
    """The forces ``plain`` at positions ``x`` and velocities ``v`` with the level and the
    position force: factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x)."""
    out = plain
    if level is not None:
        viscous = np.where(v < 0, params.sigma2_negative, params.sigma2) * v
        out = (1.0 + position_series(level, x)) * (out - viscous) + viscous
    if position_force is not None:
        out = out + position_series(position_force, x)
    return out


def simulate(
    params: ParamsLike,
    v: ArrayLike,
    dt: float,
    scheme: str = "implicit",
    *,
    x: ArrayLike | None = None,
    level: PositionLevel | None = None,
    position_force: PositionForce | None = None,
) -> FloatArray:
    """Friction force for velocity input ``v`` held over each step of length ``dt``.

    ``v`` has shape (T,) or (B, T): B channels with the same parameters, each starting relaxed.
    Returns the force with the shape of ``v``. With a ``level`` or a ``position_force`` the
    positions ``x`` (the shape of ``v``) place them, as in :func:`leuven_rt.simulate`. Same
    contract and errors as :func:`leuven_rt.simulate`, computed slowly and plainly.
    """
    params = as_params(params)
    array, one_dimensional = as_signal(v, "v")
    require_finite(array, "v", one_dimensional)
    dt = check_dt(dt)
    scheme = check_scheme(scheme)
    if (x is None) != (level is None and position_force is None):
        raise InputError(
            "`x` places a `level` or a `position_force`: give `x` with one of them, or neither",
            kind="missing" if x is None else "not_applicable",
            field="x",
        )
    out = np.stack([_run_channel(params, row, dt, scheme) for row in array])
    if x is not None:
        positions, _ = as_signal(x, "x")
        if positions.shape != array.shape:
            raise InputError(
                f"`x` must have the shape of `v`, {array.shape}, got {positions.shape}",
                kind="shape",
                field="x",
                expected=array.shape,
                got=positions.shape,
            )
        require_finite(positions, "x", one_dimensional)
        out = _with_terms(params, out, positions, array, level, position_force)
    return out[0] if one_dimensional else out


def simulate_position(
    params: ParamsLike,
    x: ArrayLike,
    dt: float,
    scheme: str = "implicit",
    *,
    level: PositionLevel | None = None,
    position_force: PositionForce | None = None,
) -> FloatArray:
    """Friction force for position input ``x``: vₖ = (xₖ − xₖ₋₁)/dt, and v = 0 on the first sample.

    With a position-dependent ``level`` and a ``position_force``
    (docs/model.md#position-dependent-level) the contact part is scaled and the force added:
    Fₖ = factor(xₖ)·(Fh(z⁺) + σ1·(z⁺ − z)/dt) + σ2(vₖ)·vₖ + r(xₖ), with factor = 1 + r of the
    level and :func:`position_series` for both (the phase 2πk·x/P unreduced).
    """
    params = as_params(params)
    array, one_dimensional = as_signal(x, "x")
    require_finite(array, "x", one_dimensional)
    dt = check_dt(dt)
    scheme = check_scheme(scheme)
    # Differences of huge positions can overflow; that is reported below, not warned about.
    with np.errstate(over="ignore", invalid="ignore"):
        v = np.diff(array, axis=1, prepend=array[:, :1]) / dt
    bad = ~np.isfinite(v)
    if bad.any():
        channel, sample = (int(index) for index in np.unravel_index(int(np.argmax(bad)), v.shape))
        value = float(v[channel, sample])
        raise InputError(
            f"`v` must be finite, got {value} at sample {sample}",
            kind="not_finite",
            field="v",
            value=value,
            sample=sample,
            channel=None if one_dimensional else channel,
        )
    out = np.stack([_run_channel(params, row, dt, scheme) for row in v])
    out = _with_terms(params, out, array, v, level, position_force)
    return out[0] if one_dimensional else out
