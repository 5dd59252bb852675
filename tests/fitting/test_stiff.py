"""The stiff element a logged velocity drives: where no presliding bank is named, its deflection
is chosen on the file's error, because a logged velocity shows the starts an encoder cannot."""

from __future__ import annotations

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt.data.records import MotionData
from leuven_rt.fitting import select

NOISE = 0.02
SUBSTEPS = 10


def strokes(deflection: float, dt: float = 1e-3, seconds: float = 8.0, dwell: float = 0.05) -> MotionData:
    """Strokes of 4.5 mm at up to 20 mm/s with a dwell at every reversal, their velocity rising
    from rest as sin² (a jerk-limited start: the first samples move by far less than 1 µm);
    the true law (one element of break deflection ``deflection``) simulated ``SUBSTEPS`` steps a
    sample, a 1 µm encoder, the velocity logged, force noise ``NOISE``."""
    h = dt / SUBSTEPS
    t = np.arange(int(seconds / h)) * h
    leg = 0.5 - dwell
    within = t % 1.0
    v = np.zeros_like(t)
    forward = (within >= dwell / 2) & (within < dwell / 2 + leg)
    back = (within >= 1.5 * dwell + leg) & (within < 1.5 * dwell + 2 * leg)
    v[forward] = 0.02 * np.sin(np.pi * (within[forward] - dwell / 2) / leg) ** 2
    v[back] = -0.02 * np.sin(np.pi * (within[back] - 1.5 * dwell - leg) / leg) ** 2
    x = np.cumsum(v) * h
    truth = lr.Params(Fc=1.0, Fs=1.5, Vs=0.002, delta=2.0, n=2.0, sigma2=5.0, W=[1.7], Delta=[deflection])
    f = lr.simulate(truth, v, h)
    kept = slice(None, None, SUBSTEPS)
    noise = np.random.default_rng(3).normal(0.0, NOISE, t[kept].size)
    return MotionData(t[kept], np.round(x[kept] / 1e-6) * 1e-6, f[kept] + noise, v=v[kept])


def test_the_deflection_follows_the_starts_a_logged_velocity_shows() -> None:
    # At the default deflection (a billionth of the stroke) the force rises at every start far
    # sooner than the true law's 1 nm element lets it: 4.7 times the noise. Chosen: 1.2 times.
    record = strokes(1e-9)
    identification = lr.identify(record, "coulomb,viscous")
    assert identification.diagnosis.named_effects == ["stribeck"]
    error = lr.predict(identification.model, record).f_model - record.f
    assert np.sqrt(np.mean(error**2)) < 1.3 * NOISE
    assert 1e-10 < identification.model.friction.Delta[0] < 1e-8


@pytest.mark.parametrize("with_velocity", [True, False])
def test_the_default_deflection_stays_where_nothing_is_gained(with_velocity: bool) -> None:
    # The true element is as stiff as a 1 kHz log can show; an encoder alone shows no start.
    record = strokes(1e-10)
    if not with_velocity:
        record = MotionData(record.t, record.x, record.f)
    model = lr.identify(record, "coulomb,viscous").model
    assert model.reconstruction.source == ("velocity" if with_velocity else "position")
    default = select.prepare(record, model.reconstruction, False)[1].stiff
    assert model.friction.Delta == (default,)
