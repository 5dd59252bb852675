"""What a candidate model is made of, and its parameters: the catalogue's effects as groups of
the model file's parameters.

A :class:`Structure` says which effects of the catalogue (docs/effects.md) the model holds and,
for ``position_dependence``, in which form. Its parameters θ are the model file's numbers in
coordinates that keep every candidate inside the model's rules with simple bounds:

| effect | θ | the file's numbers |
|---|---|---|
| ``coulomb`` | ``Fc`` | Fc |
| ``viscous`` | ``sigma2`` | σ2 |
| ``stribeck`` | ``Fs_rise``, ``log_Vs``, ``delta`` | Fs = Fc + Fs_rise, Vs = exp(log_Vs), δ |
| ``asymmetry`` | ``Fc_neg``, ``Fs_neg_rise``, ``sigma2_neg`` | the −x levels and viscous coefficient |
| ``asymmetry`` as one factor | ``log_neg_factor`` | every −x level and σ2 the +x one times the factor |
| ``presliding_hysteresis`` | ``log_margin``, ``n``, ``sigma1``, shares | W over a grid of Δ, n, σ1 |
| ``position_dependence`` | ``level_*`` or ``force_*`` | the trend and ripples |
| ``offset``, ``inertia`` | ``offset``, ``inertia`` | the measurement terms |

Without ``presliding_hysteresis`` the hysteresis is one stiff element (Δ below what the log
resolves, W = 2·max(Fs, Fs_neg)): friction that flips within one encoder step and holds its value
at a stop. With it, that stiff element is the first of the bank, so a candidate that adds the bank
starts exactly where the model without it stands.

:func:`unpack` turns θ into the file's values and the derivatives of the friction parameters with
respect to θ, so that the friction's exact sensitivities (:mod:`.sensitivity`) carry over to θ
by one matrix product.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from .._typing import FloatArray
from ..errors import InputError, shown

#: The effect names, in the order the catalogue lists them (docs/effects.md#the-effects).
CATALOGUE = (
    "coulomb",
    "viscous",
    "stribeck",
    "asymmetry",
    "presliding_hysteresis",
    "position_dependence",
    "offset",
    "inertia",
)
#: The two forms of ``position_dependence``: the friction level times 1 + r(x), or a force r(x)
#: added in both directions (docs/model.md#position-dependent-level).
FORMS = ("level", "force")
#: The friction parameters whose sensitivities the simulation gives, in its column order; then W.
FRICTION = ("Fc", "Fs", "Vs", "delta", "n", "sigma1", "sigma2", "Fc_neg", "Fs_neg", "sigma2_neg")
#: The stiff element's W relative to the larger static level.
STIFF_MARGIN = 2.0
#: Harmonics of each ripple period.
HARMONICS = 3
#: The asymmetry's one factor on the −x levels stays within 1/NEG_FACTOR … NEG_FACTOR.
NEG_FACTOR = 20.0


def parse_effects(names: str | Sequence[str], argument: str = "baseline") -> tuple[str, ...]:
    """Effect names from a list or a comma-separated string; unknown or repeated names are refused."""
    given: object = names  # checked as what may come, not as what is declared
    if not isinstance(given, (str, Sequence)) or isinstance(given, (bytes, bytearray)):
        raise InputError(
            f"`{argument}` must be effect names, as a list or comma-separated, got {shown(names)!r:.80}",
            kind="wrong_type",
            field=argument,
        )
    items = [name.strip() for name in names.split(",")] if isinstance(names, str) else list(names)
    items = [name for name in items if name]
    if any(not isinstance(name, str) for name in items):
        raise InputError(
            f"`{argument}` must be effect names (strings), got {shown(items)!r}",
            kind="wrong_type",
            field=argument,
        )
    unknown = [name for name in items if name not in CATALOGUE]
    if unknown:
        raise InputError(
            f"`{argument}` names unknown effects {unknown}: expected names among {list(CATALOGUE)}",
            kind="invalid_choice",
            field=argument,
            value=unknown[0],
            expected=list(CATALOGUE),
        )
    if len(set(items)) != len(items):
        raise InputError(f"`{argument}` repeats effects: got {items}", kind="repeated", field=argument)
    return tuple(items)


@dataclass(frozen=True)
class Structure:
    """The effects a model holds (baseline and named), the form and ripple periods of its
    position dependence, and whether a drift of the level is fitted alongside (never written)."""

    effects: frozenset[str]
    form: str | None = None
    periods: tuple[float, ...] = ()
    trend: bool = True
    drift: bool = False
    neg_factor: bool = False
    """The asymmetry as one factor on every −x level and viscous coefficient (one parameter, as
    an offset is), not levels of their own: a candidate the stand-ins are judged with
    (:func:`leuven_rt.fitting.select._exchange`), never a written file's."""

    def has(self, effect: str) -> bool:
        return effect in self.effects

    def with_effect(
        self, effect: str, *, form: str | None = None, periods: Iterable[float] = ()
    ) -> Structure:
        if effect == "position_dependence":
            return replace(self, effects=self.effects | {effect}, form=form, periods=tuple(periods))
        return replace(self, effects=self.effects | {effect})

    def without(self, effect: str) -> Structure:
        if effect == "position_dependence":
            return replace(self, effects=self.effects - {effect}, form=None, periods=())
        if effect == "asymmetry":
            return replace(self, effects=self.effects - {effect}, neg_factor=False)
        return replace(self, effects=self.effects - {effect})

    def with_drift(self, drift: bool = True) -> Structure:
        return replace(self, drift=drift)

    def names(self) -> list[str]:
        """The names of θ, in order."""
        names: list[str] = []
        if self.has("coulomb"):
            names.append("Fc")
        if self.has("viscous"):
            names.append("sigma2")
        if self.has("stribeck"):
            names += ["Fs_rise", "log_Vs", "delta"]
        if self.has("asymmetry") and self.neg_factor:
            names.append("log_neg_factor")
        elif self.has("asymmetry"):
            names.append("Fc_neg")
            if self.has("stribeck"):
                names.append("Fs_neg_rise")
            if self.has("viscous"):
                names.append("sigma2_neg")
        if self.has("presliding_hysteresis"):
            names += ["log_margin", "n", "sigma1"]
        if self.has("position_dependence"):
            prefix = f"{self.form}_"
            if self.trend:
                names += [prefix + "t1", prefix + "t2"]
            for r, _ in enumerate(self.periods):
                names += [f"{prefix}r{r}_cos{k + 1}" for k in range(HARMONICS)]
                names += [f"{prefix}r{r}_sin{k + 1}" for k in range(HARMONICS)]
        if self.has("offset"):
            names.append("offset")
        if self.has("inertia"):
            names.append("inertia")
        if self.drift:
            names.append("drift")
        return names

    def share_names(self, elements: int) -> list[str]:
        return [f"share_{i}" for i in range(elements)] if self.has("presliding_hysteresis") else []


