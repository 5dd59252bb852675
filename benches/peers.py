"""leuven-rt against the loop a Python user would write with numba, on one core, in one run:
``python benches/peers.py [--quick]`` (needs the ``bench`` extra: numba).

Each peer is an ``@njit`` loop over channels and samples of the same discrete step as the
library (docs/model.md#discrete-step), with the same parameters and inputs:

- LuGre (linear hysteresis σ0, n = 1), explicit and implicit (the implicit root is closed form);
- the modified Leuven model with N = 10 Maxwell-slip elements and n = 2, explicit and implicit
  (the implicit step walks the linear pieces of Fh and solves each in closed form, the method of
  docs/model.md#discrete-step).

Both sides get a batch of B channels × T samples (B = 256, T = 10 000; ``--quick``: 35 × 2 000)
with a different sine per channel (amplitude, frequency and phase), so that channels reverse at
different samples.

Then one long channel (T = 100 000; ``--quick``: 20 000), what a fit simulates many times, each
through the call a user makes for it and a numba loop of one channel:

- LuGre, implicit, velocity input (``leuven_rt.simulate`` on a 1-D signal);
- LuGre, implicit, position input (``leuven_rt.simulate_position``: v = (xₖ − xₖ₋₁)/dt, 0 on the
  first sample);
- the modified Leuven model, N = 10, implicit, position input with a position-dependent level
  (:class:`leuven_rt.PositionLevel`: a trend along the stroke and a ripple of the screw's pitch).

The library runs with one thread (``RAYON_NUM_THREADS=1``, set before it is imported), the numba
loop is serial. Before timing, the peer's forces are compared with the library's: a ratio
between two different computations would mean nothing.

Prints two markdown tables: ns per channel-step for each, and the ratio numba / leuven-rt (above
1: the library is faster). The one-channel times include the whole call (input checks, the copy
of the input, the output array), as a fit pays them. ``--cpu`` times with the process's CPU clock
instead of the wall clock: on a shared, loaded machine it leaves out the time the process waits
for a core (the calls of the Leuven row take 6 ms, long enough to be preempted).

Measured on the project's machine (2 cores, AMD EPYC, a shared VM, loaded by other work), the
tree before this version and this one alternating, three runs of each; one-channel rows, the
range of the runs' medians (21 calls each):

| one channel, implicit | clock (load average) | before | now | numba | numba / leuven-rt |
|---|---|---:|---:|---:|---:|
| LuGre, velocity | CPU (10.8–11.0) | 6.37–6.68 | 5.63–5.79 | 6.21–6.58 | 0.96–0.97x → 1.13–1.14x |
| LuGre, position | CPU (10.8–11.0) | 7.65–8.07 | 6.77–6.87 | 7.58–7.97 | 0.98–1.01x → 1.14–1.16x |
| Leuven N = 10, n = 2, level | CPU (10.8–11.0) | 62.8–64.2 | 57.9–59.8 | 54.1–56.7 | 0.88x → 0.93–0.94x |
| LuGre, velocity | wall (10.7–10.9) | 6.32–6.81 | 5.39–5.65 | 6.13–6.44 | 0.95–0.98x → 1.14x |
| LuGre, position | wall (10.7–10.9) | 7.76–8.24 | 6.63–6.83 | 7.61–8.04 | 0.98–1.00x → 1.15–1.16x |

ns per step; Leuven by position with the level ``LEVEL``. On the wall clock the Leuven row ranged
from 94 to 145 ns a step on both sides at that load: not a measurement. LuGre is now faster than
numba; the Leuven row is not yet. Measured apart (the same call without the level, CPU clock,
median of 21): the level costs the library 9.8 ns a step (11.1 before) and numba 10.0–11.0; the
Leuven step without it takes 49.0 ns against numba's 44.7, which is what is left. What changed:
the level's terms of 64 positions are evaluated ahead of stepping them, lane by lane and without a
branch (the phase reduced exactly to a quarter period, where libm's ``sincos`` polynomials apply
directly), so that they run in SIMD registers; the step divides by dt and Vs no more (1/dt once
per call, 1/Vs when the curve is built); and the output is written into a new array of the
caller's instead of one allocated and zeroed in Rust. gms-core is ``no_std`` and takes ``exp`` and
``sincos`` from libm (FreeBSD's algorithms, which gms-batch's lanes reproduce bit for bit),
compiled for the baseline x86-64; numba calls the C library's, compiled for this CPU with FMA.
"""

from __future__ import annotations

import os

