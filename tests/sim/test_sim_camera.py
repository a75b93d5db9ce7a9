"""What the cameras show, from the model alone: the default view frames the whole Baxter (head with
its face screen, both arms), the table and the bin at 640 x 480, with every block over 20 pixels wide;
the second camera looks over the robot's shoulder."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sim import baxter
from sim import scene_config as cfg
from sim.camera import geom_corners, project
from sim.render import HEIGHT, WIDTH
from sim.scene import CAMERAS, DEFAULT_CAMERA, block_body
from sim.tasks import paper_blocks
from sim.world import PhysicsWorld

PARTS = {
    "head": ("screen_geom", "screen_display", "eye_l", "eye_r", "head_neck"),
    "table": ("table_top",),
    "bin": ("bin_floor", "bin_wall_px", "bin_wall_nx", "bin_wall_py", "bin_wall_ny"),
}


@pytest.fixture(scope="module")
def world() -> PhysicsWorld:
    return PhysicsWorld(paper_blocks(np.random.default_rng(1)), [], seed=1)  # at rest: arms parked


def _geoms(world: PhysicsWorld, prefix: str) -> list[str]:
    names = [world.model.geom(i).name for i in range(world.model.ngeom)]
    return [n for n in names if n.startswith(prefix)]


def _pixels(world: PhysicsWorld, geoms: list[str], camera: str = DEFAULT_CAMERA) -> np.ndarray:
    corners = np.vstack([geom_corners(world.model, world.data, g) for g in geoms])
    return project(world.model, world.data, camera, corners, WIDTH, HEIGHT)


def _inside_frame(px: np.ndarray) -> bool:
    return bool(np.all(np.isfinite(px)) and np.all((px >= 0) & (px <= [WIDTH, HEIGHT])))


def test_the_default_view_shows_head_arms_table_and_bin(world: PhysicsWorld) -> None:
    arms = {side: _geoms(world, f"{side}_") for side in baxter.SIDES}
    for side, geoms in arms.items():  # every link, joint housing and the gripper of both arms
        for joint in baxter.JOINTS:
            assert f"{side}_{joint}_housing" in geoms
        assert f"{side}_palm" in geoms and f"{side}_finger_l_geom" in geoms
    parts = {**{k: list(v) for k, v in PARTS.items()}, **{f"{s} arm": g for s, g in arms.items()}}
    for part, geoms in parts.items():
        assert _inside_frame(_pixels(world, geoms)), part
    head = _pixels(world, list(PARTS["head"]))
    assert np.ptp(head[:, 0]) > 40  # the face is large enough to see


def test_every_block_is_over_twenty_pixels_wide_in_the_default_view(world: PhysicsWorld) -> None:
    widths = [float(np.ptp(_pixels(world, [f"{block_body(i)}_geom"])[:, 0])) for i in range(len(world.names))]
    assert min(widths) >= 20, widths


def test_the_second_camera_looks_over_the_left_shoulder(world: PhysicsWorld) -> None:
    assert "shoulder" in CAMERAS and "shoulder" != DEFAULT_CAMERA
    cam = world.model.camera("shoulder").id
    pos = world.data.cam_xpos[cam]
    shoulder = world.data.xpos[world.model.body("left_lower_shoulder").id]
    assert pos[0] < shoulder[0] + 0.1 and pos[2] > shoulder[2] and pos[1] > 0  # behind, above, on the left
    x0, y0, x1, y1 = world.trash_box
    looked_at = np.array([[cfg.TABLE_CENTER[0], cfg.TABLE_CENTER[1], cfg.TABLE_TOP],
                          [(x0 + x1) / 2, (y0 + y1) / 2, cfg.TABLE_TOP]])  # the table and the bin, ahead
    for u, v in project(world.model, world.data, "shoulder", looked_at, WIDTH, HEIGHT):
        assert 0.15 * WIDTH < u < 0.85 * WIDTH and 0.15 * HEIGHT < v < 0.85 * HEIGHT


@pytest.mark.slow
def test_the_projection_agrees_with_the_rendered_picture(tmp_path: Path, rendering: str) -> None:
    from sim.world import SimBlock

    alone = PhysicsWorld([SimBlock("probe", "green", (0.6, -0.5, 0.0))], [])
    alone.render_png(tmp_path / "probe.png")
    img = np.asarray(Image.open(tmp_path / "probe.png").convert("RGB")).astype(int)
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    green = (g > 80) & (g > r + 40) & (g > b + 40)  # lit and shaded faces alike
    rows, cols = np.nonzero(green)
    px = _pixels(alone, [f"{block_body(0)}_geom"])
    assert cols.min() >= px[:, 0].min() - 2 and cols.max() <= px[:, 0].max() + 2
    assert rows.min() >= px[:, 1].min() - 2 and rows.max() <= px[:, 1].max() + 2
    assert cols.max() - cols.min() >= 20


def test_run_refuses_an_unknown_camera_naming_the_known_ones() -> None:
    from ownctl.app.run import check_options
    from ownctl.errors import BadValue

    with pytest.raises(BadValue, match="known cameras: front, shoulder, top"):
        check_options("trashAll", "oracle", "auto", "weld", None, "side")
    check_options("trashAll", "oracle", "auto", "weld", None, "shoulder")
