"""Measured constants of the simulated table scene (metres, seconds, kilograms).

Reach: with a top-down hand, both arms together reach the table strip x in [0.40, 0.80] m,
y in [-0.4, 0.4] m at a table height of 0.80 m, at grasp height and at hover height alike. The
workspace map squeezes the workspace box [-1.1, 1.1]^2 into x in [0.402, 0.798], y in [-0.198, 0.198].
Blocks are 10 mm cubes: the mapped home area is only 36 mm square, yet it must hold a 2 x 2 grid of
block towers with room for the fingers between them; 20 blocks, the bin and home fit the square.
"""

from __future__ import annotations

TABLE_TOP = 0.80  # world z of the table surface
TABLE_CENTER = (0.62, 0.0)
TABLE_HALF = (0.32, 0.55)

BLOCK_HALF = 0.005  # half edge of a block
BLOCK_MASS = 0.01
REST_Z = TABLE_TOP + BLOCK_HALF  # centre height of a block resting on the table

MAP_SCALE = 0.18  # world metres per workspace metre
MAP_CENTER_X = 0.60  # where the workspace origin lands
MAP_CENTER_Y = 0.0

BIN_WALL = 0.004  # wall thickness; the bin's outer faces are the mapped trash area's edges
BIN_HEIGHT = 0.04  # wall height above the table
BIN_FLOOR = 0.003  # floor plate thickness

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
