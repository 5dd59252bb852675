"""The paper's figures, reproduced, each with the number behind it: ``leuven-rt figures --out DIR``.

- Fig. 1 (``fig1_loop_closure.png``): a force applied to a mass makes an internal presliding loop
  (reversal at b) that closes at a. The original Leuven model's friction force jumps at a, the
  modified one does not. Number: the largest |ΔFf| between consecutive samples within 10 ms of
  the closure, for both models and three step sizes: a jump keeps it constant as dt shrinks, a
  continuous force makes it shrink with dt.
- Figs. 4/5 (``fig4_5_nonlocal_memory.png``): the hysteresis force as a function of the
  deflection z, stack implementation (smooth transition curve) against Maxwell slip with 10
  elements fitted to it. Point a is reached along two paths, one with an extra internal loop,
  which is wiped out: both implementations give the same Fh at a along both. Numbers: the largest
  difference between the implementations, and Fh at a along each path.
- Free response (``free_response_memory.png``): a mass on a spring to ground with friction,
  released away from equilibrium, oscillates in presliding with many reversals and no loop
  closure. The original model's stacks grow by one extremum per reversal until they overflow at
  the chosen depth; the Maxwell-slip memory stays N numbers. Numbers: reversals before the
  overflow, its sample and time, and the memory sizes.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from itertools import pairwise
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import PchipInterpolator
from scipy.optimize import lsq_linear

from .._plot import figure, save
from .._typing import FloatArray
from ..errors import StackOverflowError
from ..mechanics import MassSystem
from ..params import Params
from ..reference.leuven import MaxwellSlip
from ..reference.original_leuven import (
    MasingMaxwell,
    OriginalLeuven,
    OriginalLeuvenMass,
    StackHysteresis,
    TanhCurve,
)

#: The friction model of Fig. 1 and the free response: four Maxwell-slip elements, and the
#: original model with the Masing transition curve of the same bank (same hysteresis, so the
#: two differ only in the state equation). σ1 near critical damping of the 1 kg mass on the
#: presliding stiffness makes the micro-viscous term, and its jump, visible.
FIG1_PARAMS = Params(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=1000.0, sigma2=0.4,
                     W=(0.5, 0.5, 0.5, 0.5), Delta=(2e-6, 4e-6, 8e-6, 1.6e-5))  # fmt: skip
#: Duration of the Fig. 1 force profile [s] and its knots (fractions of it, forces in N):
#: up to 0.9 N, back to 0.5 N (point b), up to 1.25 N past 0.9 N (point a), back to 0.
FIG1_DURATION = 0.2
FIG1_KNOTS = ((0.0, 0.3, 0.45, 0.75, 1.0), (0.0, 0.9, 0.5, 1.25, 0.0))
FIG1_STEPS = (4e-4, 1e-4, 2.5e-5)
FIG1_WINDOW = 0.01

#: The free response: an oscillator that stays on the first linear piece of the bank, so that
#: only σ1 damps it and it reverses many times.
FREE_PARAMS = Params(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=2.0, sigma2=0.0,
                     W=(0.6, 0.5, 0.4, 0.3), Delta=(5e-6, 1e-5, 2e-5, 4e-5))  # fmt: skip
FREE_MASS, FREE_STIFFNESS, FREE_START = 1.0, 1e4, 6e-5
FREE_DEPTH = 10


@dataclass
class FigureReport:
    """One figure: where it went and the numbers it shows, as printable lines."""

    path: Path
    lines: list[str] = field(default_factory=list)


# --- Fig. 1 -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LoopClosureRun:
    """Both models under the Fig. 1 force at one step size."""

    dt: float
    t: FloatArray
    u: FloatArray
    x_modified: FloatArray
    x_original: FloatArray
    friction_modified: FloatArray
    friction_original: FloatArray
    microviscous_modified: FloatArray
    microviscous_original: FloatArray
    reversal: int
    """Sample of point b (the internal loop starts)."""
    closure: int
    """Sample of point a: the original model pops its stacks at the end of this step, so its
    next sample is the first on the outer curve."""

    def largest_change(self, friction: FloatArray) -> float:
        """max |Ff[k+1] − Ff[k]| over the steps within ``FIG1_WINDOW`` of the closure."""
        half = max(1, round(FIG1_WINDOW / self.dt))
        lo, hi = max(self.closure - half, 0), min(self.closure + half, friction.size - 1)
        return float(np.max(np.abs(np.diff(friction[lo : hi + 1]))))


def loop_closure(dt: float) -> LoopClosureRun:
    """Simulates the Fig. 1 scenario at step ``dt`` with both models."""
    p = FIG1_PARAMS
    samples = round(FIG1_DURATION / dt)
    t = np.arange(samples, dtype=np.float64) * dt
    profile = PchipInterpolator(np.array(FIG1_KNOTS[0]) * FIG1_DURATION, FIG1_KNOTS[1])
    u = np.asarray(profile(t), dtype=np.float64)
    # Modified model: the Rust mass, stepped to read the hysteresis force from its state.
    system = MassSystem(p, mass=1.0)
    bank = MaxwellSlip(p.W or (), p.Delta or ())
    x_mod, f_mod, micro_mod = (np.empty(samples) for _ in range(3))
    for k, uk in enumerate(u.tolist()):
        f_mod[k], x_mod[k], v = system.step(uk, dt)
        state = system.state
        micro_mod[k] = f_mod[k] - bank.force(state.zeta[0], float(state.z[0])) - p.sigma2 * v
    # Original model on the same mass (numpy), with the stack memory.
    original = OriginalLeuvenMass(OriginalLeuven(p, depth=16), mass=1.0)
    x_org, f_org, micro_org = (np.empty(samples) for _ in range(3))
    sizes = np.empty(samples, dtype=int)
    for k, uk in enumerate(u.tolist()):
        sample = original.step(uk, dt)
        x_org[k], f_org[k], sizes[k] = original.x, sample.friction, sample.stack_size
        micro_org[k] = sample.friction - sample.hysteresis - p.sigma2 * original.v
    grows, shrinks = np.flatnonzero(np.diff(sizes) > 0), np.flatnonzero(np.diff(sizes) < 0)
    if grows.size < 2 or shrinks.size < 1:
        raise RuntimeError(f"the Fig. 1 profile made no internal loop at dt = {dt}")
    return LoopClosureRun(dt, t, u, x_mod, x_org, f_mod, f_org, micro_mod, micro_org,
                          reversal=int(grows[1]) + 1, closure=int(shrinks[0]) + 1)  # fmt: skip


def figure_1(out: Path, steps: Sequence[float] = FIG1_STEPS) -> FigureReport:
    runs = [loop_closure(dt) for dt in steps]
    run = runs[-1]
    drawing, axes = figure(2, 2, size=(12, 8))
    ms = 1e3
    for ax, (modified, original, label) in zip(
        axes.flat,
        [
            (run.x_modified * 1e6, run.x_original * 1e6, "position x [µm]"),
            (run.friction_modified, run.friction_original, "friction force Ff [N]"),
            (None, None, ""),
            (run.microviscous_modified, run.microviscous_original, "micro-viscous term σ1·dz/dt [N]"),
        ],
        strict=True,
    ):
        if modified is None:
            ax.plot(run.x_original * 1e6, run.friction_original, label="original Leuven model", linewidth=1.6)
            ax.plot(run.x_modified * 1e6, run.friction_modified, "--", label="modified model", linewidth=1.2)
            for k, name in ((run.reversal, "b"), (run.closure, "a")):
                ax.annotate(name, (run.x_original[k] * 1e6, run.friction_original[k]), fontsize=14,
                            xytext=(-14, 6), textcoords="offset points")  # fmt: skip
            ax.set(xlabel="position x [µm]", ylabel="friction force Ff [N]", title="Ff against position")
            ax.legend(loc="lower right")
            continue
        ax.plot(run.t * ms, original, label="original Leuven model", linewidth=1.6)
        ax.plot(run.t * ms, modified, "--", label="modified model", linewidth=1.2)
        for k, name in ((run.reversal, "b"), (run.closure, "a")):
            ax.axvline(run.t[k] * ms, color="grey", linewidth=0.6)
            ax.annotate(name, (run.t[k] * ms, ax.get_ylim()[1]), fontsize=14, xytext=(3, -16),
                        textcoords="offset points")  # fmt: skip
        ax.set(xlabel="time [ms]", ylabel=label, title=label.split(" [")[0] + " against time")
        ax.legend(loc="lower left")
    # Zoom on the closure: the original model's micro-viscous term jumps there.
    window = slice(max(run.closure - round(3e-3 / run.dt), 0), run.closure + round(3e-3 / run.dt))
    inset = axes[1, 1].inset_axes((0.62, 0.08, 0.35, 0.35))
    inset.plot(run.t[window] * ms, run.microviscous_original[window], ".-", markersize=2, linewidth=1)
    inset.plot(run.t[window] * ms, run.microviscous_modified[window], "--", linewidth=1)
    inset.set_title("zoom at a", fontsize=9)
    inset.tick_params(labelsize=7)
    drawing.suptitle(f"Fig. 1: a force on a mass closes an internal loop at a (dt = {run.dt * 1e6:g} µs)")
    drawing.tight_layout()
    path = save(drawing, out / FILES[0], dpi=110)
    report = FigureReport(path, [
        "Fig. 1, loop closure: largest |Ff[k+1] - Ff[k]| within 10 ms of point a",
        "| dt [s] | original Leuven [N] | modified [N] |",
        "|---:|---:|---:|",
    ])  # fmt: skip
    for r in runs:
        report.lines.append(
            f"| {r.dt:g} | {r.largest_change(r.friction_original):.3g} "
            f"| {r.largest_change(r.friction_modified):.3g} |"
        )
    return report


# --- Figs. 4 and 5 ------------------------------------------------------------------------------

#: The smooth transition curve of the stack implementation, and the deflection range it spans.
CURVE = TanhCurve(F_max=1.0, z_c=5e-6)
Z_MAX = 4.0 * CURVE.z_c
ELEMENTS = 10


def fitted_bank(curve: TanhCurve = CURVE, elements: int = ELEMENTS) -> tuple[FloatArray, FloatArray]:
    """The paper's fit: Δᵢ equally spaced up to the curve's range, Wᵢ by least squares (linear
    in W) on the virgin curve, each kept > 0."""
    delta = Z_MAX * np.arange(1, elements + 1) / elements
    z = np.linspace(0.0, 1.5 * Z_MAX, 400)
    basis = np.minimum(z[:, None] / delta[None, :], 1.0)
    target = np.array([curve.virgin(value) for value in z])
    fit = lsq_linear(basis, target, bounds=(1e-6, np.inf))
    return fit.x, delta


def _segments(points: Sequence[float], per_segment: int) -> FloatArray:
    """A piecewise-linear path through ``points``."""
    parts = [np.linspace(a, b, per_segment, endpoint=False) for a, b in pairwise(points)]
    return np.concatenate([*parts, [points[-1]]])


#: Two paths to point a (z = 0.6·Z_MAX after a reversal at −0.5·Z_MAX); the second makes an
#: extra internal loop (up to 0.3, back to −0.1) that is wiped out on the way to a.
PATH_1 = (0.0, 1.0, -0.5, 0.6)
PATH_2 = (0.0, 1.0, -0.5, 0.3, -0.1, 0.6)


def hysteresis_along(path: Sequence[float], w: FloatArray, delta: FloatArray,
                     curve: TanhCurve | MasingMaxwell = CURVE) -> tuple[FloatArray, ...]:  # fmt: skip
    """z along ``path`` (fractions of Z_MAX), and Fh of the stack and of the Maxwell-slip bank."""
    z = _segments([p * Z_MAX for p in path], 200)
    stack = StackHysteresis(curve, depth=16).run(z)
    bank = MaxwellSlip(tuple(w), tuple(delta))
    zeta = bank.relaxed()
    maxwell = np.empty_like(z)
    for k, value in enumerate(z.tolist()):
        maxwell[k] = bank.force(zeta, value)
        bank.commit(zeta, value)
    return z, stack, maxwell


def figure_4_5(out: Path) -> FigureReport:
    w, delta = fitted_bank()
    runs = [hysteresis_along(path, w, delta) for path in (PATH_1, PATH_2)]
    exact = [hysteresis_along(path, w, delta, MasingMaxwell(w, delta)) for path in (PATH_1, PATH_2)]
    drawing, axes = figure(1, 3, size=(15, 4.6))
    names, styles = ("path 1", "path 2 (extra loop)"), ("-", "--")
    for (z, stack, maxwell), name, style in zip(runs, names, styles, strict=True):
        axes[0].plot(np.arange(z.size), z * 1e6, style, label=name)
        axes[1].plot(z * 1e6, stack, style, label=name)
        axes[2].plot(z * 1e6, maxwell, style, label=name)
    za = PATH_1[-1] * Z_MAX * 1e6
    axes[0].set(xlabel="sample", ylabel="deflection z [µm]", title="Fig. 4: z against time")
    axes[1].set(
        xlabel="deflection z [µm]", ylabel="Fh [N]", title="Fig. 5 top: stack implementation (tanh curve)"
    )
    axes[2].set(
        xlabel="deflection z [µm]", ylabel="Fh [N]", title=f"Fig. 5 bottom: Maxwell slip, {ELEMENTS} elements"
    )
    for ax, index in ((axes[1], 1), (axes[2], 2)):
        ax.annotate("a", (za, runs[0][index][-1]), fontsize=14, xytext=(6, -4), textcoords="offset points")
        ax.plot([za], [runs[0][index][-1]], "ko")
    for ax in axes:
        ax.legend(loc="upper left")
        ax.grid(alpha=0.3)
    drawing.tight_layout()
    path = save(drawing, out / FILES[1], dpi=110)
    difference = max(float(np.max(np.abs(s - m))) for _, s, m in runs)
    difference_exact = max(float(np.max(np.abs(s - m))) for _, s, m in exact)
    lines = [
        f"Figs. 4/5, nonlocal memory: stack implementation (tanh curve, F_max = {CURVE.F_max} N, "
        f"z_c = {CURVE.z_c * 1e6:g} µm) vs Maxwell slip with {ELEMENTS} fitted elements",
        f"  largest |Fh_stack - Fh_maxwell| over both paths: {difference:.3g} N "
        f"({100 * difference / CURVE.F_max:.3g} % of F_max; the piecewise-linear approximation)",
        "  same, stack with the Masing curve of the 10 elements (the same hysteresis): "
        f"{difference_exact:.3g} N",
        f"  Fh at point a (z = {za:g} µm): stack {runs[0][1][-1]:.6f} / {runs[1][1][-1]:.6f} N, "
        f"Maxwell slip {runs[0][2][-1]:.6f} / {runs[1][2][-1]:.6f} N (path 1 / path 2)",
    ]
    return FigureReport(path, lines)


# --- Free response ------------------------------------------------------------------------------


@dataclass(frozen=True)
class FreeResponse:
    t: FloatArray
    x_original: FloatArray
    x_modified: FloatArray
    stack_size: NDArray[np.int_]
    reversals: int
    overflow: StackOverflowError | None
    elements: int


def free_response(dt: float = 1e-4, duration: float = 0.3, depth: int = FREE_DEPTH) -> FreeResponse:
    """Both models from x = FREE_START at rest, no applied force, until the stack overflows."""
    p = FREE_PARAMS
    samples = round(duration / dt)
    system = MassSystem(p, mass=FREE_MASS, stiffness=FREE_STIFFNESS)
    system.place(FREE_START, 0.0)
    modified = system.run(np.zeros(samples), dt)
    original = OriginalLeuvenMass(OriginalLeuven(p, depth=depth), mass=FREE_MASS, stiffness=FREE_STIFFNESS,
                                  position=FREE_START)  # fmt: skip
    x, sizes = [], []
    overflow = None
    for _ in range(samples):
        try:
            sample = original.step(0.0, dt)
        except StackOverflowError as error:
            overflow = error
            break
        x.append(original.x)
        sizes.append(sample.stack_size)
    v = np.diff(np.concatenate(([FREE_START], x)))
    reversals = int(np.count_nonzero(np.diff(np.sign(v[v != 0])) != 0))
    return FreeResponse(np.arange(1, samples + 1, dtype=np.float64) * dt, np.array(x), modified.position,
                        np.array(sizes), reversals, overflow, system.elements)  # fmt: skip


def figure_free_response(out: Path) -> FigureReport:
    run = free_response()
    n = run.x_original.size
    drawing, (position, memory) = figure(2, 1, size=(11, 7), sharex=True)
    ms = 1e3
    position.plot(run.t * ms, run.x_modified * 1e6, label="modified model (Maxwell slip)", linewidth=1.0)
    position.plot(
        run.t[:n] * ms, run.x_original * 1e6, "--", label="original Leuven model (stacks)", linewidth=1.0
    )
    position.set(ylabel="position x [µm]", title="Free response of a mass-spring system with friction, "
                 f"released at x = {FREE_START * 1e6:g} µm")  # fmt: skip
    memory.step(run.t[:n] * ms, run.stack_size, where="post", label="original: extrema on the stacks")
    memory.axhline(run.elements, color="C1", label=f"Maxwell slip: {run.elements} element positions")
    memory.axhline(
        2 * FREE_DEPTH, color="grey", linestyle=":", label=f"stack capacity (2 × depth {FREE_DEPTH})"
    )
    if run.overflow is not None:
        memory.axvline(run.t[n] * ms, color="red", linewidth=0.8)
        memory.annotate(
            "overflow", (run.t[n] * ms, FREE_DEPTH), color="red", xytext=(4, 0), textcoords="offset points"
        )
    memory.set(xlabel="time [ms]", ylabel="memory [numbers]")
    for ax in (position, memory):
        ax.legend(loc="upper right")
        ax.grid(alpha=0.3)
    drawing.tight_layout()
    path = save(drawing, out / FILES[2], dpi=110)
    lines = [
        f"Free response: m = {FREE_MASS} kg, k = {FREE_STIFFNESS:g} N/m, released at {FREE_START * 1e6:g} µm"
    ]
    if run.overflow is None:
        lines.append(f"  no overflow within {run.t[-1]:g} s ({run.reversals} reversals)")
    else:
        lines.append(f"  original model: {run.overflow} (t = {run.t[n]:.4f} s, "
                     f"after {run.reversals} reversals without a closed loop)")  # fmt: skip
    lines.append(f"  Maxwell slip memory: {run.elements} numbers throughout, no limit on reversals")
    return FigureReport(path, lines)


#: The files :func:`write_figures` writes into its folder.
FILES = ("fig1_loop_closure.png", "fig4_5_nonlocal_memory.png", "free_response_memory.png")


def write_figures(out: Path, quick: bool = False) -> list[FigureReport]:
    """Writes the three figures into ``out`` (created if needed); ``quick`` uses two coarser
    step sizes for Fig. 1, for tests."""
    out.mkdir(parents=True, exist_ok=True)
    steps = (4e-4, 1e-4) if quick else FIG1_STEPS
    return [figure_1(out, steps), figure_4_5(out), figure_free_response(out)]
