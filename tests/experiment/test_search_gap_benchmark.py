"""``benchmarks/search_gap.py`` tells a miss of the learner's search from a miss of its model."""

from __future__ import annotations

from types import ModuleType

from tests.benchmark_loader import load_benchmark


def _benchmark() -> ModuleType:
    return load_benchmark("search_gap")


def test_every_action_is_right_with_every_permission_and_exact_owners() -> None:
    assert [kind for kind, _ in _benchmark().classify(0, 0, 0)] == ["right"] * 3


def test_a_search_miss_is_told_from_a_model_miss() -> None:
    # tuning family 0, noisy claims, half the permissions: one action's true norms are a little more
    # probable under the model than the rules the greedy runs found
    kind, gap = _benchmark().classify(0, 4, 0)[2]
    assert kind == "search" and gap > 0.05


def test_the_precision_minded_runs_find_what_one_greedy_run_misses() -> None:
    # tuning family 26, noisy claims, every permission: the objective's greedy run alone ends on a
    # rule set 1.7 nats less probable than the true norms; the precision-minded runs find them
    assert _benchmark().classify(26, 3, 0)[0] == ("right", 0.0)


def test_few_permissions_miss_by_the_model() -> None:
    kinds = [kind for t in range(3) for kind, _ in _benchmark().classify(1, 2, t)]
    assert "model" in kinds and "search" not in kinds
