"""``benchmarks/task_trials.py`` pairs two runs trial by trial."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def _benchmark() -> ModuleType:
    spec = importlib.util.spec_from_file_location("task_trials", ROOT / "benchmarks" / "task_trials.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["task_trials"] = module  # the worker processes find its functions by this name
    spec.loader.exec_module(module)
    return module


def test_the_paired_difference_counts_only_trials_both_runs_have() -> None:
    before = {"0/trashAll/0": 3.0, "0/trashAll/1": 2.0, "0/trashAll/2": 5.0, "0/collectAll/0": 1.0}
    after = {"0/trashAll/0": 2.0, "0/trashAll/1": 2.0, "0/collectAll/0": 1.0}
    lines = _benchmark().paired(before, after)
    assert lines[0].startswith("collectAll: 1 trials, before 1.000, after 1.000, after - before +0.000")
    assert lines[1].startswith("trashAll: 2 trials, before 2.500, after 2.000, after - before -0.500")
    assert lines[1].endswith("(fewer in 1, more in 0)")


def test_one_trial_each_runs_end_to_end() -> None:
    out = _benchmark().run([0], 1, 1)
    assert sorted(out) == ["0/collectAll/0", "0/trashAll/0"] and all(v >= 0 for v in out.values())