@dataclass(frozen=True, eq=False)
class Scales:
    """What a log sets for every candidate: the speeds it covers (bounds of Vs), the force scale,
    the element grid, the positions' middle and half stroke (for the trend)."""

    speed_low: float
    speed_high: float
    force: float
    stiff: float
    """Δ of the stiff element [m or rad]: below what the log resolves."""
    grid: FloatArray
    """Δ of the presliding bank after the stiff element, increasing [m or rad]."""
    middle: float
    half_stroke: float

    @property
    def deltas(self) -> FloatArray:
        return np.concatenate(([self.stiff], self.grid))


@dataclass(frozen=True, eq=False)
class Values:
    """The model file's numbers at θ, and d(friction parameters)/dθ."""

    friction: dict[str, float | tuple[float, ...] | None]
    """Fc, Fs, Vs, delta, n, sigma1, sigma2, Fc_neg, Fs_neg, sigma2_neg (None when symmetric),
    W, Delta: the keyword arguments of :class:`~leuven_rt.Params`."""
    W: FloatArray
    Delta: FloatArray
    jacobian: FloatArray = field(repr=False)
    """(len(FRICTION) + len(W), len(θ)): d(Fc, Fs, Vs, δ, n, σ1, σ2, Fc_neg, Fs_neg, σ2_neg, W…)/dθ,
    the −x columns standing for the same parameter as the +x ones when the model is symmetric."""
    level: tuple[tuple[float, float], tuple[tuple[float, tuple[float, ...], tuple[float, ...]], ...]] | None
    force: tuple[tuple[float, float], tuple[tuple[float, tuple[float, ...], tuple[float, ...]], ...]] | None
    offset: float
    inertia: float
    drift: float


