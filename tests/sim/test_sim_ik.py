"""Damped-least-squares IK reaches the reachable table region, top-down, within 2 mm."""

from __future__ import annotations

import numpy as np
import pytest

from sim import scene_config as cfg
from sim.ik import Q_NOMINAL, YAW_CENTER, ArmIK, down_rotation
from sim.skills import HOVER
from sim.workspace import WORKSPACE_HALF, SimBlock
from sim.world import PhysicsWorld


@pytest.fixture(scope="module")
def world() -> PhysicsWorld:
    return PhysicsWorld([SimBlock("a", None, (0.0, 0.5, 0.0))], [])


def test_ik_reaches_sampled_targets_within_2mm(world: PhysicsWorld) -> None:
    rng = np.random.default_rng(0)
    x0, y0, x1, y1 = world.map.box_to_world(
        (-WORKSPACE_HALF, -WORKSPACE_HALF, WORKSPACE_HALF, WORKSPACE_HALF)
    )
    iks = {side: ArmIK(world.model, side) for side in ("left", "right")}
    for _ in range(60):
        x, y = rng.uniform([x0, y0], [x1, y1])
        z = rng.choice([cfg.REST_Z, HOVER])
        side = "left" if y >= 0 else "right"
        yaw = YAW_CENTER[side] + rng.uniform(-np.pi / 2, np.pi / 2)  # every grasp has such a yaw
        target = np.array([x, y, z])
        res = iks[side].solve(target, down_rotation(yaw), Q_NOMINAL, iters=200)
        pos, rot = iks[side].forward(res.q)
        assert res.ok, (side, target, yaw, res)
        assert np.linalg.norm(pos - target) < 0.002
        assert rot[:, 2] @ np.array([0.0, 0.0, -1.0]) > np.cos(0.02)  # the hand points down
        assert np.all(res.q >= iks[side].lower - 1e-9) and np.all(res.q <= iks[side].upper + 1e-9)


def test_ik_reports_failure_for_a_target_out_of_reach(world: PhysicsWorld) -> None:
    res = ArmIK(world.model, "left").solve(np.array([1.6, 0.0, cfg.REST_Z]), down_rotation(0.0), Q_NOMINAL)
    assert not res.ok and res.pos_error > 0.1


def test_ik_leaves_the_simulation_untouched(world: PhysicsWorld) -> None:
    before = world.data.qpos.copy()
    ArmIK(world.model, "right").solve(np.array([0.6, -0.1, HOVER]), down_rotation(0.3), Q_NOMINAL)
    np.testing.assert_array_equal(world.data.qpos, before)
