"""Initial block layout: the workspace map fitted to the areas and blocks, then a start spot for
every block, all computed before the scene is built.

Every block starts axis-aligned (yaw 0) on the table, or on the bin floor when its position is in
the trash area. Two blocks are far enough apart when their Chebyshev distance is at least
``SPACING``: then an opened gripper fits around either block along both face axes without touching
the other.

- :func:`map_for` gives every area room for a few blocks side by side (``ROOM``: home and the bin
  much more), every crowded piece of the areas' arrangement room for its blocks, and the pieces
  next to the bin room for the clearance blocks keep from its walls, as far as the reachable strip
  allows; the areas' own room comes first.
- Blocks in the home area go to the nearest free cell of the home grid (:func:`home_slots`, the
  cells collected blocks are stacked on), blocks in the trash area to the nearest free cell of the
  bin (:func:`sim.planner.bin_cells`, where trashed blocks are dropped); the other blocks go where the
  map puts them. A spot that is taken (too close to an earlier block, a bin wall, a home cell, or
  outside the reachable strip) is replaced by the nearest free spot inside exactly the same areas, so
  ``inArea`` is unchanged: a push out of the neighbours' way, else the nearest free point of a 4 mm
  grid over the strip; then the same where blocks merely do not touch; then with the walls and
  home cells only not touched; and only when the areas have no room at all is the block stacked on
  the lowest tower already inside the same areas (a bin holds more blocks in piles than on its floor).

The result depends only on the input order and the seed; a layout never fails unless a block's
areas are too small to hold any block and hold no block to stack it on.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sim import baxter
from sim import scene_config as cfg
from sim.errors import LayoutError
from sim.planner import BIN_REACH, MARGIN, bin_cells
from sim.workspace import WORKSPACE_HALF, AxisMap, SimArea, SimBlock, WorkspaceMap, fit_axis

Vec = NDArray[np.float64]
Box = tuple[float, float, float, float]

H = cfg.BLOCK_HALF
SPACING = 2 * H + 0.016  # minimum Chebyshev distance between block centres (m): a finger fits between
TIGHT_SPACING = 2 * H + 0.004  # fallback when SPACING cannot be met: blocks just do not touch
RESERVE = TIGHT_SPACING + 0.004  # other blocks keep this far from the home cells (free for collected blocks)
WALL_CLEARANCE = H + 0.016  # block centre to the face of a bin wall, inside or outside (a finger fits)
HOME_MARGIN = 0.006  # home grid cells keep their centres this far inside the home area
MIN_CELLS = (1, 1)  # every area holds at least this grid of blocks: world x (the strip's depth), y (width)
ROOM = {  # ... and these areas more: the strip is shallow, so they stretch across it
    "home": (1, 10),  # 10 cells, 3-block towers: room for twenty collected blocks, either arm reaching 6
    "trash": (1, 9),  # 9 drop cells in the bin, piles at most three high: room for twenty trashed blocks
}
LANE = H + baxter.FINGER_WIDTH + MARGIN  # a block this far across a closing axis leaves the fingers free
PASSES = (  # (spacing, relaxed rules, every block must keep a grasp), tried in turn
    (SPACING, False, False),
    (TIGHT_SPACING, False, True),
    (TIGHT_SPACING, True, True),
    (TIGHT_SPACING, True, False),
)
GRID_CHOICES = 400  # the nearest free grid points tried for a spot
CROWD_SHARES = (1.0, 0.8, 0.6, 0.4, 0.2, 0.0)
GRID_STEP = 0.004  # resolution of the search for a free spot when the wanted one and its pushes are taken


@dataclass(frozen=True)
class Placement:
    """World position (3,) of a block's centre at the start, and whether it was moved."""

    name: str
    position: tuple[float, float, float]
    nudged: bool


def _grid(extent: float, margin: float) -> int:
    """How many cells ``SPACING`` apart fit with their centres ``margin`` inside an ``extent``."""
    return max(1, int(np.floor((extent - 2 * margin) / SPACING + 1e-9)) + 1)


def home_slots(home: tuple[float, float, float, float]) -> list[tuple[float, float]]:
    """Centres of the home grid: cells ``SPACING`` apart, centred in the world box ``home``, row-major."""
    centre = np.array([(home[0] + home[2]) / 2, (home[1] + home[3]) / 2])
    counts = [_grid(home[2 + k] - home[k], HOME_MARGIN) for k in (0, 1)]
    offsets = [(np.arange(n) - (n - 1) / 2) * SPACING for n in counts]
    return [(float(centre[0] + dx), float(centre[1] + dy)) for dx in offsets[0] for dy in offsets[1]]