# One core for the library: rayon reads this when its pool starts, at the first batch call.
os.environ["RAYON_NUM_THREADS"] = "1"

import argparse
import math
import platform
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

import leuven_rt

try:
    from numba import njit
except ImportError:  # pragma: no cover - depends on the environment
    sys.exit("benches/peers.py needs numba: pip install 'leuven-rt[bench]' (or pip install numba)")

DT = 1e-3
FC, FS, VS, DELTA = 1.0, 1.5, 1e-3, 2.0
SIGMA0, SIGMA1_LUGRE = 1e5, 316.0
SIGMA1, SIGMA2 = 30.0, 0.4
W = np.full(10, 0.2)
DELTA_I = 1e-6 * np.arange(1, 11, dtype=np.float64)
# Agreement demanded of a peer, relative to the largest force. The peers sum the elements in one
# running sum, the library in four partial sums, so forces differ by ulps. The implicit step
# damps those differences (measured: below 1e-15); the explicit step at these parameters is past
# its stability limit (dt·|v|·W/(Δ·g) reaches about 20: the elements chatter) and amplifies them,
# to 3e-9 over 10 000 samples.
AGREEMENT = {"implicit": 1e-12, "explicit": 1e-6}

# The level of the one-channel Leuven row: a trend of ±10 % over the stroke and a ripple of a
# 1 mm screw pitch, relative to the friction level.
LEVEL_MIDDLE, LEVEL_HALF_STROKE, LEVEL_TREND = 0.0, 2e-3, (0.1, 0.05)
PITCH, PITCH_COS, PITCH_SIN = 1e-3, 0.05, 0.02
LEVEL = leuven_rt.PositionLevel(
    middle=LEVEL_MIDDLE,
    half_stroke=LEVEL_HALF_STROKE,
    trend=LEVEL_TREND,
    ripples=(leuven_rt.Ripple(period=PITCH, cos=(PITCH_COS,), sin=(PITCH_SIN,)),),
)

LUGRE = leuven_rt.Params(
    Fc=FC, Fs=FS, Vs=VS, delta=DELTA, n=1.0, sigma0=SIGMA0, sigma1=SIGMA1_LUGRE, sigma2=SIGMA2
)
LEUVEN = leuven_rt.Params(
    Fc=FC, Fs=FS, Vs=VS, delta=DELTA, n=2.0, sigma1=SIGMA1, sigma2=SIGMA2, W=list(W), Delta=list(DELTA_I)
)


@njit(cache=False, fastmath=False)
def _stribeck(v: float) -> float:
    x = v / VS
    return FC + (FS - FC) * math.exp(-(x * x))


@njit(cache=False)
def lugre_explicit(v: np.ndarray, out: np.ndarray) -> None:
    channels, samples = v.shape
    for b in range(channels):
        z = 0.0
        for t in range(samples):
            vk = v[b, t]
            z_next = z + DT * (vk - abs(vk) * SIGMA0 * z / _stribeck(vk))
            out[b, t] = SIGMA0 * z_next + SIGMA1_LUGRE * (z_next - z) / DT + SIGMA2 * vk
            z = z_next


@njit(cache=False)
def lugre_implicit(v: np.ndarray, out: np.ndarray) -> None:
    channels, samples = v.shape
    for b in range(channels):
        z = 0.0
        for t in range(samples):
            vk = v[b, t]
            # Backward Euler with n = 1 is linear in z⁺.
            z_next = (z + DT * vk) / (1.0 + DT * abs(vk) * SIGMA0 / _stribeck(vk))
            out[b, t] = SIGMA0 * z_next + SIGMA1_LUGRE * (z_next - z) / DT + SIGMA2 * vk
            z = z_next


@njit(cache=False)
def _commit(zeta: np.ndarray, stiffness: np.ndarray, delta: np.ndarray, z: float) -> float:
    force = 0.0
    for i in range(zeta.shape[0]):
        deflection = z - zeta[i]
        if deflection > delta[i]:
            deflection = delta[i]
            zeta[i] = z - deflection
        elif deflection < -delta[i]:
            deflection = -delta[i]
            zeta[i] = z - deflection
        force += stiffness[i] * deflection
    return force


