"""How the store packs what it holds for every (object, agent) pair: per agent, in chunks of object ids.

A prior and a last-touch time exist for every (object, agent) pair, so a world of 100,000 objects
and 50 agents holds 5 million of each, and refitting one agent's predictor after a claim changes
100,000 priors at once. Stored one row per pair, loading such a world spends most of its time
inserting rows and a claim most of its time rewriting them. The ``priors`` and ``touches`` tables
therefore hold one row per (agent, chunk): object ``id`` lies in chunk ``id // CHUNK`` at slot
``id % CHUNK``, and a row holds the chunk's values as packed arrays (docs/architecture.md,
section 6): float64 little-endian with NaN where nothing is held (a prior's probability, a touch's
time), or one byte per slot with 0 where nothing is held (a prior's source, :data:`SOURCES`).
Reading one object's values reads one chunk per agent; a claim rewrites its agent's prior chunks.

Pure functions over numpy arrays: no I/O here.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: Object ids per chunk: 4,096 float64 values, 32 KiB per array.
CHUNK = 4096

#: The byte code of each prior source (0: no prior held).
SOURCES: tuple[str | None, ...] = (None, "prediction", "base-rate")



def chunk_of(object_ids: Sequence[int] | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(chunk, slot) of each object id."""
    ids = np.asarray(object_ids, dtype=np.int64)
    return ids // CHUNK, ids % CHUNK


#: The packed array types: probabilities and times (NaN: none), source codes (0: none).
FLOAT = np.dtype("<f8")
CODE = np.dtype(np.uint8)


def empty(dtype: np.dtype) -> np.ndarray:
    """A chunk's array that holds nothing: NaN for floats, 0 for codes."""
    return np.full(CHUNK, np.nan, dtype=dtype) if dtype.kind == "f" else np.zeros(CHUNK, dtype=dtype)


def decode(data: bytes, dtype: np.dtype) -> np.ndarray:
    """A stored chunk array as a writable array."""
    return np.frombuffer(data, dtype=dtype).copy()


def encode(values: np.ndarray, dtype: np.dtype) -> bytes:
    """A chunk array in its stored form."""
    return np.ascontiguousarray(values, dtype=dtype).tobytes()


def source_codes(sources: Sequence[str | None] | np.ndarray) -> np.ndarray:
    """The byte code of each source (None: 0); an unknown source names the known ones."""
    names = np.asarray(sources, dtype=object)
    codes = np.zeros(len(names), dtype=np.uint8)
    for code, name in enumerate(SOURCES):
        if name is not None:
            codes[names == name] = code
    bad = (codes == 0) & (names != None)  # noqa: E711 (elementwise comparison with None)
    if bad.any():
        known = ", ".join(s for s in SOURCES if s)
        raise ValueError(f"unknown prior source {names[bad][0]!r}; known: {known}")
    return codes


def source_names(codes: np.ndarray) -> np.ndarray:
    """The source of each byte code (None for 0), as an object array."""
    table = np.array(SOURCES, dtype=object)
    return table[np.asarray(codes, dtype=np.intp)]
