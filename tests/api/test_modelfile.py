"""The versioned model file (leuven_rt.ModelFile, docs/data-and-reports.md#model-file): its JSON
form, exact round trips, plain parameter files loading as model files, every refusal naming the
key, and the output policy of ``save``."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import leuven_rt as lr
from conftest import LUGRE, MAXWELL
from leuven_rt import ModelFile, Params, PositionForce, PositionLevel, Reconstruction, Ripple
from leuven_rt.errors import ModelFileError, OutputError, ParameterError
from leuven_rt.modelfile import VERSION

LEVEL = PositionLevel(
    middle=0.0,
    half_stroke=0.01,
    trend=(0.05, -0.02),
    ripples=(Ripple(period=0.004, cos=(0.03, 0.01), sin=(0.0, 0.02)),),
)


FORCE = PositionForce(
    half_stroke=0.01, trend=(0.3, -0.1), ripples=(Ripple(period=0.002, cos=(0.2,), sin=(-0.1,)),)
)


def full_model() -> ModelFile:
    return ModelFile(
        friction=Params(**MAXWELL),
        level=LEVEL,
        position_force=FORCE,
        offset=0.1,
        inertia=0.37,
        units="rotary",
        reconstruction=Reconstruction("velocity", cutoff=25.0),
        report={"held_out_rms": 0.021, "stages": [{"name": "sliding", "rms": 0.3}], "warnings": []},
    )


def test_the_json_form_is_the_documented_one() -> None:
    model = full_model()
    mapping = json.loads(model.to_json())
    keys = [
        "format",
        "version",
        "units",
        "friction",
        "level",
        "position_force",
        "measurement",
        "reconstruction",
    ]
    assert list(mapping) == [*keys, "report"]
    assert mapping["format"] == "leuven-rt model" and mapping["version"] == 3 and mapping["units"] == "rotary"
    assert mapping["friction"] == Params(**MAXWELL).to_dict()  # exactly the parameter file
    assert mapping["level"] == {
        "middle": 0.0,
        "half_stroke": 0.01,
        "trend": [0.05, -0.02],
        "ripples": [{"period": 0.004, "cos": [0.03, 0.01], "sin": [0.0, 0.02]}],
    }
    assert mapping["position_force"] == {
        "middle": 0.0,
        "half_stroke": 0.01,
        "trend": [0.3, -0.1],
        "ripples": [{"period": 0.002, "cos": [0.2], "sin": [-0.1]}],
    }
    assert mapping["measurement"] == {"offset": 0.1, "inertia": 0.37}
    assert mapping["reconstruction"] == {"source": "velocity", "cutoff": 25.0}
    assert mapping["report"]["held_out_rms"] == 0.021
    plain = json.loads(ModelFile(friction=Params(**LUGRE)).to_json())
    assert plain["level"] is None and plain["position_force"] is None and plain["reconstruction"] is None


def test_a_model_with_a_level_and_measurement_terms_round_trips_exactly(tmp_path: Path) -> None:
    model = full_model()
    assert ModelFile.from_json(model.to_json()) == model
    assert ModelFile.from_dict(model.to_dict()) == model
    assert ModelFile.from_json(model.to_json()).to_json() == model.to_json()
    path = tmp_path / "model.json"
    model.save(path)
    assert path.read_text(encoding="utf-8") == model.to_json() + "\n"
    loaded = ModelFile.load(path)
    assert loaded == model and loaded.level == LEVEL and loaded.report == model.report
    # Awkward floats too: repr round-trips every double.
    odd = ModelFile(friction=Params(**MAXWELL), offset=0.1 + 0.2, inertia=-1e-300)
    assert ModelFile.from_json(odd.to_json()) == odd


def test_a_plain_parameter_file_loads_as_a_model_file(tmp_path: Path) -> None:
    """Every parameter file written before the model file keeps working: no level, no
    measurement terms, linear."""
    params = Params(**MAXWELL)
    path = tmp_path / "params.json"
    params.save(path)
    model = ModelFile.load(path)
    assert model == ModelFile(friction=params)
    assert model.level is None and model.offset == 0.0 and model.inertia == 0.0 and model.units == "linear"
    assert model.report is None


def test_python_values_are_coerced() -> None:
    model = ModelFile(
        friction=MAXWELL,  # type: ignore[arg-type]
        level={"trend": [0.1, 0.0], "ripples": [{"period": 1, "cos": [0.1], "sin": [0]}]},  # type: ignore[arg-type]
        offset=np.float32(0.5),  # type: ignore[arg-type]
        inertia=2,
        report={"elements": {3: 0.1}, "rms": np.float64(0.2), "missing": float("nan")},
    )
    assert model.friction == Params(**MAXWELL)
    assert model.level == PositionLevel(trend=(0.1, 0.0), ripples=(Ripple(1.0, (0.1,), (0.0,)),))
    assert type(model.offset) is float and model.offset == 0.5 and type(model.inertia) is float
    # JSON's own spelling: integer keys as text, a non-finite number as null (standard JSON).
    assert model.report == {"elements": {"3": 0.1}, "rms": 0.2, "missing": None}
    assert "NaN" not in model.to_json()
    assert hash(model) == hash(ModelFile.from_json(model.to_json()))


def test_measurement_force() -> None:
    model = ModelFile(friction=Params(**MAXWELL), offset=0.1, inertia=2.0)
    np.testing.assert_array_equal(model.measurement_force([0.0, 1.0, -0.5]), [0.1, 2.1, -0.9])
    assert ModelFile(friction=Params(**MAXWELL)).measurement_force(np.ones(3)).tolist() == [0.0] * 3


def test_load_names_the_file(tmp_path: Path) -> None:
    path = tmp_path / "model.json"
    text = full_model().to_json().replace(f'"version": {VERSION}', f'"version": {VERSION + 1}')
    path.write_text(text, encoding="utf-8")
    with pytest.raises(
        ModelFileError, match=rf"^{path}: `version` is {VERSION + 1}: .*upgrade leuven-rt"
    ) as caught:
        ModelFile.load(path)
    assert (caught.value.kind, caught.value.field) == ("invalid_choice", "version")
    with pytest.raises(ModelFileError, match=r"cannot read .*missing\.json") as caught:
        ModelFile.load(tmp_path / "missing.json")
    assert (caught.value.kind, caught.value.field) == ("unreadable_file", None)
    (tmp_path / "latin.json").write_bytes('{"é": 1}'.encode("latin-1"))
    with pytest.raises(ModelFileError, match=r"not UTF-8 text") as caught:
        ModelFile.load(tmp_path / "latin.json")
    assert caught.value.kind == "unreadable_file"
    with pytest.raises(ModelFileError, match=r"not a regular file"):
        ModelFile.load(tmp_path)


def test_a_version_1_file_loads_and_is_written_as_version_3() -> None:
    """Version 1 files (no position_force, no reconstruction) keep loading; saving writes the
    current version with those keys at their defaults."""
    mapping = full_model().to_dict()
    del mapping["position_force"], mapping["reconstruction"]
    mapping["version"] = 1
    model = ModelFile.from_dict(mapping)
    assert model == replace(full_model(), position_force=None, reconstruction=None)
    written = json.loads(model.to_json())
    assert written["version"] == 3 and written["position_force"] is None and written["reconstruction"] is None


def test_the_acceleration_cutoff_is_a_key_of_version_3() -> None:
    """A reconstruction's own acceleration cutoff is written only where there is one (so a file
    without it reads as before), round-trips, and is refused in a version 2 file and as null."""
    model = replace(full_model(), reconstruction=Reconstruction("position", None, acceleration_cutoff=400.0))
    mapping = json.loads(model.to_json())
    assert mapping["reconstruction"] == {"source": "position", "cutoff": None, "acceleration_cutoff": 400.0}
    assert ModelFile.from_json(model.to_json()) == model
    assert "acceleration_cutoff" not in json.loads(full_model().to_json())["reconstruction"]
    older = dict(mapping, version=2)
    with pytest.raises(ModelFileError, match=r"it came with version 3") as caught:
        ModelFile.from_dict(older)
    assert (caught.value.kind, caught.value.field) == ("unknown_key", "reconstruction.acceleration_cutoff")
    for value, kind in [(None, "wrong_type"), (0.0, "not_positive")]:
        changed = json.loads(json.dumps(mapping))
        changed["reconstruction"]["acceleration_cutoff"] = value
        with pytest.raises(ModelFileError) as caught:
            ModelFile.from_dict(changed)
        assert (caught.value.kind, caught.value.field) == (kind, "reconstruction.acceleration_cutoff")


def test_from_dict_refuses_what_json_cannot_hold() -> None:
    """from_dict reads with the rules of the text: a NaN, a non-text key or a Python object is
    refused naming the key, as its JSON text would be."""
    mapping = full_model().to_dict()
    for path, value, kind, key in [
        (("measurement", "offset"), math.nan, "out_of_range", "measurement.offset"),
        (("report", "rms"), math.inf, "out_of_range", "report.rms"),
        (("report", "when"), object(), "wrong_type", "report.when"),
        (("friction", "Fc"), 10**400, "out_of_range", "friction.Fc"),
    ]:
        changed = json.loads(json.dumps(mapping))
        changed[path[0]][path[1]] = value
        with pytest.raises(ModelFileError) as caught:
            ModelFile.from_dict(changed)
        assert (caught.value.kind, caught.value.field) == (kind, key), str(caught.value)
    changed = json.loads(json.dumps(mapping))
    changed["report"] = {1: 2}
    with pytest.raises(ModelFileError, match=r"keys must be text") as caught:
        ModelFile.from_dict(changed)
    assert (caught.value.kind, caught.value.field) == ("wrong_type", "report")


def test_bad_python_values_are_refused() -> None:
    """The constructor has the file's reader check the whole: a refusal names the key."""
    with pytest.raises(ParameterError, match=r"`friction` must be a leuven_rt.Params or a mapping"):
        ModelFile(friction=3)  # type: ignore[arg-type]
    for changes, kind, key in [
        ({"offset": "a"}, "wrong_type", "measurement.offset"),
        ({"inertia": math.nan}, "out_of_range", "measurement.inertia"),
        ({"units": "deg"}, "wrong_type", "units"),
        ({"level": {"half_stroke": 0.0}}, "not_positive", "level.half_stroke"),
        ({"level": {"slope": 1.0}}, "unknown_key", "level.slope"),
        ({"reconstruction": Reconstruction("position", cutoff=-1.0)}, "not_positive",
         "reconstruction.cutoff"),
        ({"position_force": {"ripples": [{"period": 0.0, "cos": [1.0], "sin": [0.0]}]}}, "ripple_period",
         "position_force.ripples[0].period"),
        ({"friction": {**MAXWELL, "Fs": 0.1}}, "static_below_coulomb", "friction.Fs"),
    ]:  # fmt: skip
        with pytest.raises(ModelFileError) as caught:
            ModelFile(**{"friction": Params(**MAXWELL), **changes})
        assert (caught.value.kind, caught.value.field) == (kind, key), str(caught.value)
    with pytest.raises(ParameterError, match=r"`report.when` must hold JSON values only, got object"):
        ModelFile(friction=Params(**MAXWELL), report={"when": object()})
    with pytest.raises(ParameterError, match=r"`report` must be a JSON object or None"):
        ModelFile(friction=Params(**MAXWELL), report=[1])  # type: ignore[arg-type]


def test_save_follows_the_output_policy(tmp_path: Path) -> None:
    """No silent overwrite: an existing file only with force; an input never."""
    model = full_model()
    path = tmp_path / "model.json"
    path.write_text("keep me", encoding="utf-8")
    with pytest.raises(OutputError, match=r"exists: refusing to overwrite it"):
        model.save(path)
    assert path.read_text(encoding="utf-8") == "keep me"
    model.save(path, force=True)
    assert ModelFile.load(path) == model
    with pytest.raises(OutputError, match=r"is the input file"):
        model.save(path, force=True, inputs=[tmp_path / "." / "model.json"])
    model.save(tmp_path / "new" / "folder" / "m.json")  # folders are made
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.json", "new"]


def test_the_public_names() -> None:
    assert lr.ModelFile is ModelFile and lr.PositionLevel is PositionLevel and lr.Ripple is Ripple
    assert lr.Reconstruction is Reconstruction and lr.PositionForce is PositionForce
    assert {"ModelFile", "PositionLevel", "Ripple", "Reconstruction", "predict", "Prediction"} <= set(
        lr.__all__
    )
