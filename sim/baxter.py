"""MJCF of a Baxter built from primitive geoms: the real kinematic tree, joint names and limits.

Body frames, joint axes, joint ranges and inertials follow Rethink Robotics' published model (as in
MuJoCo Menagerie's ``rethink_robotics_baxter``); the visual and collision geometry is cylinders and
boxes only, so the model compiles in milliseconds. Each arm ends in a two-finger parallel gripper
sized for the small blocks of :mod:`sim.scene`.

The robot's base frame sits at ``(0, 0, BASE_Z)`` in the world, facing +x; the right arm is at -y.
"""

from __future__ import annotations

from dataclasses import dataclass

SIDES: tuple[str, str] = ("left", "right")
JOINTS: tuple[str, ...] = ("s0", "s1", "e0", "e1", "w0", "w1", "w2")
BASE_Z = 0.93  # height of the base frame above the floor (Baxter's pedestal)

# Joint limits (rad), identical for both arms.
JOINT_RANGE: dict[str, tuple[float, float]] = {
    "s0": (-1.70168, 1.70168),
    "s1": (-2.147, 1.047),
    "e0": (-3.05418, 3.05418),
    "e1": (-0.05, 2.618),
    "w0": (-3.059, 3.059),
    "w1": (-1.5708, 2.094),
    "w2": (-3.059, 3.059),
}
# Position-servo stiffness (N m / rad) and torque limit (N m): stiff servos hold the hand within a mm.
KP: dict[str, float] = {"s0": 8000, "s1": 10000, "e0": 5000, "e1": 5000, "w0": 2000, "w1": 2000, "w2": 1000}
TORQUE: dict[str, float] = {"s0": 200, "s1": 400, "e0": 200, "e1": 200, "w0": 60, "w1": 60, "w2": 60}

# Gripper: each finger slides from 0 (closed on the centre line) to FINGER_TRAVEL (inner face offset).
# The hand frame's z axis points out of the wrist (down, when grasping from above).
FINGER_TRAVEL = 0.034
FINGER_THICK = 0.006  # finger thickness along the closing axis (m)
FINGER_WIDTH = 0.012  # finger half-width across the closing axis (m)
FINGER_TOP_Z = 0.03  # fingers hang from this depth below the hand frame
GRIP_SITE_Z = 0.115  # the grip site (IK target) between the fingers
TIP_BELOW_SITE = 0.004  # fingertips reach this far below the grip site
FINGER_HALF_LEN = (GRIP_SITE_Z + TIP_BELOW_SITE - FINGER_TOP_Z) / 2
PALM_HALF = (0.022, 0.048, 0.015)  # palm box half extents in the hand frame (y is the closing axis)


@dataclass(frozen=True)
class Link:
    """One arm link: body name suffix, pose in the parent, its joint, inertial and cylinder segments.

    ``housing`` is the (radius, half height) of the dark joint housing drawn around the link's joint
    axis at the body origin, so that every joint of the arm shows.
    """

    name: str
    pos: str
    quat: str | None
    joint: str
    inertial: tuple[str, str, float, str]  # (pos, quat, mass, diaginertia)
    segments: tuple[tuple[float, float], ...]  # (half height, z offset) of each cylinder
    radius: float = 0.06
    housing: tuple[float, float] = (0.068, 0.05)


# fmt: off
ARM_CHAIN: tuple[Link, ...] = (
    Link("upper_shoulder", "0.055695 0 0.011038", None, "s0",
         ("0.01783 0.00086 0.19127", "0.975667 0.0673303 -0.206117 0.0325173", 5.70044,
          "0.0498344 0.0377511 0.0331351"), ((0.1361, 0.1361),), housing=(0.075, 0.06)),
    Link("lower_shoulder", "0.069 0 0.27035", "0.707107 -0.707107 0 0", "s1",
         ("0.06845 0.00269 -0.00529", "0.447487 0.536948 0.56425 0.439391", 3.22698,
          "0.0278991 0.0212327 0.0112937"), ((0.06, 0.0),), housing=(0.072, 0.075)),
    Link("upper_elbow", "0.102 0 0", "0.5 0.5 0.5 0.5", "e0",
         ("-0.00276 0.00132 0.18086", "0.838995 -0.0423128 -0.121287 0.52876", 4.31272,
          "0.0287695 0.0273625 0.011409"), ((0.0535, -0.0535), (0.1365, 0.1365)), housing=(0.066, 0.035)),
    Link("lower_elbow", "0.069 0 0.26242", "0.5 -0.5 -0.5 -0.5", "e1",
         ("0.02611 0.00159 -0.01117", "0.440433 0.577149 0.562777 0.395221", 2.07206,
          "0.0132096 0.00950002 0.00685697"), ((0.05, 0.0),), housing=(0.066, 0.065)),
    Link("upper_forearm", "0.10359 0 0", "0.5 0.5 0.5 0.5", "w0",
         ("-0.00168 0.0046 0.13952", "0.892709 -0.0256256 0.00446984 0.449882", 2.24665,
          "0.016916 0.0165511 0.00371123"), ((0.044, -0.044), (0.1036, 0.1)), 0.05, (0.056, 0.03)),
    Link("lower_forearm", "0.01 0 0.2707", "0.5 -0.5 -0.5 -0.5", "w1",
         ("0.06041 0.00697 0.006", "0.456911 0.468526 0.475683 0.587743", 1.60979,
          "0.00708828 0.00552689 0.00379383"), ((0.05, 0.0),), 0.045, (0.054, 0.058)),
    Link("wrist", "0.115975 0 0", "0.5 0.5 0.5 0.5", "w2",
         ("0.00198 0.00125 0.01855", "0.0594843 0.68926 -0.16016 0.704082", 0.35093,
          "0.0003082 0.000269928 0.000251035"), ((0.0825, 0.0),), 0.04, (0.046, 0.025)),
)
# fmt: on
ARM_MOUNT: dict[str, tuple[str, str]] = {  # side -> (pos, quat) in the torso frame
    "right": ("0.024645 -0.219645 0.118588", "0.923879 0 0 -0.382684"),
    "left": ("0.024645 0.219645 0.118588", "0.923879 0 0 0.382684"),
}
HAND_OFFSET = 0.11355  # hand frame along the wrist's z axis
RED = "0.72 0.06 0.06 1"
GREY = "0.25 0.25 0.25 1"
DARK = "0.11 0.11 0.12 1"
SCREEN = "0.93 0.94 0.96 1"


