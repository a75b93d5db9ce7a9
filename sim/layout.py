"""Initial block layout: mapped store positions, nudged apart, and free spots for unplaced blocks.

Every block starts axis-aligned (yaw 0) on the table, or on the bin floor when its position is in
the trash area. Two blocks are far enough apart when their Chebyshev distance is at least
``SPACING``: then an opened gripper fits around either block along both face axes without touching
the other. Blocks in the (small) home area go to the nearest free cell of the home grid
(:func:`home_slots`), the same cells that collected blocks are stacked on; if home holds more blocks
than cells, the extra ones start stacked on the cells. Any other block too close
to an earlier one (or to the bin walls, or outside the reachable square) is moved to the nearest
valid point on rings of growing radius, keeping it inside exactly the same areas, so ``inArea`` is
unchanged. The result depends only on the input order and the seed.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from sim import scene_config as cfg
from sim.errors import LayoutError
from sim.workspace import WORKSPACE_HALF, SimArea, SimBlock, WorkspaceMap

SPACING = 0.02  # minimum Chebyshev distance between block centres (m)
TIGHT_SPACING = 2 * cfg.BLOCK_HALF + 0.003  # fallback when SPACING cannot be met: blocks just do not touch
WALL_CLEARANCE = 0.016  # block centre to a bin wall's face (room for a finger)
HOME_MARGIN = 0.004  # home grid cells keep their centres this far inside the home area
RING_STEP = 0.003
MAX_RINGS = 60


@dataclass(frozen=True)
class Placement:
    """World position (3,) of a block's centre at the start, and whether it was moved."""

    name: str
    position: tuple[float, float, float]
    nudged: bool


