"""``ownctl run``: the paper's tasks on the store's world, obeying and learning norms."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.cli.conftest import SMALL_WORLD, Ownctl


def without_timing(report: dict) -> dict:
    return {k: v for k, v in report.items() if k not in ("wall_seconds", "real_time_factor")}


def test_fresh_store_gets_the_paper_world_and_the_same_seed_gives_the_same_report(
    tmp_path: Path, ownctl: Ownctl
) -> None:
    first = ownctl.json("run", "trashAll", "--kinematic", "--seed", "3")
    assert first["loaded_world"] is True
    assert set(first) >= {"task", "delivered", "skipped", "mistakes", "violations", "rule", "ownership",
                          "sim_seconds", "wall_seconds"}
    assert len(first["steps"]) == 20 and first["violations"] == []
    twin = Ownctl(tmp_path / "twin.db")
    twin("init")
    assert without_timing(twin.json("run", "trashAll", "--kinematic", "--seed", "3")) == without_timing(first)
    again = ownctl.json("run", "trashAll", "--kinematic", "--seed", "3")  # works twice
    assert again["loaded_world"] is False and again["mistakes"] == 0 and again["delivered"] == []


def test_a_world_with_agents_and_no_objects_is_kept_and_the_task_finds_nothing(tmp_path: Path,
                                                                              ownctl: Ownctl) -> None:
    world = tmp_path / "bare.toml"
    world.write_text('name = "bare"\nagents = ["ana", "bo"]\nnorms = []\n'
                     '[[areas]]\nname = "trash"\nbox = [-0.3, 0.6, 0.2, 1.1]\n', encoding="utf-8")
    ownctl("world", "load", str(world))
    report = ownctl.json("run", "trashAll", "--kinematic")
    assert report["loaded_world"] is False and report["steps"] == [] and report["mistakes"] == 0
    assert {a["name"] for a in ownctl.json("agent", "list")} == {"ana", "bo"}
    assert ownctl.json("object", "list") == []


def test_oracle_corrections_are_stored_and_explain_later_decisions(ownctl: Ownctl) -> None:
    ownctl.json("run", "trashAll", "--kinematic", "--seed", "1")
    texts = {r["text"] for r in ownctl.json("rules", "list")}
    assert "forbid trash if ownedBy any" in texts
    assert any(e["payload"].get("op") == "run.step" for e in ownctl.json("log"))
    assert ownctl.json("perms", "list")


@pytest.mark.slow
def test_learning_persists_across_layouts(tmp_path: Path) -> None:
    """A second layout of the same kind of world, keeping what was learned, costs fewer mistakes."""
    first, second = [], []
    for seed in range(4):
        store = Ownctl(tmp_path / f"s{seed}.db")
        store("init")
        first.append(store.json("run", "trashAll", "--kinematic", "--seed", str(seed))["mistakes"])
        later = store.json("run", "trashAll", "--kinematic", "--layout-seed", str(100 + seed))
        assert later["loaded_world"] is True
        second.append(later["mistakes"])
    assert sum(second) < sum(first), (first, second)


def test_bad_options_are_refused_before_anything_is_written(ownctl: Ownctl) -> None:
    before = ownctl.digest()
    assert "trashall" in ownctl("run", "cleanAll", code=1).stderr.lower()
    ownctl("run", "trashAll", "--render", "x.gif", code=1)
    ownctl("run", "trashAll", "--instructor", "teacher", code=1)
    assert "valid: auto, left, right" in ownctl("run", "trashAll", "--arm", "middle", code=1).stderr
    ownctl("run", "trashAll", "--grasp", "glue", "--kinematic", code=1)
    for option in ("--seed", "--layout-seed"):
        said = ownctl("run", "trashAll", "--kinematic", f"{option}=-1", code=1).stderr
        assert f"{option} must be a non-negative integer, got -1" in said
    assert ownctl("run", "cleanAll", code=1).stdout == ""  # nothing shown before the error
    assert ownctl.digest() == before


@pytest.mark.slow
def test_physics_trash_leaves_the_forbidden_block_in_place(tmp_path: Path, ownctl: Ownctl) -> None:
    world = tmp_path / "three.toml"
    world.write_text(SMALL_WORLD)
    ownctl("world", "load", str(world))
    ownctl("forbid", "trash", "if", "ownedBy", "any")
    ownctl("claim", "wallet", "alexis")
    for name in ("cup", "can"):
        for agent in ("alexis", "xuan"):
            ownctl("claim", name, agent, "--not")
    before = {o["name"]: o for o in ownctl.json("object", "list")}
    report = ownctl.json("run", "trashAll", "--instructor", "none", "--render", str(tmp_path / "end.png"))
    after = {o["name"]: o for o in ownctl.json("object", "list")}
    assert sorted(report["delivered"]) == ["can", "cup"] and report["violations"] == []
    assert report["sim_seconds"] > 0
    moved = math.dist(before["wallet"]["position"], after["wallet"]["position"])
    assert moved < 0.01
    for name in ("can", "cup"):
        x, y, _ = after[name]["position"]
        assert -0.3 <= x <= 0.2 and 0.6 <= y <= 1.1
    assert (tmp_path / "end.png").stat().st_size > 1000


PILE = """
name = "pile"
agents = ["ana"]
norms = []

[[areas]]
name = "trash"
box = [-0.3, 0.6, 0.2, 1.1]

[[areas]]
name = "saucer"
box = [0.30, 0.30, 0.34, 0.34]
""" + "".join(f"""
[[objects]]
name = "{name}"
color = "red"
position = [0.32, 0.32, 0.0]
""" for name in ("bottom", "middle", "top"))


@pytest.mark.slow
def test_physics_takes_a_pile_down_from_the_top(tmp_path: Path, ownctl: Ownctl) -> None:
    """Three blocks in an area with room for one are piled (sim/layout.py); trashAll tries the
    lower ones again once the blocks on them are gone, and the run succeeds."""
    path = tmp_path / "pile.toml"
    path.write_text(PILE, encoding="utf-8")
    ownctl("world", "load", str(path))
    report = ownctl.json("run", "trashAll")
    assert report["failed_steps"] == [] and sorted(report["delivered"]) == ["bottom", "middle", "top"]
    reasons = {s["object"]: s["reason"] for s in report["steps"]}
    assert reasons == {"bottom": "delivered on a later try", "middle": "delivered on a later try", "top": ""}
    log = [e["payload"] for e in ownctl.json("log", "-n", "10") if e["payload"].get("op") == "run.step"]
    assert [(p["object"], p["outcome"]) for p in log] == [
        ("bottom", "skipped"), ("middle", "skipped"), ("top", "delivered"), ("middle", "delivered"),
        ("bottom", "delivered")]
    assert "middle lies on top of it" in log[0]["reason"]
