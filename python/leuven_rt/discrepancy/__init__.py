"""The discrepancy workflow: point it at a log of a machine, and it names what the friction model
is missing (the effect catalogue of docs/effects.md), where, and how much better the model gets.

:mod:`.features` (signals), :mod:`.effects` (the catalogue), :mod:`.drive` (the presliding
bank driven by the model's state), :mod:`.model` (fits),
:mod:`.scoring` (blocked cross-validation, significance), :mod:`.localise` (where, in numbers),
:mod:`.diagnose` (the rounds), :mod:`.settings` (its thresholds), :mod:`.ripple` (periods of
a position ripple), :mod:`.deploy` and :mod:`.identify` (the model file of the final model),
:mod:`.report` (JSON of docs/data-and-reports.md#diagnosis-report),
:mod:`.plot` (figure), :mod:`.hidden` (generated data with hidden effects, to test it on).

It works from the data toolkit :mod:`leuven_rt.data`, not from the identification workflow.
"""

from .._extras import require

require("scipy", "tqdm", "threadpoolctl", extra="analysis", needed_by="leuven_rt.discrepancy")


from .diagnose import DEFAULT_BASELINE, diagnose
from .effects import CATALOGUE, parse_effects
from .identify import Identification, identify
from .report import Diagnosis, Step
from .settings import Settings

__all__ = [
    "CATALOGUE",
    "DEFAULT_BASELINE",
    "Diagnosis",
    "Identification",
    "Settings",
    "Step",
    "diagnose",
    "identify",
    "parse_effects",
]
