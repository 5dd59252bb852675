"""The family of generated logs of benches/family.py: deterministic per seed, its manifest in the
form the hidden-effect scorer reads, its floor equal to the noise where the log gives the true
velocity and friction flips below the encoder step, its null cases free of every hidden effect,
and its held-out split apart from the tuning split in seeds and in generator paths.

The full scorer is not run here (minutes per log); its judging functions are, on the manifest."""

from __future__ import annotations

import dataclasses
import importlib.util
import json
import math
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from conftest import family as load_family
from leuven_rt import simulate, simulate_position
from leuven_rt.data import as_motion_data

ROOT = Path(__file__).resolve().parents[2]
SCORER = ROOT.parent / "shared" / "tools" / "score_diagnose.py"
#: The keys the scorer reads from a manifest entry, and their types.
SCORER_KEYS: dict[str, Any] = {
    "name": str,
    "hidden_effects": list,
    "extra": (str, type(None)),
    "noise_std": float,
    "scale": str,
    "floor_rms": float,
}
CATALOGUE = {"stribeck", "asymmetry", "presliding_hysteresis", "position_dependence", "offset", "inertia"}


def _load(name: str, path: Path) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # its dataclasses look their module up while being made
    spec.loader.exec_module(module)
    return module


family = load_family()


@pytest.fixture(scope="module")
def quick_tuning(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, list[dict[str, Any]]]:
    out = tmp_path_factory.mktemp("family")
    return out, family.generate(out, "tuning", quick=True)


def test_a_seed_gives_the_same_log_and_another_seed_another() -> None:
    case = family.draw_case("held-out", 0, seed_base=0, quick=True)  # the closed loop
    first, second = (
        family.make_log(case),
        family.make_log(family.draw_case("held-out", 0, seed_base=0, quick=True)),
    )
    for name in ("t", "x", "f", "force_true", "noise"):
        np.testing.assert_array_equal(getattr(first, name), getattr(second, name), err_msg=name)
    assert family.manifest_entry(first) == family.manifest_entry(second)
    other = family.make_log(family.draw_case("held-out", 0, seed_base=7, quick=True))
    assert other.case.seed != case.seed
    assert other.f.size != first.f.size or not np.array_equal(other.f, first.f)


def test_the_manifest_holds_what_the_scorer_reads(quick_tuning: tuple[Path, list[dict[str, Any]]]) -> None:
    out, returned = quick_tuning
    cases = json.loads((out / "manifest.json").read_text())  # as the scorer reads it
    assert cases == json.loads(json.dumps(returned))
    assert len(cases) == 4
    for case in cases:
        for key, kind in SCORER_KEYS.items():
            assert isinstance(case[key], kind), (case["name"], key, case[key])
        assert "judge" not in case
        assert case["split"] == "tuning"
        assert set(case["hidden_effects"]) <= CATALOGUE
        assert case["extra"] in (None, "drift")
        assert case["scale"] in ("linear", "rotary")
        assert case["noise_std"] > 0.0 and case["floor_rms"] >= 0.9 * case["noise_std"]
        record = as_motion_data(out / f"{case['name']}.csv", units=case["scale"])  # no warning either
        assert (record.v is not None) == case["sensor"]["has_v"]
        steps = np.abs(np.diff(record.x))
        assert np.min(steps[steps > 0]) == pytest.approx(case["sensor"]["quantization"], rel=1e-6)
        assert record.dt == pytest.approx(case["sensor"]["dt"], rel=1e-9)
        assert 8.0 <= record.t[-1] <= 16.0


def test_the_scorer_judges_the_manifest(quick_tuning: tuple[Path, list[dict[str, Any]]]) -> None:
    if not SCORER.exists():
        pytest.skip(f"the scorer is not at {SCORER} (expected next to the repository in shared/tools)")
    scorer = _load("score_diagnose", SCORER)
    _, cases = quick_tuning
    for case in cases:
        assert scorer.units_args(case) == (["--units", "rotary"] if case["scale"] == "rotary" else [])
        allowed = scorer.bound(case)
        assert allowed == max(1.5 * case["noise_std"], 1.2 * case["floor_rms"])
        exact = {"named_effects": case["hidden_effects"], "unexplained": {"significant": bool(case["extra"])}}
        assert scorer.judge(case, exact, allowed)[0], case["name"]
        wrong = sorted(set(case["hidden_effects"]) ^ {"offset"})
        assert not scorer.judge(case, {**exact, "named_effects": wrong}, allowed)[0], case["name"]
        if not case["extra"]:
            assert not scorer.judge(case, exact, 1.01 * allowed)[0], case["name"]


