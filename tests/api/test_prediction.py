"""``leuven_rt.predict``: a model's force along a log's motion. The true model on a simulated log
leaves only the noise; the level and the measurement terms enter as documented; a compensator in
observer mode fed ``prediction.x`` gives ``prediction.friction``; the CSV reads back exactly."""

from __future__ import annotations

import inspect
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import leuven_rt as lr
from leuven_rt import Compensator, ModelFile, Params, PositionForce, PositionLevel, Reconstruction, Ripple
from leuven_rt.data.signals import default_cutoff, estimate_derivatives, lowpass
from leuven_rt.data.synthetic import SyntheticData, make_data
from leuven_rt.errors import DataError, OutputError, ResamplingWarning
from leuven_rt.prediction import Prediction, predict

LEVEL = PositionLevel(
    middle=0.0, half_stroke=0.01, trend=(0.05, -0.02), ripples=(Ripple(0.004, (0.03, 0.01), (0.0, 0.02)),)
)


@pytest.fixture(scope="module")
def synthetic() -> SyntheticData:
    return make_data(seed=0)


def test_the_true_model_leaves_the_noise(synthetic: SyntheticData) -> None:
    prediction = predict(synthetic.params, synthetic.data)
    assert isinstance(prediction, Prediction) and lr.predict is predict
    assert prediction.samples == synthetic.data.samples
    # Only the measurement noise (0.02 N) remains: the filter and the encoder add little.
    assert synthetic.noise_std <= prediction.rms < 1.05 * synthetic.noise_std
    np.testing.assert_array_equal(prediction.f, synthetic.data.f)
    np.testing.assert_array_equal(prediction.f_model, prediction.friction)  # no measurement terms
    wrong = predict(Params(**{**synthetic.params.to_dict(), "Fc": 0.5 * synthetic.params.Fc}), synthetic.data)
    assert wrong.rms > 5.0 * synthetic.noise_std


def test_model_forms_agree(synthetic: SyntheticData, tmp_path: Path) -> None:
    """A Params, a ModelFile, a parameter file and a model file give the same prediction."""
    params_path, model_path = tmp_path / "params.json", tmp_path / "model.json"
    synthetic.params.save(params_path)
    ModelFile(friction=synthetic.params).save(model_path)
    first = predict(synthetic.params, synthetic.data)
    for model in (ModelFile(friction=synthetic.params), params_path, str(model_path)):
        np.testing.assert_array_equal(predict(model, synthetic.data).f_model, first.f_model)


def test_x_is_the_filtered_position(synthetic: SyntheticData) -> None:
    prediction = predict(synthetic.params, synthetic.data)
    expected = estimate_derivatives(synthetic.data, default_cutoff(synthetic.data.dt)).x
    np.testing.assert_array_equal(prediction.x, expected)
    np.testing.assert_array_equal(prediction.friction, lr.simulate_position(synthetic.params, expected,
                                                                            synthetic.data.dt))  # fmt: skip


def test_a_compensator_in_observer_mode_gives_the_friction(synthetic: SyntheticData) -> None:
    prediction = predict(synthetic.params, synthetic.data)
    compensator = Compensator(synthetic.params, synthetic.data.dt, mode="observer")
    forces = np.array([compensator.step(float(x)) for x in prediction.x])
    np.testing.assert_allclose(forces, prediction.friction, rtol=0.0, atol=1e-9)


def test_a_compensator_with_the_level_gives_the_friction(synthetic: SyntheticData) -> None:
    if "level" not in inspect.signature(Compensator).parameters:
        pytest.skip(
            "Compensator does not take `level=` yet (the Rust compensator's level support is not here)"
        )
    model = ModelFile(friction=synthetic.params, level=LEVEL)
    prediction = predict(model, synthetic.data)
    compensator = Compensator(synthetic.params, synthetic.data.dt, mode="observer", level=LEVEL)  # type: ignore[call-arg]
    forces = np.array([compensator.step(float(x)) for x in prediction.x])
    np.testing.assert_allclose(forces, prediction.friction, rtol=0.0, atol=1e-9)


