"""The output-error engine: the friction model a log supports, fitted and chosen on the
simulation error of the model file itself.

A candidate is a model file (:mod:`.structure`: the catalogue's effects as groups of the file's
parameters), simulated along the log's motion by gms-core's own step with the exact sensitivities
of its parameters (:func:`sensitivities`, the Rust crate gms-fit; :mod:`.evaluate`) and fitted by
bounded Gauss–Newton (:mod:`.solve`). :mod:`.select` runs the rounds that add effects against a
unit of evidence set by the noise and by the floor the log allows (:mod:`.floor`), with
:mod:`.periods` for ripples, :mod:`.remains` for what is left and :mod:`.undetermined` for what
the excitation cannot tell, on a sample of a long record (:mod:`.sample`); :mod:`.file` writes
the result; :mod:`.settings` holds the thresholds.
:func:`simulate_sets` runs many parameter sets along one signal. The equations of the
sensitivities are in docs/sensitivities.md.

:func:`sensitivities` and :func:`simulate_sets` need numpy only; the selection needs the
``analysis`` extra (scipy).
"""

from .sensitivity import Sensitivities, sensitivities, simulate_sets
from .settings import Settings
from .structure import CATALOGUE, parse_effects

__all__ = ["CATALOGUE", "Sensitivities", "Settings", "parse_effects", "sensitivities", "simulate_sets"]
