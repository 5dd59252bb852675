"""The output-error engine: the friction model a log supports, fitted and chosen on the
simulation error of the model file itself.

A candidate is a model file (:mod:`.structure`: the catalogue's effects as groups of the file's
parameters), simulated along the log's motion by gms-core's own step with the exact sensitivities
of its parameters (:mod:`.sensitivity`, :mod:`.evaluate`) and fitted by bounded Gauss–Newton
(:mod:`.solve`). :mod:`.select` runs the rounds that add effects against a unit of evidence set by
the noise and by the floor the log allows (:mod:`.floor`), with :mod:`.periods` for ripples,
:mod:`.remains` for what is left and :mod:`.undetermined` for what the excitation cannot tell;
:mod:`.file` writes the result; :mod:`.settings` holds the thresholds.
"""

from .._extras import require

require("scipy", "threadpoolctl", extra="analysis", needed_by="leuven_rt.fitting")


from .settings import Settings
from .structure import CATALOGUE, parse_effects

__all__ = ["CATALOGUE", "Settings", "parse_effects"]
