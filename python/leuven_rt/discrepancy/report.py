"""The diagnosis report: the JSON object of docs/data-and-reports.md#diagnosis-report, plus the
per-region numbers and the residuals kept for the figure and for people."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from .._typing import FloatArray
from ..units import Units, unit_names
from .features import Features
from .localise import Region
from .model import ModelFit
from .settings import Settings


@dataclass(frozen=True)
class Step:
    effect: str
    where: str
    rms_before: float
    rms_after: float
    params: dict[str, float]


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """What :func:`leuven_rt.diagnose` returns; :meth:`to_dict` is the JSON of
    docs/data-and-reports.md#diagnosis-report."""

    samples: int
    noise_std: float
    baseline: tuple[str, ...]
    rms_before: float
    rms_after: float
    steps: list[Step]
    unexplained_significant: bool
    unexplained_where: str
    drift: bool
    """The friction level changes over the record (outside the catalogue); fitted alongside."""
    settings: Settings
    final_model: ModelFit
    regions_before: list[Region]
    regions_after: list[Region]
    features: Features = field(repr=False)
    residuals: list[FloatArray] = field(repr=False)
    """In-sample residual of the baseline, then after each step (every sample)."""
    units: Units = "linear"
    """The log's kind of axis: the unit names of the story and the figure."""

    @property
    def named_effects(self) -> list[str]:
        return [step.effect for step in self.steps]

    def to_dict(self) -> dict[str, Any]:
        return {
            "samples": self.samples,
            "noise_std": self.noise_std,
            "baseline": list(self.baseline),
            "rms_before": self.rms_before,
            "rms_after": self.rms_after,
            "named_effects": self.named_effects,
            "steps": [
                {
                    "effect": s.effect,
                    "where": s.where,
                    "rms_before": s.rms_before,
                    "rms_after": s.rms_after,
                    "params": s.params,
                }
                for s in self.steps
            ],
            "unexplained": {
                "significant": self.unexplained_significant,
                "where": self.unexplained_where,
                "drift": self.drift,
            },
            "settings": self.settings.to_dict(),
            "final_model": self.final_model.to_dict(),
        }

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2)

    def story(self) -> str:
        """The diagnosis in sentences, with the numbers."""
        N = unit_names(self.units).force
        lines = [f"{self.samples} samples; force noise floor {self.noise_std:.3g} {N}",
                 f"baseline model ({', '.join(self.baseline) or 'nothing'}): rms {self.rms_before:.3g} {N}",
                 "where the baseline and the data disagree (residual rms by region):"]  # fmt: skip
        for region in sorted(self.regions_before, key=lambda r: -r.rms):
            lines.append(f"  {region.name:<38} rms {region.rms:8.3g} {N}  mean {region.mean:+9.3g} {N}  "
                         f"({region.share:.0%} of samples)")  # fmt: skip
        for number, step in enumerate(self.steps, 1):
            values = ", ".join(f"{key} = {value:.4g}" for key, value in step.params.items())
            lines.append(f"step {number}: missing `{step.effect}` ({values}); rms {step.rms_before:.3g} -> "
                         f"{step.rms_after:.3g} {N}; where: {step.where}")  # fmt: skip
        if not self.steps:
            lines.append("no catalogue effect improves the model significantly")
        verdict = "significant" if self.unexplained_significant else "at the noise floor"
        lines.append(f"final model: rms {self.rms_after:.3g} {N} ({self.rms_after / self.noise_std:.2f}x "
                     f"the noise floor); what remains is {verdict}: {self.unexplained_where}")  # fmt: skip
        return "\n".join(lines)
