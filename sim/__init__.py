"""Headless MuJoCo Baxter simulation: model, IK, scripted skills, task execution.

Importing ``sim`` picks a headless OpenGL backend for MuJoCo's renderer when none was chosen:
``MUJOCO_GL=osmesa`` if the OSMesa library (Debian ``libosmesa6``) is installed and no display is
set. MuJoCo reads ``MUJOCO_GL`` when it is first imported, so this must happen before that import.
"""

from __future__ import annotations

import ctypes.util
import os
import sys


def _default_headless_gl() -> None:
    """Set ``MUJOCO_GL=osmesa`` if unset, on Linux without a display, when libOSMesa can be found."""
    if "MUJOCO_GL" in os.environ or "mujoco" in sys.modules or not sys.platform.startswith("linux"):
        return
    if os.environ.get("DISPLAY") or os.environ.get("PYOPENGL_PLATFORM") not in (None, "osmesa"):
        return
    if ctypes.util.find_library("OSMesa"):
        os.environ["MUJOCO_GL"] = "osmesa"


_default_headless_gl()
