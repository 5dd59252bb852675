"""Generated logs in which catalogue effects are hidden, to test the discrepancy workflow.

The friction comes from the project's simulator (:func:`leuven_rt.simulate_position`) driven by
the excitation of :mod:`leuven_rt.data.synthetic`; the effects named in ``truth`` switch its parts on:

- ``coulomb`` is always there (the model needs Fc > 0); ``viscous``: σ2 = :data:`SIGMA2`;
- ``stribeck``: Fs = 1.5·Fc (otherwise Fs = Fc); ``asymmetry``: the −x levels at 0.7 of the +x
  ones (Fc_neg, Fs_neg, sigma2_neg);
- ``presliding_hysteresis``: Maxwell-slip elements up to a 10 µm presliding range; without it
  the elements end at :data:`STIFF_RANGE`, below the encoder's resolution, so presliding is
  invisible in the data;
- ``position_dependence``: a level (:class:`~leuven_rt.PositionLevel`) that scales the contact
  force linearly along the stroke, ±:data:`POSITION_SLOPE` at its ends;
- the other effects are added to the simulated friction: ``offset`` (a bias), ``inertia``
  (m·ẍ of the true motion), and, outside the catalogue, ``drift`` (the level grows linearly over
  time).

The log is the truth plus white force noise, the position quantized; ``with_velocity`` adds a
``v`` column (the true velocity: the one the friction was simulated with, the differences of the
true position over each step), otherwise only x is given.
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass

import numpy as np

from .._typing import FloatArray
from ..data.records import MotionData
from ..data.synthetic import excitation
from ..fitting.structure import parse_effects
from ..level import PositionLevel
from ..params import Params
from ..simulation import simulate_position

FC = 1.0  # N
SIGMA2 = 10.0  # N·s/m
VS = 1e-3  # m/s
PRESLIDING_RANGE = 1e-5  # m
STIFF_RANGE = 1e-12  # m
ASYMMETRY = 0.7
OFFSET = 0.3  # N
MASS = 0.05  # kg
POSITION_SLOPE = 0.25  # relative change of the level across half the stroke
DRIFT = 0.4  # N over the record


@dataclass(frozen=True, eq=False)
class HiddenData:
    data: MotionData
    truth: tuple[str, ...]
    drift: bool
    force_true: FloatArray
    noise_std: float
    x_true: FloatArray
    """The position before quantization [m]."""
    direction: FloatArray
    """The direction of motion the friction's Coulomb part follows, in [−1, 1]."""


def make_hidden(
    truth: Collection[str], *, drift: bool = False, dt: float = 4e-4, noise_std: float = 0.02,
    quantization: float = 1e-9, with_velocity: bool = False, seed: int = 0, elements: int = 6,
    samples: int | None = None,
) -> HiddenData:  # fmt: skip
    """A log of ``truth`` (module documentation). ``samples``: the log's length, the excitation
    repeated with fresh random draws (each run continuing where the last ended) until it is
    that long, then cut; default: one run of the excitation."""
    effects = parse_effects(list(truth), "truth")
    rng = np.random.default_rng(seed)
    x_true = excitation(dt, PRESLIDING_RANGE, VS, rng)
    if samples is not None:
        runs = [x_true]
        while sum(run.size for run in runs) < samples:
            runs.append(runs[-1][-1] + excitation(dt, PRESLIDING_RANGE, VS, rng))
        x_true = np.concatenate(runs)[:samples]
    # The velocity simulate_position steps with (v₀ = 0, vₖ = (xₖ − xₖ₋₁)/dt): the log's `v` is
    # then the velocity the truth saw.
    v_true = np.concatenate([[0.0], np.diff(x_true) / dt])
    asymmetric = "asymmetry" in effects
    span = PRESLIDING_RANGE if "presliding_hysteresis" in effects else STIFF_RANGE
    index = np.arange(1, elements + 1)
    fs = 1.5 * FC if "stribeck" in effects else FC
    weights = (elements + 1 - index) / np.sum(index) * fs * 1.02
    sigma2 = SIGMA2 if "viscous" in effects else 0.0
    params = Params(
        Fc=FC, Fs=fs, Vs=VS, delta=2.0, n=2.0, sigma1=0.0, sigma2=sigma2,
        W=tuple(weights), Delta=tuple(span * index / elements),
        **({"Fc_neg": ASYMMETRY * FC, "Fs_neg": ASYMMETRY * fs, "sigma2_neg": ASYMMETRY * sigma2}
           if asymmetric else {}),
    )  # fmt: skip
    level = None
    if "position_dependence" in effects:
        # The contact force (presliding included) scales with the position, as a normal load
        # that varies along the stroke scales it.
        middle, half = 0.5 * (x_true.max() + x_true.min()), 0.5 * np.ptp(x_true)
        level = PositionLevel(middle=float(middle), half_stroke=float(half), trend=(POSITION_SLOPE, 0.0))
    force = simulate_position(params, x_true, dt, level=level)
    # The direction a drift follows is that of a unit Coulomb level (one element below the
    # encoder's resolution) through the same simulator, so that it flips on the same sample as
    # the friction's Coulomb part.
    unit = Params(
        Fc=1.0, Fs=1.0, Vs=VS, delta=2.0, n=2.0, sigma1=0.0, sigma2=0.0, W=(1.02,), Delta=(STIFF_RANGE,)
    )
    direction = simulate_position(unit, x_true, dt)
    if "offset" in effects:
        force += OFFSET
    if "inertia" in effects:
        force += MASS * np.gradient(v_true, dt)
    if drift:
        force += DRIFT * direction * np.linspace(0.0, 1.0, x_true.size)
    measured = force + rng.normal(0.0, noise_std, force.size)
    x = np.round(x_true / quantization) * quantization if quantization > 0 else x_true.copy()
    t = np.arange(x.size) * dt
    data = MotionData(
        t, x, measured, v_true if with_velocity else None, source=f"hidden({','.join(effects)})"
    )
    return HiddenData(data, effects, drift, force, noise_std, x_true, direction)
