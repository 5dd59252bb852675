"""Closed-loop proof of the compensator: a simulated positioning stage under PID control.

The stage is a mass on the friction model with "true" parameters (:data:`TRUE`), simulated by
:class:`leuven_rt.MassSystem` (Rust, backward Euler on mass and friction together) at
``plant_rate``, under a force held over each control period (zero-order hold). The controller
runs at 1 kHz on the measured position: the true position plus Gaussian noise, quantized by the
encoder. It tracks a planned trajectory (:class:`Trajectory`) with a PID with a filtered
derivative, acceleration feedforward with the nominal mass, and one of the friction
compensations of :data:`COMPENSATIONS`:

- ``none``;
- ``coulomb``: Fc·sgn(v) of the planned motion (the classic), Fc of the hand-set model;
- ``leuven_feedforward``, ``leuven_observer``: :class:`leuven_rt.Compensator` on the hand-set
  model (:data:`MODEL`, 10–25 % off the true parameters), fed the planned velocity or the
  measured position;
- ``identified_feedforward``, ``identified_observer``: the same, on the model file that
  :func:`leuven_rt.identify` wrote from a log of the stage (:func:`identify_stage`).

The planned velocity of a control period is its mean, (x_d(t+dt) − x_d(t))/dt: the force is
held over the period, so the mean velocity is what it should answer to.

**The identification.** The stage is logged on a trajectory of its own
(:func:`identification_trajectory`: presliding moves of 2–30 µm, constant-speed legs from an
eighth of the Stribeck velocity to 2.5 times the evaluation's peak speed, reversals with and
without a dwell, two sine cycles), under the same PID without compensation, as a user logs a
machine that has no friction model yet. The log holds what the controller has
(:func:`identification_log`): the encoder reading (quantized, noisy), no velocity, and the
actuator force u, the command held over the period that follows the reading, as a controller's
log pairs them. ``identify`` names what the log supports from the baseline ``coulomb,viscous``;
it is never given the true parameters.

The force is u rather than u − m·a_d (the command less its mass feedforward): the log then needs
no nominal mass, and ``identify`` names the inertia itself (a compensator leaves the measurement
terms out). u − m·a_d keeps m·(ẍ − a_d), the mass times the tracking error's acceleration, which
peaks at the reversals where the friction is read.

:func:`compare` runs the compensations on the evaluation trajectory (:func:`evaluation_trajectory`:
x_d = A·(1 − cos 2πft), which reverses every half period; same noise for all) and measures the
tracking error e = x_d − x (true position): RMS, max, and the peak error in the window after
each reversal (the quadrant glitch). :func:`plot` draws the errors; :func:`report` prints the
table and what the identification named.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._plot import figure, save
from .._typing import FloatArray, Mode
from ..compensation import Compensator
from ..data.records import MotionData
from ..discrepancy.identify import Identification, identify
from ..errors import InputError, shown
from ..mechanics import MassSystem
from ..modelfile import ModelFile
from ..params import Params
from ..prediction import predict
from ..progress import Progress

#: The stage's friction: a small linear-motor stage on a ball or roller guide.
TRUE = Params(
    Fc=2.0, Fs=3.0, Vs=2e-3, delta=2.0, n=2.0, sigma1=50.0, sigma2=5.0,
    W=[1.0, 1.0, 1.0, 1.0], Delta=[2e-6, 5e-6, 1e-5, 2e-5],
)  # fmt: skip
#: The compensator's hand-set model: levels 10–13 % low, Stribeck velocity 25 % high,
#: elements 10 % weaker with 25 % larger break deflections, viscous coefficient 20 % low.
MODEL = Params(
    Fc=1.8, Fs=2.6, Vs=2.5e-3, delta=2.0, n=2.0, sigma1=40.0, sigma2=4.0,
    W=[0.9, 0.9, 0.9, 0.9], Delta=[2.5e-6, 6.25e-6, 1.25e-5, 2.5e-5],
)  # fmt: skip

#: The compensations on the hand-set model (and none), which need no identification.
HAND_SET = ("none", "coulomb", "leuven_feedforward", "leuven_observer")
#: The compensations on the identified model file.
IDENTIFIED = ("identified_feedforward", "identified_observer")
COMPENSATIONS = HAND_SET + IDENTIFIED
#: The baseline the identification starts from: what a user knows without a fit.
BASELINE = ("coulomb", "viscous")


#: The fields of :class:`Scenario` the identification log depends on.
STAGE_FIELDS = ("mass", "rate", "plant_rate", "encoder_resolution", "noise", "bandwidth", "derivative_filter",
                "true", "seed")  # fmt: skip


@dataclass(frozen=True)
class Scenario:
    """Everything that defines one closed-loop study (SI units)."""

    mass: float = 2.0
    """Moving mass [kg]; also the controller's nominal mass for acceleration feedforward."""
    rate: float = 1000.0
    """Control rate [Hz]; the identification log is sampled at it too."""
    plant_rate: float = 10_000.0
    """Simulation rate of the stage [Hz], a multiple of ``rate``."""
    amplitude: float = 2e-3
    """Amplitude A of the evaluation trajectory [m]."""
    frequency: float = 1.0
    """Frequency f of the evaluation trajectory [Hz]: reversals every 1/(2f) s."""
    duration: float = 4.0
    """Length of the evaluation run [s]."""
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
    """Seed of the evaluation run's position noise (the identification log's is ``seed + 1``)."""

    def stage(self) -> tuple[object, ...]:
        """What the identification log depends on: the stage, its loop and sensor, and the seed
        (not the hand-set model, nor the evaluation trajectory)."""
        return tuple(getattr(self, name) for name in STAGE_FIELDS)

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
class Trajectory:
    """A planned motion at the control samples: what the loop tracks."""

    t: FloatArray
    x: FloatArray
    """Desired position [m], one more sample than the run (the last period's end)."""
    a: FloatArray
    """Planned acceleration [m/s²], for the mass feedforward."""
    reversals: FloatArray
    """Times where the planned velocity changes sign [s]."""


