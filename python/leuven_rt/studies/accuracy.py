"""Accuracy of the discrete step: explicit vs implicit against a much finer solution.

docs/model.md#accuracy-of-the-schemes states that with classic LuGre-like stiffness the explicit
(forward Euler) step is useless at control-loop rates while the implicit (backward Euler) step
stays accurate. This module measures that claim so the README can quote numbers anyone can rerun (``python
benches/accuracy.py``) and the tests can hold the implicit scheme to it.

Scenario (docs/model.md#accuracy-of-the-schemes): LuGre, i.e. linear hysteresis Fh = σ0·z with n = 1,
σ0 = 1e5 N/m, Fc = 1 N, Fs = 1.5 N, Vs = 1 mm/s, δ = 2, σ1 = √σ0 ≈ 316 N·s/m, σ2 = 0.4 N·s/m, driven from rest
by v(t) = 10 mm/s · sin(2π·5 Hz·t) for 1 s.

Reference: the implicit scheme at ``dt/refine`` with the velocity sampled from the same
continuous signal at the fine rate. The coarse output Fₖ is the force over step k, which ends at
t₍ₖ₊₁₎ = (k+1)·dt; it is compared with the fine output of the fine step that ends at the same
instant, fine index (k+1)·refine − 1.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._typing import FloatArray, Scheme
from ..errors import DivergenceError, InputError, shown
from ..mechanics import simulate_mass
from ..params import Params
from ..simulation import simulate

#: The LuGre-like parameter set of docs/model.md#accuracy-of-the-schemes; σ1 = √σ0 is the usual
#: critically damped choice for a unit mass on the bristle spring.
LUGRE = Params(
    Fc=1.0,
    Fs=1.5,
    Vs=1e-3,
    delta=2.0,
    n=1.0,
    sigma0=1e5,
    sigma1=math.sqrt(1e5),
    sigma2=0.4,
)

#: Velocity amplitude [m/s] and frequency [Hz] of the driving sine.
AMPLITUDE = 0.01
FREQUENCY = 5.0

SCHEMES: tuple[Scheme, ...] = ("explicit", "implicit")


@dataclass(frozen=True)
class AccuracyRow:
    """The force error of one scheme at one sample rate against the refined solution."""

    rate_hz: float
    """Sample rate of the scheme under test [Hz]."""
    scheme: str
    """'explicit' or 'implicit'."""
    rms_error: float
    """RMS of the force error [N]; ``inf`` if the scheme diverged."""
    rms_error_relative_to_Fs: float
    """``rms_error / Fs`` (a fraction, not a percentage)."""
    max_error: float
    """Largest absolute force error [N]; ``inf`` if the scheme diverged."""

    @property
    def diverged(self) -> bool:
        """Whether the run raised :class:`DivergenceError` (reported as infinite error)."""
        return math.isinf(self.rms_error)


def velocity(times: FloatArray, amplitude: float = AMPLITUDE) -> FloatArray:
    """The driving signal v(t) [m/s], evaluated at ``times`` [s]."""
    return amplitude * np.sin(2.0 * np.pi * FREQUENCY * times)


def _samples(rate: float, duration: float) -> int:
    count = round(rate * duration)
    if count < 1 or not math.isclose(count, rate * duration, rel_tol=1e-9):
        raise InputError(
            f"`duration` must hold a whole number (>= 1) of samples at {rate} Hz, "
            f"got {duration} s = {rate * duration} samples",
            kind="not_integer",
            field="duration",
            value=duration,
        )
    return count


def _compare(
    params: Params,
    v: FloatArray,
    dt: float,
    scheme: Scheme,
    truth: FloatArray,
    rate: float,
) -> AccuracyRow:
    """One row: ``scheme`` at step ``dt`` against ``truth``; infinite errors if it diverged."""
    diverged = AccuracyRow(rate, scheme, math.inf, math.inf, math.inf)
    try:
        forces = simulate(params, v, dt, scheme)
    except DivergenceError:
        return diverged
    # An unstable run can stay finite yet so large that the difference overflows: diverged too.
    with np.errstate(over="ignore", invalid="ignore"):
        error = forces - truth
    rms, largest = _rms(error)
    if math.isinf(rms):
        return diverged
    return AccuracyRow(rate, scheme, rms, rms / params.Fs, largest)


def step_accuracy(
    rates: Sequence[float] = (100.0, 1000.0, 10000.0),
    refine: int = 100,
    duration: float = 1.0,
    params: Params = LUGRE,
    amplitude: float = AMPLITUDE,
) -> list[AccuracyRow]:
    """RMS and max force error of each scheme at each rate, against a ``refine``× finer solution.

    Rows come rate by rate, explicit before implicit. ``duration`` [s] must be a whole number of
    samples at every rate; a shorter one keeps tests quick. ``amplitude`` [m/s] scales the sine. A
    scheme that raises :class:`DivergenceError` gets a row with infinite errors instead of failing the table.
    """
    if isinstance(refine, bool) or not isinstance(refine, int) or refine < 2:
        integer = isinstance(refine, int) and not isinstance(refine, bool)
        raise InputError(
            f"`refine` must be an integer >= 2, got {shown(refine)!r}",
            kind="out_of_range" if integer else "not_integer",
            field="refine",
            value=refine,
            bound=2 if integer else None,
        )
    rows: list[AccuracyRow] = []
    for rate in rates:
        rate = float(rate)
        count = _samples(rate, duration)
        dt = 1.0 / rate
        # Times from integer indices (not accumulated or strided): both grids sample exactly the
        # same continuous signal, so the only difference between them is the step size.
        fine_v = velocity(np.arange(count * refine) / (rate * refine), amplitude)
        coarse_v = velocity(np.arange(count) / rate, amplitude)
        fine = simulate(params, fine_v, dt / refine, "implicit")
        # Fine step (k+1)·refine − 1 ends at (k+1)·dt, like coarse step k.
        truth = fine[refine - 1 :: refine]
        for scheme in SCHEMES:
            rows.append(_compare(params, coarse_v, dt, scheme, truth, rate))
    return rows


def _number(value: float) -> str:
    return "diverged" if math.isinf(value) else f"{value:.3g}"


def format_table(rows: Sequence[AccuracyRow]) -> str:
    """The rows as a markdown table (errors in N and in % of Fs)."""
    lines = [
        "| rate [Hz] | scheme | RMS error [N] | RMS error [% of Fs] | max error [N] |",
        "|---:|---|---:|---:|---:|",
    ]
    for row in rows:
        relative = "diverged" if row.diverged else f"{100.0 * row.rms_error_relative_to_Fs:.3g} %"
        lines.append(
            f"| {row.rate_hz:g} | {row.scheme} | {_number(row.rms_error)} | {relative} "
            f"| {_number(row.max_error)} |"
        )
    return "\n".join(lines)


def report(
    amplitudes: Sequence[float] = (AMPLITUDE, 3 * AMPLITUDE),
    rates: Sequence[float] = (100.0, 1000.0, 10000.0),
    refine: int = 100,
) -> str:
    """The accuracy tables of docs/benchmarks.md: one per sine amplitude, with the stability numbers.

    Linearised, the state equation is dz/dt = v − (|v|·σ0/g)·z, so forward Euler is stable only
    while dt·|v|·σ0/g(v) < 2. At the 10 mm/s of docs/model.md#accuracy-of-the-schemes that number
    peaks at exactly 1 at 1 kHz, so the explicit step is still stable there; 30 mm/s shows what
    happens past the limit.
    """
    p = LUGRE
    assert p.sigma0 is not None  # LUGRE is linear hysteresis: sigma0, no elements
    lines = [
        f"LuGre-like scenario: sigma0 = {p.sigma0:g} N/m, n = {p.n:g}, Fc = {p.Fc:g} N, "
        f"Fs = {p.Fs:g} N, Vs = {p.Vs:g} m/s, delta = {p.delta:g}, sigma1 = {p.sigma1:.4g} N*s/m, "
        f"sigma2 = {p.sigma2:g} N*s/m; reference: implicit at dt/{refine}, compared at the end "
        "of every coarse step",
    ]
    for amplitude in amplitudes:
        lines += [
            "",
            f"input: v = {amplitude:g}*sin(2*pi*{FREQUENCY:g}*t) m/s for 1 s from rest",
            "",
            format_table(step_accuracy(rates, refine=refine, amplitude=amplitude)),
            "",
        ]
        for rate in rates:
            # |v| peaks where g(v) is close to Fc.
            worst = amplitude * p.sigma0 / p.Fc / rate
            lines.append(
                f"explicit stability number at {rate:g} Hz: dt*max|v|*sigma0/Fc = {worst:.3g} (stable < 2)"
            )
    return "\n".join(lines)


# --- Force-driven case: the same friction under a mass (leuven_rt.simulate_mass) -----------------

#: The force-driven scenario: a free 1 kg mass on the LuGre-like friction, pushed by
#: u(t) = 2 N · sin(2π·5 Hz·t) from rest for 1 s. It sticks near every reversal of u and slides
#: at up to about 30 mm/s in between, so both regimes and their transitions are in the error.
MASS = 1.0
FORCE_AMPLITUDE = 2.0


@dataclass(frozen=True)
class MassAccuracyRow:
    """The error of one scheme at one sample rate in the force-driven case."""

    rate_hz: float
    scheme: str
    rms_error: float
    """RMS of the friction force error [N]; ``inf`` if the scheme diverged."""
    rms_error_relative_to_Fs: float
    max_error: float
    """Largest absolute friction force error [N]; ``inf`` if the scheme diverged."""
    rms_position_error: float
    """RMS of the position error [m]; ``inf`` if the scheme diverged."""

    @property
    def diverged(self) -> bool:
        return math.isinf(self.rms_error)


def applied_force(times: FloatArray, amplitude: float = FORCE_AMPLITUDE) -> FloatArray:
    """The applied force u(t) [N] at ``times`` [s]."""
    return amplitude * np.sin(2.0 * np.pi * FREQUENCY * times)


def _rms(error: FloatArray) -> tuple[float, float]:
    """(RMS, max) of ``error``, scaled against overflow; (inf, inf) if not finite.

    Scaled by the largest error so that an unstable but still finite run (explicit at 100 Hz
    reaches ~1e65 N) does not overflow in the square.
    """
    largest = float(np.max(np.abs(error)))
    if not math.isfinite(largest):
        return math.inf, math.inf
    return (largest * float(np.sqrt(np.mean((error / largest) ** 2))) if largest > 0 else 0.0), largest


def force_accuracy(
    rates: Sequence[float] = (100.0, 1000.0, 10000.0),
    refine: int = 100,
    duration: float = 1.0,
    params: Params = LUGRE,
    mass: float = MASS,
    amplitude: float = FORCE_AMPLITUDE,
) -> list[MassAccuracyRow]:
    """Friction force and position error of each scheme at each rate in the force-driven case,
    against the implicit mass step at ``refine``× the rate, compared at the end of every coarse
    step. Same conventions as :func:`step_accuracy`."""
    if isinstance(refine, bool) or not isinstance(refine, int) or refine < 2:
        integer = isinstance(refine, int) and not isinstance(refine, bool)
        raise InputError(
            f"`refine` must be an integer >= 2, got {shown(refine)!r}",
            kind="out_of_range" if integer else "not_integer",
            field="refine",
            value=refine,
            bound=2 if integer else None,
        )
    rows: list[MassAccuracyRow] = []
    for rate in rates:
        rate = float(rate)
        count = _samples(rate, duration)
        dt = 1.0 / rate
        fine = simulate_mass(params, applied_force(np.arange(count * refine) / (rate * refine), amplitude),
                             dt / refine, mass=mass)  # fmt: skip
        truth_force, truth_position = fine.friction[refine - 1 :: refine], fine.position[refine - 1 :: refine]
        coarse_u = applied_force(np.arange(count) / rate, amplitude)
        for scheme in SCHEMES:
            try:
                run = simulate_mass(params, coarse_u, dt, mass=mass, scheme=scheme)
            except DivergenceError:
                rows.append(MassAccuracyRow(rate, scheme, math.inf, math.inf, math.inf, math.inf))
                continue
            with np.errstate(over="ignore", invalid="ignore"):
                force_error, position_error = run.friction - truth_force, run.position - truth_position
            rms, largest = _rms(force_error)
            rms_position, _ = _rms(position_error)
            if math.isinf(rms) or math.isinf(rms_position):
                rms = largest = rms_position = math.inf
            rows.append(MassAccuracyRow(rate, scheme, rms, rms / params.Fs, largest, rms_position))
    return rows


def simulate_mass_velocity(rate: float, params: Params = LUGRE) -> FloatArray:
    """The velocity of the force-driven scenario, implicit at ``rate`` Hz."""
    count = _samples(rate, 1.0)
    return simulate_mass(params, applied_force(np.arange(count) / rate), 1.0 / rate, mass=MASS).velocity


def format_force_table(rows: Sequence[MassAccuracyRow]) -> str:
    """The force-driven rows as a markdown table."""
    lines = [
        "| rate [Hz] | scheme | RMS force error [N] | RMS force error [% of Fs] | max force error [N] "
        "| RMS position error [m] |",
        "|---:|---|---:|---:|---:|---:|",
    ]
    for row in rows:
        relative = "diverged" if row.diverged else f"{100.0 * row.rms_error_relative_to_Fs:.3g} %"
        lines.append(
            f"| {row.rate_hz:g} | {row.scheme} | {_number(row.rms_error)} | {relative} "
            f"| {_number(row.max_error)} | {_number(row.rms_position_error)} |"
        )
    return "\n".join(lines)


def force_report(rates: Sequence[float] = (100.0, 1000.0, 10000.0), refine: int = 100) -> str:
    """The force-driven table with its scenario and the explicit coupling's stability numbers."""
    p = LUGRE
    assert p.sigma0 is not None  # LUGRE is linear hysteresis: sigma0, no elements
    lines = [
        f"Force-driven scenario: a free {MASS:g} kg mass on the same friction, "
        f"u = {FORCE_AMPLITUDE:g}*sin(2*pi*{FREQUENCY:g}*t) N for 1 s from rest; reference: implicit "
        f"mass step at dt/{refine}, compared at the end of every coarse step",
        "",
        format_force_table(force_accuracy(rates, refine=refine)),
        "",
    ]
    # The explicit scheme has two limits: the coupling at stick (the bristle spring and damper
    # against the mass) and the friction's own forward Euler in sliding, dt·|v|·σ0/g(v) < 2.
    speed = float(np.max(np.abs(simulate_mass_velocity(rates[-1] * refine, p))))
    for rate in rates:
        dt = 1.0 / rate
        lines.append(
            f"explicit stability numbers at {rate:g} Hz (each must stay below 2): "
            f"dt^2*sigma0/m = {dt * dt * p.sigma0 / MASS:.3g}, dt*sigma1/m = {dt * p.sigma1 / MASS:.3g}, "
            f"dt*max|v|*sigma0/Fc = {dt * speed * p.sigma0 / p.Fc:.3g} (max|v| = {speed:.3g} m/s)"
        )
    return "\n".join(lines)


def full_report() -> str:
    """Both cases: the velocity-driven tables of :func:`report`, then the force-driven one."""
    return report() + "\n\n" + force_report()
