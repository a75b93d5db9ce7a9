"""The workspace map: invertible, inside the reachable strip, and ``inArea`` the same in both worlds."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from sim import scene_config as cfg
from sim.layout import ROOM, SPACING, home_slots, map_for
from sim.planner import bin_cells
from sim.workspace import (
    DEFAULT_HOME,
    DEFAULT_TRASH,
    WORKSPACE_HALF,
    AxisMap,
    SimArea,
    SimBlock,
    WorkspaceMap,
    fit_axis,
    with_default_areas,
)

coords = st.floats(min_value=-5.0, max_value=5.0, allow_nan=False)
boxes = st.tuples(coords, coords, coords, coords)
PAPER = with_default_areas([SimArea("workspace", (-1.0, -1.0, 1.0, 1.0)),
                            SimArea("desk", (0.0, 0.0, 0.5, 0.5))])


@given(st.tuples(coords, coords, coords))
def test_inverse_of_map_is_identity(p: tuple[float, float, float]) -> None:
    for wmap in (WorkspaceMap(), map_for(PAPER)):
        np.testing.assert_allclose(wmap.to_workspace(wmap.to_world(p)), p, atol=1e-9)


@given(st.lists(st.tuples(coords, coords, coords), min_size=1, max_size=5))
def test_map_of_arrays_is_rowwise(points: list[tuple[float, float, float]]) -> None:
    wmap = map_for(PAPER)
    rows = np.array([wmap.to_world(p) for p in points])
    np.testing.assert_allclose(wmap.to_world(points), rows)


@given(boxes, st.tuples(coords, coords))
def test_area_membership_is_the_same_in_both_worlds(box: tuple[float, float, float, float],
                                                    p: tuple[float, float]) -> None:
    area = SimArea("a", box)
    x0, y0, x1, y1 = area.bounds()
    assume(min(abs(p[0] - x0), abs(p[0] - x1), abs(p[1] - y0), abs(p[1] - y1)) > 1e-6)  # not on an edge
    wmap = map_for({**PAPER, "a": area})
    x0, y0, x1, y1 = wmap.box_to_world(box)
    w = wmap.xy_to_world(p)
    assert area.contains(p) == (x0 <= w[0] <= x1 and y0 <= w[1] <= y1)


def test_resting_block_reports_table_height_zero() -> None:
    wmap = map_for(PAPER)
    assert wmap.to_workspace(wmap.to_world([0.3, 0.2, 0.0]))[2] == pytest.approx(0.0)
    assert wmap.to_world([0.3, 0.2, 0.0])[2] == pytest.approx(cfg.REST_Z)


def test_whole_workspace_and_every_area_land_in_the_reachable_strip() -> None:
    far = SimArea("far", (1.5, -3.0, 2.0, -2.5))  # beyond the usual workspace: the map stretches to it
    for areas in (PAPER, {**PAPER, "far": far}):
        wmap = map_for(areas)
        rx0, ry0, rx1, ry1 = cfg.REACH
        for box in [(-WORKSPACE_HALF, -WORKSPACE_HALF, WORKSPACE_HALF, WORKSPACE_HALF)] + [
            a.box for a in areas.values()
        ]:
            bx0, by0, bx1, by1 = wmap.box_to_world(box)
            assert rx0 - 1e-9 <= bx0 < bx1 <= rx1 + 1e-9 and ry0 - 1e-9 <= by0 < by1 <= ry1 + 1e-9


def test_small_areas_get_room_for_blocks_side_by_side() -> None:
    wmap = map_for(PAPER)
    home = wmap.box_to_world(DEFAULT_HOME)
    cells = [(home[2 + k] - home[k] + 1e-9) // SPACING + 1 for k in (0, 1)]
    assert cells[0] >= ROOM["home"][0] and cells[1] >= ROOM["home"][1]
    assert len(home_slots(home)) >= ROOM["home"][0] * ROOM["home"][1]
    uniform = WorkspaceMap().box_to_world(DEFAULT_HOME)
    assert uniform[3] - uniform[1] < (ROOM["home"][1] - 1) * SPACING  # a plain scaling would crowd home
    trash = wmap.box_to_world(DEFAULT_TRASH)
    assert len(bin_cells(trash, SPACING)) >= ROOM["trash"][0] * ROOM["trash"][1]


def test_crowded_pieces_of_an_area_get_room_too() -> None:
    crowd = [SimBlock(f"b{i}", None, (0.3 + 0.01 * i, -0.5, 0.0)) for i in range(12)]  # in no small area
    spread = map_for(PAPER, crowd)
    plain = map_for(PAPER)
    width = [m.box_to_world((0.2, -0.6, 1.0, -0.1)) for m in (spread, plain)]
    assert width[0][3] - width[0][1] > width[1][3] - width[1][1]


def test_home_and_trash_lie_on_the_midline_one_behind_the_other() -> None:
    wmap = map_for(PAPER)
    home, trash = wmap.box_to_world(DEFAULT_HOME), wmap.box_to_world(DEFAULT_TRASH)
    assert trash[2] <= home[0]  # the trash area (large workspace y) is nearer the robot
    for box in (home, trash):
        assert box[1] < 0.05 and box[3] > -0.05  # both arms reach the midline


def test_fit_axis_gives_spans_their_room_and_keeps_the_rest_proportional() -> None:
    axis = fit_axis(-1.0, 1.0, 0.0, 1.0, [(-0.1, 0.1, 0.3), (0.5, 0.9, 0.1)])
    f = axis.forward
    assert f(0.1) - f(-0.1) == pytest.approx(0.3)
    assert f(0.9) - f(0.5) >= 0.1 - 1e-9  # had room to spare: it keeps at least its need
    assert (f(-0.1) - f(-1.0)) / 0.9 == pytest.approx((f(0.5) - f(0.1)) / 0.4)  # the rest: one density
    assert f(-1.0) == pytest.approx(0.0) and f(1.0) == pytest.approx(1.0)
    greedy = fit_axis(-1.0, 1.0, 0.0, 1.0, [(-1.0, 0.0, 0.9), (0.0, 1.0, 0.9)])  # asks for too much
    assert greedy.forward(0.0) == pytest.approx(0.5) and greedy.forward(1.0) == pytest.approx(1.0)


def test_axis_maps_are_checked_and_extrapolate() -> None:
    axis = AxisMap((0.0, 1.0, 2.0), (0.0, 0.5, 2.0))
    assert axis.forward(3.0) == pytest.approx(3.5) and axis.inverse(-0.5) == pytest.approx(-1.0)
    with pytest.raises(ValueError, match="strictly increasing"):
        AxisMap((0.0, 1.0), (1.0, 0.0))
    with pytest.raises(ValueError, match="at least two"):
        AxisMap((0.0,), (0.0,))


def test_default_areas_are_added_only_when_missing() -> None:
    areas = with_default_areas([SimArea("home", (0.2, 0.2, 0.4, 0.4))])
    assert areas["home"].box == (0.2, 0.2, 0.4, 0.4)
    assert areas["trash"].box == DEFAULT_TRASH
