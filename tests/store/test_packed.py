"""Packed priors: what is written is what is read, across chunks, agents and partial rewrites."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ownctl.store import packed as packing
from ownctl.store.engine import Store, locate, open_store


def test_encode_decode_round_trip_keeps_nan_and_codes() -> None:
    p, codes = packing.empty(packing.FLOAT), packing.empty(packing.CODE)
    p[[0, 7, packing.CHUNK - 1]] = [0.25, 1e-300, 0.999]
    codes[[0, 7, packing.CHUNK - 1]] = [1, 2, 1]
    back_p = packing.decode(packing.encode(p, packing.FLOAT), packing.FLOAT)
    back_codes = packing.decode(packing.encode(codes, packing.CODE), packing.CODE)
    assert np.array_equal(back_p, p, equal_nan=True) and np.array_equal(back_codes, codes)
    assert packing.source_names(back_codes[[0, 7, 1]]).tolist() == ["prediction", "base-rate", None]


def test_an_unknown_source_names_the_known_ones() -> None:
    with pytest.raises(ValueError, match="unknown prior source 'guess'; known: prediction, base-rate"):
        packing.source_codes(["prediction", "guess"])


def test_object_ids_map_to_chunk_and_slot() -> None:
    chunk, slot = packing.chunk_of([0, packing.CHUNK - 1, packing.CHUNK, 3 * packing.CHUNK + 5])
    assert chunk.tolist() == [0, 0, 1, 3] and slot.tolist() == [0, packing.CHUNK - 1, 0, 5]


@pytest.fixture(scope="module")
def store(tmp_path_factory: pytest.TempPathFactory) -> Store:
    path = Path(tmp_path_factory.mktemp("priors")) / "p.db"
    st_ = open_store(locate(str(path)), create=True)
    with st_.transaction() as tx:
        for name in ("a", "b", "c"):
            tx.world.add_agent(name, 0.0)
    return st_


class Undo(Exception):
    """Raised to roll a transaction back."""


IDS = st.integers(min_value=1, max_value=3 * packing.CHUNK)
WRITE = st.lists(st.tuples(IDS, st.integers(0, 2), st.one_of(st.none(), st.floats(0.0, 1.0)),
                           st.sampled_from(["prediction", "base-rate"])), min_size=1, max_size=40)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(writes=st.lists(WRITE, min_size=1, max_size=4))
def test_reading_back_gives_the_last_write_of_every_pair(store: Store, writes: list) -> None:
    with pytest.raises(Undo), store.transaction() as tx:
        agents = [a.id for a in tx.world.agents()]
        expected: dict[tuple[int, int], tuple[float, str] | None] = {}
        for k, batch in enumerate(writes):
            last = {(o, agents[j]): (p, s) for o, j, p, s in batch}  # a pair written twice: the last one
            pairs = sorted(last)
            tx.beliefs.write_priors([o for o, _ in pairs], [a for _, a in pairs], [last[q][0] for q in pairs],
                                    [last[q][1] for q in pairs], float(k))
            expected.update({q: None if last[q][0] is None else last[q] for q in pairs})
        objects = sorted({o for o, _ in expected})
        got = tx.beliefs.priors(objects, agents)
        for (o, a), want in expected.items():
            i, j = objects.index(o), agents.index(a)
            if want is None:
                assert np.isnan(got.p[i, j]) and got.source[i, j] is None
            else:
                assert got.p[i, j] == want[0] and got.source[i, j] == want[1]
                assert 0.0 <= got.time[i, j] <= len(writes) - 1
        raise Undo  # roll back: the module's store stays empty for the next example
