"""Plan-view planning: rectangle overlap, grasp directions, home towers and bin drop points."""

from __future__ import annotations

import numpy as np
import pytest

from sim import scene_config as cfg
from sim.baxter import FINGER_THICK
from sim.footprint import Rect, face_yaw, overlap
from sim.layout import SPACING
from sim.planner import (
    DROP_OPENING,
    MAX_TOWER,
    BlockState,
    bin_cells,
    drop_point,
    grasp_yaw,
    home_put_down,
    wall_rects,
)

H = cfg.BLOCK_HALF
Z = cfg.REST_Z
GAP = 2 * H + 0.004  # centres this far apart: the blocks do not touch, but no finger fits between


def _block(i: int, x: float, y: float, z: float = Z, yaw: float = 0.0) -> BlockState:
    return BlockState(i, (x, y, z), yaw)


def _axis(yaw: float) -> float:
    """Closing direction folded into [0, pi): 0 is along x, pi/2 along y."""
    return round(float(yaw % np.pi), 6) % round(np.pi, 6)


def test_overlap_is_symmetric_and_sees_rotation() -> None:
    a = Rect((0.0, 0.0), 0.0, (0.01, 0.01))
    b = Rect((0.0235, 0.0), 0.0, (0.01, 0.01))
    turned = Rect((0.0235, 0.0), np.pi / 4, (0.01, 0.01))  # a corner now reaches x = 0.0094
    assert not overlap(a, b) and not overlap(b, a)
    assert overlap(a, turned) and overlap(turned, a)
    assert overlap(a, b, margin=0.004)


def test_overlap_needs_the_height_spans_to_meet() -> None:
    low = Rect((0.0, 0.0), 0.0, (0.01, 0.01), 0.0, 0.1)
    high = Rect((0.0, 0.0), 0.0, (0.01, 0.01), 0.2, 0.3)
    assert not overlap(low, high) and overlap(low, Rect((0.0, 0.0), 0.0, (0.01, 0.01), 0.05, 0.3))


def test_face_yaw_is_congruent_modulo_a_quarter_turn() -> None:
    for yaw in np.linspace(-4, 4, 17):
        got = face_yaw(float(yaw), 1.0)
        assert abs(got - 1.0) <= np.pi / 4 + 1e-9
        assert np.isclose(np.cos(4 * got), np.cos(4 * yaw)) and np.isclose(np.sin(4 * got), np.sin(4 * yaw))


def test_grasp_closes_across_the_free_axis() -> None:
    target = _block(0, 0.6, 0.0)
    along_x = [_block(1, 0.6 + GAP, 0.0)]  # a neighbour where a finger closing along x would go
    along_y = [_block(1, 0.6, GAP)]
    assert _axis(grasp_yaw(target, along_x, [], 0.0)) == _axis(np.pi / 2)  # type: ignore[arg-type]
    assert _axis(grasp_yaw(target, along_y, [], 0.0)) == _axis(0.0)  # type: ignore[arg-type]
    assert grasp_yaw(target, along_x + [_block(2, 0.6, -GAP)], [], 0.0) is None


def test_grasp_refuses_a_covered_block_and_accepts_a_lone_one() -> None:
    target = _block(0, 0.6, 0.0)
    assert grasp_yaw(target, [_block(1, 0.6, 0.0, Z + 2 * H)], [], 0.0) is None
    assert grasp_yaw(target, [_block(1, 0.6, 0.0, Z - 2 * H)], [], 0.0) is not None  # it sits on a block
    assert grasp_yaw(target, [], [], 0.0) is not None


def test_home_put_down_picks_the_lowest_clear_tower() -> None:
    d = SPACING / 2
    cells = [(0.6 - d, -d), (0.6 - d, d), (0.6 + d, -d), (0.6 + d, d)]
    blocks = [_block(i, x, y) for i, (x, y) in enumerate(cells[:3])] + [_block(3, *cells[0], Z + 2 * H)]
    spot = home_put_down(cells, blocks, 0.0, 0.0)
    assert (
        spot is not None and spot.center[:2] == pytest.approx(cells[3]) and spot.center[2] == pytest.approx(Z)
    )
    blocks.append(_block(4, *cells[3]))
    spot = home_put_down(cells, blocks, 0.0, 0.0)
    assert spot is not None and spot.center == pytest.approx((*cells[1], Z + 2 * H))


def test_home_put_down_gives_up_when_towers_are_full() -> None:
    cell = (0.6, 0.0)
    layers = round(MAX_TOWER / (2 * H))
    tower = [_block(i, *cell, Z + 2 * H * i) for i in range(layers)]
    assert home_put_down([cell], tower, 0.0, 0.0) is None
    assert home_put_down([cell], tower[:-1], 0.0, 0.0) is not None


def test_bin_cells_keep_open_fingers_off_the_walls() -> None:
    box = (0.41, -0.2, 0.51, 0.2)
    cells = bin_cells(box, SPACING)
    assert len(cells) >= 4
    walls = wall_rects(box)
    reach = DROP_OPENING + FINGER_THICK
    for x, y in cells:
        finger_reach = Rect((x, y), 0.0, (reach, reach))
        assert not any(overlap(finger_reach, w) for w in walls)
    centre = ((box[0] + box[2]) / 2, (box[1] + box[3]) / 2)
    distance = [float(np.hypot(x - centre[0], y - centre[1])) for x, y in cells]
    assert distance == sorted(distance)  # centre first
    assert min(np.hypot(a[0] - b[0], a[1] - b[1]) for a in cells for b in cells if a != b) >= SPACING - 1e-9


def test_drop_point_prefers_the_emptiest_usable_cell() -> None:
    cells = [(0.6, 0.15), (0.6 + SPACING, 0.15), (0.6 + 2 * SPACING, 0.15)]
    assert drop_point(cells, []) == (*cells[0], cfg.TABLE_TOP + cfg.BIN_FLOOR)
    assert drop_point(cells, [_block(0, 0.6, 0.15, Z + 0.003)])[:2] == cells[2]  # type: ignore[index]
    assert drop_point(cells, [], lambda spot: spot[0] > 0.65)[:2] == cells[1]  # type: ignore[index]
    assert drop_point(cells, [], lambda spot: False) is None


def test_home_put_down_skips_cells_the_arm_cannot_use() -> None:
    cells = [(0.6, 0.0), (0.6, SPACING)]
    spot = home_put_down(cells, [], 0.0, 0.0, lambda put: put.center[1] > 0.01)
    assert spot is not None and spot.center[:2] == pytest.approx(cells[1])
    assert home_put_down(cells, [], 0.0, 0.0, lambda put: False) is None