def joint_name(side: str, joint: str) -> str:
    """The real robot's joint name, e.g. ``left_s0``."""
    return f"{side}_{joint}"


def finger_joint(side: str, finger: str) -> str:
    """Slide joint of finger ``"l"`` or ``"r"`` of ``side``'s gripper."""
    return f"{side}_gripper_{finger}_finger_joint"


def _gripper(side: str) -> str:
    """Palm, grip site and two sliding fingers; the hand frame's +z points out of the wrist."""
    fz = FINGER_TOP_Z + FINGER_HALF_LEN
    px, py, pz = PALM_HALF
    fingers = []
    for finger, sign in (("l", 1), ("r", -1)):
        fingers.append(
            f'<body name="{side}_finger_{finger}" pos="0 0 0" gravcomp="1">'
            f'<inertial pos="0 {sign * 0.005} {fz}" mass="0.04" diaginertia="2e-5 2e-5 5e-6"/>'
            f'<joint name="{finger_joint(side, finger)}" type="slide" axis="0 {sign} 0" '
            f'range="0 {FINGER_TRAVEL}" damping="5" armature="0.01"/>'
            f'<geom name="{side}_finger_{finger}_geom" type="box" class="finger" '
            f'size="{FINGER_WIDTH} {FINGER_THICK / 2} {FINGER_HALF_LEN}" '
            f'pos="0 {sign * FINGER_THICK / 2} {fz}"/>'
            "</body>"
        )
    return (
        f'<geom name="{side}_palm" type="box" size="{px} {py} {pz}" pos="0 0 {pz}" rgba="0.15 0.15 0.15 1" '
        'class="robot"/>'
        f'<site name="{side}_grip_site" pos="0 0 {GRIP_SITE_Z}" size="0.005" rgba="0 1 0 0.6" group="3"/>'
        + "".join(fingers)
    )


def arm_xml(side: str) -> str:
    """The 7-DoF arm of ``side`` ("left" or "right") with its gripper, as nested MJCF bodies."""
    pos, quat = ARM_MOUNT[side]
    parts = [f'<body name="{side}_arm_mount" pos="{pos}" quat="{quat}">']
    for i, link in enumerate(ARM_CHAIN):
        q = f' quat="{link.quat}"' if link.quat else ""
        ipos, iquat, mass, diag = link.inertial
        lo, hi = JOINT_RANGE[link.joint]
        rgba = RED if i % 2 == 0 else GREY
        parts.append(f'<body name="{side}_{link.name}" pos="{link.pos}"{q} gravcomp="1">')
        parts.append(f'<inertial pos="{ipos}" quat="{iquat}" mass="{mass}" diaginertia="{diag}"/>')
        parts.append(
            f'<joint name="{joint_name(side, link.joint)}" axis="0 0 1" range="{lo} {hi}" '
            'armature="0.05" damping="1"/>'
        )
        for k, (half, z) in enumerate(link.segments):
            parts.append(
                f'<geom name="{side}_{link.name}_g{k}" type="cylinder" size="{link.radius} {half}" '
                f'pos="0 0 {z}" rgba="{rgba}" class="robot"/>'
            )
        radius, half = link.housing
        parts.append(
            f'<geom name="{side}_{link.joint}_housing" type="cylinder" size="{radius} {half}" rgba="{DARK}" '
            'class="visual"/>'
        )
    parts.append(f'<body name="{side}_hand" pos="0 0 {HAND_OFFSET}" gravcomp="1">')
    parts.append('<inertial pos="0 0 0.02" mass="0.3" diaginertia="3e-4 3e-4 2e-4"/>')
    parts.append(_gripper(side))
    parts.append("</body>" * (len(ARM_CHAIN) + 2))
    return "\n".join(parts)


