"""A pure description of a world: agents, objects with percepts, areas, true norms and owners.

Interaction times here are *ages*: seconds since each agent last touched the object, measured at
the moment the world is described. The store turns them into absolute times on its own clock.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ownctl.logic.frame import Frame

Position = tuple[float, float, float]


@dataclass(frozen=True)
class Area:
    """An axis-aligned box on the table plane: ``box = (x0, y0, x1, y1)`` in workspace metres."""

    name: str
    box: tuple[float, float, float, float]

    def contains(self, xy: np.ndarray) -> np.ndarray:
        """Bool vector: which of the (n, 2+) points lie inside the box (edges included)."""
        pts = np.asarray(xy, dtype=float).reshape(-1, np.shape(xy)[-1] if np.ndim(xy) else 2)
        x0, y0, x1, y1 = self.box
        return (pts[:, 0] >= x0) & (pts[:, 0] <= x1) & (pts[:, 1] >= y0) & (pts[:, 1] <= y1)

    @property
    def center(self) -> tuple[float, float]:
        """The box centre (x, y)."""
        x0, y0, x1, y1 = self.box
        return ((x0 + x1) / 2, (y0 + y1) / 2)


@dataclass(frozen=True)
class ObjectSpec:
    """An object and its percepts. ``last_touch[agent]`` is the age in seconds of that agent's last touch."""

    name: str
    color: str | None = None
    position: Position | None = None
    categories: frozenset[str] = frozenset()
    last_touch: Mapping[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class World:
    """Agents, objects and areas, plus the ground truth: true norms and true ownership."""

    name: str
    agents: tuple[str, ...]
    objects: tuple[ObjectSpec, ...]
    areas: tuple[Area, ...] = ()
    norms: tuple[str, ...] = ()
    owners: Mapping[str, Mapping[str, float]] = field(default_factory=dict)

    def object(self, name: str) -> ObjectSpec:
        """The object called ``name`` (KeyError if absent)."""
        for obj in self.objects:
            if obj.name == name:
                return obj
        raise KeyError(name)

    def true_ownership(self) -> np.ndarray:
        """(n, m) matrix of true ownership, rows in object order, columns in agent order."""
        return np.array(
            [[float(self.owners.get(o.name, {}).get(a, 0.0)) for a in self.agents] for o in self.objects]
        ).reshape(len(self.objects), len(self.agents))


def positions(objects: Sequence[ObjectSpec]) -> np.ndarray:
    """(n, 3) positions; objects without one get NaN (they are in no area)."""
    return np.array(
        [o.position if o.position is not None else (np.nan, np.nan, np.nan) for o in objects], dtype=float
    ).reshape(len(objects), 3)


def make_frame(
    objects: Sequence[ObjectSpec], areas: Sequence[Area], agents: Sequence[str], own: np.ndarray
) -> Frame:
    """The evaluation frame of ``objects`` with ownership matrix ``own`` (n, len(agents))."""
    pos = positions(objects)
    return Frame(
        tuple(agents),
        np.asarray(own, dtype=float),
        tuple(o.color for o in objects),
        {a.name: a.contains(pos[:, :2]) for a in areas},
        tuple(frozenset(o.categories) for o in objects),
    )
