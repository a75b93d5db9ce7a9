"""Where to grasp, where to put down, where to drop: collision-free choices in plan view.

Every choice is checked against the other blocks and the bin walls as :class:`~sim.footprint.Rect`
obstacles with heights: the fingers sweep down to their tips, the palm down to its underside, and
nothing they sweep may touch a block other than the one handled (or the tower it is put on).
Choices are deterministic: ties go to the first candidate in a fixed order.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sim import baxter
from sim import scene_config as cfg
from sim.footprint import Rect, face_yaw, finger_rects, overlap, palm_rect, square

Vec = NDArray[np.float64]

H = cfg.BLOCK_HALF
PICK_OPENING = H + 0.006  # finger inner faces this far from the block centre when going down to grasp
PLACE_OPENING = H + 0.004  # ... and when letting go of a block on a tower
DROP_OPENING = H + 0.01
MARGIN = 0.0015  # clearance kept between a swept finger and any obstacle
PALM_DEPTH = baxter.GRIP_SITE_Z - 2 * baxter.PALM_HALF[2]  # palm underside above the grip site
ALIGNED = 0.008  # a block within this distance of a cell's centre belongs to that cell's tower
MAX_TOWER = 6 * H + 0.005  # a home tower may not grow above this height over the table (3 blocks)
MAX_PILE = 3  # blocks on one drop cell of the bin at most: a higher pile may topple over the wall
BIN_REACH = DROP_OPENING + baxter.FINGER_THICK + MARGIN + 0.002  # bin cell centre to a wall's inner face


@dataclass(frozen=True)
class BlockState:
    """A block as the planner sees it: index, centre (3,) and yaw about z."""

    index: int
    center: tuple[float, float, float]
    yaw: float

    def rect(self, pad: float = 0.0) -> Rect:
        """Footprint with the block's height span, grown by ``pad`` on every side."""
        z = self.center[2]
        return square(np.asarray(self.center[:2]), self.yaw, H + pad, z - H - pad, z + H + pad)


def wall_rects(bin_box: tuple[float, float, float, float]) -> list[Rect]:
    """The four bin walls of the world box ``bin_box`` as obstacles."""
    x0, y0, x1, y1 = bin_box
    w, top = cfg.BIN_WALL / 2, cfg.TABLE_TOP + cfg.BIN_HEIGHT
    cx, cy, hx, hy = (x0 + x1) / 2, (y0 + y1) / 2, (x1 - x0) / 2, (y1 - y0) / 2
    return [
        Rect((x0 + w, cy), 0.0, (w, hy), cfg.TABLE_TOP, top),
        Rect((x1 - w, cy), 0.0, (w, hy), cfg.TABLE_TOP, top),
        Rect((cx, y0 + w), 0.0, (hx, w), cfg.TABLE_TOP, top),
        Rect((cx, y1 - w), 0.0, (hx, w), cfg.TABLE_TOP, top),
    ]


def hand_clear(
    center: Vec, closing_yaw: float, opening: float, grip_z: float, obstacles: Sequence[Rect]
) -> bool:
    """True if fingers (at ``opening``) and palm going down to grip-site height ``grip_z`` touch no obstacle.

    The gap between the fingers must be free above the handled block too (nothing stacked on it).
    """
    tips = grip_z - baxter.TIP_BELOW_SITE
    parts = finger_rects(center, closing_yaw, opening, tips, np.inf)
    parts.append(palm_rect(center, closing_yaw, grip_z + PALM_DEPTH))
    parts.append(
        Rect(
            (float(center[0]), float(center[1])),
            closing_yaw,
            (opening, baxter.FINGER_WIDTH),
            grip_z + H + 0.002,
        )
    )
    return not any(overlap(p, o, MARGIN) for p in parts for o in obstacles)


def closing_options(face: float, current: float) -> list[float]:
    """The two closing directions square to a block face, nearest to ``current`` first.

    The gripper is symmetric under a half turn, so each option is chosen within pi/2 of ``current``
    (the arm's comfortable yaw, :data:`sim.ik.YAW_CENTER`).
    """
    first = face_yaw(face, current)
    second = first + np.pi / 2
    second = second - np.pi if second - current > np.pi / 2 else second
    return sorted([first, second], key=lambda y: abs(y - current))


def grasp_yaw(
    target: BlockState, others: Sequence[BlockState], walls: Sequence[Rect], current: float
) -> float | None:
    """A closing yaw for grasping ``target`` with free fingers and palm, or None if both are blocked."""
    if covered(target, others):
        return None
    obstacles = [b.rect() for b in others] + list(walls)
    center = np.asarray(target.center[:2])
    for yaw in closing_options(target.yaw, current):
        if hand_clear(center, yaw, PICK_OPENING, target.center[2], obstacles):
            return float(yaw)
    return None


