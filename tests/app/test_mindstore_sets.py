"""The store's set operations on cell indices agree with numpy's (which import numpy.ma)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from ownctl.app.mindstore import _distinct, _within

cells = st.lists(st.integers(min_value=0, max_value=40), max_size=30).map(lambda v: np.array(v, dtype=int))


@given(cells)
def test_distinct_is_numpys_unique(values: np.ndarray) -> None:
    assert np.array_equal(_distinct(values), np.unique(values))


@given(cells, cells)
def test_within_is_numpys_isin(values: np.ndarray, members: np.ndarray) -> None:
    assert np.array_equal(_within(values, members), np.isin(values, members))