def bounds(structure: Structure, scales: Scales, elements: int) -> tuple[FloatArray, FloatArray]:
    """Lower and upper bounds of θ."""
    tiny = 1e-9 * scales.force
    low, high = [], []
    for name in structure.names() + structure.share_names(elements):
        if name in ("Fc", "Fc_neg"):
            lo, hi = tiny, math.inf
        elif name in (
            "sigma1",
            "sigma2",
            "sigma2_neg",
            "Fs_rise",
            "Fs_neg_rise",
            "inertia",
        ) or name.startswith("share_"):
            lo, hi = 0.0, math.inf
        elif name == "log_Vs":
            lo, hi = math.log(scales.speed_low), math.log(scales.speed_high)
        elif name == "log_neg_factor":
            lo, hi = -math.log(NEG_FACTOR), math.log(NEG_FACTOR)
        elif name == "delta":
            lo, hi = 0.5, 4.0
        elif name == "n":
            lo, hi = 0.5, 6.0
        elif name == "log_margin":
            lo, hi = math.log(1.01), math.log(10.0)
        elif name.startswith("level_") or name == "drift":
            # The level's factor must stay positive: each coefficient within ±0.5 (the file's rule,
            # Σ|coefficients| < 1, is checked at every evaluation: evaluate.evaluate).
            lo, hi = -0.5, 0.5
        else:
            lo, hi = -math.inf, math.inf
        low.append(lo)
        high.append(hi)
    return np.array(low), np.array(high)


def start(
    structure: Structure, scales: Scales, elements: int, previous: Mapping[str, float]
) -> dict[str, float]:
    """θ where a candidate starts: the values of the model it extends, and for the new effect the
    values at which it adds nothing (Fs = Fc, −x levels = +x levels, a flat level, no force), so
    that such a candidate starts exactly at the model it extends. The presliding bank is the
    exception: it starts with its weight spread evenly over its elements. With all of it on the
    stiff element (the model it extends) the fit starts where the other elements' sensitivities
    vanish at their bound, and under the robust loss it stays there: a log whose reversals the
    baseline misses by far more than the noise never got its bank (measured on closed-loop logs;
    on holdout-v2's presliding logs the even start also ends lower)."""
    out: dict[str, float] = {}
    middle_speed = 0.5 * (math.log(scales.speed_low) + math.log(scales.speed_high))
    for name in structure.names() + structure.share_names(elements):
        if name in previous:
            out[name] = previous[name]
        elif name == "Fc":
            out[name] = 0.5 * scales.force
        elif name == "Fc_neg":
            out[name] = previous.get("Fc", 0.5 * scales.force)
        elif name == "Fs_neg_rise":
            out[name] = previous.get("Fs_rise", 0.0)
        elif name == "sigma2_neg":
            out[name] = previous.get("sigma2", 0.0)
        elif name == "log_Vs":
            out[name] = middle_speed
        elif name == "delta":
            out[name] = 1.0
        elif name == "log_margin":
            out[name] = math.log(STIFF_MARGIN)
        elif name == "n":
            out[name] = 2.0
        elif name.startswith("share_"):
            out[name] = 1.0
        else:
            out[name] = 0.0
    return out


