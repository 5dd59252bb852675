"""Closed-loop proof of the compensator: a simulated positioning stage under PID control.

The stage is a mass on the friction model with "true" parameters (:data:`TRUE`), simulated by
:class:`leuven_rt.MassSystem` (Rust, backward Euler on mass and friction together) at
``plant_rate``, under a force held over each control period (zero-order hold). The controller
runs at 1 kHz on the measured position: the true position plus Gaussian noise, quantized by the
encoder. It tracks x_d = A·(1 − cos 2πft), which reverses every half period, with a PID with
a filtered derivative, acceleration feedforward with the nominal mass, and one of four friction
compensations, all with the compensator's parameters (:data:`MODEL`, which differ from the
true ones by 10–25 %):

- ``none``;
- ``coulomb``: Fc·sgn(v) of the planned motion (the classic);
- ``leuven_feedforward``: :class:`leuven_rt.Compensator` fed the desired velocity;
- ``leuven_observer``: :class:`leuven_rt.Compensator` fed the measured position.

The planned velocity of a control period is its mean, (x_d(t+dt) − x_d(t))/dt: the force is
held over the period, so the mean velocity is what it should answer to.

:func:`compare` runs the four and measures the tracking error e = x_d − x (true position):
RMS, max, and the peak error in the window after each reversal (the quadrant glitch).
:func:`plot` draws the errors; :func:`report` prints the table.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._plot import figure, save
from .._typing import FloatArray
from ..compensation import Compensator
from ..errors import InputError, shown
from ..mechanics import MassSystem
from ..params import Params

#: The stage's friction: a small linear-motor stage on a ball or roller guide.
TRUE = Params(
    Fc=2.0, Fs=3.0, Vs=2e-3, delta=2.0, n=2.0, sigma1=50.0, sigma2=5.0,
    W=[1.0, 1.0, 1.0, 1.0], Delta=[2e-6, 5e-6, 1e-5, 2e-5],
)  # fmt: skip
#: The compensator's identified model: levels 10–13 % low, Stribeck velocity 25 % high,
#: elements 10 % weaker with 25 % larger break deflections, viscous coefficient 20 % low.
MODEL = Params(
    Fc=1.8, Fs=2.6, Vs=2.5e-3, delta=2.0, n=2.0, sigma1=40.0, sigma2=4.0,
    W=[0.9, 0.9, 0.9, 0.9], Delta=[2.5e-6, 6.25e-6, 1.25e-5, 2.5e-5],
)  # fmt: skip

COMPENSATIONS = ("none", "coulomb", "leuven_feedforward", "leuven_observer")


@dataclass(frozen=True)
class Scenario:
    """Everything that defines one closed-loop run (SI units)."""

    mass: float = 2.0
    """Moving mass [kg]; also the controller's nominal mass for acceleration feedforward."""
    rate: float = 1000.0
    """Control rate [Hz]."""
    plant_rate: float = 10_000.0
    """Simulation rate of the stage [Hz], a multiple of ``rate``."""
    amplitude: float = 2e-3
    """Amplitude A of the trajectory [m]."""
    frequency: float = 1.0
    """Frequency f of the trajectory [Hz]: reversals every 1/(2f) s."""
    duration: float = 4.0
    """Length of the run [s]."""
    encoder_resolution: float = 1e-7
    """Quantization step of the measured position [m]."""
    noise: float = 5e-8
    """Standard deviation of the position noise before quantization [m]."""
    bandwidth: float = 20.0
    """The PID places the three closed-loop poles of the rigid mass at -2π·bandwidth [Hz]."""
    derivative_filter: float = 300.0
    """Cut-off of the first-order filter on the derivative [Hz]."""
    glitch_window: float = 0.05
    """Length of the window after each reversal in which the glitch is measured [s]."""
    true: Params = field(default=TRUE)
    model: Params = field(default=MODEL)
    seed: int = 0

    def __post_init__(self) -> None:
        for name in ("mass", "rate", "plant_rate", "amplitude", "frequency", "duration", "bandwidth",
                     "derivative_filter", "glitch_window", "encoder_resolution"):  # fmt: skip
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and np.isfinite(value) and value > 0):
                raise InputError(
                    f"`{name}` must be a finite number > 0, got {shown(value)!r}",
                    kind="not_positive",
                    field=name,
                    value=value,
                )
        if not (np.isfinite(self.noise) and self.noise >= 0):
            raise InputError(
                f"`noise` must be finite and >= 0, got {shown(self.noise)!r}",
                kind="negative",
                field="noise",
                value=self.noise,
            )
        ratio = self.plant_rate / self.rate
        if abs(ratio - round(ratio)) > 1e-9 or round(ratio) < 1:
            raise InputError(
                f"`plant_rate` must be a multiple of `rate`, got {self.plant_rate} and {self.rate}",
                kind="not_integer",
                field="plant_rate",
                value=self.plant_rate,
                bound=self.rate,
            )


