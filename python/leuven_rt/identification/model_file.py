"""The model file that ``leuven-rt identify -o`` writes, built from an identification result.

One function, :func:`model_file_from_identification`, so that what a fit puts in the file is
decided in one place: today the friction parameters and the report; the level and the
measurement terms join when the fit identifies them.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..modelfile import ModelFile
from ..units import Units
from .report import IdentificationResult


def model_file_from_identification(
    result: IdentificationResult, *, units: Units = "linear", notes: Sequence[str] = ()
) -> ModelFile:
    """The :class:`ModelFile` (version 1) of ``result``: its parameters as the friction model, no
    level, no measurement terms, and its report (with ``notes``, the warnings given when the log
    was loaded, under ``data_notes``)."""
    report = result.report.to_dict()
    if notes:
        report["data_notes"] = list(notes)
    return ModelFile(friction=result.params, units=units, report=report)


__all__ = ["model_file_from_identification"]
