"""The MJCF of the whole scene: Baxter, table, blocks, trash bin, home mat, grasp welds, servos.

The model is generated as a string and compiles in milliseconds. Physics settings follow the
measured sketch: 2 ms implicit-fast steps, elliptic friction cones, resting bodies allowed to sleep,
and no automatic reset on numerical trouble (the caller detects it and fails the step instead).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.errors import BadValue
from sim import baxter
from sim import scene_config as cfg


@dataclass(frozen=True)
class BlockSpec:
    """A block body to generate: body name, colour name, world centre (3,)."""

    body: str
    color: str | None
    position: tuple[float, float, float]


def block_body(index: int) -> str:
    """MJCF body name of the ``index``-th block (store names may contain characters MJCF dislikes)."""
    return f"block{index}"


def weld_name(side: str, index: int) -> str:
    """Name of the (initially inactive) weld that holds block ``index`` in ``side``'s hand."""
    return f"grasp_{side}_{index}"


def _camera(
    name: str, pos: tuple[float, float, float], target: tuple[float, float, float], fovy: float
) -> str:
    """A camera at ``pos`` looking at ``target`` with the world's z axis up in the image."""
    forward = np.subtract(target, pos) / np.linalg.norm(np.subtract(target, pos))
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    axes = " ".join(f"{v:.4f}" for v in (*right, *up))
    return f'<camera name="{name}" pos="{pos[0]} {pos[1]} {pos[2]}" xyaxes="{axes}" fovy="{fovy}"/>'


# name -> (position, point looked at, vertical field of view in degrees)
CAMERAS: dict[str, tuple[tuple[float, float, float], tuple[float, float, float], float]] = {
    # the default view: in front of the table, off to the robot's left, framed on the whole robot,
    # the table and the bin (tests/sim/test_sim_camera.py checks it)
    "front": ((2.2, -0.8, 1.6), (0.4, 0.05, 1.2), 36.0),
    # over the robot's left shoulder, looking down at the table as the robot sees it
    "shoulder": ((0.0, 0.75, 1.95), (0.62, -0.12, cfg.TABLE_TOP), 50.0),
}
DEFAULT_CAMERA = "front"
CAMERA_NAMES = (*CAMERAS, "top")


def check_camera(name: str) -> None:
    """Refuse an unknown camera name, listing the known ones."""
    if name not in CAMERA_NAMES:
        raise BadValue(f"unknown camera {name!r}; known cameras: {', '.join(CAMERA_NAMES)}", CAMERA_NAMES)


def _cameras() -> str:
    """The named views (:data:`CAMERAS`) and a top view of the table strip."""
    top = cfg.TABLE_TOP + 1.15
    cx = (cfg.REACH[0] + cfg.REACH[2]) / 2
    return "\n".join(
        [_camera(name, pos, target, fovy) for name, (pos, target, fovy) in CAMERAS.items()]
        + [f'<camera name="top" pos="{cx} 0 {top}" xyaxes="0 -1 0 1 0 0" fovy="36"/>']
    )


def _block(spec: BlockSpec) -> str:
    x, y, z = spec.position
    h = cfg.BLOCK_HALF
    return (
        f'<body name="{spec.body}" pos="{x:.5f} {y:.5f} {z:.5f}"><freejoint name="{spec.body}_free"/>'
        f'<geom name="{spec.body}_geom" type="box" size="{h} {h} {h}" mass="{cfg.BLOCK_MASS}" '
        f'rgba="{cfg.rgba(spec.color)}" class="block"/></body>'
    )


def _bin(box: tuple[float, float, float, float]) -> str:
    """Open-top bin whose outer faces are ``box`` (world x0, y0, x1, y1): floor and four walls."""
    x0, y0, x1, y1 = box
    cx, cy, hx, hy = (x0 + x1) / 2, (y0 + y1) / 2, (x1 - x0) / 2, (y1 - y0) / 2
    w, hz, f = cfg.BIN_WALL / 2, cfg.BIN_HEIGHT / 2, cfg.BIN_FLOOR / 2
    color = 'rgba="0.25 0.25 0.28 1"'
    return f"""
    <body name="trash_bin" pos="{cx:.5f} {cy:.5f} {cfg.TABLE_TOP}">
      <geom name="bin_floor" type="box" size="{hx} {hy} {f}" pos="0 0 {f}" {color}/>
      <geom name="bin_wall_px" type="box" size="{w} {hy} {hz}" pos="{hx - w} 0 {hz}" {color}/>
      <geom name="bin_wall_nx" type="box" size="{w} {hy} {hz}" pos="{-hx + w} 0 {hz}" {color}/>
      <geom name="bin_wall_py" type="box" size="{hx - 2 * w} {w} {hz}" pos="0 {hy - w} {hz}" {color}/>
      <geom name="bin_wall_ny" type="box" size="{hx - 2 * w} {w} {hz}" pos="0 {-hy + w} {hz}" {color}/>
    </body>"""


