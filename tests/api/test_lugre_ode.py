"""The LuGre special case (n = 1, Fh = σ0·z) of the discrete step against the LuGre ODE.

Both the numpy reference and the Rust core are checked against an independent solution of

    dz/dt = v − σ0·|v|·z/g(v),    F = σ0·z + σ1·dz/dt + σ2·v,

integrated by scipy's Radau (rtol 1e-10) for a smooth velocity that slides, slows down, reverses
and comes back: v(t) = 5e-3·sin(2π·2·t) + 2e-3 m/s over one period (0.5 s).

Time alignment. Step k holds v(t_k) over [t_k, t_{k+1}] and ends with z_{k+1}, so Fₖ claims to
be the force at the END of the step and is compared with the continuous force there,
F(t_{k+1}) = σ0·z(t_{k+1}) + σ1·ż(t_{k+1}) + σ2·v(t_{k+1}), ż taken from the ODE's right-hand
side (not by differentiating the interpolant). Every term of Fₖ differs from its continuous
counterpart by O(dt): z_{k+1} from backward Euler and from the held input, (z_{k+1} − z_k)/dt as a
one-sided difference, σ2·v(t_k) for σ2·v(t_{k+1}) from the hold. In quasi-static sliding (the
state's rate σ0·|v|/g, up to ~700 /s, far above the input's 4π rad/s except right at the
reversals) the two first-order errors
add up to a plain delay: the hold delays the input by dt/2 on average and backward Euler lags by
another dt/2, so z_{k+1} ≈ z(t_k). `test_the_discrete_force_lags_by_about_one_step` pins that
down (error against F(t_k) is ~2.3 × smaller than against F(t_{k+1})); it is what a controller
using this step as a feedforward sees, and it vanishes at first order as dt → 0.

Tolerance. With first-order error the RMS force error is C·dt; at dt = 1e-5 s it is 2.0e-4 N
(0.013 % of Fs) for the implicit scheme, and the bound asserted is 5e-4 N (2.5 × the observed
value; the Radau solution is ~3e-11 N accurate, checked once against rtol 1e-12, so it contributes
nothing). The convergence check is what shows the step is right rather than merely close:
halving dt from 2e-5 to 1e-5 to 5e-6 s must divide the RMS error by 2 ± 0.2 each time (observed
2.00). A wrong g, n, or a mis-scaled σ0, σ1 or σ2 term would leave an error floor that does not
shrink with dt, and the ratio would collapse towards 1.
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import pairwise

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

import leuven_rt
from leuven_rt import reference

SIGMA0, SIGMA1, SIGMA2 = 1e5, float(np.sqrt(1e5)), 0.4
FC, FS, VS, DELTA = 1.0, 1.5, 1e-3, 2.0
LUGRE = dict(Fc=FC, Fs=FS, Vs=VS, delta=DELTA, n=1.0, sigma0=SIGMA0, sigma1=SIGMA1, sigma2=SIGMA2)

DURATION = 0.5  # one period of the velocity
STEPS = (2e-5, 1e-5, 5e-6)
FINEST = STEPS[-1]
RMS_BOUND_AT_1E5 = 5e-4  # N

Simulate = Callable[..., NDArray[np.float64]]
IMPLEMENTATIONS = {"reference": reference.simulate, "rust": leuven_rt.simulate}


def velocity(t: NDArray[np.float64]) -> NDArray[np.float64]:
    return 5e-3 * np.sin(2 * np.pi * 2 * t) + 2e-3


def g(v: NDArray[np.float64]) -> NDArray[np.float64]:
    return FC + (FS - FC) * np.exp(-(np.abs(v / VS) ** DELTA))


def dz_dt(t: NDArray[np.float64], z: NDArray[np.float64]) -> NDArray[np.float64]:
    v = velocity(t)
    return v - SIGMA0 * np.abs(v) * z / g(v)


def jacobian(t: float, z: NDArray[np.float64]) -> NDArray[np.float64]:
    v = velocity(np.asarray(t))
    return np.array([[-SIGMA0 * np.abs(v) / g(v)]])


@pytest.fixture(scope="module")
def ode_force() -> NDArray[np.float64]:
    """F(t) of the ODE at t = 0, FINEST, 2·FINEST, …, DURATION (the ends of the finest steps)."""
    t = np.arange(round(DURATION / FINEST) + 1) * FINEST
    solution = solve_ivp(
        dz_dt, (0.0, DURATION), [0.0], method="Radau", rtol=1e-10, atol=1e-18, jac=jacobian, t_eval=t
    )
    assert solution.success, solution.message
    z = solution.y[0]
    return SIGMA0 * z + SIGMA1 * dz_dt(t, z) + SIGMA2 * velocity(t)


def rms_error(
    simulate: Simulate, ode_force: NDArray[np.float64], dt: float, scheme: str, at: str = "end"
) -> float:
    """RMS of Fₖ − F(t_{k+1}) (``at="end"``) or of Fₖ − F(t_k) (``at="start"``) over the run."""
    samples = round(DURATION / dt)
    stride = round(dt / FINEST)
    t_start = np.arange(samples) * dt  # v is held at the start of each step
    force = simulate(LUGRE, velocity(t_start), dt, scheme)
    first = stride if at == "end" else 0
    continuous = ode_force[first : first + samples * stride : stride]
    assert continuous.shape == force.shape
    return float(np.sqrt(np.mean((force - continuous) ** 2)))


def test_the_velocity_reverses_and_slides() -> None:
    v = velocity(np.linspace(0.0, DURATION, 10_001))
    assert v.min() < -2 * VS and v.max() > 5 * VS


@pytest.mark.parametrize("name", IMPLEMENTATIONS)
def test_implicit_step_converges_to_the_ode_at_first_order(name: str, ode_force: NDArray[np.float64]) -> None:
    errors = [rms_error(IMPLEMENTATIONS[name], ode_force, dt, "implicit") for dt in STEPS]
    assert errors[1] < RMS_BOUND_AT_1E5
    for coarse, fine in pairwise(errors):
        assert coarse / fine == pytest.approx(2.0, abs=0.2)


@pytest.mark.parametrize("name", IMPLEMENTATIONS)
def test_explicit_step_is_as_close_when_the_step_is_fine(name: str, ode_force: NDArray[np.float64]) -> None:
    """At dt = 1e-5, dt·|v|·σ0/g ≤ 0.007: forward Euler is far inside its stability limit of 2."""
    assert rms_error(IMPLEMENTATIONS[name], ode_force, 1e-5, "explicit") < RMS_BOUND_AT_1E5


@pytest.mark.parametrize("name", IMPLEMENTATIONS)
def test_the_discrete_force_lags_by_about_one_step(name: str, ode_force: NDArray[np.float64]) -> None:
    """Half a step from the hold, half from backward Euler (see the module docstring)."""
    simulate = IMPLEMENTATIONS[name]
    at_end = rms_error(simulate, ode_force, 1e-5, "implicit", at="end")
    at_start = rms_error(simulate, ode_force, 1e-5, "implicit", at="start")
    assert at_start < at_end / 1.5
