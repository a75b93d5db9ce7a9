"""Computing once per distinct truth (``ownctl.learn.distinct``) against plain Python: the distinct
rows of a boolean table, and the disjunctions of rule sets read back from the distinct ones."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from ownctl.learn.distinct import DENSE_KINDS, distinct_rows, distinct_unions, unions


def _table(seed: int, rows: int, cols: int, kinds: int) -> np.ndarray:
    """A (rows, cols) boolean table drawn from ``kinds`` distinct random rows, with an all-false last
    row (the padding row of :func:`unions`)."""
    rng = np.random.default_rng(seed)
    palette = rng.random((kinds, cols)) < 0.4
    out = palette[rng.integers(0, kinds, rows)]
    return np.vstack([out, np.zeros((1, cols), dtype=bool)])


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10_000), st.integers(1, 80), st.integers(0, 130), st.integers(1, 90))
def test_distinct_rows_are_the_rows_once_each(seed: int, rows: int, cols: int, kinds: int) -> None:
    table = _table(seed, rows, cols, kinds)
    first, which = distinct_rows(table)
    assert np.array_equal(table[first][which], table)
    expected = {row.tobytes() for row in table}
    assert len(first) == len(expected) == len({table[k].tobytes() for k in first})
    for j, k in enumerate(first):  # each distinct row is given at its first occurrence
        assert k == min(i for i in range(len(table)) if which[i] == j)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10_000), st.integers(1, 70), st.integers(1, 40), st.integers(1, 70),
       st.integers(1, 4), st.integers(1, 300))
def test_distinct_unions_read_back_every_sets_disjunction(seed: int, rules: int, cols: int, kinds: int,
                                                           width: int, sets: int) -> None:
    truth = _table(seed, rules, cols, kinds)
    rng = np.random.default_rng(seed + 1)
    index = rng.integers(-1, rules, (sets, width))  # -1 pads, a rule may repeat in a row
    out, which = distinct_unions(truth, index)
    assert np.array_equal(out[which], unions(truth, index))
    # plain Python: the OR of each row's rules
    for k, row in enumerate(index.tolist()):
        expected = np.zeros(cols, dtype=bool)
        for r in row:
            expected |= truth[r]
        assert np.array_equal(out[which[k]], expected)
    # two sets share a disjunction's slot only if their rules have the same truths
    kinds_of = {k: frozenset(truth[r].tobytes() for r in row if truth[r].any())
                for k, row in enumerate(index.tolist())}
    for a in range(len(index)):
        for b in range(a + 1, min(len(index), a + 20)):
            if kinds_of[a] == kinds_of[b]:
                assert which[a] == which[b]


def test_distinct_unions_beyond_the_dense_and_the_mask_paths() -> None:
    """More kinds of truth than a bit mask holds: the sorted codes give the same disjunctions."""
    for kinds in (DENSE_KINDS + 1, 70, 200):
        truth = np.vstack([np.eye(kinds, dtype=bool), np.zeros((1, kinds), dtype=bool)])
        index = np.random.default_rng(kinds).integers(-1, kinds, (500, 3))
        out, which = distinct_unions(truth, index)
        assert np.array_equal(out[which], unions(truth, index))
        rows = {frozenset(x for x in row if x >= 0) for row in index.tolist()}
        assert len(out) == len(rows)  # one slot per distinct set of (here all distinct) truths
