"""The demo (``leuven-rt demo``): the standard presliding-to-sliding scenario simulated and drawn,
then the discrepancy workflow's story: a built-in generated log with hidden effects, diagnosed
from the baseline ``coulomb,viscous``, told in numbers, with its figure; then the loop closed
(:mod:`.closed_loop`): a simulated stage logged under PID, identified, and the identified
compensator run on another trajectory beside the hand-set one and none, in numbers (``leuven-rt
control`` draws the whole study)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._plot import figure, save
from ..data.scenarios import presliding_to_sliding, standard_params
from ..discrepancy.diagnose import diagnose
from ..discrepancy.hidden import make_hidden
from ..discrepancy.plot import plot_diagnosis
from ..discrepancy.report import Diagnosis
from ..params import Params
from ..progress import Progress
from ..simulation import simulate_position
from .closed_loop import Comparison, compare, gains_of_identification

#: What the story's machine really has; the baseline knows only coulomb and viscous.
DEMO_TRUTH = ("coulomb", "viscous", "presliding_hysteresis", "position_dependence")
DEMO_BASELINE = ("coulomb", "viscous")
#: The files :func:`run_demo` and :func:`run_story` write into their folder.
FILES = ("presliding_to_sliding.png", "diagnose.png")


@dataclass(frozen=True)
class DemoResult:
    """What the demo computed and where it wrote the figure."""

    figure: Path
    samples: int
    peak_force: float
    sliding_force: float
    presliding_peak: float
    params: Params

    def text(self) -> str:
        params = self.params
        assert params.Delta is not None  # the standard parameters have Maxwell-slip elements
        return "\n".join([
            "Presliding-to-sliding scenario (position input, 10 kHz, implicit step)",
            f"  parameters: Fc = {params.Fc} N, Fs = {params.Fs} N, Vs = {params.Vs} m/s, "
            f"N = {params.elements} Maxwell-slip elements up to {max(params.Delta) * 1e6:.0f} µm",
            f"  samples: {self.samples}",
            f"  largest |F| while the amplitude stays below 5 µm (presliding): {self.presliding_peak:.3f} N",
            f"  median |F| over the last second (sliding): {self.sliding_force:.3f} N",
            f"  largest |F| overall: {self.peak_force:.3f} N",
            f"  figure: {self.figure}",
        ])  # fmt: skip


def run_demo(out: Path) -> DemoResult:
    """Simulates the scenario with the standard parameters and writes ``presliding_to_sliding.png``."""
    params = standard_params()
    excitation = presliding_to_sliding()
    force = simulate_position(params, excitation.x, excitation.dt)

    drawing, (by_position, by_time) = figure(1, 2, size=(12, 4.5))
    by_position.plot(excitation.x * 1e6, force, linewidth=0.7)
    by_position.set_xlabel("displacement x [µm]")
    by_position.set_ylabel("friction force F [N]")
    by_position.set_title("Force vs displacement: presliding loops, then sliding")
    by_position.set_xscale("symlog", linthresh=1.0)
    by_time.plot(excitation.t, force, linewidth=0.7)
    by_time.set_xlabel("time t [s]")
    by_time.set_ylabel("friction force F [N]")
    by_time.set_title("Force vs time")
    for axis in (by_position, by_time):
        axis.axhline(params.Fs, color="grey", linestyle=":", linewidth=0.8)
        axis.axhline(-params.Fs, color="grey", linestyle=":", linewidth=0.8)
        axis.grid(alpha=0.3)
    drawing.tight_layout()
    figure_path = save(drawing, out / FILES[0], dpi=120)

    assert params.Delta is not None  # the standard parameters have Maxwell-slip elements
    presliding = excitation.amplitude < 0.5 * params.Delta[-1]
    sliding = excitation.t > excitation.t[-1] - 1.0
    return DemoResult(
        figure=figure_path,
        samples=len(force),
        peak_force=float(np.max(np.abs(force))),
        sliding_force=float(np.median(np.abs(force[sliding]))),
        presliding_peak=float(np.max(np.abs(force[presliding]))),
        params=params,
    )


@dataclass(frozen=True, eq=False)
class Story:
    """The diagnosis of the story's log, the effects hidden from its baseline, and the figure."""

    diagnosis: Diagnosis
    hidden: tuple[str, ...]
    figure: Path

    def text(self) -> str:
        named = ", ".join(self.diagnosis.named_effects) or "nothing"
        return (f"Diagnose story: a generated log whose friction has {', '.join(self.hidden)} hidden from "
                f"the baseline model ({', '.join(DEMO_BASELINE)})\n{self.diagnosis.story()}\n"
                f"named: {named}; figure: {self.figure}")  # fmt: skip


def run_story(out: Path, progress: bool = False) -> Story:
    """Diagnoses the generated log of :data:`DEMO_TRUTH` from :data:`DEMO_BASELINE` and writes
    ``diagnose.png``."""
    hidden = tuple(name for name in DEMO_TRUTH if name not in DEMO_BASELINE)
    diagnosis = diagnose(make_hidden(DEMO_TRUTH, seed=0).data, DEMO_BASELINE, progress=progress)
    return Story(diagnosis, hidden, plot_diagnosis(diagnosis, out / FILES[1]))


#: The compensations the demo's loop compares: none, the hand-set model, the identified one.
LOOP_COMPENSATIONS = (
    "none",
    "leuven_feedforward",
    "leuven_observer",
    "identified_feedforward",
    "identified_observer",
)


@dataclass(frozen=True, eq=False)
class LoopStory:
    """The closed-loop study of :mod:`.closed_loop` on :data:`LOOP_COMPENSATIONS`."""

    comparison: Comparison

    def text(self) -> str:
        identified = self.comparison.identified
        assert identified is not None  # the identified compensations are among the compared
        diagnosis = identified.identification.diagnosis
        scenario = self.comparison.scenario
        lines = [
            "Closing the loop: a simulated stage (its true friction unknown to the controller) logged "
            "under a 1 kHz PID, identified from the log, compensated on another trajectory",
            f"  log: {identified.log.t.size} samples of the encoder and the actuator force; identify named "
            f"{', '.join(identified.named) or 'nothing'} from {', '.join(diagnosis.baseline)}; "
            f"rms on its own log {diagnosis.rms_before:.3g} -> {identified.rms:.3g} N",
            f"  tracking x_d = {scenario.amplitude * 1e3:g} mm·(1 − cos 2π·{scenario.frequency:g} Hz·t) "
            "(RMS error, and the mean peak error after a reversal):",
        ]
        for name, metrics in self.comparison.metrics.items():
            lines.append(
                f"    {name:<24} RMS {metrics.rms * 1e6:7.3f} µm   "
                f"reversal glitch {metrics.glitch * 1e6:7.3f} µm"
            )
        lines += [f"  {line}" for line in gains_of_identification(self.comparison)]
        return "\n".join(lines)


def run_loop(progress: bool | Progress = False) -> LoopStory:
    """The closed-loop study (log, identify, compensate) on :data:`LOOP_COMPENSATIONS`."""
    return LoopStory(compare(compensations=LOOP_COMPENSATIONS, progress=progress))