@dataclass(frozen=True)
class Run:
    """One closed-loop run: signals at the control samples."""

    compensation: str
    t: FloatArray
    desired: FloatArray
    position: FloatArray
    """True position at the sample [m]."""
    measured: FloatArray
    """The encoder's reading at the sample (noisy, quantized) [m]: what the controller sees."""
    command: FloatArray
    """Total force applied over the following period [N]."""
    feedforward: FloatArray
    """The mass feedforward m·a_d in the command [N]."""
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


@dataclass(frozen=True, eq=False)
class StageIdentification:
    """The stage logged on the identification trajectory and what ``identify`` made of the log."""

    scenario: Scenario
    run: Run
    log: MotionData
    identification: Identification

    @property
    def named(self) -> list[str]:
        """The effects ``identify`` added to the baseline."""
        return list(self.identification.diagnosis.named_effects)

    @property
    def rms(self) -> float:
        """The model file's rms error on its own log [N]."""
        return self.identification.diagnosis.rms_after

    def text(self) -> str:
        diagnosis = self.identification.diagnosis
        friction = self.identification.params
        return (
            f"Identification log: {diagnosis.samples} samples at {1.0 / self.log.dt:g} Hz of the stage under "
            f"the PID without compensation (encoder position, no velocity, actuator force); "
            f"from the baseline {', '.join(BASELINE)}, identify named {', '.join(self.named) or 'nothing'}; "
            f"rms on its own log {diagnosis.rms_before:.3g} N (baseline) -> {self.rms:.3g} N "
            f"(noise {diagnosis.noise_std:.3g} N); the model is driven by "
            f"{diagnosis.reconstruction['description']}; Fc = {friction.Fc:.3g} N, Fs = {friction.Fs:.3g} N, "
            f"Vs = {friction.Vs * 1e3:.3g} mm/s, sigma2 = {friction.sigma2:.3g} N*s/m, "
            f"{friction.elements} elements (sum W = {sum(friction.W or ()):.3g} N)."
        )


@dataclass(frozen=True, eq=False)
class Comparison:
    scenario: Scenario
    runs: dict[str, Run]
    metrics: dict[str, Metrics]
    reversals: FloatArray
    identified: StageIdentification | None
    """The identification behind the ``identified_*`` runs (None when none was run)."""

    def ratio(self, baseline: str, compensation: str) -> float:
        """How many times smaller the RMS error with ``compensation`` is than with ``baseline``."""
        return self.metrics[baseline].rms / self.metrics[compensation].rms