def home_slots(home: tuple[float, float, float, float]) -> list[tuple[float, float]]:
    """Centres of the home grid: cells ``SPACING`` apart, centred in the world box ``home``, row-major.

    The default home area (36 mm square) gives a 2 x 2 grid 20 mm apart: fingers fit between cells.
    """
    centre = np.array([(home[0] + home[2]) / 2, (home[1] + home[3]) / 2])
    counts = [max(1, int((home[2 + k] - home[k] - 2 * HOME_MARGIN) // SPACING) + 1) for k in (0, 1)]
    offsets = [(np.arange(n) - (n - 1) / 2) * SPACING for n in counts]
    return [(float(centre[0] + dx), float(centre[1] + dy)) for dx in offsets[0] for dy in offsets[1]]


def _inside(box: tuple[float, float, float, float], xy: np.ndarray, pad: float = 0.0) -> bool:
    return box[0] - pad <= xy[0] <= box[2] + pad and box[1] - pad <= xy[1] <= box[3] + pad


class _Layout:
    """Accumulates accepted block centres and checks candidates against them."""

    def __init__(self, wmap: WorkspaceMap, areas: dict[str, SimArea]) -> None:
        self.wmap = wmap
        self.areas = {name: wmap.box_to_world(a.box) for name, a in areas.items()}
        self.bin = self.areas["trash"]
        edge = WORKSPACE_HALF
        lo, hi = wmap.xy_to_world([-edge, -edge]), wmap.xy_to_world([edge, edge])
        pad = cfg.BLOCK_HALF + 0.002
        self.region = (lo[0] + pad, lo[1] + pad, hi[0] - pad, hi[1] - pad)
        inner = cfg.BIN_WALL + WALL_CLEARANCE  # room for a finger between a block and the inside of a wall
        self.bin_inner = (self.bin[0] + inner, self.bin[1] + inner, self.bin[2] - inner, self.bin[3] - inner)
        self.accepted: list[np.ndarray] = []

    def membership(self, xy: np.ndarray) -> frozenset[str]:
        """Names of the areas whose world box contains ``xy``."""
        return frozenset(name for name, box in self.areas.items() if _inside(box, xy))

    def valid(self, xy: np.ndarray, areas: frozenset[str], spacing: float) -> bool:
        """True if ``xy`` is reachable, clear of walls and blocks, and inside exactly ``areas``."""
        if not _inside(self.region, xy):
            return False
        if "trash" in areas:
            if not _inside(self.bin_inner, xy):
                return False
        elif _inside(self.bin, xy, WALL_CLEARANCE):
            return False
        if self.membership(xy) != areas:
            return False
        return all(np.max(np.abs(xy - other)) >= spacing - 1e-9 for other in self.accepted)

    def nearest_valid(self, xy: np.ndarray, areas: frozenset[str]) -> np.ndarray | None:
        """The first valid point on rings of growing radius around ``xy`` (full, then tight spacing)."""
        for spacing in (SPACING, TIGHT_SPACING):
            if self.valid(xy, areas, spacing):
                return xy
            for ring in range(1, MAX_RINGS + 1):
                radius = ring * RING_STEP
                count = max(8, int(np.ceil(2 * np.pi * radius / RING_STEP)))
                for angle in np.arange(count) * (2 * np.pi / count):
                    cand = xy + radius * np.array([np.cos(angle), np.sin(angle)])
                    if self.valid(cand, areas, spacing):
                        return cand
        return None

    def free_spot(self, rng: np.random.Generator, tries: int = 2000) -> np.ndarray | None:
        """A random valid point outside every area (for blocks the store has no position for)."""
        for _ in range(tries):
            cand = rng.uniform(self.region[:2], self.region[2:])
            if self.valid(cand, frozenset(), SPACING):
                return cand
        return None


def _rest_z(areas: Iterable[str]) -> float:
    """Centre height of a resting block: on the bin floor inside the trash area, else on the table."""
    return cfg.REST_Z + (cfg.BIN_FLOOR if "trash" in areas else 0.0)


def place_blocks(
    blocks: Sequence[SimBlock], areas: dict[str, SimArea], wmap: WorkspaceMap, rng: np.random.Generator
) -> list[Placement]:
    """World start positions for ``blocks`` (same order): mapped, clamped into reach, nudged apart.

    Blocks in the home area are placed first (on home cells), then the other blocks with a position in
    input order; then blocks without one get a random
    free spot drawn from ``rng``. Raises :class:`LayoutError` if a block cannot be placed.
    """
    layout = _Layout(wmap, areas)
    result: dict[str, Placement] = {}
    wanted = {b.name: wmap.xy_to_world(b.position[:2]) for b in blocks if b.position is not None}
    cells = [np.array(c) for c in home_slots(layout.areas["home"])]
    stacks = [0] * len(cells)  # blocks already on each home cell
    home_first = sorted(
        (b for b in blocks if b.name in wanted),
        key=lambda b: "home" not in layout.membership(wanted[b.name]),
    )
    for block in home_first:
        assert block.position is not None
        want = wanted[block.name]
        areas_in = layout.membership(want)
        got, z = None, _rest_z(areas_in)
        if "home" in areas_in and cells:
            lowest = min(stacks)
            cell = min(
                (k for k in range(len(cells)) if stacks[k] == lowest),
                key=lambda k: float(np.linalg.norm(cells[k] - want)),
            )
            if lowest > 0 or layout.valid(cells[cell], areas_in, SPACING):
                got, z = cells[cell], z + 2 * cfg.BLOCK_HALF * lowest  # more blocks than cells: stack them
                stacks[cell] += 1
        if got is None:
            clamped = np.clip(want, layout.region[:2], layout.region[2:])
            got = layout.nearest_valid(clamped, areas_in)
        if got is None:
            raise LayoutError(f"no room for block {block.name!r} near workspace {block.position[:2]}")
        layout.accepted.append(got)
        moved = bool(np.max(np.abs(got - want)) > 1e-9)
        result[block.name] = Placement(block.name, (float(got[0]), float(got[1]), z), moved)
    for block in blocks:
        if block.position is not None:
            continue
        got = layout.free_spot(rng)
        if got is None:
            raise LayoutError(f"no free spot for block {block.name!r}")
        layout.accepted.append(got)
        result[block.name] = Placement(block.name, (float(got[0]), float(got[1]), cfg.REST_Z), True)
    return [result[b.name] for b in blocks]
