"""Offscreen rendering: single PNG frames and frames captured while acting, written as MP4 or GIF.

Rendering needs an OpenGL backend; :mod:`sim.gl` picks one (EGL, then OSMesa on a headless machine)
and checks that it draws before a recorder with a target is made, so a run that cannot render fails
before it starts, with one line naming the package to install. The renderer itself is created on
first use, so a world that never renders never touches OpenGL.
"""

from __future__ import annotations

import atexit
import weakref
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import mujoco
import numpy as np
from numpy.typing import NDArray

from sim.errors import RenderUnavailable
from sim.gl import ensure_rendering
from sim.scene import DEFAULT_CAMERA

__all__ = ["FPS", "HEIGHT", "WIDTH", "Recorder", "RenderUnavailable"]

VIDEO_SUFFIXES = (".mp4", ".gif")
WIDTH, HEIGHT, FPS = 640, 480, 25


_LIVE: weakref.WeakSet[Recorder] = weakref.WeakSet()


@atexit.register
def _close_all() -> None:
    """Free GL contexts before interpreter shutdown tears down the OpenGL bindings they need."""
    for recorder in list(_LIVE):
        recorder.close()


@dataclass(eq=False)
class Recorder:
    """Renders frames of one model; captures video frames from ``camera`` every ``1 / fps`` s of sim time
    when ``video``."""

    model: mujoco.MjModel
    target: Path | None = None
    video: bool = False
    camera: str = DEFAULT_CAMERA
    fps: int = FPS
    frames: list[NDArray[np.uint8]] = field(default_factory=list)
    _renderer: mujoco.Renderer | None = None
    _next: float = 0.0

    @classmethod
    def for_target(cls, model: mujoco.MjModel, render: str | None, camera: str = DEFAULT_CAMERA) -> Recorder:
        """A recorder for ``render``: None (no frames), a PNG path, or an MP4/GIF path (frames kept).

        With a target, raises :class:`RenderUnavailable` at once if no OpenGL backend can draw here.
        """
        if render is None:
            return cls(model, camera=camera)
        ensure_rendering()
        target = Path(render)
        return cls(model, target, video=target.suffix.lower() in VIDEO_SUFFIXES, camera=camera)

    def _frame(self, data: mujoco.MjData, camera: str) -> NDArray[np.uint8]:
        """One RGB frame (HEIGHT, WIDTH, 3) of ``data`` seen from ``camera``."""
        if self._renderer is None:
            ensure_rendering()
            try:
                self._renderer = mujoco.Renderer(self.model, height=HEIGHT, width=WIDTH)
            except Exception as exc:  # the GL backends raise ImportError, RuntimeError or OSError
                first = (str(exc).splitlines() or [type(exc).__name__])[0]
                raise RenderUnavailable(f"cannot create an OpenGL context for rendering: {first}") from exc
            _LIVE.add(self)
        self._renderer.update_scene(data, camera=camera)
        return self._renderer.render().copy()

    def hook(self, data: mujoco.MjData) -> None:
        """Per-step callback: keep a frame whenever another ``1 / fps`` s of sim time has passed."""
        if data.time + 1e-9 >= self._next:
            self.frames.append(self._frame(data, self.camera))
            self._next = data.time + 1.0 / self.fps

    def png(self, data: mujoco.MjData, path: Path, camera: str) -> Path:
        """Render ``data`` from ``camera`` and save it as a PNG at ``path``."""
        from PIL import Image

        path.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(self._frame(data, camera)).save(path)
        return path

    def write_video(self, path: Path | None, data: mujoco.MjData | None = None) -> Path:
        """Write the captured frames to ``path`` (or the render target) as MP4 (H.264) or GIF.

        With nothing captured (no action was performed), the video holds one frame of ``data``.
        """
        import imageio.v2 as imageio

        out = path or self.target
        if out is None or out.suffix.lower() not in VIDEO_SUFFIXES:
            raise ValueError(f"a video needs an .mp4 or .gif path, got {out}")
        if not self.frames and data is not None:
            self.frames.append(self._frame(data, self.camera))
        if not self.frames:
            raise ValueError("no frames were captured: create the world with render='FILE.mp4' and act first")
        out.parent.mkdir(parents=True, exist_ok=True)
        if out.suffix.lower() == ".mp4":
            imageio.mimwrite(
                out, list[Any](self.frames), fps=self.fps, codec="libx264", quality=7, macro_block_size=8
            )
        else:
            imageio.mimwrite(out, list[Any](self.frames), duration=1000 / self.fps, loop=0)
        return out

    def close(self) -> None:
        """Release the OpenGL context, if one was made."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