def _face() -> str:
    """Baxter's face on the head screen: two eyes with pupils and two brows (screen frame: x across,
    y up, z out of the screen)."""
    z = 0.0165
    parts = []
    for side, x in (("l", 0.042), ("r", -0.042)):
        parts += [
            f'<geom name="eye_{side}" type="cylinder" size="0.021 0.0008" pos="{x} 0.002 {z}" rgba="1 1 1 1" '
            'class="visual"/>',
            f'<geom name="pupil_{side}" type="cylinder" size="0.012 0.001" pos="{x} -0.002 {z + 0.0012}" '
            f'rgba="{DARK}" class="visual"/>',
            f'<geom name="brow_{side}" type="box" size="0.022 0.0035 0.0008" pos="{x} 0.036 {z}" '
            f'euler="0 0 {-0.15 if x > 0 else 0.15}" rgba="{DARK}" class="visual"/>',
        ]
    return "\n".join(parts)


def robot_xml() -> str:
    """Pedestal, torso, head with its face screen and both arms (worldbody content)."""
    half = (BASE_Z - 0.1) / 2
    return f"""
    <body name="pedestal">
      <geom name="pedestal_geom" type="cylinder" size="0.11 {half:.4f}" pos="0 0 {half + 0.05:.4f}"
            rgba="{DARK}" contype="0" conaffinity="0"/>
      <geom name="pedestal_base" type="box" size="0.3 0.3 0.025" pos="0 0 0.025" rgba="0.2 0.2 0.21 1"
            class="visual"/>
      <geom name="pedestal_leg_x" type="box" size="0.34 0.04 0.035" pos="0 0 0.035" rgba="{DARK}"
            class="visual"/>
      <geom name="pedestal_leg_y" type="box" size="0.04 0.34 0.035" pos="0 0 0.035" rgba="{DARK}"
            class="visual"/>
    </body>
    <body name="base" pos="0 0 {BASE_Z}">
      <body name="torso">
        <inertial pos="0 0 0" mass="35.3365" diaginertia="1.87139 1.66268 0.779991"/>
        <geom name="torso_geom" type="box" size="0.13 0.14 0.25" pos="-0.05 0 0.2" rgba="0.2 0.2 0.22 1"
              contype="0" conaffinity="0"/>
        <geom name="torso_panel" type="box" size="0.004 0.1 0.16" pos="0.081 0 0.2" rgba="{RED}"
              class="visual"/>
        <geom name="torso_base_geom" type="box" size="0.16 0.16 0.06" pos="-0.04 0 -0.04"
              rgba="{DARK}" contype="0" conaffinity="0"/>
        <geom name="sonar_ring" type="cylinder" size="0.1 0.03" pos="-0.03 0 0.48" rgba="{DARK}"
              class="visual"/>
        <geom name="head_column" type="cylinder" size="0.035 0.07" pos="0.0 0 0.57" rgba="{DARK}"
              class="visual"/>
        <body name="head" pos="0.06 0 0.686">
          <geom name="head_neck" type="cylinder" size="0.03 0.06" pos="-0.02 0 -0.06" rgba="{DARK}"
                contype="0" conaffinity="0"/>
          <body name="screen" pos="0.1227 0 0" quat="0.453099 0.542864 0.542864 0.453099">
            <geom name="screen_geom" type="box" size="0.125 0.088 0.015" rgba="{DARK}"
                  contype="0" conaffinity="0"/>
            <geom name="screen_display" type="box" size="0.108 0.072 0.0008" pos="0 0 0.0152"
                  rgba="{SCREEN}" class="visual"/>
            {_face()}
          </body>
        </body>
        {arm_xml("right")}
        {arm_xml("left")}
      </body>
    </body>"""


def actuators_xml() -> str:
    """Position servos for the 14 arm joints and the 4 finger slides (actuator section content)."""
    acts = []
    for side in SIDES:
        for j in JOINTS:
            acts.append(
                f'<position name="{side}_{j}_act" joint="{joint_name(side, j)}" kp="{KP[j]}" dampratio="1" '
                f'inheritrange="1" forcerange="{-TORQUE[j]} {TORQUE[j]}"/>'
            )
        for f in "lr":
            acts.append(
                f'<position name="{side}_gripper_{f}_act" joint="{finger_joint(side, f)}" kp="400" '
                f'dampratio="1" ctrlrange="0 {FINGER_TRAVEL}" forcerange="-15 15"/>'
            )
    return "\n".join(acts)