def _home(box: tuple[float, float, float, float]) -> str:
    """A thin, collision-free mat drawn over the home area."""
    x0, y0, x1, y1 = box
    cx, cy, hx, hy = (x0 + x1) / 2, (y0 + y1) / 2, (x1 - x0) / 2, (y1 - y0) / 2
    z = cfg.TABLE_TOP + cfg.HOME_MAT / 2
    return (
        f'<geom name="home_mat" type="box" size="{hx} {hy} {cfg.HOME_MAT / 2}" pos="{cx:.5f} {cy:.5f} {z}" '
        'rgba="0.95 0.9 0.55 1" contype="0" conaffinity="0"/>'
    )


def _welds(n_blocks: int) -> str:
    return "\n".join(
        f'<weld name="{weld_name(side, i)}" body1="{side}_hand" body2="{block_body(i)}" active="false" '
        'relpose="0 0 0.1 1 0 0 0" solref="0.004 1"/>'
        for side in baxter.SIDES
        for i in range(n_blocks)
    )


def scene_xml(
    blocks: Sequence[BlockSpec],
    trash_box: tuple[float, float, float, float],
    home_box: tuple[float, float, float, float],
) -> str:
    """Complete MJCF: robot, table, ``blocks``, the bin on ``trash_box`` and the mat on ``home_box``."""
    tx, ty = cfg.TABLE_CENTER
    hx, hy = cfg.TABLE_HALF
    leg = (cfg.TABLE_TOP - 0.04) / 2
    return f"""<mujoco model="ownctl_baxter_table">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="{cfg.TIMESTEP}" integrator="implicitfast" cone="elliptic" impratio="10">
    <flag sleep="enable" autoreset="disable"/>
  </option>
  <visual>
    <global offwidth="1280" offheight="960"/>
    <headlight ambient="0.3 0.3 0.3" diffuse="0.4 0.4 0.4" specular="0.1 0.1 0.1"/>
    <quality shadowsize="2048"/>
  </visual>
  <asset>
    <texture name="sky" type="skybox" builtin="gradient" rgb1="0.62 0.66 0.72" rgb2="0.2 0.21 0.24"
             width="256" height="256"/>
    <texture name="grid" type="2d" builtin="checker" rgb1="0.75 0.75 0.78" rgb2="0.65 0.65 0.68"
             width="256" height="256"/>
    <material name="floor" texture="grid" texrepeat="8 8"/>
  </asset>
  <default>
    <default class="robot"><geom contype="2" conaffinity="1" group="1"/></default>
    <default class="visual"><geom contype="0" conaffinity="0" group="2" mass="0"/></default>
    <default class="finger">
      <geom contype="1" conaffinity="1" condim="4" friction="1.5 0.02 0.001" solref="0.005 1"
            solimp="0.95 0.99 0.001" rgba="0.3 0.3 0.3 1"/>
    </default>
    <default class="block"><geom contype="1" conaffinity="1" condim="4" friction="1 0.01 0.001"/></default>
  </default>
  <worldbody>
    <light name="sun" pos="0.6 0 3" dir="0 0 -1" diffuse="0.45 0.45 0.45" specular="0.1 0.1 0.1"
           castshadow="false"/>
    <geom name="floor" type="plane" size="3 3 0.05" material="floor"/>
    {_cameras()}
    {baxter.robot_xml()}
    <body name="table" pos="{tx} {ty} 0">
      <geom name="table_top" type="box" size="{hx} {hy} 0.02" pos="0 0 {cfg.TABLE_TOP - 0.02}"
            rgba="0.62 0.45 0.3 1"/>
      <geom name="table_leg" type="box" size="{hx - 0.08} {hy - 0.08} {leg}" pos="0 0 {leg}"
            rgba="0.45 0.32 0.2 1" contype="0" conaffinity="0"/>
    </body>
    {_home(home_box)}
    {_bin(trash_box)}
    {chr(10).join(_block(b) for b in blocks)}
  </worldbody>
  <contact>
    <exclude body1="right_hand" body2="right_wrist"/>
    <exclude body1="left_hand" body2="left_wrist"/>
  </contact>
  <equality>
    {_welds(len(blocks))}
  </equality>
  <actuator>
    {baxter.actuators_xml()}
  </actuator>
</mujoco>
"""
