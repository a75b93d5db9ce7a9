"""benchmarks/fleet.py: its writers' instructions, its check for lost writes, and a small run."""

from __future__ import annotations

from pathlib import Path
from types import ModuleType

import pytest

from ownctl.api import Ownctl
from tests.benchmark_loader import load_benchmark


def _fleet() -> ModuleType:
    return load_benchmark("fleet", "fleet_benchmark")


fleet = _fleet()


def test_every_writer_has_a_mix_on_objects_of_its_own() -> None:
    plans = [fleet.plan(k, 9) for k in range(3)]
    objects = [ins.obj for p in plans for ins in p]
    assert len(set(objects)) == len(objects) == 27
    assert {ins.kind for ins in plans[0]} == {"permission", "claim", "touch"}
    assert {ins.forbid for ins in plans[0] if ins.kind == "permission"} == {True, False}
    commands = [ins.command for p in plans for ins in p]
    assert len(set(commands)) == len(commands)


def test_verify_reports_every_instruction_that_is_not_there(tmp_path: Path) -> None:
    db = f"sqlite:///{tmp_path}/fleet.db"
    fleet.prepare(db, 2, 3)
    with Ownctl.open(db, speaker="robot0") as robot:  # writer 0's first two instructions, by hand
        first, second, _ = fleet.plan(0, 3)
        robot.permit("trash", first.obj, forbid=first.forbid)
        robot.claim(second.obj, second.agent)
    assert fleet.verify(db, 2, 3, [[0, 1], []]) == []
    lost = fleet.verify(db, 2, 3, [[0, 1, 2], [0]])  # a touch and a permission that never happened
    assert sorted(lost) == sorted([
        "store: robot0 object touch o0_2 --by xuan", "log (0 times): robot0 object touch o0_2 --by xuan",
        "store: robot1 forbid trash on o1_0", "log (0 times): robot1 forbid trash on o1_0"])
    with Ownctl.open(db, speaker="robot0") as robot:  # the same instruction twice is in the log twice
        robot.permit("trash", first.obj, forbid=first.forbid)
    assert fleet.verify(db, 2, 3, [[0], []]) == ["log (2 times): robot0 forbid trash on o0_0"]


def test_percentile_is_the_nearest_rank() -> None:
    values = list(range(1, 101))
    assert fleet.percentile(values, 50) == 50 and fleet.percentile(values, 99) == 99
    assert fleet.percentile([7.0], 99) == 7.0 and fleet.percentile([], 50) == 0.0


@pytest.mark.slow
def test_a_small_run_on_sqlite_loses_nothing() -> None:
    run = fleet.run_one("sqlite", None, 3, 4)
    assert (run.ok, run.failed, run.lost_store, run.lost_log) == (12, 0, 0, 0), run
    assert run.per_second > 0 and 0 < run.p50_ms <= run.p99_ms