@njit(cache=False)
def leuven_explicit(v: np.ndarray, out: np.ndarray) -> None:
    channels, samples = v.shape
    stiffness = W / DELTA_I
    zeta = np.zeros(W.shape[0])
    for b in range(channels):
        z = 0.0
        zeta[:] = 0.0
        for t in range(samples):
            vk = v[b, t]
            force = 0.0
            for i in range(zeta.shape[0]):
                force += stiffness[i] * min(max(z - zeta[i], -DELTA_I[i]), DELTA_I[i])
            u = force / _stribeck(vk)
            z_next = z + DT * (vk - abs(vk) * u * abs(u))
            force = _commit(zeta, stiffness, DELTA_I, z_next)
            out[b, t] = force + SIGMA1 * (z_next - z) / DT + SIGMA2 * vk
            z = z_next


@njit(cache=False)
def _trial(
    zeta: np.ndarray, stiffness: np.ndarray, delta: np.ndarray, y: float
) -> tuple[float, float, float, float, float]:
    """Fh(y), its slopes left and right of y, and the nearest breakpoints below and above."""
    force, slope_left, slope_right = 0.0, 0.0, 0.0
    left, right = -math.inf, math.inf
    for i in range(zeta.shape[0]):
        lower, upper = zeta[i] - delta[i], zeta[i] + delta[i]
        force += stiffness[i] * min(max(y - zeta[i], -delta[i]), delta[i])
        if lower <= y < upper:
            slope_right += stiffness[i]
        if lower < y <= upper:
            slope_left += stiffness[i]
        if lower > y:
            right = min(right, lower)
        elif upper > y:
            right = min(right, upper)
        if upper < y:
            left = max(left, upper)
        elif lower < y:
            left = max(left, lower)
    return force, slope_left, slope_right, left, right


@njit(cache=False)
def _quadratic_step(r: float, q: float, alpha: float, beta: float, c: float) -> float:
    """The s with s + q + c·φ(α + β·s) = 0 for φ(u) = u·|u| (r is its value at s = 0)."""
    s_zero = -alpha / beta
    p_zero = s_zero + q
    sigma = 1.0 if p_zero <= 0.0 else -1.0
    if sigma * alpha >= 0.0:
        a2 = sigma * c * beta * beta
        a1 = 1.0 + 2.0 * c * abs(alpha) * beta
        return -2.0 * r / (a1 + math.sqrt(max(a1 * a1 - 4.0 * a2 * r, 0.0)))
    a2 = sigma * c * beta
    a0 = beta * p_zero
    w = -2.0 * a0 / (1.0 + math.sqrt(max(1.0 - 4.0 * a2 * a0, 0.0)))
    return (w - alpha) / beta


@njit(cache=False)
def leuven_implicit(v: np.ndarray, out: np.ndarray) -> None:
    channels, samples = v.shape
    stiffness = W / DELTA_I
    zeta = np.zeros(W.shape[0])
    for b in range(channels):
        z = 0.0
        zeta[:] = 0.0
        for t in range(samples):
            vk = v[b, t]
            inverse_g = 1.0 / _stribeck(vk)
            c = DT * abs(vk)
            y = z
            force, slope_left, slope_right, left, right = _trial(zeta, stiffness, DELTA_I, y)
            u = force * inverse_g
            r = -DT * vk + c * u * abs(u)
            if r != 0.0:
                lo, hi = (y, y - r) if r < 0.0 else (y - r, y)
                # Walk from z towards the root one linear piece of Fh at a time.
                while True:
                    rightward = r < 0.0
                    if rightward:
                        slope, end = slope_right, min(right, hi)
                    else:
                        slope, end = slope_left, max(left, lo)
                    beta = slope * inverse_g
                    q = (y - z) - DT * vk
                    s = -r if beta == 0.0 else _quadratic_step(r, q, force * inverse_g, beta, c)
                    s_end = end - y
                    if (rightward and s < s_end) or (not rightward and s > s_end):
                        y = min(max(y + s, lo), hi)
                        break
                    y = end
                    if end == lo or end == hi:
                        break
                    force, slope_left, slope_right, left, right = _trial(zeta, stiffness, DELTA_I, y)
                    u = force * inverse_g
                    r = (y - z) - DT * vk + c * u * abs(u)
                    if r == 0.0:
                        break
                    if r < 0.0:
                        lo = y
                    else:
                        hi = y
            force = _commit(zeta, stiffness, DELTA_I, y)
            out[b, t] = force + SIGMA1 * (y - z) / DT + SIGMA2 * vk
            z = y


@njit(cache=False)
def lugre_channel(v: np.ndarray, out: np.ndarray) -> None:
    z = 0.0
    for t in range(v.shape[0]):
        vk = v[t]
        z_next = (z + DT * vk) / (1.0 + DT * abs(vk) * SIGMA0 / _stribeck(vk))
        out[t] = SIGMA0 * z_next + SIGMA1_LUGRE * (z_next - z) / DT + SIGMA2 * vk
        z = z_next


