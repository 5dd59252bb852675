"""The demo's stories: the diagnose story names the hidden effects of the built-in log, the gap
shrinks, and the figure is written; the loop story identifies the simulated stage from its log
and tells what its compensator buys against the hand-set one."""

from __future__ import annotations

from pathlib import Path

from leuven_rt.studies.demo import LOOP_COMPENSATIONS, run_loop, run_story


def test_story_names_the_hidden_effects_and_writes_the_figure(tmp_path: Path) -> None:
    story = run_story(tmp_path)
    assert sorted(story.diagnosis.named_effects) == sorted(story.hidden)
    assert story.diagnosis.rms_after < 0.2 * story.diagnosis.rms_before
    assert story.figure.stat().st_size > 10_000
    text = story.text()
    assert "where the baseline and the data disagree" in text and "step 2" in text


def test_loop_story_tells_what_identification_buys() -> None:
    """The chain runs (log, identify, compensate) and the text tells each run's numbers and the
    ratio of identified to hand-set in each mode. (Whether identification wins is asserted in
    tests/studies/test_closed_loop.py, on the same study.)"""
    story = run_loop()
    metrics = story.comparison.metrics
    assert tuple(metrics) == LOOP_COMPENSATIONS
    identified = story.comparison.identified
    assert identified is not None
    assert identified.rms < identified.identification.diagnosis.rms_before
    for mode in ("feedforward", "observer"):
        assert metrics[f"leuven_{mode}"].rms < metrics["none"].rms, mode
        assert metrics[f"leuven_{mode}"].glitch < metrics["none"].glitch, mode
    text = story.text()
    for name, value in metrics.items():
        assert f"{name:<24} RMS {value.rms * 1e6:7.3f} µm" in text, name
    for mode in ("feedforward", "observer"):
        hand, found = metrics[f"leuven_{mode}"], metrics[f"identified_{mode}"]
        assert (
            f"hand-set -> identified ({mode}): RMS {hand.rms * 1e6:.3f} -> {found.rms * 1e6:.3f} µm" in text
        )
    assert f"identify named {', '.join(identified.named) or 'nothing'}" in text
