"""The generated scene: Baxter's joints and limits, fast compilation, blocks at rest, the layout."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from sim import baxter
from sim import scene_config as cfg
from sim.layout import ROOM, SPACING, home_slots, map_for, place_blocks
from sim.workspace import DEFAULT_TRASH, SimArea, SimBlock, with_default_areas
from sim.world import PhysicsWorld

REAL_LIMITS = {  # Rethink Robotics' published joint limits (rad), both arms
    "s0": (-1.70168, 1.70168),
    "s1": (-2.147, 1.047),
    "e0": (-3.05418, 3.05418),
    "e1": (-0.05, 2.618),
    "w0": (-3.059, 3.059),
    "w1": (-1.5708, 2.094),
    "w2": (-3.059, 3.059),
}


def _blocks(n: int = 6) -> list[SimBlock]:
    rng = np.random.default_rng(3)
    return [
        SimBlock(f"b{i}", "red", (float(x), float(y), 0.0))
        for i, (x, y) in enumerate(rng.uniform(-1, 1, (n, 2)))
    ]


def test_a_scene_of_twenty_blocks_compiles() -> None:
    """(Its build time is measured by ``benchmarks/sim_tasks.py``, not asserted here.)"""
    world = PhysicsWorld(_blocks(20), [])
    assert world.model.nbody > 20


def test_both_arms_have_the_real_joint_names_and_limits() -> None:
    model = PhysicsWorld(_blocks(1), []).model
    for side in ("left", "right"):
        for joint, (lo, hi) in REAL_LIMITS.items():
            j = model.joint(f"{side}_{joint}")
            assert j.range.tolist() == pytest.approx([lo, hi])
        for finger in "lr":
            assert model.joint(baxter.finger_joint(side, finger)).type == mujoco.mjtJoint.mjJNT_SLIDE
    assert model.nu == 18  # 14 arm servos and 4 finger servos


def test_blocks_rest_stably_for_two_seconds() -> None:
    world = PhysicsWorld(_blocks(20), [])
    start = {n: world.world_position(n) for n in world.names}
    world.robot.wait(2.0)
    moved = max(np.linalg.norm(np.subtract(world.world_position(n), start[n])) for n in start)
    assert moved < 0.001
    assert world.sim_time == pytest.approx(2.0, abs=0.02)


def test_unknown_colours_render_grey_and_known_ones_do_not() -> None:
    world = PhysicsWorld(
        [
            SimBlock("a", "chartreuse", (0, 0.5, 0)),
            SimBlock("b", None, (0.5, 0, 0)),
            SimBlock("c", "red", (-0.5, 0, 0)),
        ],
        [],
    )
    rgba = [world.model.geom(f"block{i}_geom").rgba[:3].tolist() for i in range(3)]
    assert rgba[0] == pytest.approx(list(cfg.GREY)) and rgba[1] == pytest.approx(list(cfg.GREY))
    assert rgba[2] == pytest.approx(list(cfg.COLORS["red"]))


def test_blocks_without_position_get_a_free_spot_outside_the_areas() -> None:
    blocks = [SimBlock(f"n{i}", None, None) for i in range(8)]
    world = PhysicsWorld(blocks, [], seed=5)
    pos = world.positions()
    assert all(not world.in_area(n, "home") and not world.in_area(n, "trash") for n in pos)
    assert all(abs(p[0]) <= 1.1 and abs(p[1]) <= 1.1 for p in pos.values())


def test_layout_keeps_blocks_apart_and_in_the_same_areas() -> None:
    areas = with_default_areas([])
    rng = np.random.default_rng(0)
    raw = [(float(x), float(y), 0.0) for x, y in rng.normal(0, 0.15, (12, 2))]  # crowded around home
    raw += [
        (0.0, 0.85, 0.0),
        (-0.28, 0.62, 0.0),
        (0.25, 0.85, 0.0),
    ]  # in, at the edge of, beside the trash area
    blocks = [SimBlock(f"b{i}", None, p) for i, p in enumerate(raw)]
    wmap = map_for(areas, blocks)
    placed = place_blocks(blocks, areas, wmap, rng)
    xyz = np.array([p.position for p in placed])
    cheb = np.max(np.abs(xyz[:, None] - xyz[None]), axis=2) + np.eye(len(xyz))
    assert cheb.min() >= 2 * cfg.BLOCK_HALF - 1e-9  # nobody overlaps (crowded home blocks stack)
    assert np.mean(cheb.min(axis=1) >= SPACING - 1e-9) > 0.5
    for block, p in zip(blocks, placed, strict=True):
        back = wmap.to_workspace(p.position)
        for area in areas.values():
            assert area.contains(block.position) == area.contains(back), (block, area.name)


def test_home_blocks_sit_on_the_home_grid() -> None:
    world = PhysicsWorld([SimBlock("a", None, (0.01, 0.02, 0)), SimBlock("b", None, (0.05, -0.05, 0))], [])
    cells = home_slots(world.home_box)
    assert len(cells) >= ROOM["home"][0] * ROOM["home"][1]
    for name in ("a", "b"):
        x, y, _ = world.world_position(name)
        assert min(np.hypot(x - cx, y - cy) for cx, cy in cells) < 1e-3


def test_bin_occupies_the_mapped_trash_area() -> None:
    world = PhysicsWorld(_blocks(2), [SimArea("trash", DEFAULT_TRASH)])
    x0, y0, x1, y1 = world.trash_box
    walls = [world.model.geom(f"bin_wall_{s}") for s in ("px", "nx", "py", "ny")]
    body = world.data.xpos[world.model.body("trash_bin").id]
    xs = [body[0] + w.pos[0] + sgn * w.size[0] for w in walls for sgn in (-1, 1)]
    ys = [body[1] + w.pos[1] + sgn * w.size[1] for w in walls for sgn in (-1, 1)]
    assert min(xs) == pytest.approx(x0, abs=1e-5) and max(xs) == pytest.approx(x1, abs=1e-5)
    assert min(ys) == pytest.approx(y0, abs=1e-5) and max(ys) == pytest.approx(y1, abs=1e-5)
