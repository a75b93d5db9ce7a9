"""``benchmarks/search_gap.py`` tells a miss of the learner's search from a miss of its model."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def _benchmark() -> ModuleType:
    spec = importlib.util.spec_from_file_location("search_gap", ROOT / "benchmarks" / "search_gap.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["search_gap"] = module
    spec.loader.exec_module(module)
    return module


def test_every_action_is_right_with_every_permission_and_exact_owners() -> None:
    assert [kind for kind, _ in _benchmark().classify(0, 0, 0)] == ["right"] * 3


def test_a_disjunction_the_greedy_search_misses_is_a_search_miss() -> None:
    # three two-literal rules for trash, which the greedy covering explains with two rules and one
    # misfit permission: the true norms are more probable under the model than what it found
    kinds = _benchmark().classify(1078, 0, 2)
    kind, gap = kinds[0]
    assert kind == "search" and gap > 1.0


def test_few_permissions_miss_by_the_model() -> None:
    kinds = [kind for t in range(3) for kind, _ in _benchmark().classify(1, 2, t)]
    assert "model" in kinds and "search" not in kinds