def test_the_level_scales_the_contact_part_and_the_measurement_terms_add(synthetic: SyntheticData) -> None:
    params = synthetic.params
    plain = predict(params, synthetic.data)
    model = ModelFile(friction=params, level=LEVEL, offset=0.3, inertia=0.05)
    prediction = predict(model, synthetic.data)
    x, dt = plain.x, synthetic.data.dt
    v = np.r_[0.0, np.diff(x) / dt]
    expected = LEVEL.factor(x) * (plain.friction - params.sigma2 * v) + params.sigma2 * v
    np.testing.assert_allclose(prediction.friction, expected, rtol=1e-12, atol=1e-12)
    a = estimate_derivatives(synthetic.data).a
    np.testing.assert_allclose(
        prediction.f_model - prediction.friction, 0.3 + 0.05 * a, rtol=1e-12, atol=1e-12
    )
    assert not np.allclose(prediction.friction, plain.friction)


def test_the_acceleration_comes_through_the_file_s_own_cutoff(synthetic: SyntheticData) -> None:
    """A reconstruction's ``acceleration_cutoff`` is the low-pass the inertia term's acceleration
    is taken through (the default: at most a tenth of the Nyquist frequency), and ``--cutoff``
    replaces the motion's cutoff but keeps it."""
    data, dt = synthetic.data, synthetic.data.dt
    cutoff = 0.6 * 0.5 / dt
    own = ModelFile(friction=synthetic.params, inertia=0.05,
                    reconstruction=Reconstruction("position", acceleration_cutoff=cutoff))  # fmt: skip
    prediction = predict(own, data)
    a = np.gradient(np.gradient(lowpass(data.x, dt, cutoff), dt), dt)
    np.testing.assert_allclose(prediction.f_model - prediction.friction, 0.05 * a, rtol=1e-12, atol=1e-12)
    default = predict(replace(own, reconstruction=Reconstruction("position")), data)
    np.testing.assert_array_equal(default.friction, prediction.friction)
    assert not np.allclose(default.f_model, prediction.f_model)
    replaced = predict(own, data, cutoff=0.2 * 0.5 / dt)
    assert replaced.reconstruction == Reconstruction("position", 0.2 * 0.5 / dt, acceleration_cutoff=cutoff)
    assert replaced.to_dict()["reconstruction"]["acceleration_cutoff"] == cutoff
    # A velocity's acceleration cutoff is not the raw position's: a log without `v` takes the
    # default.
    logged = replace(own, reconstruction=Reconstruction("velocity", acceleration_cutoff=cutoff))
    fallback = predict(logged, data)
    assert fallback.reconstruction == Reconstruction("position") and fallback.notes
    # A file's own cutoff that this log's rate does not support is refused by its name.
    beyond = replace(own, reconstruction=Reconstruction("position", acceleration_cutoff=0.6 / dt))
    with pytest.raises(DataError, match=r"^`reconstruction.acceleration_cutoff` must be below") as caught:
        predict(beyond, data)
    assert (caught.value.kind, caught.value.field) == ("out_of_range", "reconstruction.acceleration_cutoff")


def test_the_model_file_s_position_force_is_added(synthetic: SyntheticData) -> None:
    """A model file's position force is part of the friction a compensator adds: predict adds
    r(x) to the friction, as a compensator in observer mode with the same terms does."""
    force = PositionForce(half_stroke=0.01, trend=(0.2, -0.1), ripples=(Ripple(0.003, (0.05,), (-0.02,)),))
    plain = predict(synthetic.params, synthetic.data)
    prediction = predict(ModelFile(friction=synthetic.params, position_force=force), synthetic.data)
    np.testing.assert_allclose(
        prediction.friction, plain.friction + force.force(plain.x), rtol=0.0, atol=1e-12
    )
    compensator = Compensator(synthetic.params, synthetic.data.dt, mode="observer", position_force=force)
    forces = np.array([compensator.step(float(x)) for x in prediction.x])
    np.testing.assert_allclose(forces, prediction.friction, rtol=0.0, atol=1e-9)


