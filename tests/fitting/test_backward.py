"""The backward round (:mod:`leuven_rt.fitting.select`): the scale it counts errors at, the
exchange of a named effect for its stand-in, and the drift pass, which runs the rounds again
from the forward rounds' target."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest
from scipy import signal
from threadpoolctl import threadpool_limits

import leuven_rt as lr
from leuven_rt.data.reconstruction import noisy_position
from leuven_rt.data.records import MotionData
from leuven_rt.fitting import Settings, select
from leuven_rt.fitting.select import ROBUST, STAND_INS, Step
from leuven_rt.fitting.solve import Fitted, Target, fit
from leuven_rt.fitting.structure import Scales, Structure

NOISE = 0.02
#: The unit of evidence the exchanges are judged in: the noise's variance.
UNIT = NOISE**2
DT = 1e-3
BASE = Structure(frozenset({"coulomb", "viscous"}))
SYMMETRIC = lr.Params(Fc=1.0, Fs=1.0, Vs=0.01, delta=2.0, n=2.0, sigma2=2.0, W=[2.0], Delta=[1e-9])
#: The −x levels lower and the −x viscous slope steeper: an offset can take up only part of it.
ASYMMETRIC = lr.Params(Fc=1.0, Fs=1.0, Vs=0.01, delta=2.0, n=2.0, sigma2=2.0, Fc_neg=0.6, Fs_neg=0.6,
                       sigma2_neg=4.0, W=[2.0], Delta=[1e-9])  # fmt: skip
STRIBECK = lr.Params(Fc=1.0, Fs=1.5, Vs=0.01, delta=2.0, n=2.0, sigma2=2.0, W=[3.0], Delta=[1e-9])


@pytest.fixture(autouse=True)
def one_blas_thread() -> Iterator[None]:
    """As :func:`leuven_rt.identify` runs the rounds: their many small factorisations are slower
    with threads on a busy machine."""
    with threadpool_limits(limits=1, user_api="blas"):
        yield


def log(
    truth: lr.Params,
    *,
    offset: float = 0.0,
    drift: float = 0.0,
    cutoff: float | None = None,
    samples: int = 8000,
) -> MotionData:
    """A slide back and forth with its velocity logged: ``truth``'s force, plus ``offset``, plus a
    Coulomb level growing by ``drift`` over the record, plus noise of rms :data:`NOISE`, white or
    low-passed at ``cutoff`` [Hz]."""
    t = np.arange(samples) * DT
    x = 0.02 * np.sin(2 * np.pi * 0.5 * t) + 0.004 * np.sin(2 * np.pi * 1.7 * t)
    v = np.diff(x, prepend=x[0]) / DT
    f = lr.simulate(truth, v, DT) + offset
    if drift:
        coulomb = lr.Params(Fc=1.0, Fs=1.0, Vs=0.01, delta=2.0, n=2.0, W=[1.02], Delta=[1e-9])
        f += drift * lr.simulate(coulomb, v, DT) * np.linspace(0.0, 1.0, samples)
    noise = np.random.default_rng(0).standard_normal(samples)
    if cutoff is not None:
        b, a = signal.butter(1, cutoff, fs=1.0 / DT)
        noise = signal.lfilter(b, a, noise)
    return MotionData(t, x, f + NOISE * noise / noise.std(), v=v)


def prepared(record: MotionData) -> tuple[Target, Scales]:
    noisy = noisy_position(record.x, record.dt)
    return select.prepare(record, select.rounds_reconstruction(record, noisy), noisy)


def named(
    record: MotionData, effect: str, structure: Structure = BASE
) -> tuple[Fitted, Fitted, list[Step], Target, Scales]:
    """What the forward round leaves when it names ``effect`` on a model of ``structure``: that
    model (fitted from the Coulomb–viscous one), the model with ``effect`` fitted from it, and the
    step between them; counted robustly at 5 times the noise."""
    target, scales = prepared(record)
    target = dataclasses.replace(target, scale=ROBUST * NOISE)
    base = fit(BASE, scales, target, {"Fc": 1.0, "sigma2": 1.0})
    if structure != BASE:
        base = fit(structure, scales, target, base.theta)
    final = fit(structure.with_effect(effect), scales, target, base.theta)
    return base, final, [Step(effect, base, final)], target, scales


@pytest.mark.parametrize(
    ("truth", "offset", "wrong", "right"),
    [
        (ASYMMETRIC, 0.0, "offset", "asymmetry"),
        # A load larger than the friction (an axis holding up a weight): the −x force is positive,
        # which −x levels cannot give.
        (SYMMETRIC, 1.5, "asymmetry", "offset"),
    ],
)
def test_the_stand_in_the_log_shows_replaces_the_one_the_forward_round_named(
    truth: lr.Params, offset: float, wrong: str, right: str
) -> None:
    assert {wrong, right} == set(STAND_INS[0])
    base, final, steps, target, scales = named(log(truth, offset=offset), wrong)
    said: list[str] = []
    exchanged, regrown, stand_ins = select._exchange(
        base, final, steps, scales, target, Settings(), UNIT, said.append
    )
    assert exchanged.structure == BASE.with_effect(right)
    assert exchanged.mse < 1.2 * UNIT < final.mse
    assert [step.effect for step in regrown] == [right]
    assert regrown[0].before is base and regrown[0].after is exchanged
    assert len(said) == 1 and said[0].startswith(f"{right} in place of {wrong}")
    # The one replaced, in the named one's place, is what the model was before the exchange.
    assert stand_ins == [select.StandIn(right, wrong, (exchanged.mse - final.mse) / UNIT)]
    assert stand_ins[0].gain < -Settings().significance


def test_an_exchange_that_gains_less_than_the_threshold_is_not_taken() -> None:
    base, final, steps, target, scales = named(log(ASYMMETRIC), "offset")
    # The exchange is judged on the stand-in's screened fit in the named one's place.
    swapped = select._in_place(final, "offset", "asymmetry", scales, target)
    gain = (final.mse - swapped.mse) / UNIT
    assert gain > 1.0

    def exchanged(significance: float) -> tuple[Fitted, list[Step], list[select.StandIn]]:
        settings = Settings(significance=significance)
        return select._exchange(base, final, steps, scales, target, settings, UNIT, lambda _: None)

    kept, kept_steps, stand_ins = exchanged(1.01 * gain)
    assert kept is final and kept_steps is steps
    # The −x level lower and its viscous slope steeper: no one factor on the −x levels gives
    # that, and it fits worse than the offset, which stays.
    [pair] = stand_ins
    assert pair == select.StandIn("offset", "asymmetry", gain, pair.factor)
    assert pair.factor is not None and pair.factor < 0.0
    taken, _, _ = exchanged(0.99 * gain)
    assert taken.structure == BASE.with_effect("asymmetry")


def test_an_offset_within_both_levels_and_its_asymmetry_are_not_told_apart() -> None:
    """Levels of their own for −x hold an offset smaller than both levels: while the axis
    slides, the two models give the same force, and the stand-in gains about nothing in the
    offset's place, which the report says. Screened from the levels as the offset's removal
    leaves them, the asymmetry stops far from that."""
    base, final, steps, target, scales = named(log(SYMMETRIC, offset=0.3), "offset")
    settings = Settings()
    _, kept_steps, stand_ins = select._exchange(
        base, final, steps, scales, target, settings, UNIT, lambda _: None
    )
    assert kept_steps is steps
    [pair] = stand_ins
    assert (pair.named, pair.stand_in) == ("offset", "asymmetry")
    assert abs(pair.gain) < 0.1 * settings.significance
    structure = final.structure.without("offset").with_effect("asymmetry")
    held = fit(structure, scales, target, select._held(final, structure, scales), select.SCREEN)
    assert (final.mse - held.mse) / UNIT < -settings.significance


def factored(factor: float) -> lr.Params:
    """:data:`STRIBECK` with every −x level and its viscous coefficient ``factor`` times the +x ones."""
    return dataclasses.replace(STRIBECK, Fc_neg=factor * STRIBECK.Fc, Fs_neg=factor * STRIBECK.Fs,
                               sigma2_neg=factor * STRIBECK.sigma2)  # fmt: skip


@pytest.mark.parametrize(
    ("truth", "offset", "wrong", "right"),
    [
        # Every −x level 0.8 times the +x one: the full asymmetry gains 0.23 units over the offset.
        (factored(0.8), 0.0, "offset", "asymmetry"),
        # An offset within both levels, which the asymmetry's −x levels hold as well as it does.
        (STRIBECK, 0.3, "asymmetry", "offset"),
    ],
)
def test_where_the_fit_does_not_tell_the_pair_apart_one_factor_on_the_minus_x_levels_does(
    truth: lr.Params, offset: float, wrong: str, right: str
) -> None:
    """An offset adds the same force at every speed; an asymmetry whose −x levels are one factor
    times the +x ones scales the −x viscous slope and Stribeck rise with them."""
    structure = BASE.with_effect("stribeck")
    base, final, steps, target, scales = named(log(truth, offset=offset), wrong, structure)
    settings = Settings()
    swapped = select._in_place(final, wrong, right, scales, target)
    assert abs(final.mse - swapped.mse) < settings.significance * UNIT
    said: list[str] = []
    exchanged, regrown, stand_ins = select._exchange(
        base, final, steps, scales, target, settings, UNIT, said.append
    )
    assert exchanged.structure == structure.with_effect(right)
    assert [step.effect for step in regrown] == [right]
    assert len(said) == 1 and said[0].startswith(f"{right} in place of {wrong}")
    [pair] = stand_ins
    assert (pair.named, pair.stand_in) == (right, wrong)
    assert pair.factor is not None and abs(pair.factor) > select.TIE
    assert (pair.factor > 0) == (right == "asymmetry")


def test_an_asymmetry_the_offset_does_not_hold_stays_where_one_factor_fits_worse_still() -> None:
    """The −x level lower and its viscous slope steeper: the offset in the asymmetry's place does
    far worse, and one factor on the −x levels worse still; the named asymmetry stays."""
    base, final, steps, target, scales = named(log(ASYMMETRIC), "asymmetry")
    settings = Settings()
    exchanged, kept_steps, stand_ins = select._exchange(
        base, final, steps, scales, target, settings, UNIT, lambda _: None
    )
    assert exchanged is final and kept_steps is steps
    [pair] = stand_ins
    assert (pair.named, pair.stand_in) == ("asymmetry", "offset")
    assert pair.gain < -settings.significance
    assert pair.factor is not None and pair.factor < -select.TIE


def test_without_a_viscous_slope_or_stribeck_rise_one_factor_does_not_tell_the_pair_apart() -> None:
    """The −x levels one factor times the +x ones, or shifted by an offset: with no viscous slope
    and no Stribeck rise to scale, the two give the same force, and the offset named stays."""
    truth = dataclasses.replace(SYMMETRIC, sigma2=0.0)
    base, final, steps, target, scales = named(log(truth, offset=0.3), "offset")
    exchanged, kept_steps, stand_ins = select._exchange(
        base, final, steps, scales, target, Settings(), UNIT, lambda _: None
    )
    assert exchanged is final and kept_steps is steps
    [pair] = stand_ins
    assert pair.factor is not None and abs(pair.factor) < select.TIE


def stopping(levels: tuple[float, float], offset: float, released: bool) -> MotionData:
    """Slides at 5–50 mm/s each way with a stop of 100 samples after each, the velocity logged:
    Coulomb levels ``levels`` (+x, −x), viscous 2 N·s/m, plus ``offset`` and noise of rms
    :data:`NOISE`. At a stop the friction holds its force (a stiff element), or lets go of it
    (``released``), as a static friction curve does at zero speed."""
    speeds = np.geomspace(5e-3, 5e-2, 6)
    v = np.concatenate([np.concatenate([np.full(300, s), np.zeros(100), np.full(300, -s), np.zeros(100)])
                        for s in speeds])  # fmt: skip
    x = np.cumsum(v) * DT
    t = np.arange(v.size) * DT
    plus, minus = levels
    if released:
        f = np.where(v > 0, plus, np.where(v < 0, -minus, 0.0)) + 2.0 * v
    else:
        truth = lr.Params(Fc=plus, Fs=plus, Vs=0.01, delta=2.0, n=2.0, sigma2=2.0, Fc_neg=minus, Fs_neg=minus,
                          W=[2.0 * plus], Delta=[1e-9])  # fmt: skip
        f = lr.simulate(truth, v, DT)
    noise = np.random.default_rng(1).standard_normal(v.size)
    return MotionData(t, x, f + offset + NOISE * noise, v=v)


@pytest.mark.parametrize(
    ("levels", "offset", "wrong", "right"),
    [((1.0, 0.6), 0.0, "offset", "asymmetry"), ((0.8, 0.8), 0.2, "asymmetry", "offset")],
)
def test_where_friction_lets_go_at_a_stop_the_force_there_tells_an_offset_from_an_asymmetry(
    levels: tuple[float, float], offset: float, wrong: str, right: str
) -> None:
    """The −x Coulomb level 0.6 times the +x one and the same viscous slope, or an offset of 0.2
    within both levels: while the axis slides the two models give the same force. Where the
    friction lets go at every stop, the force there is the measurement's own: the offset, or
    nothing."""
    base, final, steps, target, scales = named(stopping(levels, offset, released=True), wrong)
    assert target.let_go is not None and target.let_go.sum() > 0.9 * 12 * 100
    assert not target.weight[target.let_go].any()  # weighed out of the fit
    settings = Settings()
    said: list[str] = []
    exchanged, regrown, stand_ins = select._exchange(
        base, final, steps, scales, target, settings, UNIT, said.append
    )
    assert exchanged.structure == BASE.with_effect(right)
    assert [step.effect for step in regrown] == [right]
    assert len(said) == 1 and "the stops where friction lets go" in said[0]
    [pair] = stand_ins
    assert (pair.named, pair.stand_in) == (right, wrong)
    assert pair.stops is not None and pair.stops < -settings.significance  # the one replaced


def test_where_friction_holds_at_a_stop_the_stops_tell_nothing() -> None:
    """The same Coulomb-only asymmetry, its friction held at every stop: no stop lets go, and the
    offset named stays (one factor on the −x levels would scale the viscous slope too)."""
    base, final, steps, target, scales = named(stopping((1.0, 0.6), 0.0, released=False), "offset")
    assert target.let_go is None
    exchanged, kept_steps, stand_ins = select._exchange(
        base, final, steps, scales, target, Settings(), UNIT, lambda _: None
    )
    assert exchanged is final and kept_steps is steps
    [pair] = stand_ins
    assert pair.stops is None


def test_no_stand_in_is_tried_where_both_are_named() -> None:
    base, final, steps, target, scales = named(log(ASYMMETRIC), "offset")
    both = fit(final.structure.with_effect("asymmetry"), scales, target, final.theta)
    steps = [*steps, Step("asymmetry", final, both)]
    kept, kept_steps, stand_ins = select._exchange(
        base, both, steps, scales, target, Settings(), UNIT, lambda _: None
    )
    assert kept is both and kept_steps is steps and stand_ins == []


def test_a_pair_is_exchanged_once_per_pass(monkeypatch: pytest.MonkeyPatch) -> None:
    """Were every exchange to count, the named effect is replaced by its stand-in and not
    brought back in its place in the same pass."""
    base, final, steps, target, scales = named(log(ASYMMETRIC), "offset")
    monkeypatch.setattr(select, "_significant", lambda *_: True)
    said: list[str] = []
    settings = Settings()
    exchanged, regrown, _ = select._exchange(base, final, steps, scales, target, settings, UNIT, said.append)
    assert exchanged.structure == BASE.with_effect("asymmetry")
    assert [step.effect for step in regrown] == ["asymmetry"]
    assert len(said) == 1


def coloured_forward(record: MotionData) -> tuple[Fitted, Target, Target, Scales]:
    """The truth's structure fitted at the forward rounds' scale: ``ROBUST`` times the noise the
    one-sample differences of a residual read, which for coloured noise is far below its rms."""
    target, scales = prepared(record)
    structure = BASE.with_effect("stribeck")
    plain = fit(structure, scales, target, {"Fc": 1.0, "sigma2": 1.0})
    forward = dataclasses.replace(target, scale=ROBUST * select._sample_noise(plain, target))
    return fit(structure, scales, forward, plain.theta), target, forward, scales


def test_the_final_model_is_refitted_at_five_times_its_noise_when_that_is_above_the_forward_scale() -> None:
    final, _, forward, scales = coloured_forward(log(STRIBECK, cutoff=30.0))
    noise = select._noise(final, forward)
    assert forward.scale is not None and ROBUST * noise > 2.0 * forward.scale
    backward, refitted = select._rescaled(final, scales, forward, noise)
    assert backward.scale == ROBUST * noise
    assert refitted.theta == fit(final.structure, scales, backward, final.theta).theta != final.theta
    assert refitted.mse == backward.mse(refitted.force)


def test_a_final_model_whose_noise_is_within_the_scale_is_not_refitted() -> None:
    final, plain, forward, scales = coloured_forward(log(STRIBECK, cutoff=30.0))
    noise = select._noise(final, forward)
    # At five times the noise exactly, above it, and counted plainly (no scale): as given.
    for target in (dataclasses.replace(forward, scale=ROBUST * noise),
                   dataclasses.replace(forward, scale=2.0 * ROBUST * noise), plain):  # fmt: skip
        same_target, same = select._rescaled(final, scales, target, noise)
        assert same_target is target and same is final


Spied = list[tuple[str, Target]]


def spied(monkeypatch: pytest.MonkeyPatch) -> Spied:
    """Each call of the rounds, the pruning and the exchange, with the target it counts on."""
    calls: Spied = []
    for name in ("_rounds", "_prune", "_exchange"):
        original: Callable[..., Any] = getattr(select, name)

        def spy(*args: Any, _original: Callable[..., Any] = original, _name: str = name) -> Any:
            calls.append((_name, next(arg for arg in args if isinstance(arg, Target))))
            return _original(*args)

        monkeypatch.setattr(select, name, spy)
    return calls


def test_the_backward_round_counts_at_five_times_the_final_models_noise(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    target, scales = prepared(log(STRIBECK, cutoff=30.0, samples=10_000))
    calls = spied(monkeypatch)
    run = select._select_on(BASE, target, scales, Settings(), lambda _: None)
    assert not run.drift and run.final.structure == BASE.with_effect("stribeck")
    assert [name for name, _ in calls] == ["_rounds", "_prune", "_exchange"]
    (_, forward), (_, pruned), (_, exchanged) = calls
    assert forward.scale is not None and run.target.scale is not None
    assert pruned is exchanged is run.target
    assert run.target.scale == ROBUST * run.noise > 2.0 * forward.scale
    # The final model is the one fitted at that scale.
    assert run.final.mse == run.target.mse(run.final.force)
    assert run.steps[-1].after is run.final


def test_the_drift_pass_runs_the_rounds_again_from_the_forward_target(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    target, scales = prepared(log(STRIBECK, drift=0.2, cutoff=30.0, samples=10_000))
    calls = spied(monkeypatch)
    run = select._select_on(BASE, target, scales, Settings(), lambda _: None)
    assert run.drift and run.final.structure == BASE.with_effect("stribeck").with_drift()
    assert [name for name, _ in calls] == ["_rounds", "_prune", "_exchange"] * 2
    forward, backward, again, backward_again = calls[0][1], calls[1][1], calls[3][1], calls[4][1]
    assert forward.scale is not None and backward.scale is not None and backward_again.scale is not None
    assert backward.scale > 2.0 * forward.scale
    # The forward rounds of the drift pass count at the forward scale, not at the backward one
    # the first pass ended at.
    assert again is forward
    assert backward_again is run.target and run.target.scale == ROBUST * run.noise > 2.0 * forward.scale
