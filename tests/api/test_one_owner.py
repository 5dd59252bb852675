"""One owner per check: Python coerces, gms-core validates, and nothing is checked twice.

A Params is validated once and the validated set is what every engine takes; a signal is scanned
for finiteness once, by gms-core; a log validated on load passes through the workflows as it is.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from typing import Any

import numpy as np
import pytest

import conftest
import leuven_rt
from leuven_rt import Compensator, InputError, LeuvenModel, MassSystem, ParameterError, Params, _core
from leuven_rt._checks import as_signal
from leuven_rt.data import records
from leuven_rt.params import core_params

DT = 1e-3
MAXWELL = Params(**conftest.MAXWELL)
LUGRE = Params(**conftest.LUGRE)


@pytest.mark.parametrize("params", [MAXWELL, LUGRE], ids=["maxwell", "lugre"])
def test_params_survive_pickle_copy_and_replace(params: Params) -> None:
    for clone in (pickle.loads(pickle.dumps(params)), copy.copy(params), copy.deepcopy(params)):
        assert clone == params and hash(clone) == hash(params) and repr(clone) == repr(params)
        assert isinstance(core_params(clone), _core.CoreParams)
        assert core_params(clone).elements == params.elements
    assert dataclasses.replace(params, Fc=params.Fc) == params
    assert "_validated" not in repr(params) and "_validated" not in params.to_dict()
    assert [field.name for field in dataclasses.fields(params)][-1] == "sigma0"
    with pytest.raises(ParameterError, match=r"`Fc` must be finite and > 0, got -1"):
        dataclasses.replace(params, Fc=-1.0)


def test_params_are_validated_once_and_engines_take_the_validated_set() -> None:
    validated = core_params(MAXWELL)
    assert core_params(MAXWELL) is validated  # kept on the instance, not rebuilt
    assert core_params(conftest.MAXWELL).elements == MAXWELL.elements
    _core.check_params(validated)
    for engine in (
        _core.Engine(validated, 2, "implicit"),
        _core.MassEngine(validated, 1.0, 0.0, 0.0, 1, "implicit"),
        _core.CompensatorEngine(validated, DT, "feedforward"),
    ):
        assert engine.elements == MAXWELL.elements
    # The engine runs the same model from the validated set as from the Params it came from.
    v = np.sin(np.linspace(0.0, 6.0, 300))[None, :] * 1e-3
    from_set, from_params = np.empty_like(v), np.empty_like(v)
    _core.Engine(validated, 1, "implicit")._run(v, DT, False, from_set)
    _core.Engine(MAXWELL, 1, "implicit")._run(v, DT, False, from_params)
    np.testing.assert_array_equal(from_set, from_params)


def test_wrappers_keep_the_users_params() -> None:
    assert LeuvenModel(MAXWELL).params is MAXWELL
    assert MassSystem(MAXWELL, 1.0).params is MAXWELL
    compensator = Compensator(MAXWELL, DT)
    assert compensator.params is MAXWELL
    changed = dataclasses.replace(MAXWELL, Fc=MAXWELL.Fc * 1.1)
    compensator.set_params(changed)
    assert compensator.params is changed
    with pytest.raises(ParameterError):
        compensator.set_params(LUGRE)  # another kind: refused, and the params stay
    assert compensator.params is changed
    assert LeuvenModel(conftest.MAXWELL).params == MAXWELL


def test_a_signal_is_scanned_once_by_gms_core() -> None:
    # Python only coerces: a NaN passes as_signal, so the error below is gms-core's.
    signal = np.zeros((3, 50))
    signal[2, 17] = np.nan
    array, _ = as_signal(signal, "v")
    assert np.isnan(array[2, 17])
    with pytest.raises(InputError, match=r"^`v` must be finite, got nan at channel 2, sample 17$"):
        leuven_rt.simulate(MAXWELL, signal, DT)
    with pytest.raises(InputError, match=r"^`x` must be finite, got inf at sample 4$"):
        leuven_rt.simulate_position(MAXWELL, [0.0, 0.0, 0.0, 0.0, np.inf], DT)
    with pytest.raises(InputError, match=r"^`u` must be finite, got nan at channel 2, sample 17$"):
        leuven_rt.simulate_mass(MAXWELL, signal, DT, mass=1.0)
    # One step of B channels: the index is the channel's (Python used to call it "sample 1").
    with pytest.raises(InputError, match=r"^`v` must be finite, got nan at channel 1, sample 0$"):
        LeuvenModel(MAXWELL, channels=2).step_channels([0.0, np.nan], DT)
    # The numpy reference has no Rust call behind it and checks for itself, with the same message.
    with pytest.raises(InputError, match=r"^`v` must be finite, got nan at channel 2, sample 17$"):
        leuven_rt.reference.simulate(MAXWELL, signal, DT)


@pytest.mark.parametrize("dt", [0.0, -1.0, float("nan"), 1e-310])
def test_dt_values_are_checked_by_gms_core_like_the_reference(dt: float) -> None:
    with pytest.raises(InputError) as rust:
        leuven_rt.simulate(MAXWELL, [0.0, 1e-3], dt)
    with pytest.raises(InputError) as reference:
        leuven_rt.reference.simulate(MAXWELL, [0.0, 1e-3], dt)
    assert str(rust.value) == str(reference.value)
    with pytest.raises(InputError, match=r"`dt` must be a real number, got True"):
        leuven_rt.simulate(MAXWELL, [0.0, 1e-3], True)


def test_online_settings_are_checked_by_gms_core() -> None:
    with pytest.raises(ParameterError, match=r"^`initial` must be finite, got inf at entry 2$"):
        leuven_rt.OnlineIdentifier([1e-6], initial=[0.0, 0.0, np.inf, 0.0])
    with pytest.raises(ParameterError, match=r"^`Delta` must have 1 to 32 elements, got 0$"):
        leuven_rt.OnlineIdentifier([])


def test_a_log_validated_on_load_is_not_validated_again(monkeypatch: pytest.MonkeyPatch) -> None:
    t = np.arange(400) * 1e-3
    columns = {"t": t, "x": 1e-3 * np.sin(20.0 * t), "f": np.cos(20.0 * t)}
    calls = []
    check = records.check_columns

    def counted(given: dict[str, np.ndarray], **options: Any) -> dict[str, np.ndarray]:
        calls.append(sorted(given))
        return check(given, **options)

    monkeypatch.setattr(records, "check_columns", counted)
    record = records.as_motion_data(columns)
    assert len(calls) == 1
    assert records.as_motion_data(record) is record
    assert len(calls) == 1
    assert not record.t.flags.writeable and record.v is None and record.source == "arrays"
    assert record.samples == 400 and record.dt == pytest.approx(1e-3)
