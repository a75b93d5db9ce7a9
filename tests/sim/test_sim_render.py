"""Headless rendering: a PNG of the scene and an MP4 of an action (skipped only without OpenGL)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from sim.world import PhysicsWorld, SimBlock

pytestmark = pytest.mark.usefixtures("rendering")  # skipped, with the reason, where nothing can draw


def _render(world: PhysicsWorld, path: Path, camera: str = "top") -> np.ndarray:
    world.render_png(path, camera=camera)
    return np.asarray(Image.open(path).convert("RGB")).astype(int)


def _red_pixels(img: np.ndarray) -> int:
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return int(np.sum((r > 150) & (g < 90) & (b < 90)))


@pytest.mark.slow
def test_png_shows_the_scene_with_its_coloured_blocks(tmp_path: Path) -> None:
    red = _render(PhysicsWorld([SimBlock("a", "red", (0.3, -0.3, 0.0))], []), tmp_path / "red.png")
    blue = _render(PhysicsWorld([SimBlock("a", "blue", (0.3, -0.3, 0.0))], []), tmp_path / "blue.png")
    assert red.shape == (480, 640, 3)
    assert red.std() > 10  # not a blank frame
    assert _red_pixels(red) > 20 and _red_pixels(blue) == 0


@pytest.mark.slow
def test_video_of_an_action_is_written(tmp_path: Path) -> None:
    import imageio.v2 as imageio

    world = PhysicsWorld([SimBlock("a", "green", (0.3, 0.3, 0.0))], [], render=str(tmp_path / "run.mp4"))
    _render(world, tmp_path / "probe.png")
    world.recorder.fps = 10  # fewer frames keep the test quick
    assert world.trash("a").ok
    out = world.finish_video()
    assert out == tmp_path / "run.mp4" and out.stat().st_size > 10_000
    with imageio.get_reader(out) as reader:
        assert reader.count_frames() >= int(world.sim_time * 10) - 2