def evaluation_trajectory(scenario: Scenario) -> Trajectory:
    """x_d = A·(1 − cos 2πft) over the scenario's duration, reversing every half period."""
    samples = round(scenario.duration * scenario.rate)
    t = np.arange(samples + 1, dtype=np.float64) * (1.0 / scenario.rate)
    w = 2.0 * np.pi * scenario.frequency
    a = scenario.amplitude
    half = 0.5 / scenario.frequency
    return Trajectory(
        t=t,
        x=a * (1.0 - np.cos(w * t)),
        a=a * w * w * np.cos(w * t),
        reversals=np.arange(half, scenario.duration - 1e-12, half),
    )


#: The identification trajectory's first moves, after a rest: (distance [m], speed [m/s], dwell
#: after [s]), each in the direction opposite to the one before; presliding moves of growing
#: amplitude, across the elements' break deflections.
PRESLIDING_MOVES = tuple((d * 1e-6, 1e-4, 0.05) for d in (2.0, 2.0, 5.0, 5.0, 12.0, 12.0, 30.0, 30.0))
#: Then a leg out and one back at each of these speeds [m/s], from an eighth of this stage's
#: Stribeck velocity to 2.5 times the evaluation's peak speed (the Stribeck curve and the viscous
#: slope), a dwell of 0.1 s at the reversals of every other speed.
SLIDING_SPEEDS = (2.5e-4, 5e-4, 1e-3, 2e-3, 4e-3, 8e-3, 1.6e-2, 3.2e-2)
#: Seconds at constant speed on each sliding leg.
CRUISE = 0.3
#: Largest planned acceleration of the identification trajectory's legs [m/s²].
ACCELERATION = 0.5
#: Its last two cycles: x = A·(1 − cos 2πft), of another amplitude A [m] and frequency f [Hz]
#: than the evaluation's.
SINE = (1e-3, 2.0)


def _leg(distance: float, speed: float, dt: float) -> FloatArray:
    """Velocity samples of one move of ``distance`` (signed) at peak ``speed``: raised-cosine
    ramps with at most :data:`ACCELERATION`, the speed lowered when the move is too short."""
    length = abs(distance)
    ramp = max(speed * math.pi / (2.0 * ACCELERATION), 10 * dt)
    if length < speed * ramp:
        speed = math.sqrt(length * 2.0 * ACCELERATION / math.pi)
        ramp = max(speed * math.pi / (2.0 * ACCELERATION), 10 * dt)
        speed = min(speed, length / ramp)
    cruise = length / speed - ramp
    up = 0.5 * (1.0 - np.cos(np.pi * np.arange(round(ramp / dt)) / round(ramp / dt)))
    profile = np.concatenate((up, np.ones(round(cruise / dt)), up[::-1]))
    # The samples are rounded to the control period: scale to the exact distance.
    return np.asarray(math.copysign(length, distance) * profile / (profile.sum() * dt), dtype=np.float64)


def identification_trajectory(scenario: Scenario) -> Trajectory:
    """The rich excitation the stage is logged on for :func:`identify_stage` (module
    documentation): presliding moves, constant-speed legs over two decades, two sine cycles."""
    dt = 1.0 / scenario.rate
    pieces = [np.zeros(round(0.3 / dt))]
    moves = list(PRESLIDING_MOVES)
    for index, speed in enumerate(SLIDING_SPEEDS):
        dwell = 0.1 if index % 2 else 0.0
        moves += [(speed * CRUISE, speed, dwell)] * 2
    direction = 1.0
    for distance, speed, dwell in moves:
        pieces += [_leg(direction * distance, speed, dt), np.zeros(round(dwell / dt) + 1)]
        direction = -direction
    amplitude, frequency = SINE
    w = 2.0 * np.pi * frequency
    cycles = np.arange(round(2.0 / (frequency * dt))) * dt
    pieces += [amplitude * w * np.sin(w * cycles), np.zeros(round(0.3 / dt))]
    v = np.concatenate(pieces)
    x = np.concatenate(([0.0], np.cumsum(v) * dt))
    t = np.arange(x.size, dtype=np.float64) * dt
    # The planned velocity of a period is v[k]; its acceleration the central difference.
    a = np.gradient(np.concatenate((v, [0.0])), dt)
    moving = np.flatnonzero(v != 0.0)
    signs = np.sign(v[moving])
    reversals = t[moving[1:][signs[1:] != signs[:-1]]]
    return Trajectory(t=t, x=x, a=a, reversals=reversals)