@dataclass(frozen=True)
class Run:
    """One closed-loop run: signals at the control samples."""

    compensation: str
    t: FloatArray
    desired: FloatArray
    position: FloatArray
    """True position at the sample [m]."""
    command: FloatArray
    """Total force applied over the following period [N]."""
    compensation_force: FloatArray
    friction: FloatArray
    """The stage's true friction, mean over the following period [N]."""

    @property
    def error(self) -> FloatArray:
        return self.desired - self.position


@dataclass(frozen=True)
class Metrics:
    """Tracking-error figures of one run [m]."""

    rms: float
    max: float
    glitch: float
    """Mean over the reversals of the peak |e| in the window after each."""


@dataclass(frozen=True)
class Comparison:
    scenario: Scenario
    runs: dict[str, Run]
    metrics: dict[str, Metrics]
    reversals: FloatArray

    def ratio(self, baseline: str, compensation: str) -> float:
        """How many times smaller the RMS error with ``compensation`` is than with ``baseline``."""
        return self.metrics[baseline].rms / self.metrics[compensation].rms


def trajectory(scenario: Scenario, t: FloatArray) -> tuple[FloatArray, ...]:
    """Desired position, velocity and acceleration of x_d = A·(1 − cos 2πft) at times ``t``."""
    w = 2.0 * np.pi * scenario.frequency
    a = scenario.amplitude
    return a * (1.0 - np.cos(w * t)), a * w * np.sin(w * t), a * w * w * np.cos(w * t)


def gains(scenario: Scenario) -> tuple[float, float, float]:
    """Kp, Ki, Kd placing m·s³ + Kd·s² + Kp·s + Ki = m·(s + ω)³, ω = 2π·bandwidth."""
    w = 2.0 * np.pi * scenario.bandwidth
    m = scenario.mass
    return 3.0 * m * w * w, m * w**3, 3.0 * m * w


def simulate(scenario: Scenario, compensation: str) -> Run:
    """One closed-loop run with the given compensation (one of :data:`COMPENSATIONS`)."""
    if compensation not in COMPENSATIONS:
        raise InputError(
            f"`compensation` must be one of {COMPENSATIONS}, got {shown(compensation)!r}",
            kind="invalid_choice",
            field="compensation",
            value=compensation,
            expected=COMPENSATIONS,
        )
    dt = 1.0 / scenario.rate
    substeps = round(scenario.plant_rate / scenario.rate)
    plant_dt = dt / substeps
    samples = round(scenario.duration * scenario.rate)
    t = np.arange(samples + 1, dtype=np.float64) * dt
    desired, _, acceleration = trajectory(scenario, t)
    planned_velocity = np.diff(desired) / dt  # mean velocity of each control period
    rng = np.random.default_rng(scenario.seed)
    noise = rng.normal(0.0, scenario.noise, samples) if scenario.noise > 0 else np.zeros(samples)

    stage = MassSystem(scenario.true, scenario.mass)
    compensator: Compensator | None = None
    if compensation == "leuven_feedforward":
        compensator = Compensator(scenario.model, dt, "feedforward")
    elif compensation == "leuven_observer":
        compensator = Compensator(scenario.model, dt, "observer")
    kp, ki, kd = gains(scenario)
    alpha = float(np.exp(-2.0 * np.pi * scenario.derivative_filter * dt))
    resolution = scenario.encoder_resolution
    fc = scenario.model.Fc

    position = np.zeros(samples)
    command = np.zeros(samples)
    compensation_force = np.zeros(samples)
    friction = np.zeros(samples)
    x = 0.0
    integral = derivative = previous_error = 0.0
    for k in range(samples):
        measured = resolution * round((x + noise[k]) / resolution)
        error = desired[k] - measured
        integral += ki * error * dt
        if k > 0:
            derivative = alpha * derivative + (1.0 - alpha) * kd * (error - previous_error) / dt
        previous_error = error
        v_plan = planned_velocity[k]
        if compensation == "coulomb":
            force = fc * float(np.sign(v_plan))
        elif compensation == "leuven_feedforward":
            force = compensator.step(v_plan)  # type: ignore[union-attr]
        elif compensation == "leuven_observer":
            force = compensator.step(measured)  # type: ignore[union-attr]
        else:
            force = 0.0
        u = scenario.mass * acceleration[k] + kp * error + integral + derivative + force
        position[k] = x
        command[k] = u
        compensation_force[k] = force
        total = 0.0
        for _ in range(substeps):
            ff, x, _ = stage.step(u, plant_dt)
            total += ff
        friction[k] = total / substeps
    return Run(compensation, t[:-1], desired[:-1], position, command, compensation_force, friction)


def reversal_times(scenario: Scenario) -> FloatArray:
    """Times where the desired velocity changes sign (multiples of the half period, t > 0)."""
    half = 0.5 / scenario.frequency
    return np.arange(half, scenario.duration - 1e-12, half)


