"""Measured constants of the simulated table scene (metres, seconds, kilograms).

Reach: with a top-down hand, the nearer arm reaches every block centre of the table strip
``REACH`` (x 0.43-0.77 m in front of the robot, y within 0.46 m of its midline) at grasp height and at
hover height, with any closing direction within a quarter turn of the arm's comfortable one
(``tests/sim/test_sim_ik.py`` checks it). The strip is wider than it is deep, so the workspace map
(:mod:`sim.workspace`) scales the two axes separately.

Blocks are 44 mm cubes: at 640 x 480 the default camera, framed on the whole robot, the table and
the bin, shows each one more than 20 pixels wide, so their colours can be told apart.
"""

from __future__ import annotations

TABLE_TOP = 0.88  # world z of the table surface
TABLE_CENTER = (0.56, 0.0)
TABLE_HALF = (0.24, 0.5)  # the table spans x 0.32-0.80, y -0.5-0.5: the strip and a margin

REACH: tuple[float, float, float, float] = (0.43, -0.46, 0.77, 0.46)  # block centres, world x0 y0 x1 y1

BLOCK_HALF = 0.022  # half edge of a block
BLOCK_MASS = 0.06
REST_Z = TABLE_TOP + BLOCK_HALF  # centre height of a block resting on the table

BIN_WALL = 0.006  # wall thickness; the bin's outer faces are the mapped trash area's edges
BIN_HEIGHT = 0.10  # wall height above the table: under the palm of a hand grasping on the bin floor
BIN_FLOOR = 0.004  # floor plate thickness

HOME_MAT = 0.0005  # the home area is drawn as a thin, collision-free mat

TIMESTEP = 0.002

COLORS: dict[str, tuple[float, float, float]] = {
    "red": (0.85, 0.1, 0.1),
    "green": (0.1, 0.7, 0.2),
    "blue": (0.15, 0.3, 0.9),
    "yellow": (0.95, 0.85, 0.1),
    "orange": (1.0, 0.5, 0.05),
    "purple": (0.55, 0.2, 0.7),
    "cyan": (0.1, 0.8, 0.85),
    "white": (0.95, 0.95, 0.95),
    "black": (0.08, 0.08, 0.08),
    "brown": (0.5, 0.3, 0.1),
    "pink": (1.0, 0.55, 0.7),
}
GREY = (0.55, 0.55, 0.55)  # unknown colours and "none"


def rgba(color: str | None) -> str:
    """MJCF rgba string of a colour name; unknown names and None render grey."""
    r, g, b = COLORS.get((color or "").lower(), GREY)
    return f"{r} {g} {b} 1"
