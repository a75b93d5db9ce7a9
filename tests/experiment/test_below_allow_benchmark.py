"""``benchmarks/below_allow.py``: family cells below allowing everything, and cautious decisions."""

from __future__ import annotations

from dataclasses import replace
from types import ModuleType

import numpy as np

from ownctl.experiment.metrics import rule_scores
from ownctl.experiment.norms import NORM_CONDITIONS, NormsSetup, norms_setup, taught_mind
from ownctl.experiment.runner import trial_rng
from ownctl.mind import Mind
from ownctl.world.families import norm_family
from tests.benchmark_loader import load_benchmark

SPARSE = [i for i, c in enumerate(NORM_CONDITIONS) if c.name == "noiseless 0.25"][0]


def _benchmark() -> ModuleType:
    return load_benchmark("below_allow")


def _trial(family: int, t: int) -> tuple[NormsSetup, Mind]:
    setup = norms_setup(norm_family(family), NORM_CONDITIONS[SPARSE], trial_rng(0, SPARSE, t, family))
    return setup, taught_mind(setup)


def test_none_is_ownctls_own_decision() -> None:
    setup, mind = _trial(1, 5)
    got = _benchmark().cautious(mind, "collect", setup.true_frame, "none", 1.0)
    assert np.array_equal(got, mind.p_rules_on("collect", setup.true_frame))


def test_the_least_over_near_best_rule_sets_forbids_only_what_they_all_forbid() -> None:
    # tuning family 1, a quarter of the permissions: the one forbidden example (owned by agent3,
    # red) is generalised to "ownedBy agent3", which also forbids agent3's other objects; "red"
    # explains the permissions as well, and only the object both describe is forbidden by both
    setup, mind = _trial(1, 5)
    bench = _benchmark()
    answers = setup.answers["collect"]
    learned = rule_scores(answers, bench.cautious(mind, "collect", setup.true_frame, "none", 1.0))
    least = bench.cautious(mind, "collect", setup.true_frame, "min", 1.0)
    assert learned.accuracy < 0.85
    assert rule_scores(answers, least).accuracy == 1.0


def test_the_mean_is_at_least_the_least_and_differs_where_near_best_sets_disagree() -> None:
    setup, mind = _trial(1, 11)
    bench = _benchmark()
    frame = setup.true_frame
    least, mean = (bench.cautious(mind, "collect", frame, t, 1.0) for t in ("min", "mean"))
    assert np.all(least <= mean + 1e-12)
    assert np.any(mean > least + 0.1)


def test_a_cell_reports_ours_and_allowing_everything() -> None:
    out = _benchmark().cell(1, SPARSE, 2)
    assert out["family"] == 1 and out["condition"] == "noiseless 0.25"
    assert set(out["actions"]) == {"trash", "pickUp", "collect"}
    assert 0.0 <= out["ours"] <= 1.0 and 0.0 <= out["allow"] <= 1.0


def test_paired_is_ours_minus_probfoils_cached_scores() -> None:
    bench = _benchmark()
    cache = {"1/noiseless 0.25/5": {"actions": {"collect": {"scores": [0.9, 1.0, 0.5, 0.6]},
                                                "pickUp": {"scores": [0.7, 1.0, 0.5, 0.4]}}}}
    acc, f1 = bench._trial_scores((1, SPARSE, 5, "none", 1e-6))
    got = bench.paired(cache, "none", 1e-6, 1)["noiseless 0.25"]
    assert got["families"] == 1
    assert abs(got["accuracy"][0] - (acc - 0.8)) < 1e-12 and abs(got["f1"][0] - (f1 - 0.5)) < 1e-12


def test_the_mean_is_ownctls_window_decision() -> None:
    setup, mind = _trial(1, 11)
    frame = setup.true_frame
    got = _benchmark().cautious(mind, "collect", frame, "mean", 0.5)
    windowed = taught_mind(setup, decide="window")
    windowed.settings = replace(windowed.settings, decide_window=0.5)
    assert np.allclose(got, windowed.p_rules_on("collect", frame), atol=1e-12)