@njit(cache=False)
def lugre_channel_position(x: np.ndarray, out: np.ndarray) -> None:
    z = 0.0
    previous = x[0]  # v = 0 on the first sample
    for t in range(x.shape[0]):
        vk = (x[t] - previous) / DT
        previous = x[t]
        z_next = (z + DT * vk) / (1.0 + DT * abs(vk) * SIGMA0 / _stribeck(vk))
        out[t] = SIGMA0 * z_next + SIGMA1_LUGRE * (z_next - z) / DT + SIGMA2 * vk
        z = z_next


@njit(cache=False)
def _level_factor(x: float) -> float:
    p = min(max((x - LEVEL_MIDDLE) / LEVEL_HALF_STROKE, -1.0), 1.0)
    angle = 2.0 * math.pi * x / PITCH
    trend = LEVEL_TREND[0] * p + LEVEL_TREND[1] * (1.5 * p * p - 0.5)
    return 1.0 + trend + (PITCH_COS * math.cos(angle) + PITCH_SIN * math.sin(angle))


@njit(cache=False)
def leuven_channel_position_level(x: np.ndarray, out: np.ndarray) -> None:
    stiffness = W / DELTA_I
    zeta = np.zeros(W.shape[0])
    z = 0.0
    previous = x[0]  # v = 0 on the first sample
    for t in range(x.shape[0]):
        vk = (x[t] - previous) / DT
        previous = x[t]
        # The implicit step of leuven_implicit.
        inverse_g = 1.0 / _stribeck(vk)
        c = DT * abs(vk)
        y = z
        force, slope_left, slope_right, left, right = _trial(zeta, stiffness, DELTA_I, y)
        u = force * inverse_g
        r = -DT * vk + c * u * abs(u)
        if r != 0.0:
            lo, hi = (y, y - r) if r < 0.0 else (y - r, y)
            while True:
                rightward = r < 0.0
                if rightward:
                    slope, end = slope_right, min(right, hi)
                else:
                    slope, end = slope_left, max(left, lo)
                beta = slope * inverse_g
                q = (y - z) - DT * vk
                s = -r if beta == 0.0 else _quadratic_step(r, q, force * inverse_g, beta, c)
                s_end = end - y
                if (rightward and s < s_end) or (not rightward and s > s_end):
                    y = min(max(y + s, lo), hi)
                    break
                y = end
                if end == lo or end == hi:
                    break
                force, slope_left, slope_right, left, right = _trial(zeta, stiffness, DELTA_I, y)
                u = force * inverse_g
                r = (y - z) - DT * vk + c * u * abs(u)
                if r == 0.0:
                    break
                if r < 0.0:
                    lo = y
                else:
                    hi = y
        force = _commit(zeta, stiffness, DELTA_I, y) + SIGMA1 * (y - z) / DT + SIGMA2 * vk
        # The level scales the contact force, not the viscous one.
        viscous = SIGMA2 * vk
        out[t] = _level_factor(x[t]) * (force - viscous) + viscous
        z = y


@dataclass(frozen=True)
class Case:
    """One row: the library's call on ``signal`` and the numba loop on it, with the scheme whose
    agreement the peer must reach."""

    name: str
    scheme: str
    library: Callable[[np.ndarray], np.ndarray]
    peer: Callable[[np.ndarray, np.ndarray], None]


def velocity_run(params: leuven_rt.Params, scheme: str) -> Callable[[np.ndarray], np.ndarray]:
    """The library on velocity input, (B, T) or (T,)."""
    return lambda v: leuven_rt.simulate(params, v, DT, scheme)


CASES = (
    Case("LuGre, explicit", "explicit", velocity_run(LUGRE, "explicit"), lugre_explicit),
    Case("LuGre, implicit", "implicit", velocity_run(LUGRE, "implicit"), lugre_implicit),
    Case("Leuven N = 10, n = 2, explicit", "explicit", velocity_run(LEUVEN, "explicit"), leuven_explicit),
    Case("Leuven N = 10, n = 2, implicit", "implicit", velocity_run(LEUVEN, "implicit"), leuven_implicit),
)

