"""From the workflow's final model to the model file a compensator runs.

The final model of :func:`~leuven_rt.diagnose` is linear in its coefficients: a Coulomb column,
the bank of Maxwell-slip deflections driven by the state z, the Stribeck column, the level's
position columns, and the measurement terms. The modified Leuven model (docs/model.md) holds the
same friction in a different form: one hysteresis force Fh that saturates at the Stribeck level.
The mapping:

- the sliding level is everything the contact columns reach once every element has slipped:
  Fc = Fc(column) + ΣWⱼ, and Fs = Fc + (Fs − Fc)(column), per direction with ``asymmetry``;
- the elements are the bank's (Δⱼ as the workflow built them) plus one element below the
  position's resolution that carries the Coulomb column (the force that follows a reversal at
  once), scaled so that ΣW exceeds the largest static level by :data:`MARGIN` (the model's rule);
  without presliding that element is the whole bank;
- n is the drive's exponent (2 without presliding), σ1 = 0;
- the level's trend and ripple coefficients are those of the position columns over Fc;
- offset and inertia are the measurement terms; the viscous asymmetry and the drift have no place
  in the file and are reported as warnings.

What the data did not determine is named in the warnings, with its standard error.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..level import PositionLevel, Ripple
from ..modelfile import ModelFile
from ..params import Params
from ..units import Units
from .features import Features
from .model import PRESLIDING, ModelFit

#: ΣW over the largest static level (the model needs ΣW > Fs).
MARGIN = 1.02
#: The smallest Coulomb level a file holds, as a share of the force's spread, when the fit found
#: none (the model needs Fc > 0).
FLOOR = 1e-6
#: A coefficient is "not determined" when its standard error exceeds this share of its value.
UNDETERMINED = 0.5


@dataclass(frozen=True, eq=False)
class Deployment:
    model: ModelFile
    warnings: tuple[str, ...]


def deploy(fit: ModelFit, features: Features, units: Units, report: dict[str, object]) -> Deployment:
    """The :class:`ModelFile` of ``fit`` (fitted on ``features``), with the warnings of the
    mapping (module documentation)."""
    c = fit.coefficients
    warnings: list[str] = []
    bank = np.array([max(c[name], 0.0) for name in fit.groups.get(PRESLIDING, ())])
    floor = FLOOR * max(float(np.ptp(features.force)), 1e-300)
    coulomb = c.get("Fc", 0.0)
    if coulomb <= floor and bank.sum() <= floor:
        warnings.append(f"no Coulomb level found (Fc = {coulomb:.3g}): the file holds Fc = {floor:.3g}")
    fc = max(coulomb + float(bank.sum()), floor)
    bump = max(c.get("Fs_minus_Fc", 0.0), 0.0)
    fc_neg = fc + c.get("Fc_neg_shift", 0.0)
    fs_neg = fc_neg + bump + c.get("Fs_neg_shift", 0.0)
    if fc_neg <= floor:
        warnings.append(f"the negative direction's Coulomb level came out {fc_neg:.3g}: held at {floor:.3g}")
        fc_neg = floor
    fs_neg = max(fs_neg, fc_neg)
    fs = fc + bump
    if abs(c.get("sigma2_neg_shift", 0.0)) > 0.0:
        warnings.append(
            f"the viscous coefficient differs by direction by {c['sigma2_neg_shift']:.4g}: the file holds "
            f"sigma2 = {c.get('sigma2', 0.0):.4g} for both"
        )
    shape = fit.shape
    stiff = max(features.scales.play, float(features.scales.deflections[0]) * 2.0**-20)
    weights = [max(coulomb, 0.0), *bank]
    widths = [stiff, *features.scales.deflections[: bank.size]]
    kept = [(w, d) for w, d in zip(weights, widths, strict=True) if w > 0.0]
    if not kept:
        kept = [(1.0, stiff)]
    total = sum(w for w, _ in kept)
    scale = MARGIN * max(fs, fs_neg) / total
    asymmetric = "asymmetry" in fit.effects
    vs, delta = (shape.Vs, shape.delta) if shape is not None else (1.0, 2.0)
    params = Params(
        Fc=fc, Fs=fs, Vs=vs, delta=delta,
        n=fit.drive.n if fit.drive is not None else 2.0, sigma1=0.0, sigma2=max(c.get("sigma2", 0.0), 0.0),
        W=tuple(w * scale for w, _ in kept), Delta=tuple(float(d) for _, d in kept),
        **({"Fc_neg": fc_neg, "Fs_neg": fs_neg} if asymmetric else {}),
    )  # fmt: skip
    level = _level(fit, features, fc, warnings)
    if "drift" in fit.effects:
        warnings.append("the friction level drifts over the record: the file holds its average")
    if c.get("Fc_rest") is not None:
        report = {**report, "force_at_rest": c["Fc_rest"] / fc}
    for name, value in c.items():
        error = fit.standard_errors.get(name, 0.0)
        if name.startswith("W") or name == "Fc_rest":
            continue
        if abs(value) > 0.0 and error > UNDETERMINED * abs(value):
            warnings.append(
                f"{name} = {value:.4g} is not determined by this excitation (standard error {error:.3g})"
            )
    model = ModelFile(
        friction=params, level=level, offset=c.get("offset", 0.0), inertia=max(c.get("M", 0.0), 0.0),
        units=units, report={**report, "warnings": warnings},
    )  # fmt: skip
    return Deployment(model, tuple(warnings))


def _level(fit: ModelFit, features: Features, fc: float, warnings: list[str]) -> PositionLevel | None:
    if "position_dependence" not in fit.effects:
        return None
    c = fit.coefficients
    trend = (c.get("Fc_P1", 0.0) / fc, c.get("Fc_P2", 0.0) / fc)
    ripples = []
    for number, period in enumerate(fit.periods, 1):
        harmonics = sum(1 for name in c if name.startswith(f"Fc_R{number}_cos"))
        ripples.append(Ripple(
            period=period,
            cos=tuple(c[f"Fc_R{number}_cos{k}"] / fc for k in range(1, harmonics + 1)),
            sin=tuple(c[f"Fc_R{number}_sin{k}"] / fc for k in range(1, harmonics + 1)),
        ))  # fmt: skip
    total = abs(trend[0]) + abs(trend[1]) + sum(sum(map(abs, r.cos)) + sum(map(abs, r.sin)) for r in ripples)
    if total >= 1.0:  # the factor must stay positive: the level's variation is scaled back
        shrink = 0.95 / total
        warnings.append(
            f"the position-dependent level varies by {total:.0%} of the level: held at 95 % in the file"
        )
        trend = (trend[0] * shrink, trend[1] * shrink)
        ripples = [Ripple(r.period, tuple(x * shrink for x in r.cos), tuple(x * shrink for x in r.sin))
                   for r in ripples]  # fmt: skip
    return PositionLevel(
        middle=features.scales.middle,
        half_stroke=features.scales.half_stroke,
        trend=trend,
        ripples=tuple(ripples),
    )
