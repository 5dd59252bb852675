"""Params: the validated, immutable parameter set and its parameter-file (JSON) form."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leuven_rt
from conftest import LUGRE, MAXWELL, params_dicts
from leuven_rt import LeuvenModel, Params

KEYS = {"Fc", "Fs", "Vs", "delta", "n", "sigma1", "sigma2", "W", "Delta", "Fc_neg", "Fs_neg", "sigma0"}


@settings(max_examples=60, deadline=None)
@given(p=params_dicts())
def test_json_and_dict_round_trips(p: dict[str, Any]) -> None:
    """to_json → from_json and to_dict → from_dict give back an equal Params, with every float
    bit-identical; to_dict is the given dict (W, Delta as lists, sigma1/sigma2 filled in with
    their defaults), and to_json is that dict as JSON."""
    params = Params(**p)
    assert Params.from_json(params.to_json()) == params
    assert Params.from_dict(params.to_dict()) == params
    expected = {"sigma1": 0.0, "sigma2": 0.0, **p}
    assert params.to_dict() == expected
    assert json.loads(params.to_json()) == expected
    again = Params.from_json(params.to_json())
    for key, value in params.to_dict().items():
        got = again.to_dict()[key]
        assert np.array_equal(
            np.asarray(got).view(np.int64), np.asarray(value, dtype=np.float64).view(np.int64)
        ), key


def test_to_dict_leaves_unset_optional_keys_out() -> None:
    """The parameter-file form has exactly the keys of docs/parameters.md#keys that are set: no Fc_neg/Fs_neg
    for a symmetric model, no W/Delta for linear hysteresis, no sigma0 for Maxwell slip."""
    symmetric = {k: v for k, v in MAXWELL.items() if k not in ("Fc_neg", "Fs_neg")}
    assert set(Params(**symmetric).to_dict()) == KEYS - {"Fc_neg", "Fs_neg", "sigma0"}
    assert set(Params(**MAXWELL).to_dict()) == KEYS - {"sigma0"}
    assert set(Params(**LUGRE).to_dict()) == KEYS - {"Fc_neg", "Fs_neg", "W", "Delta"}
    minimal = Params(Fc=1.0, Fs=2.0, Vs=1e-3, delta=1.0, n=1.0, sigma0=1e4)
    assert minimal.to_dict() == dict(
        Fc=1.0, Fs=2.0, Vs=1e-3, delta=1.0, n=1.0, sigma1=0.0, sigma2=0.0, sigma0=1e4
    )


@pytest.mark.parametrize("model", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
def test_save_and_load(tmp_path: Path, model: dict[str, Any]) -> None:
    """save writes a JSON parameter file (one object, newline-terminated) that load reads back
    into an equal Params, which drives the model bit-identically."""
    params = Params(**model)
    path = tmp_path / "friction.json"
    params.save(path)
    text = path.read_text(encoding="utf-8")
    assert text.endswith("}\n")
    assert json.loads(text) == params.to_dict()
    loaded = Params.load(str(path))  # a str path works as well as a Path
    assert loaded == params
    v = 1e-2 * np.sin(np.linspace(0.0, 12.0, 500))
    np.testing.assert_array_equal(leuven_rt.simulate(loaded, v, 1e-4), leuven_rt.simulate(params, v, 1e-4))


def test_a_hand_written_file_loads(tmp_path: Path) -> None:
    """A parameter file written by hand with the keys of docs/parameters.md#keys (ints where floats
    are meant, no sigma1/sigma2) loads, with floats and defaults filled in."""
    path = tmp_path / "hand.json"
    path.write_text(
        '{"Fc": 1, "Fs": 2, "Vs": 0.001, "delta": 2, "n": 1,\n "W": [1, 2], "Delta": [1e-6, 2e-6]}'
    )
    params = Params.load(path)
    assert params == Params(Fc=1.0, Fs=2.0, Vs=1e-3, delta=2.0, n=1.0, W=(1.0, 2.0), Delta=(1e-6, 2e-6))
    assert (params.sigma1, params.sigma2, params.sigma0, params.Fc_neg) == (0.0, 0.0, None, None)
    assert type(params.Fc) is float and type(params.W[1]) is float


@pytest.mark.parametrize("key", ["Fc", "W", "sigma1", "Fc_neg"])
def test_params_is_frozen(key: str) -> None:
    """Params cannot be changed after validation: attribute assignment raises
    FrozenInstanceError and the value stays; W/Delta are tuples, so they cannot be changed in
    place, and changing the list given to the constructor does not reach the Params."""
    given = dict(MAXWELL, W=list(MAXWELL["W"]))
    params = Params(**given)
    before = getattr(params, key)
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(params, key, 123.0)
    assert getattr(params, key) == before
    assert isinstance(params.W, tuple) and isinstance(params.Delta, tuple)
    given["W"][0] = -5.0
    assert params.W[0] == 0.5
    with pytest.raises(TypeError):
        params.W[0] = 2.0  # type: ignore[index]


def test_equal_params_are_equal_and_hash_alike() -> None:
    """Params compare by value and hash alike when equal (usable as dict keys)."""
    a, b = Params(**MAXWELL), Params.from_dict(dict(MAXWELL))
    assert a == b and hash(a) == hash(b)
    assert a != Params(**dict(MAXWELL, sigma2=0.5))
    assert {a: 1}[b] == 1


def test_numpy_and_int_values_are_normalised() -> None:
    """numpy arrays, numpy scalars and ints are accepted for every number and normalised:
    scalars to Python floats, W and Delta to tuples of Python floats; the result equals the
    all-float Params and serialises to JSON."""
    params = Params(
        Fc=np.int64(1), Fs=np.float32(1.5), Vs=np.float64(1e-3), delta=2, n=np.int32(2),
        sigma1=30, sigma2=np.float16(0.5), W=np.array([1, 1]), Delta=np.array([2e-6, 4e-6]),
        Fc_neg=1, Fs_neg=np.int8(1),
    )  # fmt: skip
    expected = Params(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=30.0, sigma2=0.5,
                      W=(1.0, 1.0), Delta=(2e-6, 4e-6), Fc_neg=1.0, Fs_neg=1.0)  # fmt: skip
    assert params == expected
    for key in ("Fc", "Fs", "Vs", "delta", "n", "sigma1", "sigma2", "Fc_neg", "Fs_neg"):
        assert type(getattr(params, key)) is float, key
    assert type(params.W) is tuple and all(type(w) is float for w in params.W + params.Delta)
    assert Params.from_json(params.to_json()) == expected


@pytest.mark.parametrize(
    "values",
    [np.array([0.5, 0.5, 0.5, 0.5]), [0.5, 0.5, 0.5, 0.5], (0.5, 0.5, 0.5, 0.5), range(1, 5),
     np.array([1, 1, 1, 1], dtype=np.uint8), [np.float32(0.5)] * 4],
    ids=["ndarray", "list", "tuple", "range", "uint8", "np-scalars"],
)  # fmt: skip
def test_w_accepts_any_flat_sequence_of_reals(values: Any) -> None:
    """W (and Delta) may be any flat sequence or 1-D array of reals; it is stored as a tuple of
    Python floats with the same values."""
    params = Params(**dict(MAXWELL, W=values))
    assert params.W == tuple(float(x) for x in values)
    assert all(type(w) is float for w in params.W)


def test_derived_properties() -> None:
    """elements is N (0 for linear hysteresis); Fc_negative/Fs_negative are Fc_neg/Fs_neg, or
    fall back to Fc/Fs when not given."""
    maxwell, lugre = Params(**MAXWELL), Params(**LUGRE)
    assert (maxwell.elements, lugre.elements) == (4, 0)
    assert (maxwell.Fc_negative, maxwell.Fs_negative) == (0.7, 1.2)
    assert (lugre.Fc_negative, lugre.Fs_negative) == (1.0, 1.5)
    assert Params(**dict(LUGRE, Fs_neg=2.0)).Fc_negative == 1.0


def test_model_keeps_the_params_it_was_built_with() -> None:
    """LeuvenModel.params is the validated Params (a dict is converted), equal to the input."""
    model = LeuvenModel(dict(MAXWELL))
    assert isinstance(model.params, Params)
    assert model.params == Params(**MAXWELL)
    given = Params(**LUGRE)
    assert LeuvenModel(given).params is given


@settings(max_examples=30, deadline=None)
@given(p=params_dicts(), scale=st.floats(0.5, 2.0))
def test_validation_accepts_what_the_rules_allow(p: dict[str, Any], scale: float) -> None:
    """Every parameter set drawn within the rules of docs/parameters.md#rules is accepted by Params and by
    the Rust core (a LeuvenModel is built with the right number of elements)."""
    p = dict(p, sigma2=p["sigma2"] * scale)
    model = LeuvenModel(p)
    assert model.elements == len(p.get("W", []))
    assert model.params == Params(**p)