def test_a_log_with_the_hidden_terms_is_explained_by_the_full_model(synthetic: SyntheticData) -> None:
    """A log whose force carries a level, an offset and inertia: the full model leaves the noise,
    the plain friction model does not."""
    dt, x_true = synthetic.data.dt, synthetic.x_true
    params = synthetic.params
    v = np.r_[0.0, np.diff(x_true) / dt]
    a = np.gradient(np.gradient(x_true, dt), dt)
    plain = lr.simulate_position(params, x_true, dt)
    force = LEVEL.factor(x_true) * (plain - params.sigma2 * v) + params.sigma2 * v + 0.3 + 0.05 * a
    noisy = force + np.random.default_rng(1).normal(0.0, synthetic.noise_std, force.size)
    data = {"t": synthetic.data.t, "x": synthetic.data.x, "f": noisy}
    full = predict(ModelFile(friction=params, level=LEVEL, offset=0.3, inertia=0.05), data)
    assert full.rms < 1.1 * synthetic.noise_std
    assert predict(params, data).rms > 3.0 * synthetic.noise_std


def test_the_csv_reads_back_exactly(synthetic: SyntheticData, tmp_path: Path) -> None:
    prediction = predict(ModelFile(friction=synthetic.params, offset=0.1), synthetic.data)
    path = tmp_path / "pred.csv"
    assert prediction.to_csv(path) == path
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0] == "t,f,f_model,friction" and len(lines) == prediction.samples + 1
    table = np.loadtxt(path, delimiter=",", skiprows=1)
    for index, name in enumerate(("t", "f", "f_model", "friction")):
        np.testing.assert_array_equal(table[:, index], getattr(prediction, name))
    with pytest.raises(OutputError, match=r"exists: refusing to overwrite it"):
        prediction.to_csv(path)
    prediction.to_csv(path, force=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pred.csv"]


def test_irregular_logs_are_resampled_and_the_warning_kept(synthetic: SyntheticData) -> None:
    data = synthetic.data
    t = data.t.copy()
    t[1::2] += 0.2 * data.dt
    with pytest.warns(ResamplingWarning, match=r"resampled linearly"):
        prediction = predict(synthetic.params, {"t": t, "x": data.x, "f": data.f})
    assert len(prediction.notes) == 1 and "resampled linearly" in prediction.notes[0]
    assert "warning: `t` is not uniformly sampled" in prediction.summary()
    np.testing.assert_allclose(np.diff(prediction.t), np.diff(prediction.t)[0], rtol=1e-9)


def test_units_in_the_summary_and_a_mismatch_is_refused(synthetic: SyntheticData) -> None:
    rotary = ModelFile(friction=synthetic.params, units="rotary")
    data = synthetic.data
    prediction = predict(rotary, {"t": data.t, "x": data.x, "f": data.f})  # a mapping takes the model's units
    assert (
        prediction.units == "rotary" and "N·m" in prediction.summary() and "(rotary)" in prediction.summary()
    )
    assert " N " in predict(synthetic.params, synthetic.data).summary()
    with pytest.raises(DataError, match=r"`units` is 'linear', but the model is 'rotary'"):
        predict(rotary, synthetic.data, units="linear")
    with pytest.raises(DataError, match=r"`units` must be 'linear' or 'rotary', got 'm'"):
        predict(rotary, synthetic.data, units="m")  # type: ignore[arg-type]


def test_columns_are_mapped(synthetic: SyntheticData) -> None:
    data = synthetic.data
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        renamed = predict(synthetic.params, {"time": data.t, "q": data.x, "tau": data.f},
                          columns={"t": "time", "x": "q", "f": "tau"})  # fmt: skip
    np.testing.assert_array_equal(renamed.f_model, predict(synthetic.params, data).f_model)
