"""Workspace coordinates <-> simulator world coordinates, and the plain inputs of a simulated world.

The store describes a blocks world in *workspace* metres: the paper's world spans about
x, y in [-1.1, 1.1] around a home area at the origin; z = 0 is the table. The Baxter can only reach
a strip of table about 0.4 m deep in front of it, so one affine map (uniform scale + offset, no
rotation) shrinks the whole workspace box into that strip. Applying the same map to blocks and areas
keeps ``inArea`` meaning the same in both worlds; the inverse map reports simulated positions back.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sim import scene_config as cfg

Vec = NDArray[np.float64]

WORKSPACE_HALF = 1.1  # the workspace box is [-1.1, 1.1]^2 (metres)
DEFAULT_TRASH: tuple[float, float, float, float] = (-0.3, 0.6, 0.2, 1.1)
DEFAULT_HOME: tuple[float, float, float, float] = (-0.1, -0.1, 0.1, 0.1)


@dataclass(frozen=True)
class SimBlock:
    """A block to simulate: its store name, colour name (None or unknown -> grey), workspace position.

    A position of None asks for a free spot; z is ignored when placing (blocks start on the table).
    """

    name: str
    color: str | None
    position: tuple[float, float, float] | None


@dataclass(frozen=True)
class SimArea:
    """A named axis-aligned area ``box = (x0, y0, x1, y1)`` in workspace metres."""

    name: str
    box: tuple[float, float, float, float]

    def contains(self, point: tuple[float, float] | tuple[float, float, float]) -> bool:
        """True if the (x, y) of ``point`` lies inside the box (z is ignored, as for ``inArea``)."""
        x0, y0, x1, y1 = self.box
        return min(x0, x1) <= point[0] <= max(x0, x1) and min(y0, y1) <= point[1] <= max(y0, y1)


@dataclass(frozen=True)
class WorkspaceMap:
    """World = offset + scale * workspace, for points of shape (3,) or (n, 3).

    ``offset`` is where the workspace origin lands in the world: the table point in front of the robot
    at the height of a resting block's centre, so a block on the table reports z = 0.
    """

    scale: float = cfg.MAP_SCALE
    offset: tuple[float, float, float] = field(default=(cfg.MAP_CENTER_X, cfg.MAP_CENTER_Y, cfg.REST_Z))

    def __post_init__(self) -> None:
        if not np.isfinite(self.scale) or self.scale <= 0:
            raise ValueError(f"workspace map scale must be positive, got {self.scale!r}")

    def to_world(self, points: ArrayLike) -> Vec:
        """Map workspace points (3,) or (n, 3) into world coordinates of the same shape."""
        return np.asarray(self.offset) + self.scale * np.asarray(points, dtype=float)

    def to_workspace(self, points: ArrayLike) -> Vec:
        """Inverse of :meth:`to_world`: world points (3,) or (n, 3) into workspace coordinates."""
        return (np.asarray(points, dtype=float) - np.asarray(self.offset)) / self.scale

    def xy_to_world(self, xy: ArrayLike) -> Vec:
        """Map workspace (x, y) pairs (2,) or (n, 2) into world (x, y)."""
        return np.asarray(self.offset[:2]) + self.scale * np.asarray(xy, dtype=float)

    def box_to_world(self, box: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
        """Map a workspace box (x0, y0, x1, y1) into a world box with x0 <= x1 and y0 <= y1."""
        (ax, ay), (bx, by) = self.xy_to_world([box[0], box[1]]), self.xy_to_world([box[2], box[3]])
        return (float(min(ax, bx)), float(min(ay, by)), float(max(ax, bx)), float(max(ay, by)))


def with_default_areas(areas: list[SimArea]) -> dict[str, SimArea]:
    """Areas by name, adding the default ``trash`` and ``home`` boxes when they are absent."""
    by_name = {a.name: a for a in areas}
    by_name.setdefault("trash", SimArea("trash", DEFAULT_TRASH))
    by_name.setdefault("home", SimArea("home", DEFAULT_HOME))
    return by_name
