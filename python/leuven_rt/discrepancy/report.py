"""The diagnosis report: the JSON object of docs/data-and-reports.md#diagnosis-report, the
story in sentences, and the residuals kept for the figure.

Every rms in it is the model file's: the force of the step's model simulated along the log as
:func:`leuven_rt.predict` simulates the written file, over every sample."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from .._typing import FloatArray
from ..units import Units, unit_names
from .localise import Layout, Region


@dataclass(frozen=True)
class Step:
    """One effect added: where it helped, the rms before and after, its parameters in the file."""

    effect: str
    where: str
    rms_before: float
    rms_after: float
    params: dict[str, Any]
    robust_before: float
    """The error the rounds weigh, before and after [N or N·m]: the root of the robust mean loss
    over the samples the fit uses, at the backward round's scale, where a gross error counts
    little more than one at that scale. Over every sample an effect can raise the rms while it
    lowers this (its models are fitted to a robust loss)."""
    robust_after: float


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """What :func:`leuven_rt.diagnose` returns; :meth:`to_dict` is the JSON of
    docs/data-and-reports.md#diagnosis-report."""

    samples: int
    noise_std: float
    floor_estimate: float
    """The error the right model would still have with this log's motion signal [N or N·m]."""
    reconstruction: dict[str, Any]
    named_under: dict[str, Any]
    """The reconstruction the effects were named under, as ``reconstruction`` says it: the logged
    velocity, the raw encoder, or a low-pass of it (a noisy position, or the second look)."""
    gross_errors: int
    """Samples the fit left out as gross errors (beyond 5 times the noise of the final model)."""
    baseline: tuple[str, ...]
    rms_before: float
    rms_after: float
    steps: list[Step]
    stand_ins: list[dict[str, Any]]
    """Each named effect that has a stand-in (an offset, an asymmetry), the stand-in and what it
    gains fitted in the named one's place, in units of evidence (negative: it does worse)."""
    unexplained_significant: bool
    unexplained_where: str
    drift: bool
    """The friction level changes over the record (outside the catalogue); fitted alongside."""
    settings: dict[str, Any]
    final_model: dict[str, Any]
    """The model file's object without its report: what the compensator runs."""
    regions_before: list[Region]
    regions_after: list[Region]
    layout: Layout = field(repr=False)
    t: FloatArray = field(repr=False)
    v: FloatArray = field(repr=False)
    x: FloatArray = field(repr=False)
    travel: FloatArray = field(repr=False)
    residuals: list[FloatArray] = field(repr=False)
    """The residual of the baseline, then of each step's model (every sample)."""
    units: Units = "linear"

    @property
    def named_effects(self) -> list[str]:
        return [step.effect for step in self.steps]

    def to_dict(self) -> dict[str, Any]:
        return {
            "samples": self.samples,
            "noise_std": self.noise_std,
            "floor_estimate": self.floor_estimate,
            "reconstruction": self.reconstruction,
            "named_under": self.named_under,
            "gross_errors": self.gross_errors,
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
                    "robust_before": s.robust_before,
                    "robust_after": s.robust_after,
                    "params": s.params,
                }
                for s in self.steps
            ],
            "stand_ins": self.stand_ins,
            "unexplained": {
                "significant": self.unexplained_significant,
                "where": self.unexplained_where,
                "drift": self.drift,
            },
            "settings": self.settings,
            "final_model": self.final_model,
        }

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2)

    def story(self) -> str:
        """The diagnosis in sentences, with the numbers."""
        N = unit_names(self.units).force
        lines = [
            f"{self.samples} samples; force noise {self.noise_std:.3g} {N}; the floor this log allows "
            f"{self.floor_estimate:.3g} {N} (the error of the right model driven by what the log gives)",
            f"the model is driven by {self.reconstruction['description']}",
            *(
                [f"the effects were named with it driven by {self.named_under['description']}"]
                if _motion(self.named_under) != _motion(self.reconstruction)
                else []
            ),
            *(
                [
                    f"{_counted(self.gross_errors, 'sample')} ({self.gross_errors / self.samples:.1%}) "
                    f"{'is a gross error' if self.gross_errors == 1 else 'are gross errors'} the model "
                    "cannot explain (beyond 5 times the noise); choosing the effects counts them little, "
                    "the written file is fitted on every sample"
                ]
                if self.gross_errors
                else []
            ),
            f"baseline model ({', '.join(self.baseline) or 'nothing'}): rms {self.rms_before:.3g} {N}",
            "where the baseline and the data disagree (residual rms by region):",
        ]
        for region in sorted(self.regions_before, key=lambda r: -r.rms):
            lines.append(f"  {region.name:<38} rms {region.rms:8.3g} {N}  mean {region.mean:+9.3g} {N}  "
                         f"({region.share:.0%} of samples)")  # fmt: skip
        for number, step in enumerate(self.steps, 1):
            values = ", ".join(f"{key} = {_show(value)}" for key, value in step.params.items())
            lines.append(f"step {number}: missing `{step.effect}` ({values}); rms {step.rms_before:.3g} -> "
                         f"{step.rms_after:.3g} {N} (robust, as chosen: {step.robust_before:.3g} -> "
                         f"{step.robust_after:.3g} {N}); where: {step.where}")  # fmt: skip
        if not self.steps:
            lines.append("no catalogue effect improves the model significantly")
        significance = self.settings["significance"]
        for pair in self.stand_ins:
            gain = round(pair["gain"], 2) + 0.0  # not "-0.00"
            told = (
                "this log does not tell the two apart"
                if abs(pair["gain"]) <= significance
                else "it does worse in its place"
                if gain < 0
                else "it gains more, but not one-sidedly over the record"
            )
            factor, stops = pair.get("factor"), pair.get("stops")
            if abs(pair["gain"]) <= significance and (factor is not None or stops is not None):
                told += " by their fit"
            if factor is not None:
                # Where neither gained the threshold one-sidedly in the other's place, the
                # asymmetry as one −x factor against the offset decides (fitting.select._exchange).
                one = "the asymmetry as one factor on every -x level"
                better, worse = (one, "the offset") if factor >= 0 else ("the offset", one)
                told += f"; {better} fits {abs(factor):.2f} units better than {worse}"
            if stops is not None:
                # On a log whose friction lets go at its stops, the force there decides before the
                # factor does.
                at_stops = round(stops, 2) + 0.0  # not "-0.00"
                told += f"; with the stops where friction lets go counted, it gains {at_stops:.2f} units"
            lines.append(f"`{pair['stand_in']}` in place of `{pair['named']}`: gains {gain:.2f} units of "
                         f"max(σ², floor²), an effect counts above {significance:g}: {told}")  # fmt: skip
        verdict = "significant" if self.unexplained_significant else "no more than noise and the floor"
        if self.gross_errors and not self.unexplained_significant:
            # The final rms counts them in full, and can stand far above the noise.
            the = "the " if self.gross_errors > 1 else ""
            verdict += f", {the}{_counted(self.gross_errors, 'gross error')} aside"
        ratio = self.rms_after / max(self.noise_std, 1e-300)
        lines.append(f"final model: rms {self.rms_after:.3g} {N} ({ratio:.2f}x "
                     f"the noise); what remains is {verdict}: {self.unexplained_where}")  # fmt: skip
        return "\n".join(lines)


def _counted(count: int, noun: str) -> str:
    return f"{count} {noun}{'' if count == 1 else 's'}"


def _show(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_show(item) for item in value) + "]"
    return str(value)


def _motion(reconstruction: dict[str, Any]) -> tuple[Any, Any]:
    """What drives the friction model in a report's reconstruction: its source and cutoff (the
    file's own acceleration cutoff changes only the inertia term)."""
    return reconstruction["source"], reconstruction["cutoff"]


__all__ = ["Diagnosis", "Step"]
