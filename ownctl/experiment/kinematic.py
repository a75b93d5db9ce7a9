"""A kinematic executor: actions succeed at once and put the object on a free spot of the target area.

``trash`` moves the object into the world's ``trash`` area, ``collect`` into ``home`` (the paper's
simulated arm, reference 7.1, dropped them all on one point; free spots keep objects apart, as a
physical table would). The spots are a grid inside the area, nearest its centre first.
"""

from __future__ import annotations

import numpy as np

from ownctl.errors import UnknownName
from ownctl.experiment.task import Execution, area_named
from ownctl.world.model import Area, Position, World

DESTINATIONS = {"trash": "trash", "collect": "home"}
SPACING = 0.04  # metres between grid spots
MARGIN = 0.01  # metres kept from the area's edges


def free_spots(area: Area, spacing: float = SPACING) -> list[tuple[float, float]]:
    """Grid points inside ``area`` (at least its centre), nearest the centre first."""
    x0, y0, x1, y1 = area.box
    cx, cy = area.center
    xs = np.arange(x0 + MARGIN, x1 - MARGIN + 1e-9, spacing)
    ys = np.arange(y0 + MARGIN, y1 - MARGIN + 1e-9, spacing)
    pts = [(float(x), float(y)) for x in xs for y in ys] or [(cx, cy)]
    return sorted(pts, key=lambda p: ((p[0] - cx) ** 2 + (p[1] - cy) ** 2, p))


class KinematicExecutor:
    """Teleports objects: the in-memory stand-in for the MuJoCo runner's physics executor."""

    def __init__(self, world: World, spacing: float = SPACING) -> None:
        self.world = world
        self.spacing = spacing
        self.positions: dict[str, Position | None] = {o.name: o.position for o in world.objects}

    def position(self, name: str) -> Position | None:
        """Where object ``name`` is now."""
        return self.positions[name]

    def perform(self, action: str, name: str) -> Execution:
        """Move ``name`` to a free spot of the action's destination area."""
        if action not in DESTINATIONS:
            raise UnknownName("task action", action, DESTINATIONS)
        if name not in self.positions:
            return Execution(False, f"unknown object {name!r}")
        area = area_named(self.world.areas, DESTINATIONS[action])
        self.positions[name] = self._spot(area, name)
        return Execution(True)

    def _spot(self, area: Area, name: str) -> Position:
        others = np.array([p[:2] for k, p in self.positions.items() if p is not None and k != name])
        for x, y in free_spots(area, self.spacing):
            if not len(others) or np.min(np.hypot(others[:, 0] - x, others[:, 1] - y)) >= self.spacing * 0.99:
                return (x, y, 0.0)
        cx, cy = area.center
        return (cx, cy, 0.0)