@pytest.mark.parametrize(
    ("split", "index", "seed_base", "law"),
    [
        ("tuning", 1, 1, "leuven"),
        ("tuning", 2, 0, "leuven"),
        ("tuning", 7, 1, "leuven"),
        ("held-out", 11, 1, "leuven"),
        ("tuning", 2, 0, "lugre"),
        ("held-out", 11, 1, "lugre"),
    ],
)
def test_the_true_velocity_drives_the_true_law_to_the_clean_force(
    split: str, index: int, seed_base: int, law: str
) -> None:
    """Null, asymmetry and offset logs with ``v``: the true law with its measurement terms,
    driven by the logged ``v``, gives the force before noise on every sample but those in which
    the motion starts or reverses and the next few. There the truth is between its levels (it
    flips over 1e-10 of travel) while a law driven at the log's rate flips whole, or nearly: the
    floor's excess over the noise."""
    case = family.draw_case(split, index, seed_base, quick=True, law=law)
    assert (
        case.has_v
        and case.recipe.excitation not in family.CLOSED_LOOP
        and "stribeck" not in case.recipe.hidden
    )
    log = family.make_log(case)
    truth, v = log.case.truth, log.v
    expected = simulate(family.contact_params(truth), v, case.dt) + family.viscous(truth, v) + truth["offset"]
    direction = np.sign(v)
    turns = np.concatenate(([False], direction[1:] != direction[:-1])) & (direction != 0)
    assert 10 <= np.count_nonzero(turns) <= 0.02 * v.size
    error = np.abs(log.force_true - expected)
    # Beyond a micrometre of travel after each start or reversal (trapezoidal in the true
    # velocity) the flip, of the truth and of the law at the log's step, is over.
    travel = np.concatenate(([0.0], np.cumsum(0.5 * (np.abs(v[1:]) + np.abs(v[:-1])) * case.dt)))
    last_turn = np.maximum.accumulate(np.where(turns, np.arange(v.size), 0))
    settled = ~(turns | ((travel - travel[last_turn] < 1e-6) & (last_turn > 0)))
    assert np.mean(settled) > 0.98
    assert np.max(error[settled]) <= 1e-7 * truth["Fc"]


@pytest.mark.parametrize(
    ("split", "index", "law"),
    [
        ("tuning", 3, "leuven"),
        ("tuning", 8, "leuven"),
        ("tuning", 9, "leuven"),
        ("tuning", 12, "leuven"),
        ("tuning", 15, "leuven"),
        ("tuning", 22, "leuven"),
        ("held-out", 0, "leuven"),
        ("held-out", 0, "lugre"),
        ("held-out", 4, "lugre"),
    ],
)
def test_where_the_law_driven_by_v_is_the_clean_force_the_floor_is_the_noise(
    split: str, index: int, law: str
) -> None:
    """The floor's terms, one case each: the ripple, the trend, the drift, cogging, the −x
    levels with inertia, offset with inertia and Stribeck, the closed loop, and the floor's
    reading of the LuGre law (its contact part in the floor's drives, on a closed-loop log and a
    presliding one). Each log is given the true velocity, and its force is made the true law
    driven by it plus the log's noise: the floor is then the noise, and it comes from the logged
    ``v``."""
    case = dataclasses.replace(family.draw_case(split, index, quick=True, law=law), has_v=True)
    log = family.make_log(case)
    truth, v = log.case.truth, log.v
    assert v is not None
    expected = (
        family.level_factor(truth, log.x, log.t) * simulate(family.contact_params(truth), v, case.dt)
        + family.viscous(truth, v)
        + truth["offset"]
        + family.cogging(truth, log.x)
        + truth["mass"] * np.gradient(v, case.dt)
    )
    floor, source = family.floor(log.case, log.t, log.x, expected + log.noise, v)
    assert floor == pytest.approx(float(np.std(log.noise)), rel=1e-3)
    assert source.startswith("logged v")
    # The physical log's floor is at least that: no drive explains the noise.
    assert log.floor_rms >= 0.99 * float(np.std(log.noise))