def gains(scenario: Scenario) -> tuple[float, float, float]:
    """Kp, Ki, Kd placing m·s³ + Kd·s² + Kp·s + Ki = m·(s + ω)³, ω = 2π·bandwidth."""
    w = 2.0 * np.pi * scenario.bandwidth
    m = scenario.mass
    return 3.0 * m * w * w, m * w**3, 3.0 * m * w


def _compensator(
    scenario: Scenario, compensation: str, identified: ModelFile | None, x: float
) -> Compensator | None:
    """The compensator a compensation runs, or None for ``none`` and ``coulomb``."""
    check_compensations([compensation], "compensation")
    if compensation in ("none", "coulomb"):
        return None
    dt = 1.0 / scenario.rate
    mode: Mode = "observer" if compensation.endswith("observer") else "feedforward"
    if compensation in HAND_SET:
        return Compensator(scenario.model, dt, mode)
    if identified is None:
        raise InputError(
            f"`identified` must be the identified model file for {compensation!r}, got None",
            kind="missing",
            field="identified",
            value=None,
        )
    # The file's own terms (a level, a position force) are placed from the start position.
    return Compensator(identified, dt, mode, x=x)


def check_compensations(names: Sequence[str], argument: str) -> None:
    """Refuses, naming ``argument``, a name that is not one of :data:`COMPENSATIONS`."""
    what = f"`{argument}` must be one of" if argument == "compensation" else f"`{argument}` must be among"
    for name in names:
        if name not in COMPENSATIONS:
            raise InputError(
                f"{what} {COMPENSATIONS}, got {shown(name)!r}",
                kind="invalid_choice",
                field=argument,
                value=name,
                expected=COMPENSATIONS,
            )


def simulate(
    scenario: Scenario,
    compensation: str,
    path: Trajectory | None = None,
    identified: ModelFile | None = None,
    seed: int | None = None,
) -> Run:
    """One closed-loop run along ``path`` (default: the evaluation trajectory) with the given
    compensation (one of :data:`COMPENSATIONS`; the ``identified_*`` ones run the model file
    ``identified``). ``seed``: of the position noise (default: the scenario's)."""
    path = path if path is not None else evaluation_trajectory(scenario)
    compensator = _compensator(scenario, compensation, identified, float(path.x[0]))
    dt = 1.0 / scenario.rate
    substeps = round(scenario.plant_rate / scenario.rate)
    plant_dt = dt / substeps
    samples = path.t.size - 1
    planned_velocity = np.diff(path.x) / dt  # mean velocity of each control period
    rng = np.random.default_rng(scenario.seed if seed is None else seed)
    noise = rng.normal(0.0, scenario.noise, samples) if scenario.noise > 0 else np.zeros(samples)

    stage = MassSystem(scenario.true, scenario.mass)
    stage.place(float(path.x[0]), 0.0)
    kp, ki, kd = gains(scenario)
    alpha = float(np.exp(-2.0 * np.pi * scenario.derivative_filter * dt))
    resolution = scenario.encoder_resolution
    fc = scenario.model.Fc
    observer = compensation.endswith("observer")

    position, measured, command, feedforward, compensation_force, friction = (
        np.zeros(samples) for _ in range(6)
    )
    x = float(path.x[0])
    integral = derivative = previous_error = 0.0
    for k in range(samples):
        reading = resolution * round((x + noise[k]) / resolution)
        error = path.x[k] - reading
        integral += ki * error * dt
        if k > 0:
            derivative = alpha * derivative + (1.0 - alpha) * kd * (error - previous_error) / dt
        previous_error = error
        v_plan = planned_velocity[k]
        if compensator is not None:
            force = compensator.step(reading if observer else v_plan)
        elif compensation == "coulomb":
            force = fc * float(np.sign(v_plan))
        else:
            force = 0.0
        mass_force = scenario.mass * path.a[k]
        u = mass_force + kp * error + integral + derivative + force
        position[k], measured[k], command[k] = x, reading, u
        feedforward[k], compensation_force[k] = mass_force, force
        total = 0.0
        for _ in range(substeps):
            ff, x, _ = stage.step(u, plant_dt)
            total += ff
        friction[k] = total / substeps
    return Run(compensation, path.t[:-1], path.x[:-1], position, measured, command, feedforward,
               compensation_force, friction)  # fmt: skip


