"""A long record is named on whole segments of it (docs/effects.md#long-records): the segments
are spread over the record, their lead-ins are simulated but neither fitted nor judged, and the
forces on them are those of a simulation of the whole record."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt.data.reconstruction import noisy_position
from leuven_rt.data.synthetic import make_data
from leuven_rt.discrepancy.hidden import make_hidden
from leuven_rt.fitting import Settings, select
from leuven_rt.fitting.evaluate import evaluate
from leuven_rt.fitting.sample import LONGEST_LEAD, MIN_LEAD, SEGMENTS, segments
from leuven_rt.fitting.select import FIT_ROWS, prepare, rounds_reconstruction
from leuven_rt.fitting.solve import Target
from leuven_rt.fitting.structure import Scales, Structure, start

BUDGET = 8192
EFFECTS = ("coulomb", "viscous", "stribeck", "presliding_hysteresis")


def whole_target(data: lr.MotionData) -> tuple[Target, Scales]:
    noisy = noisy_position(data.x, data.dt)
    return prepare(data, rounds_reconstruction(data, noisy), noisy)


def test_a_record_within_the_budget_is_used_whole() -> None:
    data = make_data(seed=0).data
    target, scales = whole_target(data)
    assert segments(target.motion, float(scales.grid[-1]), data.samples) is None
    assert segments(target.motion, float(scales.grid[-1]), data.samples - 1) is not None


def test_the_segments_are_spread_over_the_record_and_their_lead_ins_are_not_fitted() -> None:
    data = make_data(seed=0).data
    target, scales = whole_target(data)
    sample = segments(target.motion, float(scales.grid[-1]), BUDGET)
    assert sample is not None
    assert sample.size == BUDGET
    fitted = sample.take[~sample.lead]
    length = BUDGET // SEGMENTS
    assert fitted[0] == 0 and fitted[-1] == data.samples - 1
    assert np.all(np.diff(fitted) > 0)  # no sample fitted twice
    pieces = np.split(sample.take, sample.starts[1:])
    assert len(pieces) == SEGMENTS
    for piece, begin in zip(pieces, sample.starts, strict=True):
        lead = sample.lead[begin : begin + piece.size]
        assert np.count_nonzero(~lead) == length
        assert np.all(np.diff(piece) == 1)  # each piece is contiguous in the record
        assert begin == 0 or MIN_LEAD <= np.count_nonzero(lead) <= LONGEST_LEAD * length
    on = sample.of(target, FIT_ROWS)
    assert np.all(on.weight[sample.lead] == 0) and not np.any(on.judged[sample.lead])
    assert np.array_equal(on.weight[~sample.lead], target.weight[fitted])


@pytest.mark.parametrize("logged_velocity", [False, True])
def test_the_forces_on_the_segments_are_those_of_the_whole_record(logged_velocity: bool) -> None:
    """To within 5 % of the noise in rms, for a bank that settles slowly (equal weights over the
    grid, 1.05 times the static level)."""
    if logged_velocity:
        log = make_hidden(EFFECTS, dt=2e-4, with_velocity=True, samples=100_000)
        data, noise, budget = log.data, log.noise_std, 65_536
    else:
        synthetic = make_data(seed=0)
        data, noise, budget = synthetic.data, synthetic.noise_std, 16_384
    target, scales = whole_target(data)
    structure = Structure(frozenset(EFFECTS))
    elements = scales.deltas.size
    given = {"Fc": 1.0, "sigma2": 10.0, "Fs_rise": 0.5, "log_margin": float(np.log(1.05))}
    theta = start(structure, scales, elements, given)
    theta.update({f"share_{i}": 1.0 / elements for i in range(elements)})
    whole = evaluate(structure, scales, theta, target.motion, target.tau, None).force
    sample = segments(target.motion, float(scales.grid[-1]), budget)
    assert sample is not None
    on = sample.of(target, FIT_ROWS)
    assert on.motion.input == ("velocity" if logged_velocity else "position")
    sampled = evaluate(structure, scales, theta, on.motion, on.tau, None).force
    error = (sampled - whole[sample.take])[~sample.lead]
    assert np.sqrt(np.mean(error**2)) <= 0.05 * noise
    assert np.max(np.abs(error)) <= 0.25 * noise


def test_a_long_record_is_named_on_the_sample_and_its_file_fitted_whole() -> None:
    log = make_data(seed=0)
    result = lr.identify(log.data, settings=Settings(rounds_samples=16_384))
    assert set(result.diagnosis.named_effects) == {"stribeck", "presliding_hysteresis"}
    assert lr.predict(result.model, log.data).rms <= 1.2 * log.noise_std
    assert result.diagnosis.rms_after == pytest.approx(lr.predict(result.model, log.data).rms, rel=1e-12)


PERIOD = 0.0125


def ripple_log(form: str) -> lr.MotionData:
    """A slide over a 0.1 stroke (8 periods of :data:`PERIOD`) with its velocity logged: a force
    that repeats with the position, or a friction level that does."""
    dt = 1e-3
    t = np.arange(20_000) * dt
    x = 0.05 * (1.0 - np.cos(2 * np.pi * 0.25 * t))
    v = np.diff(x, prepend=x[0]) / dt
    friction = lr.Params(Fc=1.0, Fs=1.0, Vs=0.01, delta=2.0, n=2.0, sigma2=2.0, W=[1.02], Delta=[1e-9])
    ripple = 0.1 * np.sin(2 * np.pi * x / PERIOD)
    force = lr.simulate(friction, v, dt)
    force = force + ripple if form == "force" else force * (1.0 + ripple)
    noise = 0.01 * np.random.default_rng(0).standard_normal(t.size)
    return lr.MotionData(t, x, force + noise, v=v)


@pytest.mark.parametrize("form", ["force", "level"])
def test_the_written_files_ripple_period_is_found_again_on_the_whole_record(form: str) -> None:
    """A period read on a sample that covers part of the stroke can be off: the written file's
    is searched again on the whole record (docs/effects.md#long-records)."""
    target, scales = whole_target(ripple_log(form))
    quiet: list[str] = []
    base = Structure(frozenset({"coulomb", "viscous"}))
    off = base.with_effect("position_dependence", form=form, periods=(0.8 * PERIOD,))
    written = select.fit(off, scales, target, {"Fc": 1.0, "sigma2": 1.0})
    found = select._period_on_whole(written, target, scales, quiet.append)
    (again,) = found.structure.periods
    assert again == pytest.approx(PERIOD, rel=1e-3)
    assert select.full_mse(found, target) < 0.5 * select.full_mse(written, target)
    assert len(quiet) == 1 and quiet[0].startswith("the ripple's period found anew on the whole record")
    # Within the search's refinement of the period the file holds, the file stays as it is.
    assert select._period_on_whole(found, target, scales, quiet.append) is found
    plain = select.fit(base, scales, target, {"Fc": 1.0, "sigma2": 1.0})
    assert select._period_on_whole(plain, target, scales, quiet.append) is plain
    assert len(quiet) == 1


def test_a_sampled_record_gives_the_file_and_the_report_the_period_found_on_the_whole(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Where the period changes on the whole record, the file holds it, the rounds' model that
    what remains is judged on is refitted with it, and the report's step gives it."""
    calls: list[tuple[float, ...]] = []
    search = select._period_on_whole

    def off_first(written: Any, target: Target, scales: Scales, say: Any) -> Any:
        # As if the sample had read the period 20 % short.
        calls.append(written.structure.periods)
        (period,) = written.structure.periods
        start = select.fit(dataclasses.replace(written.structure, periods=(0.8 * period,)), scales, target,
                           written.theta)  # fmt: skip
        return search(start, target, scales, say)

    monkeypatch.setattr(select, "_period_on_whole", off_first)
    record = ripple_log("force")
    run = select.select(record, ("coulomb", "viscous"), Settings(rounds_samples=4096))
    assert len(calls) == 1
    (period,) = run.written.structure.periods
    assert period == pytest.approx(PERIOD, rel=1e-3)
    assert run.without_drift.structure == run.written.structure
    assert run.final.structure.periods == (period,)
    found = lr.identify(record, settings=Settings(rounds_samples=4096))
    [step] = found.diagnosis.to_dict()["steps"]
    [ripple] = found.model.to_dict()["position_force"]["ripples"]
    assert step["params"]["periods"] == [ripple["period"]] and len(calls) == 2