@pytest.mark.parametrize(
    ("split", "index"), [("held-out", 4), ("held-out", 0), ("tuning", 1), ("tuning", 20)]
)
def test_a_lugre_log_is_its_leuven_pair_with_another_contact_law(split: str, index: int) -> None:
    """``--law lugre`` changes the contact part alone: the case (recipe, sensors, excitation,
    noise) and every true value outside the contact part are the Leuven log's of the same seed,
    and so are the force noise and the motion of a position-driven log."""
    leuven = family.draw_case(split, index, seed_base=3, quick=True)
    lugre = family.draw_case(split, index, seed_base=3, quick=True, law="lugre")
    assert dataclasses.replace(lugre, truth=leuven.truth) == leuven
    keys = leuven.truth.keys() | lugre.truth.keys()
    changed = {key for key in keys if leuven.truth.get(key) != lugre.truth.get(key)}
    assert changed <= {"law", "n", "sigma0", "sigma1", "N", "grid", "W", "Delta", "presliding_range"}
    assert lugre.truth["law"] == "lugre" and leuven.truth["law"] == "leuven"
    params = family.contact_params(lugre.truth)
    assert params.W is None and params.n == 1.0 and params.sigma2 == 0.0
    assert params.sigma0 is not None and params.sigma0 > 0.0 and params.sigma1 > 0.0
    assert family.describe(lugre).startswith("LuGre law, ")
    first, second = family.make_log(leuven), family.make_log(lugre)
    np.testing.assert_array_equal(first.noise, second.noise)
    assert not np.array_equal(first.force_true, second.force_true)
    if lugre.recipe.excitation not in family.CLOSED_LOOP:
        np.testing.assert_array_equal(first.x, second.x)


def test_an_unknown_law_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(ValueError, match="`law` must be one of \\['leuven', 'lugre'\\], got 'dahl'"):
        family.draw_case("tuning", 0, law="dahl")
    with pytest.raises(SystemExit) as exit_info:
        family.main([str(tmp_path), "--law", "dahl"])
    assert exit_info.value.code == 2
    assert "--law: invalid choice: 'dahl'" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())


def test_a_lugre_bristle_reaches_95_percent_of_the_level_over_the_presliding_range() -> None:
    """Where presliding is hidden, the LuGre law's force builds up from rest as
    Fs·(1 − e^(−σ0·x/Fs)) at speeds far below Vs: 1 − e⁻³ of Fs at the experimenter's range.
    Where it is not, one implicit step of a thousand ``STIFF_DELTA`` (far longer than the
    bristle's reach) takes it to 1000/1001 of its level."""
    case = family.draw_case("held-out", 4, quick=True, law="lugre")
    truth = case.truth
    assert "presliding_hysteresis" in case.recipe.hidden and truth["Fs_neg"] == truth["Fs"]
    reach = truth["excitation_presliding_range"]
    assert truth["presliding_range"] == pytest.approx(reach)
    x = np.linspace(0.0, 2.0 * reach, 20001)
    force = simulate_position(family.contact_params(truth), x, 1.0)  # 1e-4 ranges a second: far below Vs
    curve = truth["Fs"] * (1.0 - np.exp(-truth["sigma0"] * x / truth["Fs"]))
    np.testing.assert_allclose(force, curve, atol=1e-3 * truth["Fs"])
    assert force[10000] == pytest.approx((1.0 - math.exp(-3.0)) * truth["Fs"], rel=2e-3)
    stiff = family.draw_case("held-out", 1, quick=True, law="lugre").truth
    assert stiff["presliding_range"] == pytest.approx(family.LUGRE_REACH * family.STIFF_DELTA)
    step = simulate_position(family.contact_params(stiff), np.array([0.0, 1e3 * family.STIFF_DELTA]), 1.0)
    assert step[-1] == pytest.approx(stiff["Fs"] * 1e3 / (1e3 + 1.0), rel=1e-6)


