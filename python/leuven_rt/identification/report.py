"""What an identification did and how well: errors per stage, held-out error, conditioning,
warnings. Plain data with a JSON form, printed by ``leuven-rt identify``."""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from typing import Any

from ..params import Params


@dataclass(frozen=True)
class Stage:
    """One fitting stage."""

    name: str
    rms: float
    """RMS error of the stage's own model over the samples it fitted [N]."""
    samples: int
    condition: float
    """Condition number of the stage's (scaled) regressor or Jacobian matrix."""
    details: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class IdentificationReport:
    samples: int
    dt: float
    cutoff: float
    """Cutoff of the zero-phase filter on the position [Hz]."""
    noise_std: float
    """Estimated noise floor of the force [N]."""
    reversals: int
    presliding_range: float
    """Displacement after a reversal over which the force is in transition [m]."""
    training_samples: int
    held_out_samples: int
    training_rms: float
    """RMS simulation error of the final model over the training samples [N]."""
    held_out_rms: float
    """RMS simulation error over the held-out samples (the end of the record, never fitted) [N];
    nan when nothing was held out."""
    stages: list[Stage]
    warnings: list[str]
    seconds: float

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2, default=float)

    def summary(self) -> str:
        """A few lines for people."""
        lines = [
            f"samples: {self.samples} at dt = {self.dt:g} s ({self.training_samples} fitted, "
            f"{self.held_out_samples} held out); reversals: {self.reversals}",
            f"force noise floor: {self.noise_std:.4g} N; presliding range: {self.presliding_range:.4g} m",
        ]
        for stage in self.stages:
            lines.append(f"  {stage.name:<11} rms {stage.rms:.4g} N over {stage.samples} samples, "
                         f"condition {stage.condition:.3g}")  # fmt: skip
        final = f"final model: training rms {self.training_rms:.4g} N"
        if self.held_out_samples:
            final += f", held-out rms {self.held_out_rms:.4g} N"
            if self.noise_std > 0:
                final += f" ({self.held_out_rms / self.noise_std:.2f}× the noise floor)"
        lines.append(final)
        lines.extend(f"warning: {text}" for text in self.warnings)
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class IdentificationResult:
    """What :func:`leuven_rt.identify` returns."""

    params: Params
    report: IdentificationReport
