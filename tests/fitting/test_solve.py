"""The fit's result: the force it returns is the one its θ simulates."""

from __future__ import annotations

import numpy as np
from test_rounds import rounds_target, slowly_sampled_bank

from leuven_rt.fitting import select
from leuven_rt.fitting.evaluate import evaluate
from leuven_rt.fitting.solve import fit
from leuven_rt.fitting.structure import Structure


def test_the_force_returned_is_the_one_the_returned_theta_simulates() -> None:
    # The force is taken from the solver's last accepted point, not simulated again. On this log
    # the asymmetry's fit from the baseline evaluates a step it rejects last (after 4 evaluations
    # and when it converges after 6), so the point it returns is not the last one evaluated.
    record = slowly_sampled_bank()
    target, scales = rounds_target(record)
    structure = Structure(frozenset({"coulomb", "viscous"}))
    base = fit(structure, scales, target, {"Fc": 4.0, "sigma2": 50.0})
    asymmetric = structure.with_effect("asymmetry")
    for iterations in range(2, select.SCREEN + 1):
        fitted = fit(asymmetric, scales, target, base.theta, iterations)
        simulated = evaluate(asymmetric, scales, fitted.theta, target.motion, target.tau, None)
        assert np.array_equal(fitted.force, simulated.force)
        assert fitted.mse == target.mse(simulated.force)
