"""The versioned model file (leuven_rt.ModelFile, docs/data-and-reports.md#model-file): its JSON
form, exact round trips, plain parameter files loading as model files, every refusal naming the
key, and the output policy of ``save``."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import leuven_rt as lr
from conftest import LUGRE, MAXWELL
from leuven_rt import ModelFile, Params, PositionLevel, Ripple
from leuven_rt.errors import OutputError, ParameterError

LEVEL = PositionLevel(
    middle=0.0,
    half_stroke=0.01,
    trend=(0.05, -0.02),
    ripples=(Ripple(period=0.004, cos=(0.03, 0.01), sin=(0.0, 0.02)),),
)


def full_model() -> ModelFile:
    return ModelFile(
        friction=Params(**MAXWELL),
        level=LEVEL,
        offset=0.1,
        inertia=0.37,
        units="rotary",
        report={"held_out_rms": 0.021, "stages": [{"name": "sliding", "rms": 0.3}], "warnings": []},
    )


def test_the_json_form_is_the_documented_one() -> None:
    model = full_model()
    mapping = json.loads(model.to_json())
    assert list(mapping) == ["format", "version", "units", "friction", "level", "measurement", "report"]
    assert mapping["format"] == "leuven-rt model" and mapping["version"] == 1 and mapping["units"] == "rotary"
    assert mapping["friction"] == Params(**MAXWELL).to_dict()  # exactly the parameter file
    assert mapping["level"] == {
        "middle": 0.0,
        "half_stroke": 0.01,
        "trend": [0.05, -0.02],
        "ripples": [{"period": 0.004, "cos": [0.03, 0.01], "sin": [0.0, 0.02]}],
    }
    assert mapping["measurement"] == {"offset": 0.1, "inertia": 0.37}
    assert mapping["report"]["held_out_rms"] == 0.021
    assert json.loads(ModelFile(friction=Params(**LUGRE)).to_json())["level"] is None


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


def _file(**changes: Any) -> str:
    mapping = full_model().to_dict()
    for key, value in changes.items():
        if value is None:
            mapping.pop(key)
        else:
            mapping[key] = value
    return json.dumps(mapping)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (_file(format="leuven-rt params"), r"`format` must be 'leuven-rt model', got 'leuven-rt params'"),
        (_file(version=2), r"`version` must be 1, got 2: .*newer leuven-rt; upgrade leuven-rt"),
        (_file(version="1"), r"`version` must be 1, got '1'"),
        (_file(version=1.0), r"`version` must be 1, got 1\.0"),
        (_file(version=True), r"`version` must be 1, got True"),
        (_file(version=None), r"missing key `version`: expected 1"),
        (_file(comment="hi"), r"unknown keys \['comment'\] in the model file"),
        (_file(friction=None), r"missing key `friction`"),
        (_file(friction={"Fc": 1.0}), r"friction: missing parameter keys \['Fs', 'Vs', 'delta', 'n'\]"),
        (_file(friction=[1.0]), r"`friction` must be an object of parameters"),
        (_file(units="metric"), r"`units` must be 'linear' or 'rotary', got 'metric'"),
        (_file(measurement={"offset": "NaN"}), r"`measurement.offset` must be a real number"),
        (
            '{"format": "leuven-rt model", "version": 1, "friction": ' + json.dumps(MAXWELL)
            + ', "measurement": {"offset": NaN}}',
            r"`measurement.offset` must be finite, got nan",
        ),
        (_file(measurement={"inertia": 1e400}), r"`measurement.inertia` must be finite, got inf"),
        (_file(measurement={"mass": 1.0}), r"unknown keys \['mass'\] in `measurement`"),
        (_file(level={"middle": 0.0, "slope": 1.0}), r"unknown keys \['slope'\] in `level`"),
        (_file(level={"half_stroke": 0.0}), r"`level.half_stroke` must be > 0, got 0\.0"),
        (_file(level={"trend": [0.1]}), r"`level.trend` must hold 2 numbers"),
        (
            _file(level={"ripples": [{"period": 1.0, "cos": [0.1, 0.2], "sin": [0.1]}]}),
            r"`level.ripples\[0\].cos` and `level.ripples\[0\].sin` must have the same length",
        ),
        (
            _file(level={"ripples": [{"period": 1.0, "cos": [0.1]}]}),
            r"`level.ripples\[0\]` lacks the keys \['sin'\]",
        ),
        (
            _file(level={"ripples": [{"period": -1.0, "cos": [0.1], "sin": [0.0]}]}),
            r"`level.ripples\[0\].period` must be > 0",
        ),
        (_file(report=[1, 2]), r"`report` must be a JSON object or null"),
        ("[1, 2]", r"a model file must be a JSON object, got list"),
        ("{", r"a model file must be JSON text of an object"),
    ],
)  # fmt: skip
def test_bad_files_are_refused_naming_the_key(text: str, match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        ModelFile.from_json(text)


def test_load_names_the_file(tmp_path: Path) -> None:
    path = tmp_path / "model.json"
    path.write_text(_file(version=3), encoding="utf-8")
    with pytest.raises(ParameterError, match=rf"^{path}: `version` must be 1, got 3"):
        ModelFile.load(path)
    with pytest.raises(ParameterError, match=r"cannot read model file .*missing\.json"):
        ModelFile.load(tmp_path / "missing.json")
    (tmp_path / "latin.json").write_bytes('{"é": 1}'.encode("latin-1"))
    with pytest.raises(ParameterError, match=r"is not UTF-8 text"):
        ModelFile.load(tmp_path / "latin.json")


def test_bad_python_values_are_refused() -> None:
    with pytest.raises(ParameterError, match=r"`friction` must be a leuven_rt.Params or a mapping"):
        ModelFile(friction=3)  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match=r"`measurement.offset` must be a real number, got 'a'"):
        ModelFile(friction=Params(**MAXWELL), offset="a")  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match=r"`measurement.inertia` must be finite, got nan"):
        ModelFile(friction=Params(**MAXWELL), inertia=math.nan)
    with pytest.raises(ParameterError, match=r"`units` must be 'linear' or 'rotary', got 'deg'"):
        ModelFile(friction=Params(**MAXWELL), units="deg")  # type: ignore[arg-type]
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
    assert {"ModelFile", "PositionLevel", "Ripple", "predict", "Prediction"} <= set(lr.__all__)
