"""Headless MuJoCo Baxter simulation: model, IK, scripted skills, task execution.

Importing ``sim`` chooses MuJoCo's OpenGL backend for rendering when none was chosen (see
:mod:`sim.gl`): MuJoCo reads ``MUJOCO_GL`` when it is first imported, so this happens first.
"""

from __future__ import annotations

from sim.gl import preselect

preselect()
