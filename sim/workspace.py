"""Workspace coordinates <-> simulator world coordinates, and the plain inputs of a simulated world.

The store describes a blocks world in *workspace* metres: the paper's world spans about
x, y in [-1.1, 1.1] around a home area at the origin; z = 0 is the table. The Baxter reaches only a
strip of table about 0.34 m deep and 0.92 m wide in front of it (``scene_config.REACH``), so a map
squeezes the whole workspace into that strip. The map treats each axis on its own, with a strictly
monotone piecewise-linear function, so a point lies inside an axis-aligned box in the workspace
exactly when its image lies inside the box's image (up to rounding, for points within a nanometre of
an edge): ``inArea`` means the same in both worlds, for every area, whatever the pieces. The pieces
let a small area (the home area, the trash area) take more of the table than its share, so that
blocks fit in it side by side (:func:`sim.layout.map_for` decides how much); heights are not scaled
(workspace z = world height of a block's centre above a block resting on the table).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sim import scene_config as cfg

Vec = NDArray[np.float64]

WORKSPACE_HALF = 1.1  # the workspace box is at least [-1.1, 1.1]^2 (metres)
KNOT_GAP = 1e-9  # area edges closer than this share one knot of the map
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

    def bounds(self) -> tuple[float, float, float, float]:
        """The box with x0 <= x1 and y0 <= y1."""
        x0, y0, x1, y1 = self.box
        return (min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))


@dataclass(frozen=True)
class AxisMap:
    """A strictly increasing piecewise-linear function of one axis: ``knots`` (workspace) to ``values``
    (world), continued beyond the end knots with the slopes of the end pieces."""

    knots: tuple[float, ...]
    values: tuple[float, ...]

    def __post_init__(self) -> None:
        k, v = np.asarray(self.knots, float), np.asarray(self.values, float)
        if len(k) < 2 or len(k) != len(v) or not np.all(np.isfinite(k)) or not np.all(np.isfinite(v)):
            raise ValueError(f"an axis map needs at least two finite knots and values, got {self.knots}, "
                             f"{self.values}")
        if np.any(np.diff(k) <= 0) or np.any(np.diff(v) <= 0):
            raise ValueError(f"an axis map must be strictly increasing, got {self.knots} -> {self.values}")

    @classmethod
    def linear(cls, lo: float, hi: float, world_lo: float, world_hi: float) -> AxisMap:
        """The affine map sending [lo, hi] onto [world_lo, world_hi]."""
        return cls((lo, hi), (world_lo, world_hi))

    @staticmethod
    def _apply(xs: Vec, src: Vec, dst: Vec) -> Vec:
        out = np.interp(xs, src, dst)
        low, high = xs < src[0], xs > src[-1]
        out = np.where(low, dst[0] + (xs - src[0]) * (dst[1] - dst[0]) / (src[1] - src[0]), out)
        return np.where(high, dst[-1] + (xs - src[-1]) * (dst[-1] - dst[-2]) / (src[-1] - src[-2]), out)

    def forward(self, xs: ArrayLike) -> Vec:
        """World coordinates of workspace coordinates ``xs`` (any shape)."""
        return self._apply(np.asarray(xs, float), np.asarray(self.knots), np.asarray(self.values))

    def inverse(self, ws: ArrayLike) -> Vec:
        """Workspace coordinates of world coordinates ``ws`` (any shape)."""
        return self._apply(np.asarray(ws, float), np.asarray(self.values), np.asarray(self.knots))


def _default_depth() -> AxisMap:
    return AxisMap.linear(-WORKSPACE_HALF, WORKSPACE_HALF, cfg.REACH[0], cfg.REACH[2])


def _default_width() -> AxisMap:
    return AxisMap.linear(-WORKSPACE_HALF, WORKSPACE_HALF, cfg.REACH[1], cfg.REACH[3])


@dataclass(frozen=True)
class WorkspaceMap:
    """World = (depth(-ws_y), width(ws_x), ``rest_z`` + ws_z) for points of shape (3,) or (n, 3).

    The workspace is turned a quarter turn: its y axis runs towards the robot (world -x) and its x
    axis across the table (world y). The paper's trash area (at large y) then lies along the near edge
    of the table in front of the robot and its home area (at the origin) in the middle, both across
    the midline, where both arms reach them. The default sends the workspace box [-1.1, 1.1]^2
    affinely onto the reachable strip; :func:`sim.layout.map_for` fits the pieces to a world's areas.
    """

    depth: AxisMap = field(default_factory=_default_depth)
    width: AxisMap = field(default_factory=_default_width)
    rest_z: float = cfg.REST_Z

    def xy_to_world(self, xy: ArrayLike) -> Vec:
        """Map workspace (x, y) pairs (2,) or (n, 2) into world (x, y)."""
        p = np.asarray(xy, dtype=float)
        return np.stack([self.depth.forward(-p[..., 1]), self.width.forward(p[..., 0])], -1)

    def xy_to_workspace(self, xy: ArrayLike) -> Vec:
        """Inverse of :meth:`xy_to_world`."""
        p = np.asarray(xy, dtype=float)
        return np.stack([self.width.inverse(p[..., 1]), -self.depth.inverse(p[..., 0])], -1)

    def to_world(self, points: ArrayLike) -> Vec:
        """Map workspace points (3,) or (n, 3) into world coordinates of the same shape."""
        p = np.asarray(points, dtype=float)
        return np.concatenate([self.xy_to_world(p[..., :2]), self.rest_z + p[..., 2:3]], -1)

    def to_workspace(self, points: ArrayLike) -> Vec:
        """Inverse of :meth:`to_world`: world points (3,) or (n, 3) into workspace coordinates."""
        p = np.asarray(points, dtype=float)
        return np.concatenate([self.xy_to_workspace(p[..., :2]), p[..., 2:3] - self.rest_z], -1)

    def box_to_world(self, box: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
        """Map a workspace box (x0, y0, x1, y1) into a world box with x0 <= x1 and y0 <= y1."""
        (ax, ay), (bx, by) = self.xy_to_world([box[0], box[1]]), self.xy_to_world([box[2], box[3]])
        return (float(min(ax, bx)), float(min(ay, by)), float(max(ax, bx)), float(max(ay, by)))


def fit_axis(lo: float, hi: float, world_lo: float, world_hi: float,
             spans: Sequence[tuple[float, float, float]]) -> AxisMap:
    """A map of [lo, hi] onto [world_lo, world_hi] giving each span ``(a, b, need)`` of the workspace
    at least ``need`` world metres, and the rest of the axis in proportion to workspace length.

    Every span's ends become knots. Spans that are short are stretched and the pieces outside every
    stretched span shrink to pay for them, until every span has its room; if the spans together ask
    for more than the axis has, each keeps its proportional share of what there is.
    """
    clipped = [(max(lo, min(a, b)), min(hi, max(a, b)), need) for a, b, need in spans]
    clipped = [(a, b, need) for a, b, need in clipped if b > a]
    knots = np.unique(np.array([lo, hi] + [v for a, b, _ in clipped for v in (a, b)]))
    knots = knots[np.concatenate([[True], np.diff(knots) > KNOT_GAP])]  # merge knots closer than KNOT_GAP
    knots[-1] = hi
    ws = np.diff(knots)
    length = world_hi - world_lo
    ell = length * ws / ws.sum()
    members = [(np.flatnonzero((knots[:-1] >= a - KNOT_GAP) & (knots[1:] <= b + KNOT_GAP)), need)
               for a, b, need in clipped]
    members = [(m, need) for m, need in members if len(m)]
    for _ in range(60):
        if all(ell[m].sum() >= need * (1 - 1e-9) for m, need in members):
            break
        held = np.zeros(len(ell), dtype=bool)
        for m, need in members:
            have = ell[m].sum()
            if have < need:
                ell[m] *= need / have
            if ell[m].sum() <= need * (1 + 1e-9):
                held[m] = True
        excess = ell.sum() - length
        free = ~held
        if not free.any() or ell[free].sum() <= excess + 1e-6 * length:
            ell *= length / ell.sum()  # the spans ask for more than there is: proportional shares
            break
        ell[free] *= (ell[free].sum() - excess) / ell[free].sum()
    ell *= length / ell.sum()
    values = world_lo + np.concatenate([[0.0], np.cumsum(ell)])
    values[-1] = world_hi
    return AxisMap(tuple(float(k) for k in knots), tuple(float(v) for v in values))


def with_default_areas(areas: list[SimArea]) -> dict[str, SimArea]:
    """Areas by name, adding the default ``trash`` and ``home`` boxes when they are absent."""
    by_name = {a.name: a for a in areas}
    by_name.setdefault("trash", SimArea("trash", DEFAULT_TRASH))
    by_name.setdefault("home", SimArea("home", DEFAULT_HOME))
    return by_name