def identification_log(run: Run) -> MotionData:
    """The log a controller keeps of ``run`` (module documentation): t, the encoder reading, and
    the actuator force u held after it; no velocity."""
    return MotionData(t=run.t, x=run.measured, f=run.command)


def identify_stage(
    scenario: Scenario | None = None, progress: bool | Progress = False
) -> StageIdentification:
    """Logs the stage on :func:`identification_trajectory` under the PID without compensation and
    identifies the log from :data:`BASELINE` with :func:`leuven_rt.identify`."""
    scenario = scenario or Scenario()
    run = simulate(scenario, "none", identification_trajectory(scenario), seed=scenario.seed + 1)
    log = identification_log(run)
    return StageIdentification(scenario, run, log, identify(log, BASELINE, progress=progress))


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


def compare(
    scenario: Scenario | None = None,
    compensations: Sequence[str] = COMPENSATIONS,
    identified: StageIdentification | None = None,
    progress: bool | Progress = False,
) -> Comparison:
    """Runs each of ``compensations`` on the evaluation trajectory (same noise) and measures the
    errors. When an ``identified_*`` one is among them, the stage is identified first
    (:func:`identify_stage`), unless ``identified`` gives that identification already: one made
    with the same :data:`STAGE_FIELDS` (the evaluation trajectory and the hand-set model may
    differ), else :class:`InputError` naming ``identified``."""
    scenario = scenario or Scenario()
    check_compensations(compensations, "compensations")
    if identified is not None and identified.scenario.stage() != scenario.stage():
        differing = [
            name for name in STAGE_FIELDS if getattr(identified.scenario, name) != getattr(scenario, name)
        ]
        raise InputError(
            f"`identified` must be an identification of this scenario's stage, got one whose "
            f"{', '.join(differing)} differ",
            kind="not_applicable",
            field="identified",
            value=differing,
        )
    if identified is None and set(compensations) & set(IDENTIFIED):
        identified = identify_stage(scenario, progress)
    path = evaluation_trajectory(scenario)
    model = None if identified is None else identified.identification.model
    runs = {name: simulate(scenario, name, path, model) for name in compensations}
    metrics = {name: measure(run, scenario, path.reversals) for name, run in runs.items()}
    return Comparison(scenario, runs, metrics, path.reversals, identified)


