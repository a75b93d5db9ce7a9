"""Scripted trash and collect: delivery into the areas, untouched neighbours, failures reported."""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.errors import BadValue, DuplicateName, UnknownName
from sim.robot import PARK
from sim.world import PhysicsWorld, SimArea, SimBlock, StepOutcome

AREAS = [SimArea("trash", (-0.3, 0.6, 0.2, 1.1)), SimArea("home", (-0.1, -0.1, 0.1, 0.1))]


def _world(**kwargs: object) -> PhysicsWorld:
    blocks = [
        SimBlock("red1", "red", (0.5, -0.6, 0.0)),
        SimBlock("green1", "green", (0.35, 0.45, 0.0)),
        SimBlock("blue1", "blue", (-0.7, -0.3, 0.0)),
        SimBlock("near1", None, (0.62, -0.48, 0.0)),  # a close neighbour of red1
        SimBlock("home1", None, (0.02, 0.03, 0.0)),
    ]
    return PhysicsWorld(blocks, AREAS, **kwargs)  # type: ignore[arg-type]


def _moved(world: PhysicsWorld, before: dict[str, tuple[float, float, float]], skip: str) -> float:
    """Largest world displacement (m) of any block other than ``skip`` since ``before`` (world positions)."""
    return max(np.linalg.norm(np.subtract(world.world_position(n), before[n])) for n in before if n != skip)


def _where(world: PhysicsWorld) -> dict[str, tuple[float, float, float]]:
    return {n: world.world_position(n) for n in world.names}


def test_trash_puts_the_block_in_the_bin_and_leaves_the_others() -> None:
    world = _world()
    before = _where(world)
    outcome = world.trash("red1")
    assert outcome == StepOutcome(True, "trash", "red1", None, outcome.sim_seconds)
    assert outcome.sim_seconds > 1.0 and world.sim_time == pytest.approx(outcome.sim_seconds)
    assert AREAS[0].contains(world.position("red1"))
    assert _moved(world, before, "red1") < 0.01


def test_collect_puts_the_block_down_inside_home() -> None:
    world = _world()
    before = _where(world)
    outcome = world.collect("blue1")
    assert outcome.ok, outcome.error
    assert AREAS[1].contains(world.position("blue1"))
    assert world.position("blue1")[2] < 0.2  # put down on the home grid, not left hanging
    assert _moved(world, before, "blue1") < 0.01


@pytest.mark.slow
def test_forced_arm_and_friction_grasp_also_deliver() -> None:
    world = _world(arm="left", grasp="friction")  # green1 and red1 lie on the left half
    assert world.trash("green1").ok
    assert world.collect("red1").ok
    assert AREAS[0].contains(world.position("green1")) and AREAS[1].contains(world.position("red1"))
    assert world.robot.held == {"left": None, "right": None}


def test_same_seed_gives_the_same_final_positions() -> None:
    finals = []
    for _ in range(2):
        world = _world(seed=7)
        world.trash("green1")
        world.collect("blue1")
        finals.append(world.positions())
    assert finals[0] == finals[1]


def test_physics_instability_fails_the_step_and_restores_the_state() -> None:
    world = _world()
    before, t0 = world.positions(), world.sim_time
    steps = {"n": 0}

    def blow_up(data: object) -> None:
        steps["n"] += 1
        if steps["n"] == 200:
            data.qvel[:] = 1e20  # type: ignore[attr-defined]

    world.robot.frame_hook = blow_up
    outcome = world.trash("red1")
    assert not outcome.ok and "unstable" in (outcome.error or "")
    assert world.positions() == before and world.sim_time == t0
    world.robot.frame_hook = None
    assert world.trash("red1").ok  # the world is still usable


def test_unknown_object_is_an_error_naming_the_known_ones() -> None:
    with pytest.raises(UnknownName, match="known objects: blue1, green1, home1, near1, red1"):
        _world().trash("thrash")


def test_bad_settings_are_errors_listing_the_valid_values() -> None:
    with pytest.raises(BadValue, match="known arms: auto, left, right"):
        _world(arm="middle")
    with pytest.raises(BadValue, match="known grasps: weld, friction"):
        _world(grasp="suction")
    with pytest.raises(DuplicateName, match="repeated: a"):
        PhysicsWorld([SimBlock("a", None, None), SimBlock("a", None, None)], AREAS)


def test_out_of_reach_forced_arm_fails_without_moving_anything() -> None:
    world = PhysicsWorld([SimBlock("far", None, (1.05, -1.05, 0.0))], AREAS, arm="right")  # far left
    before = _where(world)
    outcome = world.trash("far")
    assert not outcome.ok and "reach" in (outcome.error or "")
    assert _moved(world, before, "") < 0.001


def test_a_block_with_something_on_top_is_not_grasped() -> None:
    crowded = [SimBlock(f"h{i}", None, (0.0, 0.0, 0.0)) for i in range(40)]  # more than fit side by side
    world = PhysicsWorld(crowded, AREAS)
    where = _where(world)
    bottom = next(
        n for n in world.names
        if any(m != n and np.max(np.abs(np.subtract(where[m], where[n])[:2])) < 1e-6
               and where[m][2] > where[n][2] for m in world.names)
    )
    outcome = world.trash(bottom)
    assert not outcome.ok and "grasp" in (outcome.error or "")
    assert _moved(world, where, "") < 0.003  # nothing pushed over (the four-high towers settle a little)


def test_stop_short_reaches_for_the_block_and_goes_back_without_touching_it() -> None:
    world = _world()
    before = _where(world)
    closest = {"d": np.inf}
    side = "left" if before["red1"][1] >= 0 else "right"  # the nearer arm reaches
    site = world.robot.ik[side].site

    def watch(data: object) -> None:
        grip = world.data.site_xpos[site]
        closest["d"] = min(closest["d"], float(np.linalg.norm(grip - np.array(before["red1"]))))

    world.robot.frame_hook = watch
    outcome = world.stop_short("red1")
    assert outcome.ok and outcome.action == "stopShort", outcome
    assert closest["d"] < 0.1  # the hand came down close over the block
    assert _moved(world, before, "") < 0.001  # and left every block where it was
    assert np.linalg.norm(world.robot.grip_pos(side) - np.array(PARK[side])) < 0.01  # back at rest