def _room(name: str, axis: int) -> float:
    """World extent area ``name`` needs along world ``axis`` to hold its minimum grid of blocks."""
    cells = ROOM.get(name, MIN_CELLS)[axis]
    if name == "trash":
        return (cells - 1) * SPACING + 2 * (cfg.BIN_WALL + BIN_REACH)
    return (cells - 1) * SPACING + 2 * HOME_MARGIN


def _crowd_spans(spans: list[list[tuple[float, float]]], spots: list[tuple[float, float]],
                 trash: Box, home: Box, lo: tuple[float, float],
                 hi: tuple[float, float]) -> list[list[tuple[float, float, float]]]:
    """Room for crowds: along each axis, spans asking that each piece of the areas' arrangement
    (between consecutive area edges on both axes) hold its blocks side by side, in as many rows as its
    share of the shallow depth axis allows and as many columns as needed across; a piece that borders
    the home area also needs the room its blocks keep from the home cells, and the pieces just outside
    the bin the room blocks keep from its walls.
    Blocks in the trash area are left out: they go to the bin's cells. Boxes are (depth, width) pairs
    like the spans; ``lo`` and ``hi`` bound the mapped workspace."""
    knots = [np.unique([lo[axis], hi[axis], *[v for a, b in spans[axis] for v in (a, b)]]) for axis in (0, 1)]
    density = (cfg.REACH[2] - cfg.REACH[0]) / (hi[0] - lo[0])  # depth metres per workspace metre, evenly
    pts = np.array(spots, dtype=float).reshape(-1, 2)
    outside = ~_inside(trash, pts)
    keys = np.column_stack([np.clip(np.searchsorted(knots[axis], pts[outside, axis]), 1, len(knots[axis]) - 1)
                            for axis in (0, 1)])
    found, tally = np.unique(keys, axis=0, return_counts=True)
    out: list[list[tuple[float, float, float]]] = [[], []]
    for axis in (0, 1):  # the pieces just outside the bin: the room blocks keep from its walls
        k = knots[axis]
        below, above = k[k < trash[axis] - 1e-9], k[k > trash[axis + 2] + 1e-9]
        if len(below):
            out[axis].append((float(below[-1]), trash[axis], WALL_CLEARANCE))
        if len(above):
            out[axis].append((trash[axis + 2], float(above[0]), WALL_CLEARANCE))
    for (i, j), n in zip(found.tolist(), tally.tolist(), strict=True):
        piece = (knots[0][i - 1], knots[1][j - 1], knots[0][i], knots[1][j])
        share = (piece[2] - piece[0]) * density
        rows = min(n, max(1, int((share - 2 * HOME_MARGIN) // SPACING) + 1))
        cols = -(-n // rows)
        in_home = piece[0] >= home[0] and piece[2] <= home[2] and piece[1] >= home[1] and piece[3] <= home[3]
        for axis, k, cells in ((0, i, rows), (1, j, cols)):
            need = (cells - 1) * SPACING + 2 * HOME_MARGIN
            if not in_home and _borders(piece, home, axis):
                need += RESERVE
            if need > 2 * HOME_MARGIN:
                out[axis].append((knots[axis][k - 1], knots[axis][k], need))
    return out


def _borders(piece: Box, box: Box, axis: int) -> bool:
    """Whether ``piece`` touches ``box`` end to end along ``axis`` and overlaps it across."""
    other = 1 - axis
    across = piece[other] < box[other + 2] and box[other] < piece[other + 2]
    touches = abs(piece[axis + 2] - box[axis]) < 1e-9 or abs(piece[axis] - box[axis + 2]) < 1e-9
    return across and touches


def map_for(areas: dict[str, SimArea], blocks: Sequence[SimBlock] = ()) -> WorkspaceMap:
    """The workspace map of a world: every area and block inside the reachable strip, each area with
    room for its minimum grid of blocks, and, where the strip allows, each crowded piece of the areas'
    arrangement with room for its blocks side by side.

    The mapped workspace spans [-1.1, 1.1]^2 and every area and block position beyond it.
    """
    boxes = [a.bounds() for a in areas.values()]
    # world x (depth) follows workspace -y; world y (width) follows workspace x
    spans_of: list[list[tuple[float, float]]] = [[(-b[3], -b[1]) for b in boxes],
                                                 [(b[0], b[2]) for b in boxes]]
    spots = [(-b.position[1], b.position[0]) for b in blocks if b.position is not None]
    bounds = []
    for axis in (0, 1):
        ends = [v for span in spans_of[axis] for v in span] + [p[axis] for p in spots]
        bounds.append((min([-WORKSPACE_HALF, *ends]), max([WORKSPACE_HALF, *ends])))
    lo, hi = (bounds[0][0], bounds[1][0]), (bounds[0][1], bounds[1][1])
    def turned(name: str) -> Box:  # an area's bounds as (depth, width) pairs
        x0, y0, x1, y1 = areas[name].bounds()
        return (-y1, x0, -y0, x1)

    crowds = _crowd_spans(spans_of, spots, turned("trash"), turned("home"), lo, hi)
    axes = []
    for axis in (0, 1):
        needed = [(a, b, _room(name, axis)) for name, (a, b) in zip(areas, spans_of[axis], strict=True)]
        for share in CROWD_SHARES:  # crowds that cannot all have their room get less: the areas come first
            extra = [(a, b, need * share) for a, b, need in crowds[axis]]
            fitted = fit_axis(lo[axis], hi[axis], cfg.REACH[axis], cfg.REACH[axis + 2], needed + extra)
            if _has_room(fitted, needed):
                break
        axes.append(fitted)
    return WorkspaceMap(axes[0], axes[1])


def _has_room(axis: AxisMap, spans: Sequence[tuple[float, float, float]]) -> bool:
    """Whether every span ``(a, b, need)`` got at least ``need`` world metres."""
    return all(float(axis.forward(b) - axis.forward(a)) >= need * (1 - 1e-6) for a, b, need in spans)


def _inside(box: tuple[float, float, float, float], pts: Vec, pad: float = 0.0) -> NDArray[np.bool_]:
    return (
        (pts[:, 0] >= box[0] - pad) & (pts[:, 0] <= box[2] + pad)
        & (pts[:, 1] >= box[1] - pad) & (pts[:, 1] <= box[3] + pad)
    )


@functools.cache
def _search_grid() -> tuple[Vec, Vec, Vec]:
    """The search grid over the reachable strip: its x and y coordinates and its points, row-major
    (the ravel of an (x, y) table)."""
    x0, y0, x1, y1 = cfg.REACH
    gx, gy = np.arange(x0, x1 + 1e-9, GRID_STEP), np.arange(y0, y1 + 1e-9, GRID_STEP)
    mx, my = np.meshgrid(gx, gy, indexing="ij")
    return gx, gy, np.column_stack([mx.ravel(), my.ravel()])


_STEPS = np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]], dtype=float)


def _has_lanes(xy: Vec, others: Vec) -> bool:
    """Whether fingers closing along x or along y at ``xy`` meet none of the blocks at ``others``
    (the block at ``xy`` itself, if among them, is ignored)."""
    d = np.abs(others - xy)
    d = d[np.max(d, axis=1) > 1e-9]
    return any(not np.any((d[:, axis] < SPACING - 1e-9) & (d[:, 1 - axis] < LANE)) for axis in (0, 1))


def _far(pts: Vec, others: Vec, spacing: float) -> NDArray[np.bool_]:
    """Which points of ``pts`` (n, 2) are at least ``spacing`` (Chebyshev) from every point of ``others``."""
    if not len(others):
        return np.ones(len(pts), dtype=bool)
    return np.max(np.abs(pts[:, None, :] - others[None, :, :]), axis=2).min(axis=1) >= spacing - 1e-9


class _Layout:
    """Accepted block centres so far, and which candidate points are free for a block of some areas."""

    def __init__(self, wmap: WorkspaceMap, areas: dict[str, SimArea]) -> None:
        self.names = list(areas)
        self.boxes = [wmap.box_to_world(a.box) for a in areas.values()]
        self._box_array = np.array(self.boxes)
        self.bin = wmap.box_to_world(areas["trash"].box)
        self.home = wmap.box_to_world(areas["home"].box)
        self.trash_column = self.names.index("trash")
        self.region = cfg.REACH
        inner = cfg.BIN_WALL + WALL_CLEARANCE
        self.bin_inner = (self.bin[0] + inner, self.bin[1] + inner, self.bin[2] - inner, self.bin[3] - inner)
        self.home_column = self.names.index("home")
        self.home_cells = np.array(home_slots(self.home))
        self.bin_cells = np.array(bin_cells(self.bin, SPACING))
        self._xy = np.zeros((64, 2))
        self.count = 0
        self.xy = self._xy[:0]  # the accepted block centres
        self.z: list[float] = []
        self.gx, self.gy, self.grid = _search_grid()
        shape = (len(self.gx), len(self.gy))
        self.taken = {gap: np.zeros(shape, dtype=bool) for gap in (SPACING, TIGHT_SPACING)}
        self._static: dict[tuple[bytes, bool], NDArray[np.bool_]] = {}

    def membership(self, pts: Vec) -> NDArray[np.bool_]:
        """(n, areas) table: which areas' world boxes contain each point of ``pts`` (n, 2)."""
        b = self._box_array
        x, y = pts[:, 0:1], pts[:, 1:2]
        return (x >= b[:, 0]) & (x <= b[:, 2]) & (y >= b[:, 1]) & (y <= b[:, 3])

    def rules(self, areas: NDArray[np.bool_], relaxed: bool) -> tuple[list[tuple[Box, bool]], list[Vec]]:
        """Where a block inside exactly ``areas`` may start: boxes its centre must be inside (True) or
        outside (False), and points (the home cells) it must keep ``RESERVE`` from.

        The centre stays in the reachable strip, in the boxes of its areas and out of the others; in
        the bin, ``WALL_CLEARANCE`` inside the walls, else that far outside them; outside home, off the
        home cells, which stay free for the blocks collected there. ``relaxed`` rules, for an area
        with no room otherwise, only keep blocks from touching walls and let them near the home cells.
        """
        boxes = [(self.region, True), *((box, bool(a)) for box, a in zip(self.boxes, areas, strict=True))]
        if areas[self.trash_column]:
            boxes.append((self.bin_inner, True))
        else:
            pad = H + 0.003 if relaxed else WALL_CLEARANCE
            x0, y0, x1, y1 = self.bin
            boxes.append(((x0 - pad, y0 - pad, x1 + pad, y1 + pad), False))
        reserved = [] if relaxed or areas[self.home_column] else list(self.home_cells)
        return boxes, reserved

    def free(self, pts: Vec, areas: NDArray[np.bool_], spacing: float,
             relaxed: bool = False) -> NDArray[np.bool_]:
        """Which points of ``pts`` (n, 2) obey the :meth:`rules` and are ``spacing`` from every block."""
        boxes, reserved = self.rules(areas, relaxed)
        ok = np.ones(len(pts), dtype=bool)
        for box, inside in boxes:
            ok &= _inside(box, pts) == inside
        for others, gap in ((np.array(reserved).reshape(-1, 2), RESERVE), (self.xy, spacing)):
            if len(others) and ok.any():
                keep = np.flatnonzero(ok)
                ok[keep] = _far(pts[keep], others, gap)
        return ok

    def point_free(self, xy: Vec, areas: NDArray[np.bool_]) -> bool:
        """:meth:`free` with ``SPACING`` for one point, without array overhead (the common case)."""
        x, y = float(xy[0]), float(xy[1])
        boxes, reserved = self.rules(areas, False)
        if any((b[0] <= x <= b[2] and b[1] <= y <= b[3]) != inside for b, inside in boxes):
            return False
        if any(max(abs(x - cx), abs(y - cy)) < RESERVE - 1e-9 for cx, cy in reserved):
            return False
        return not self.count or bool(_far(xy[None, :], self.xy, SPACING)[0])

    def _near_on_grid(self, xy: Vec, gap: float) -> NDArray[np.bool_]:
        """Grid points closer than ``gap`` (Chebyshev) to ``xy``, as an (x, y) table."""
        return np.outer(np.abs(self.gx - xy[0]) < gap - 1e-9, np.abs(self.gy - xy[1]) < gap - 1e-9)

    def on_grid(self, want: Vec, areas: NDArray[np.bool_], spacing: float, relaxed: bool) -> Vec:
        """The grid points that obey the :meth:`rules` and are ``spacing`` from every block (the grid
        covers the reachable strip), nearest ``want`` first (at most ``GRID_CHOICES``)."""
        key = (areas.tobytes(), relaxed)
        if key not in self._static:
            boxes, reserved = self.rules(areas, relaxed)
            ok = np.ones((len(self.gx), len(self.gy)), dtype=bool)
            for b, inside in boxes:
                inx, iny = (self.gx >= b[0]) & (self.gx <= b[2]), (self.gy >= b[1]) & (self.gy <= b[3])
                ok &= np.outer(inx, iny) == inside
            for cell in reserved:
                ok &= ~self._near_on_grid(cell, RESERVE)
            self._static[key] = ok.ravel()
        pts = self.grid[self._static[key] & ~self.taken[spacing].ravel()]
        distance = np.linalg.norm(pts - want, axis=1)
        nearest = np.argpartition(distance, GRID_CHOICES)[:GRID_CHOICES] if len(pts) > GRID_CHOICES else None
        if nearest is not None:
            pts, distance = pts[nearest], distance[nearest]
        return pts[np.argsort(distance, kind="stable")]

    def candidates(self, want: Vec, areas: NDArray[np.bool_], cells: Vec | None, spacing: float,
                   relaxed: bool) -> Iterator[Vec]:
        """Free spots for a block wanted at ``want``, in order of preference: its area's free cells
        (nearest first), the point itself and its pushes out of the neighbours' way, the grid."""
        if cells is not None and len(cells):
            free = cells[self.free(cells, areas, spacing, relaxed)]
            yield from free[np.argsort(np.linalg.norm(free - want, axis=1), kind="stable")]
        pushed = self.pushed(want, spacing)
        yield from pushed[self.free(pushed, areas, spacing, relaxed)]
        yield from self.on_grid(want, areas, spacing, relaxed)

    def keeps_a_grasp(self, xy: Vec) -> bool:
        """Whether a block at ``xy`` leaves itself and every block near it a free pair of finger lanes
        (along one face axis), as it always does at ``SPACING``."""
        near = self.xy[np.max(np.abs(self.xy - xy), axis=1) < SPACING - 1e-9]
        if not len(near):
            return True
        with_new = np.vstack([self.xy, xy[None, :]])
        return _has_lanes(xy, near) and all(_has_lanes(q, with_new) for q in near)

    def nearest_free(self, want: Vec, areas: NDArray[np.bool_], cells: Vec | None) -> Vec | None:
        """The free spot for a block wanted at ``want`` (see :meth:`candidates`): with ``SPACING``;
        else with ``TIGHT_SPACING`` where every block keeps a grasp; else under relaxed :meth:`rules`;
        else anywhere the blocks do not touch."""
        if (cells is None or not len(cells)) and self.point_free(want, areas):
            return want
        for spacing, relaxed, grasp in PASSES:
            for xy in self.candidates(want, areas, cells, spacing, relaxed):
                if not grasp or self.keeps_a_grasp(xy):
                    return xy
        return None

    def pushed(self, want: Vec, spacing: float) -> Vec:
        """``want`` and the points it is pushed to just out of the way of each block too close to it
        (along an axis, or diagonally), nearest first: where the nearest free spot usually is."""
        near = self.xy[np.max(np.abs(self.xy - want), axis=1) < 2 * spacing]
        out = near[:, None, :] + spacing * _STEPS[None, :, :]
        out[:, :2, 1] = want[1]  # pushed along x, keeping y
        out[:, 2:4, 0] = want[0]  # pushed along y, keeping x
        cand = np.vstack([want[None, :], out.reshape(-1, 2)])
        return cand[np.argsort(np.linalg.norm(cand - want, axis=1), kind="stable")]

    def lowest_tower(self, want: Vec, areas: NDArray[np.bool_]) -> tuple[Vec, float] | None:
        """The base and next free height of the lowest tower inside exactly ``areas`` (nearest ``want``)."""
        if not len(self.xy):
            return None
        same = np.all(self.membership(self.xy) == areas, axis=1)
        if not same.any():
            return None
        bases = np.unique(np.round(self.xy[same], 9), axis=0)
        heights = [sum(1 for p in self.xy if np.allclose(p, b, atol=1e-9)) for b in bases]
        order = min(range(len(bases)), key=lambda k: (heights[k], float(np.linalg.norm(bases[k] - want))))
        base = bases[order]
        below = [z for p, z in zip(self.xy, self.z, strict=True) if np.allclose(p, base, atol=1e-9)]
        return base, max(below) + 2 * H

    def accept(self, xy: Vec, z: float) -> None:
        """Add a block centred at ``xy`` (2,), height ``z``, and mark the grid points too close to it."""
        if self.count == len(self._xy):
            self._xy = np.vstack([self._xy, np.zeros_like(self._xy)])
        self._xy[self.count] = xy
        self.count += 1
        self.xy = self._xy[: self.count]
        self.z.append(z)
        for gap, taken in self.taken.items():
            i0, i1 = np.searchsorted(self.gx, [xy[0] - gap + 1e-9, xy[0] + gap - 1e-9], side="left")
            j0, j1 = np.searchsorted(self.gy, [xy[1] - gap + 1e-9, xy[1] + gap - 1e-9], side="left")
            taken[i0:i1, j0:j1] = True


def _rest_z(in_trash: bool) -> float:
    """Centre height of a resting block: on the bin floor inside the trash area, else on the table."""
    return cfg.REST_Z + (cfg.BIN_FLOOR if in_trash else 0.0)


def place_blocks(
    blocks: Sequence[SimBlock], areas: dict[str, SimArea], wmap: WorkspaceMap, rng: np.random.Generator
) -> list[Placement]:
    """World start positions for ``blocks`` (same order): mapped, then moved apart where needed.

    Blocks in the home or trash area are placed first (on their cells), then the other blocks with
    a position in input order; then blocks without one get a free spot outside every area (or, if
    there is none, outside home and trash) drawn from ``rng``. Raises :class:`LayoutError` only if
    a block's areas have no room at all and hold no block to stack it on.
    """
    layout = _Layout(wmap, areas)
    home_column = layout.home_column
    result: dict[str, Placement] = {}
    placed = [b for b in blocks if b.position is not None]
    if placed:
        spots = wmap.xy_to_world(np.array([b.position[:2] for b in placed if b.position is not None]))
        rows = layout.membership(spots)
    wanted = {b.name: spots[k] for k, b in enumerate(placed)}
    member = {b.name: rows[k] for k, b in enumerate(placed)}

    def small_area_first(block: SimBlock) -> int:
        row = member[block.name]
        return 0 if row[home_column] or row[layout.trash_column] else 1

    for block in sorted(placed, key=small_area_first):
        want, row = wanted[block.name], member[block.name]
        in_trash = bool(row[layout.trash_column])
        cells = layout.bin_cells if in_trash else layout.home_cells if row[home_column] else None
        got, z = layout.nearest_free(want, row, cells), _rest_z(in_trash)
        if got is None:
            tower = layout.lowest_tower(want, row)
            if tower is None:
                inside = ", ".join(n for n, r in zip(layout.names, row, strict=True) if r) or "no area"
                raise LayoutError(f"no room for block {block.name!r} at workspace {tuple(want[:2])} "
                                  f"(inside {inside}): the areas there are too small for a block")
            got, z = tower
        layout.accept(got, z)
        moved = bool(np.max(np.abs(got - want)) > 1e-9) or z > _rest_z(in_trash) + 1e-9
        result[block.name] = Placement(block.name, (float(got[0]), float(got[1]), float(z)), moved)
    for block in blocks:
        if block.position is None:
            got, z = _free_spot(layout, rng)
            layout.accept(got, z)
            result[block.name] = Placement(block.name, (float(got[0]), float(got[1]), z), True)
    return [result[b.name] for b in blocks]


def _free_spot(layout: _Layout, rng: np.random.Generator, tries: int = 400) -> tuple[Vec, float]:
    """A random free point outside every area, else a free point outside home and trash, else a tower."""
    x0, y0, x1, y1 = layout.region
    cands = rng.uniform((x0, y0), (x1, y1), size=(tries, 2))
    outside = np.zeros(len(layout.names), dtype=bool)
    ok = layout.free(cands, outside, SPACING)
    if ok.any():
        return cands[np.flatnonzero(ok)[0]], cfg.REST_Z
    rows = layout.membership(cands)
    trash, home = layout.trash_column, layout.home_column
    for free in np.flatnonzero(~rows[:, trash] & ~rows[:, home]):
        if layout.free(cands[free : free + 1], rows[free], TIGHT_SPACING)[0]:
            return cands[free], cfg.REST_Z
    for k in range(tries):
        tower = layout.lowest_tower(cands[k], rows[k])
        if tower is not None:
            return tower[0], tower[1]
    raise LayoutError("no free spot on the table for a block without a position")
