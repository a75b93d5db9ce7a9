"""Plan-view geometry: oriented rectangles, their overlap test, and the gripper's footprint.

Planning questions ("may the fingers go down here without touching another block?") reduce to
rectangles in the table plane plus a height: a block, a finger or a bin wall is a :class:`Rect`
whose ``top`` says how high it reaches. Everything is in world metres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sim import baxter

Vec = NDArray[np.float64]


@dataclass(frozen=True)
class Rect:
    """Rectangle at ``center`` (2,) turned by ``yaw`` with half extents ``half`` (2,), z in [bottom, top]."""

    center: tuple[float, float]
    yaw: float
    half: tuple[float, float]
    bottom: float = -np.inf
    top: float = np.inf

    def axes(self) -> Vec:
        """Unit axes of the rectangle as rows, shape (2, 2)."""
        c, s = np.cos(self.yaw), np.sin(self.yaw)
        return np.array([[c, s], [-s, c]])

    def corners(self) -> Vec:
        """Corner points, shape (4, 2)."""
        ax = self.axes()
        hx, hy = self.half
        signs = np.array([[1, 1], [1, -1], [-1, -1], [-1, 1]], dtype=float)
        return np.asarray(self.center) + (signs[:, :1] * hx) * ax[0] + (signs[:, 1:] * hy) * ax[1]


def overlap(a: Rect, b: Rect, margin: float = 0.0) -> bool:
    """True if ``a`` grown by ``margin`` on every side meets ``b`` in plan view and their z spans meet.

    Far-apart rectangles are told apart by their circumscribed circles; the others by the
    separating-axis test on the four edge normals of the two rectangles.
    """
    if a.bottom > b.top or b.bottom > a.top:
        return False
    reach = float(np.hypot(*a.half) + np.hypot(*b.half)) + margin * np.sqrt(2)  # circumscribed circles
    if (a.center[0] - b.center[0]) ** 2 + (a.center[1] - b.center[1]) ** 2 > reach * reach:
        return False
    ca, cb = a.corners(), b.corners()
    for axis in np.vstack([a.axes(), b.axes()]):
        pa, pb = ca @ axis, cb @ axis
        if pa.max() + margin < pb.min() or pb.max() + margin < pa.min():
            return False
    return True


def finger_rects(center: Vec, closing_yaw: float, opening: float, bottom: float, top: float) -> list[Rect]:
    """The two fingers of a gripper centred at ``center`` (2,), closing along ``closing_yaw``.

    ``opening`` is the distance of each finger's inner face from the centre line (m).
    """
    axis = np.array([np.cos(closing_yaw), np.sin(closing_yaw)])
    mid = opening + baxter.FINGER_THICK / 2
    half = (baxter.FINGER_THICK / 2, baxter.FINGER_WIDTH)
    return [
        Rect(tuple(np.asarray(center) + sign * mid * axis), closing_yaw, half, bottom, top)
        for sign in (1.0, -1.0)
    ]


def palm_rect(center: Vec, closing_yaw: float, bottom: float) -> Rect:
    """The palm and wrist above the fingers, as one box reaching up from ``bottom``."""
    return Rect(
        (float(center[0]), float(center[1])), closing_yaw, (baxter.PALM_HALF[1], baxter.PALM_HALF[0]), bottom
    )


def square(center: Vec, yaw: float, half: float, bottom: float, top: float) -> Rect:
    """A block's footprint: a square of half edge ``half`` at ``center`` (2,)."""
    return Rect((float(center[0]), float(center[1])), float(yaw), (half, half), bottom, top)


def face_yaw(yaw: float, near: float = 0.0) -> float:
    """The angle congruent to ``yaw`` modulo 90 degrees that is closest to ``near``."""
    return near + (yaw - near + np.pi / 4) % (np.pi / 2) - np.pi / 4