# One channel: (case, whether its signal is the position).
CHANNEL_CASES = (
    (Case("LuGre, implicit, velocity", "implicit", velocity_run(LUGRE, "implicit"), lugre_channel), False),
    (
        Case(
            "LuGre, implicit, position",
            "implicit",
            lambda x: leuven_rt.simulate_position(LUGRE, x, DT, "implicit"),
            lugre_channel_position,
        ),
        True,
    ),
    (
        Case(
            "Leuven N = 10, n = 2, implicit, position, level",
            "implicit",
            lambda x: leuven_rt.simulate_position(LEUVEN, x, DT, "implicit", level=LEVEL),
            leuven_channel_position_level,
        ),
        True,
    ),
)


def inputs(channels: int, samples: int) -> np.ndarray:
    """A different 1 kHz sine per channel: 5–15 mm/s, 2–8 Hz, any phase (seeded)."""
    rng = np.random.default_rng(13)
    amplitude = rng.uniform(5e-3, 15e-3, (channels, 1))
    frequency = rng.uniform(2.0, 8.0, (channels, 1))
    phase = rng.uniform(0.0, 2.0 * np.pi, (channels, 1))
    t = np.arange(samples) * DT
    return np.ascontiguousarray(amplitude * np.sin(2.0 * np.pi * frequency * t + phase))


def seconds(run: Callable[[], object], clock: Callable[[], float]) -> float:
    start = clock()
    run()
    return clock() - start


def measure(
    case: Case, signal: np.ndarray, repeats: int, failures: list[str], clock: Callable[[], float]
) -> str:
    """The row of ``case`` on ``signal``: both sides checked against each other, then timed
    alternately."""
    expected = case.library(signal)
    out = np.empty_like(signal)
    case.peer(signal, out)
    scale = float(np.max(np.abs(expected)))
    agreement = float(np.max(np.abs(out - expected))) / scale
    if not agreement <= AGREEMENT[case.scheme]:
        failures.append(f"{case.name}: numba and leuven-rt differ by {agreement:.1e} (relative)")
    library_run = lambda: case.library(signal)  # noqa: E731
    peer_run = lambda: case.peer(signal, out)  # noqa: E731
    # Both were run once above (compiled, pages touched); now alternate, so that a burst of load
    # elsewhere on the machine falls on both sides alike.
    library_times, peer_times = [], []
    for _ in range(repeats):
        library_times.append(seconds(library_run, clock))
        peer_times.append(seconds(peer_run, clock))
    library = float(np.median(library_times)) / signal.size * 1e9
    peer = float(np.median(peer_times)) / signal.size * 1e9
    return f"| {case.name} | {library:.2f} | {peer:.2f} | {peer / library:.2f}x | {agreement:.0e} |"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a small batch and 3 repeats (a smoke run)")
    parser.add_argument(
        "--cpu",
        action="store_true",
        help="time with the process's CPU clock instead of the wall clock: on a shared, loaded "
        "machine it leaves out the time the process waits for a core",
    )
    args = parser.parse_args()
    clock = time.process_time if args.cpu else time.perf_counter
    # --quick: 35 channels, so that three run outside the batch kernel's groups of eight.
    channels, samples, repeats = (35, 2_000, 3) if args.quick else (256, 10_000, 7)
    # One channel: short calls, so more of them.
    channel_samples, channel_repeats = (20_000, 3) if args.quick else (100_000, 21)
    v = inputs(channels, samples)
    import numba

    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    header = "| model, scheme | leuven-rt [ns/step] | numba [ns/step] | numba / leuven-rt | agree to |"
    print("# leuven-rt against numba, one core" + (" (--quick)" if args.quick else ""))
    print()
    print(
        f"numba {numba.__version__}, Python {platform.python_version()}, {platform.machine()}; "
        f"load average {load} at the start; {'CPU' if args.cpu else 'wall'} clock"
    )
    print()
    print(
        f"## A batch: B = {channels} channels x T = {samples:,} samples at 1 kHz; median of {repeats} "
        "runs, the two sides alternating"
    )
    print()
    print(header)
    print("|---|---:|---:|---:|---:|")
    failures: list[str] = []
    for case in CASES:
        print(measure(case, v, repeats, failures, clock))
    print()
    print(
        f"## One channel: T = {channel_samples:,} samples at 1 kHz, the whole call; median of "
        f"{channel_repeats} runs, the two sides alternating"
    )
    print()
    print(header)
    print("|---|---:|---:|---:|---:|")
    velocity = inputs(1, channel_samples)[0]
    position = np.cumsum(velocity) * DT
    for case, by_position in CHANNEL_CASES:
        print(measure(case, position if by_position else velocity, channel_repeats, failures, clock))
    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    print()
    print(f"load average {load} at the end")
    if failures:
        sys.exit("\n".join(failures))


if __name__ == "__main__":
    main()
