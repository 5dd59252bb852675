"""The thresholds of the rounds, in one object that :func:`leuven_rt.identify` and
:func:`leuven_rt.diagnose` take and their reports echo. Every threshold is a plain count or a
multiple of the unit of evidence, max(σ², floor²): the force noise σ or, where the log cannot do
better, the floor of the error the right model would still have with this log's motion signal
(docs/effects.md#the-floor). Never a share of the current error, so that the same evidence counts
the same whether the model is far from the data or close to it."""

from __future__ import annotations

import math
import numbers
import sys
from dataclasses import asdict, dataclass
from typing import Any

from ..errors import InputError, shown

#: The fewest samples the rounds may run on: 8 segments of 512 samples.
MIN_ROUNDS_SAMPLES = 4096


@dataclass(frozen=True, kw_only=True)
class Settings:
    """What counts as evidence in :func:`leuven_rt.identify` and :func:`leuven_rt.diagnose`
    (docs/effects.md#how-an-effect-is-chosen); "unit" is max(σ², floor²)."""

    chunks: int = 16
    """Contiguous runs of held-out samples over which a gain must be one-sided."""
    significance: float = 0.5
    """An effect counts when it lowers the held-out mean squared error by more than this many units."""
    loss: float = 0.2
    """... and the runs where it does worse lose less than this share of what the others gain."""
    joint: float = 1.0
    """When no single effect counts but the held-out mean squared error exceeds σ² by more than this
    many units, pairs of effects are tried together."""
    drift: float = 1.0
    """A friction level drifting over the record is fitted alongside (and reported) when it lowers
    the final model's held-out mean squared error by more than this many units (one-sided as above)."""
    unexplained: float = 0.2
    """What remains is significant when its weighted mean square exceeds σ² by more than this many
    units."""
    second_look: float = 1.0
    """Where the raw encoder drives the rounds, the effects named again under a low-pass of it
    replace theirs when that file lowers the squared error ``predict`` judges by more than this
    many units (σ² of the first rounds, or the lower of the two files' floors squared); ``inf``:
    no second look."""
    rounds_samples: int = 65_536
    """On a longer record the rounds name effects and choose the reconstruction on this many of
    its samples, in whole segments spread over it, and the written file is then fitted on the
    whole record (docs/effects.md#long-records): the rounds' cost stops growing with the length
    of the log, while a sample this size still reads a mean squared error to 0.006·σ²
    (σ²·√(2/N)), far below the thresholds above. Above the 60 000 samples of the logs the
    thresholds were set on, which are identified whole."""

    def __post_init__(self) -> None:
        # Each value is kept as a plain int or float, so that the report echoes it as JSON.
        for name, low in (("chunks", 2), ("rounds_samples", MIN_ROUNDS_SAMPLES)):
            value: Any = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < low:
                integer = isinstance(value, numbers.Integral) and not isinstance(value, bool)
                raise InputError(
                    f"`settings.{name}` must be an integer >= {low}, got {shown(value)!r:.80}",
                    kind="out_of_range" if integer else "not_integer",
                    field=f"settings.{name}",
                    value=value,
                    bound=low if integer else None,
                )
            object.__setattr__(self, name, int(value))
        for name in ("significance", "loss", "joint", "drift", "unexplained", "second_look"):
            value = getattr(self, name)
            # inf turns the second look off; every other threshold must be one a gain can reach.
            off = name == "second_look"
            highest = math.inf if off else sys.float_info.max
            real = isinstance(value, numbers.Real) and not isinstance(value, bool)
            number = _float(value) if real else math.nan
            if not 0.0 <= number <= highest:
                what = "a number >= 0 (inf: none)" if off else "a finite number >= 0"
                raise InputError(
                    f"`settings.{name}` must be {what}, got {shown(value)!r:.80}",
                    kind="not_real" if not real else "negative" if number < 0 else "not_finite_value",
                    field=f"settings.{name}",
                    value=value,
                )
            object.__setattr__(self, name, number)

    def to_dict(self) -> dict[str, int | float | None]:
        """The settings as JSON values: an ``inf`` (no second look) as None."""
        return {name: None if value == math.inf else value for name, value in asdict(self).items()}


def _float(value: Any) -> float:
    """``value`` as a float; an integer beyond the float range as inf (refused as not finite)."""
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf
