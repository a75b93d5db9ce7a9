"""Where things land in a camera's picture, from the model alone (no rendering, no OpenGL).

MuJoCo cameras look along their frame's -z axis with x to the right and y up; a fixed camera's pose
is ``data.cam_xpos`` / ``data.cam_xmat`` after forward kinematics and its vertical field of view is
``model.cam_fovy``. :func:`project` applies that pinhole model, so tests and tools can check what a
frame shows without drawing it.
"""

from __future__ import annotations

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

Vec = NDArray[np.float64]


def project(model: mujoco.MjModel, data: mujoco.MjData, camera: str, points: ArrayLike,
            width: int, height: int) -> Vec:
    """Pixel coordinates (n, 2) (column from the left, row from the top) of world ``points`` (n, 3)
    seen by ``camera`` in a ``width`` x ``height`` picture; points behind the camera give NaN."""
    cam = model.camera(camera).id
    pos, rot = data.cam_xpos[cam], data.cam_xmat[cam].reshape(3, 3)
    local = (np.asarray(points, dtype=float).reshape(-1, 3) - pos) @ rot  # camera frame: x right, y up
    depth = -local[:, 2]
    focal = (height / 2) / np.tan(np.radians(model.cam_fovy[cam]) / 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = width / 2 + focal * local[:, 0] / depth
        v = height / 2 - focal * local[:, 1] / depth
    out = np.column_stack([u, v])
    out[depth <= 0] = np.nan
    return out


def geom_corners(model: mujoco.MjModel, data: mujoco.MjData, geom: int | str) -> Vec:
    """The 8 corners (8, 3) of the box around geom ``geom`` (a box's own corners; a cylinder's or
    capsule's bounding box in its frame), in world coordinates."""
    g = model.geom(geom).id
    size = model.geom_size[g]
    kind = model.geom_type[g]
    if kind == mujoco.mjtGeom.mjGEOM_BOX:
        half = size
    elif kind in (mujoco.mjtGeom.mjGEOM_CYLINDER, mujoco.mjtGeom.mjGEOM_CAPSULE):
        cap = size[0] if kind == mujoco.mjtGeom.mjGEOM_CAPSULE else 0.0
        half = np.array([size[0], size[0], size[1] + cap])
    else:
        half = np.full(3, model.geom_rbound[g])
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    return data.geom_xpos[g] + (signs * half) @ data.geom_xmat[g].reshape(3, 3).T
