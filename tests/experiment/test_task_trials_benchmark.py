"""``benchmarks/task_trials.py`` pairs two runs trial by trial."""

from __future__ import annotations

from types import ModuleType

from tests.benchmark_loader import load_benchmark


def _benchmark() -> ModuleType:
    return load_benchmark("task_trials")


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