def covering(target: BlockState, others: Sequence[BlockState]) -> list[BlockState]:
    """The blocks of ``others`` resting on ``target`` (overlapping its footprint, higher up)."""
    top = target.rect()
    return [b for b in others if b.center[2] > target.center[2] + H and overlap(top, b.rect(), 0.0)]


def covered(target: BlockState, others: Sequence[BlockState]) -> bool:
    """True if another block rests on ``target``."""
    return bool(covering(target, others))


@dataclass(frozen=True)
class PutDown:
    """Where a held block goes: block centre (3,) and the hand's closing yaw."""

    center: tuple[float, float, float]
    closing_yaw: float


def home_put_down(
    cells: Sequence[tuple[float, float]],
    blocks: Sequence[BlockState],
    block_yaw_in_hand: float,
    current: float,
    usable: Callable[[PutDown], bool] | None = None,
) -> PutDown | None:
    """The home cell with the lowest clear tower (ties: first cell) that is ``usable`` (say, reachable by
    the arm); None if every cell is blocked, full or unusable.

    ``block_yaw_in_hand`` is the held block's yaw relative to the hand; the block lands axis-aligned.
    """
    choices: list[tuple[float, int, PutDown]] = []
    for k, cell in enumerate(cells):
        c = np.asarray(cell)
        members = [b for b in blocks if np.hypot(*(np.asarray(b.center[:2]) - c)) < ALIGNED]
        others = [b for b in blocks if b not in members]
        support = max((b.center[2] + H for b in members), default=cfg.TABLE_TOP)
        if support + 2 * H > cfg.TABLE_TOP + MAX_TOWER:
            continue
        z = support + H
        footprint = square(c, 0.0, H, z - H, z + H)
        obstacles = [b.rect() for b in others]
        if any(overlap(footprint, o, MARGIN) for o in obstacles):
            continue
        for yaw in closing_options(-block_yaw_in_hand, current):
            if hand_clear(c, yaw, PLACE_OPENING, z, obstacles):
                choices.append((support, k, PutDown((float(c[0]), float(c[1]), float(z)), float(yaw))))
                break
    for _, _, choice in sorted(choices, key=lambda t: t[:2]):
        if usable is None or usable(choice):
            return choice
    return None


def bin_cells(bin_box: tuple[float, float, float, float], pitch: float) -> list[tuple[float, float]]:
    """Drop points in the bin, centre first: a grid at least ``pitch`` apart, spread out to where open
    fingers still clear the walls, so dropped blocks land apart and can be picked up again.
    """
    x0, y0, x1, y1 = bin_box
    half = (np.array([x1 - x0, y1 - y0]) / 2) - cfg.BIN_WALL - BIN_REACH
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    counts = [max(1, int(np.floor(2 * half[k] / pitch + 1e-9)) + 1) for k in (0, 1)]
    axes = [np.linspace(-half[k], half[k], counts[k]) if counts[k] > 1 else np.zeros(1) for k in (0, 1)]
    pts = [centre + np.array([dx, dy]) for dx in axes[0] for dy in axes[1]]
    pts.sort(key=lambda p: (round(float(np.linalg.norm(p - centre)), 6), float(p[0]), float(p[1])))
    return [(float(p[0]), float(p[1])) for p in pts]


def drop_point(
    cells: Sequence[tuple[float, float]],
    blocks: Sequence[BlockState],
    usable: Callable[[tuple[float, float, float]], bool] | None = None,
) -> tuple[float, float, float] | None:
    """The ``usable`` bin cell (say, reachable by the arm) with the fewest blocks on it, below
    ``MAX_PILE`` (ties: the lowest pile top, then the first cell), and the pile's top height there;
    None if no cell is usable.

    The top counts every block within 2 block widths of the cell's centre (tilted ones included), so
    a dropped block clears its neighbours' piles too.
    """
    floor = cfg.TABLE_TOP + cfg.BIN_FLOOR
    spots = []
    for k, (x, y) in enumerate(cells):
        gaps = [np.hypot(b.center[0] - x, b.center[1] - y) for b in blocks]
        on = sum(1 for g in gaps if g < 1.5 * H)
        if on >= MAX_PILE:
            continue
        near = [b.center[2] + 1.5 * H for b, g in zip(blocks, gaps, strict=True) if g < 4 * H]
        top = max(near, default=floor)
        spots.append((on, top, k, (x, y)))
    for _, top, _, (x, y) in sorted(spots):
        if usable is None or usable((x, y, top)):
            return (x, y, top)
    return None