def report(comparison: Comparison) -> str:
    """A markdown table of the errors and the ratios against none and Coulomb-only, with the
    identification beside it (what it named, its rms on its own log) and what it buys."""
    s = comparison.scenario
    kp, ki, kd = gains(s)
    lines = [
        f"Stage: m = {s.mass:g} kg; true friction Fc = {s.true.Fc:g} N, Fs = {s.true.Fs:g} N, "
        f"Vs = {s.true.Vs * 1e3:g} mm/s, sigma2 = {s.true.sigma2:g} N*s/m, {s.true.elements} Maxwell-slip "
        f"elements (sum W = {sum(s.true.W or ()):g} N); simulated at {s.plant_rate:g} Hz.",
        f"Hand-set model: Fc = {s.model.Fc:g} N, Fs = {s.model.Fs:g} N, Vs = {s.model.Vs * 1e3:g} mm/s, "
        f"sigma2 = {s.model.sigma2:g} N*s/m, sum W = {sum(s.model.W or ()):g} N, Delta x1.25.",
        f"Control: {s.rate:g} Hz PID (poles at -2π·{s.bandwidth:g} Hz: Kp = {kp:.3g} N/m, "
        f"Ki = {ki:.3g} N/(m*s), Kd = {kd:.3g} N*s/m, derivative filtered at {s.derivative_filter:g} Hz) "
        "+ m·a_d feedforward; "
        f"encoder {s.encoder_resolution * 1e9:g} nm, noise {s.noise * 1e9:g} nm rms.",
    ]
    if comparison.identified is not None:
        lines.append(comparison.identified.text())
    lines += [
        f"Evaluation: x_d = {s.amplitude * 1e3:g} mm·(1 − cos 2π·{s.frequency:g} Hz·t) over {s.duration:g} s "
        f"(peak {s.amplitude * 2 * np.pi * s.frequency * 1e3:.3g} mm/s, "
        f"{len(comparison.reversals)} reversals); "
        f"glitch = mean peak |e| in the {s.glitch_window * 1e3:g} ms after each reversal.",
        "",
        "| compensation | RMS error [µm] | max error [µm] | reversal glitch [µm] "
        "| RMS ratio vs none | RMS ratio vs Coulomb |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for name, m in comparison.metrics.items():
        against = [
            f"{comparison.ratio(other, name):.2f}×" if other in comparison.metrics else "–"
            for other in ("none", "coulomb")
        ]
        errors = " | ".join(f"{value * 1e6:.3f}" for value in (m.rms, m.max, m.glitch))
        lines.append(f"| {name} | {errors} | {against[0]} | {against[1]} |")
    bought = gains_of_identification(comparison)
    if bought:
        lines += ["", *bought]
    return "\n".join(lines)


def gains_of_identification(comparison: Comparison) -> list[str]:
    """One line per mode run both on the hand-set and on the identified model: what the
    identification buys in tracking RMS and reversal glitch, as hand-set over identified (above 1:
    the identified compensator tracks better)."""
    lines = []
    for mode in ("feedforward", "observer"):
        hand, found = f"leuven_{mode}", f"identified_{mode}"
        if hand in comparison.metrics and found in comparison.metrics:
            before, after = comparison.metrics[hand], comparison.metrics[found]
            lines.append(
                f"hand-set -> identified ({mode}): RMS {before.rms * 1e6:.3f} -> {after.rms * 1e6:.3f} µm "
                f"(hand-set/identified {before.rms / after.rms:.2f}), reversal glitch "
                f"{before.glitch * 1e6:.3f} -> {after.glitch * 1e6:.3f} µm "
                f"(hand-set/identified {before.glitch / after.glitch:.2f})"
            )
    return lines


def plot(comparison: Comparison, path: str | Path) -> Path:
    """Tracking error of every compensation over the run, and zoomed on one reversal; with an
    identification, a third panel: its log's force and the identified model's."""
    identified = comparison.identified
    rows = 2 if identified is None else 3
    drawing, axes = figure(rows, 1, size=(9, 3.5 * rows), layout="constrained")
    whole, zoom = axes[0], axes[1]
    reversal = comparison.reversals[len(comparison.reversals) // 2]
    for name, run in comparison.runs.items():
        style = "--" if name in IDENTIFIED else "-"
        whole.plot(run.t, run.error * 1e6, style, lw=0.9,
                   label=f"{name} (RMS {comparison.metrics[name].rms * 1e6:.2f} µm)")  # fmt: skip
        window = (run.t > reversal - 0.05) & (run.t < reversal + 0.15)
        zoom.plot((run.t[window] - reversal) * 1e3, run.error[window] * 1e6, style, label=name, lw=1.2)
    for t in comparison.reversals:
        whole.axvline(t, color="0.85", lw=0.8, zorder=0)
    whole.set(xlabel="t [s]", ylabel="tracking error [µm]", title="PID at 1 kHz on a stage with friction")
    whole.legend(fontsize=8, loc="upper right")
    zoom.axvline(0.0, color="0.6", lw=0.8)
    zoom.set(xlabel=f"time after the reversal at t = {reversal:.2f} s [ms]", ylabel="tracking error [µm]",
             title="around one velocity reversal (quadrant glitch)")  # fmt: skip
    zoom.legend(fontsize=8)
    if identified is not None:
        log = axes[2]
        model = predict(identified.identification.model, identified.log)
        log.plot(identified.log.t, identified.log.f, color="0.6", lw=0.8, label="logged force u")
        log.plot(identified.log.t, model.f_model, "--", color="C3", lw=0.8,
                 label=f"identified model (rms {identified.rms:.3g} N)")  # fmt: skip
        named = ", ".join(identified.named) or "nothing"
        log.set(xlabel="t [s]", ylabel="force [N]",
                title=f"identification log; named from {', '.join(BASELINE)}: {named}")  # fmt: skip
        log.legend(fontsize=8, loc="upper right")
    return save(drawing, path, dpi=120)


#: The file :func:`run` writes into its folder.
FILE = "closed_loop.png"


def run(out: Path, progress: bool | Progress = False) -> str:
    """``leuven-rt control``: the stage identified from its log, every compensation compared,
    the table and the figure ``closed_loop.png`` in ``out``."""
    comparison = compare(progress=progress)
    return f"{report(comparison)}\nfigure: {plot(comparison, out / FILE)}"
