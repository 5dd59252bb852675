"""``diagnose``: the story of :func:`~.identify.identify` (module documentation there)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from ..data.records import DataLike
from ..fitting.settings import Settings
from ..progress import Progress
from ..units import Units
from .identify import DEFAULT_BASELINE, identify
from .report import Diagnosis


def diagnose(
    data: DataLike,
    baseline: str | Sequence[str] = DEFAULT_BASELINE,
    *,
    settings: Settings | None = None,
    progress: bool | Progress = False,
    columns: Mapping[str, str] | None = None,
    units: Units | None = None,
) -> Diagnosis:
    """Names the catalogue effects (docs/effects.md) that ``baseline`` misses in ``data``: where
    the model and the data disagree, what each named effect gains, and what remains. The same
    arguments and the same fit as :func:`~leuven_rt.identify`, whose diagnosis it returns."""
    return identify(
        data, baseline, settings=settings, progress=progress, columns=columns, units=units
    ).diagnosis


__all__ = ["diagnose"]
