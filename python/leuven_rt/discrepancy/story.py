"""The demo's diagnose story: a built-in generated log with hidden effects, diagnosed from the
baseline ``coulomb,viscous``, told in numbers, with the figure."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .diagnose import diagnose
from .hidden import make_hidden
from .plot import plot_diagnosis
from .report import Diagnosis

#: What the demo's machine really has; the baseline knows only coulomb and viscous.
DEMO_TRUTH = ("coulomb", "viscous", "presliding_hysteresis", "position_dependence")
DEMO_BASELINE = ("coulomb", "viscous")


@dataclass(frozen=True, eq=False)
class Story:
    diagnosis: Diagnosis
    hidden: tuple[str, ...]
    figure: Path

    def text(self) -> str:
        named = ", ".join(self.diagnosis.named_effects) or "nothing"
        return (f"Diagnose story: a generated log whose friction has {', '.join(self.hidden)} hidden from "
                f"the baseline model ({', '.join(DEMO_BASELINE)})\n{self.diagnosis.story()}\n"
                f"named: {named}; figure: {self.figure}")  # fmt: skip


def run_story(out: Path, progress: bool = False) -> Story:
    hidden = tuple(name for name in DEMO_TRUTH if name not in DEMO_BASELINE)
    diagnosis = diagnose(make_hidden(DEMO_TRUTH, seed=0).data, DEMO_BASELINE, progress=progress)
    return Story(diagnosis, hidden, plot_diagnosis(diagnosis, out / "diagnose.png"))