def unpack(structure: Structure, scales: Scales, theta: Mapping[str, float]) -> Values:
    """The model file's values at ``theta`` (module documentation)."""
    names = structure.names() + structure.share_names(scales.deltas.size)
    index = {name: i for i, name in enumerate(names)}
    deltas = scales.deltas
    elements = deltas.size if structure.has("presliding_hysteresis") else 1
    jac = np.zeros((len(FRICTION) + elements, len(names)))
    row = {name: i for i, name in enumerate(FRICTION)}

    def depends(parameter: str, on: str, value: float = 1.0) -> None:
        if on in index:
            jac[row[parameter], index[on]] += value

    tiny = 1e-9 * scales.force
    fc = theta["Fc"] if structure.has("coulomb") else tiny
    fs = fc + theta.get("Fs_rise", 0.0)
    vs = math.exp(theta["log_Vs"]) if structure.has("stribeck") else scales.speed_high
    delta = theta.get("delta", 2.0)
    sigma2 = theta.get("sigma2", 0.0)
    asymmetric = structure.has("asymmetry")
    factored = asymmetric and structure.neg_factor
    if factored:
        factor = math.exp(theta["log_neg_factor"])
        fc_neg, fs_neg, sigma2_neg = factor * fc, factor * fs, factor * sigma2
    else:
        factor = 1.0
        fc_neg = theta["Fc_neg"] if asymmetric else fc
        fs_neg = fc_neg + theta.get("Fs_neg_rise", 0.0) if asymmetric else fs
        sigma2_neg = theta.get("sigma2_neg", sigma2) if asymmetric else sigma2
    for side, suffix in (("", ""), ("_neg", "_neg")):
        # A symmetric model's −x parameters are the +x ones: their columns add to the same θ; a
        # factored one's are the factor times them.
        source = suffix if asymmetric and not factored else ""
        scale = factor if side else 1.0
        depends("Fc" + side, "Fc" + source, scale)
        depends("Fs" + side, "Fc" + source, scale)
        depends("Fs" + side, "Fs" + (source + "_rise" if source else "_rise"), scale)
        depends("sigma2" + side, "sigma2" + source, scale)
    if factored:
        depends("Fc_neg", "log_neg_factor", fc_neg)
        depends("Fs_neg", "log_neg_factor", fs_neg)
        depends("sigma2_neg", "log_neg_factor", sigma2_neg)
    depends("Vs", "log_Vs", vs)
    depends("delta", "delta")
    top = max(fs, fs_neg)
    # d(top)/dθ: the larger static level's.
    if factored and fs_neg > fs:
        top_theta = {"Fc": factor, "Fs_rise": factor, "log_neg_factor": fs_neg}
    elif asymmetric and fs_neg > fs:
        top_theta = {"Fc_neg": 1.0, "Fs_neg_rise": 1.0}
    else:
        top_theta = {"Fc": 1.0, "Fs_rise": 1.0}
    if structure.has("presliding_hysteresis"):
        shares = np.array([theta[f"share_{i}"] for i in range(elements)])
        total = max(float(shares.sum()), 1e-300)
        margin = math.exp(theta["log_margin"])
        weights = shares / total * margin * top
        n = theta["n"]
        depends("n", "n")
        depends("sigma1", "sigma1")
        for i in range(elements):
            r = len(FRICTION) + i
            jac[r, index["log_margin"]] = weights[i]
            for j in range(elements):
                jac[r, index[f"share_{j}"]] = margin * top * ((i == j) / total - shares[i] / total**2)
            for name, slope in top_theta.items():
                if name in index:
                    jac[r, index[name]] += weights[i] / top * slope
        used = deltas
    else:
        weights = np.array([STIFF_MARGIN * top])
        n = 2.0
        for name, slope in top_theta.items():
            if name in index:
                jac[len(FRICTION), index[name]] += STIFF_MARGIN * slope
        used = deltas[:1]
    friction: dict[str, float | tuple[float, ...] | None] = {
        "Fc": fc, "Fs": fs, "Vs": vs, "delta": delta, "n": n, "sigma1": theta.get("sigma1", 0.0),
        "sigma2": sigma2,
        "Fc_neg": fc_neg if asymmetric else None, "Fs_neg": fs_neg if asymmetric else None,
        "sigma2_neg": sigma2_neg if asymmetric else None,
    }  # fmt: skip
    return Values(
        friction=friction,
        W=weights,
        Delta=used,
        jacobian=jac,
        level=_series(structure, "level", theta),
        force=_series(structure, "force", theta),
        offset=theta.get("offset", 0.0),
        inertia=theta.get("inertia", 0.0),
        drift=theta.get("drift", 0.0),
    )


def _series(
    structure: Structure, form: str, theta: Mapping[str, float]
) -> tuple[tuple[float, float], tuple[tuple[float, tuple[float, ...], tuple[float, ...]], ...]] | None:
    if not structure.has("position_dependence") or structure.form != form:
        return None
    prefix = f"{form}_"
    trend = (theta.get(prefix + "t1", 0.0), theta.get(prefix + "t2", 0.0))
    ripples = tuple(
        (
            period,
            tuple(theta[f"{prefix}r{r}_cos{k + 1}"] for k in range(HARMONICS)),
            tuple(theta[f"{prefix}r{r}_sin{k + 1}"] for k in range(HARMONICS)),
        )
        for r, period in enumerate(structure.periods)
    )
    return trend, ripples


__all__ = [
    "CATALOGUE",
    "FORMS",
    "FRICTION",
    "HARMONICS",
    "Scales",
    "Structure",
    "Values",
    "bounds",
    "parse_effects",
    "start",
    "unpack",
]