def measure(run: Run, scenario: Scenario, reversals: FloatArray) -> Metrics:
    error = np.abs(run.error)
    peaks = [
        float(error[(run.t >= start) & (run.t < start + scenario.glitch_window)].max()) for start in reversals
    ]
    return Metrics(
        rms=float(np.sqrt(np.mean(run.error**2))),
        max=float(error.max()),
        glitch=float(np.mean(peaks)) if peaks else float("nan"),
    )


def compare(scenario: Scenario | None = None) -> Comparison:
    """Runs every compensation on the same scenario (same noise) and measures the errors."""
    scenario = scenario or Scenario()
    reversals = reversal_times(scenario)
    runs = {name: simulate(scenario, name) for name in COMPENSATIONS}
    metrics = {name: measure(run, scenario, reversals) for name, run in runs.items()}
    return Comparison(scenario, runs, metrics, reversals)


def report(comparison: Comparison) -> str:
    """A markdown table of the errors and the ratios against none and Coulomb-only."""
    s = comparison.scenario
    kp, ki, kd = gains(s)
    lines = [
        f"Stage: m = {s.mass:g} kg; true friction Fc = {s.true.Fc:g} N, Fs = {s.true.Fs:g} N, "
        f"Vs = {s.true.Vs * 1e3:g} mm/s, sigma2 = {s.true.sigma2:g} N*s/m, {s.true.elements} Maxwell-slip "
        f"elements (sum W = {sum(s.true.W or ()):g} N); simulated at {s.plant_rate:g} Hz.",
        f"Compensator's model: Fc = {s.model.Fc:g} N, Fs = {s.model.Fs:g} N, Vs = {s.model.Vs * 1e3:g} mm/s, "
        f"sigma2 = {s.model.sigma2:g} N*s/m, sum W = {sum(s.model.W or ()):g} N, Delta x1.25.",
        f"Control: {s.rate:g} Hz PID (poles at -2π·{s.bandwidth:g} Hz: Kp = {kp:.3g} N/m, "
        f"Ki = {ki:.3g} N/(m*s), Kd = {kd:.3g} N*s/m, derivative filtered at {s.derivative_filter:g} Hz) "
        "+ m·a_d feedforward; "
        f"encoder {s.encoder_resolution * 1e9:g} nm, noise {s.noise * 1e9:g} nm rms.",
        f"Trajectory: x_d = {s.amplitude * 1e3:g} mm·(1 − cos 2π·{s.frequency:g} Hz·t) over {s.duration:g} s "
        f"(peak {s.amplitude * 2 * np.pi * s.frequency * 1e3:.3g} mm/s, "
        f"{len(comparison.reversals)} reversals); "
        f"glitch = mean peak |e| in the {s.glitch_window * 1e3:g} ms after each reversal.",
        "",
        "| compensation | RMS error [µm] | max error [µm] | reversal glitch [µm] "
        "| RMS ratio vs none | RMS ratio vs Coulomb |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for name in COMPENSATIONS:
        m = comparison.metrics[name]
        lines.append(
            f"| {name} | {m.rms * 1e6:.3f} | {m.max * 1e6:.3f} | {m.glitch * 1e6:.3f} | "
            f"{comparison.ratio('none', name):.2f}× | {comparison.ratio('coulomb', name):.2f}× |"
        )
    return "\n".join(lines)


def plot(comparison: Comparison, path: str | Path) -> Path:
    """Tracking error of every compensation over the run, and zoomed on one reversal."""
    drawing, (whole, zoom) = figure(2, 1, size=(9, 7), layout="constrained")
    reversal = comparison.reversals[len(comparison.reversals) // 2]
    for name, run in comparison.runs.items():
        whole.plot(
            run.t, run.error * 1e6, label=f"{name} (RMS {comparison.metrics[name].rms * 1e6:.2f} µm)", lw=0.9
        )
        window = (run.t > reversal - 0.05) & (run.t < reversal + 0.15)
        zoom.plot((run.t[window] - reversal) * 1e3, run.error[window] * 1e6, label=name, lw=1.2)
    for t in comparison.reversals:
        whole.axvline(t, color="0.85", lw=0.8, zorder=0)
    whole.set(xlabel="t [s]", ylabel="tracking error [µm]", title="PID at 1 kHz on a stage with friction")
    whole.legend(fontsize=8, loc="upper right")
    zoom.axvline(0.0, color="0.6", lw=0.8)
    zoom.set(xlabel=f"time after the reversal at t = {reversal:.2f} s [ms]", ylabel="tracking error [µm]",
             title="around one velocity reversal (quadrant glitch)")  # fmt: skip
    zoom.legend(fontsize=8)
    return save(drawing, path, dpi=120)


#: The file :func:`run` writes into its folder.
FILE = "closed_loop.png"


def run(out: Path) -> str:
    """``leuven-rt control``: the four compensations compared, the table and the figure
    ``closed_loop.png`` in ``out``."""
    comparison = compare()
    return f"{report(comparison)}\nfigure: {plot(comparison, out / FILE)}"