def test_a_null_case_hides_nothing() -> None:
    nulls = [
        (split, index)
        for split in family.SPLITS
        for index, recipe in enumerate(family.RECIPES[split])
        if not recipe.hidden
    ]
    assert len(nulls) >= 4
    for split, index in nulls:
        truth = family.draw_case(split, index).truth
        assert truth["Fs"] == truth["Fc"] == truth["Fc_neg"] == truth["Fs_neg"]
        assert truth["sigma2_neg"] == truth["sigma2"] > 0.0
        assert truth["Delta"] == [family.STIFF_DELTA] and truth["W"][0] > truth["Fs"]
        assert truth["offset"] == 0.0 and truth["mass"] == 0.0
        assert truth["level"] is None and truth["cogging"] is None
    # The clean force of a null log is ±Fc + σ2·v, the sign that of the last motion, on every
    # sample but those where the motion turns (friction flips within 1e-10 of travel).
    case = family.draw_case("tuning", 1, seed_base=1, quick=True)
    assert not case.recipe.hidden and case.recipe.extra is None and case.has_v
    log = family.make_log(case)
    moved = np.argmax(log.v != 0.0)  # the friction is relaxed (0) until the first motion
    contact = (log.force_true - case.truth["sigma2"] * log.v)[moved:]
    assert np.mean(np.isclose(np.abs(contact), case.truth["Fc"], rtol=1e-9)) > 0.99
    moving = np.abs(log.v[moved:]) > 1e-3 * case.truth["Vs"]
    assert np.mean(np.sign(contact[moving]) == np.sign(log.v[moved:][moving])) > 0.99


def test_the_held_out_split_has_seeds_and_paths_of_its_own() -> None:
    tuning = [family.draw_case("tuning", index) for index in range(len(family.TUNING))]
    held = [family.draw_case("held-out", index) for index in range(len(family.HELD_OUT))]
    for seed_base in (0, 1, 5, 1000):
        seeds = {
            split: {family.draw_case(split, index, seed_base).seed for index in range(24)}
            for split in family.SPLITS
        }
        assert not seeds["tuning"] & seeds["held-out"]
    assert all(case.recipe.excitation not in family.CLOSED_LOOP for case in tuning)
    assert all(case.rate < 2000.0 and case.noise_kind in ("white", "coloured") for case in tuning)
    closed = [case for case in held if case.recipe.excitation in family.CLOSED_LOOP]
    assert len(closed) >= 8 and all("inertia" in case.recipe.hidden for case in closed)
    assert all(case.rate >= 2000.0 for case in held if case not in closed)
    assert any(case.noise_kind == "pink" for case in held)
    for cases in (tuning, held):
        assert {case.axis.kind for case in cases} == {"linear", "rotary"}
        assert {case.has_v for case in cases} == {True, False}
        assert {case.recipe.extra for case in cases} == {None, "drift"}
        assert {case.recipe.position for case in cases} >= {"ripple", "trend", "cogging"}
        hidden = {effect for case in cases for effect in case.recipe.hidden}
        assert hidden == CATALOGUE


def test_an_existing_manifest_is_kept_and_a_negative_seed_base_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    manifest = tmp_path / "manifest.json"
    manifest.write_text("[]\n")
    assert family.main([str(tmp_path), "--quick"]) == 2
    assert manifest.read_text() == "[]\n" and sorted(tmp_path.iterdir()) == [manifest]
    assert "exists; give --force" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exit_info:
        family.main([str(tmp_path / "other"), "--seed-base", "-1"])
    assert exit_info.value.code == 2
    assert "--seed-base: must be >= 0, got -1" in capsys.readouterr().err
    with pytest.raises(ValueError, match="`seed_base` must be >= 0") as error:
        family.draw_case("tuning", 0, seed_base=-1)
    assert type(error.value) is ValueError
    with pytest.raises(ValueError, match="`index` must be in \\[0, 24\\) for the tuning split, got 24"):
        family.draw_case("tuning", 24)
