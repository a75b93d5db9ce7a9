"""The workspace map: one affine map, invertible, that puts the whole workspace box within reach."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sim import scene_config as cfg
from sim.workspace import (
    DEFAULT_HOME,
    DEFAULT_TRASH,
    WORKSPACE_HALF,
    SimArea,
    WorkspaceMap,
    with_default_areas,
)

coords = st.floats(min_value=-5.0, max_value=5.0, allow_nan=False)


@given(st.tuples(coords, coords, coords))
def test_inverse_of_map_is_identity(p: tuple[float, float, float]) -> None:
    wmap = WorkspaceMap()
    np.testing.assert_allclose(wmap.to_workspace(wmap.to_world(p)), p, atol=1e-9)


@given(st.lists(st.tuples(coords, coords, coords), min_size=1, max_size=5))
def test_map_of_arrays_is_rowwise(points: list[tuple[float, float, float]]) -> None:
    wmap = WorkspaceMap()
    rows = np.array([wmap.to_world(p) for p in points])
    np.testing.assert_allclose(wmap.to_world(points), rows)


def test_map_is_uniform_scale_plus_offset() -> None:
    wmap = WorkspaceMap()
    a, b = np.array([0.1, -0.4, 0.0]), np.array([-0.7, 0.2, 0.3])
    assert np.linalg.norm(wmap.to_world(a) - wmap.to_world(b)) == pytest.approx(
        wmap.scale * np.linalg.norm(a - b)
    )
    assert wmap.to_world([0, 0, 0]).tolist() == pytest.approx(list(wmap.offset))


def test_resting_block_reports_table_height_zero() -> None:
    assert WorkspaceMap().to_workspace([0.6, 0.0, cfg.REST_Z])[2] == pytest.approx(0.0)


def test_whole_workspace_box_lands_in_the_reachable_strip() -> None:
    wmap = WorkspaceMap()
    x0, y0, x1, y1 = wmap.box_to_world((-WORKSPACE_HALF, -WORKSPACE_HALF, WORKSPACE_HALF, WORKSPACE_HALF))
    assert 0.40 <= x0 < x1 <= 0.80
    assert -0.40 <= y0 < y1 <= 0.40
    for box in (DEFAULT_HOME, DEFAULT_TRASH):
        bx0, by0, bx1, by1 = wmap.box_to_world(box)
        assert x0 <= bx0 < bx1 <= x1 and y0 <= by0 < by1 <= y1


def test_area_membership_is_the_same_in_both_worlds() -> None:
    wmap = WorkspaceMap()
    home = SimArea("home", DEFAULT_HOME)
    wx0, wy0, wx1, wy1 = wmap.box_to_world(home.box)
    for p in [(0.0, 0.0), (0.099, -0.099), (0.101, 0.0), (-0.5, 0.5)]:
        w = wmap.xy_to_world(p)
        assert home.contains(p) == (wx0 <= w[0] <= wx1 and wy0 <= w[1] <= wy1)


def test_default_areas_are_added_only_when_missing() -> None:
    areas = with_default_areas([SimArea("home", (0.2, 0.2, 0.4, 0.4))])
    assert areas["home"].box == (0.2, 0.2, 0.4, 0.4)
    assert areas["trash"].box == DEFAULT_TRASH


def test_scale_must_be_positive() -> None:
    with pytest.raises(ValueError, match="scale"):
        WorkspaceMap(scale=0.0)
