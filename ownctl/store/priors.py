"""How the store packs the predicted ownership priors: per agent, in chunks of object ids.

A prior exists for every (object, agent) pair, so a world of 100,000 objects and 50 agents holds 5
million of them, and refitting one agent's predictor after a claim changes 100,000 at once. Stored
one row per pair, loading such a world spends most of its time inserting rows and a claim most of
its time rewriting them. The ``priors`` table therefore holds one row per (agent, chunk): object
``id`` lies in chunk ``id // CHUNK`` at slot ``id % CHUNK``, and a row holds the chunk's
probabilities (float64, little-endian, NaN where no prior is held), their sources (one byte each,
:data:`SOURCES`) and the time of the chunk's last write (docs/architecture.md, section 6).
Reading one object's priors reads one chunk per agent; a claim rewrites its agent's chunks.

Pure functions over numpy arrays: no I/O here.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: Object ids per chunk: 4,096 float64 probabilities, 32 KiB per row.
CHUNK = 4096

#: The byte code of each prior source (0: no prior held).
SOURCES: tuple[str | None, ...] = (None, "prediction", "base-rate")

_P = np.dtype("<f8")


def chunk_of(object_ids: Sequence[int] | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(chunk, slot) of each object id."""
    ids = np.asarray(object_ids, dtype=np.int64)
    return ids // CHUNK, ids % CHUNK


def empty() -> tuple[np.ndarray, np.ndarray]:
    """A chunk that holds no prior: (probabilities all NaN, sources all 0)."""
    return np.full(CHUNK, np.nan, dtype=_P), np.zeros(CHUNK, dtype=np.uint8)


def decode(p: bytes, source: bytes) -> tuple[np.ndarray, np.ndarray]:
    """A stored chunk as writable arrays (probabilities, source codes)."""
    return np.frombuffer(p, dtype=_P).copy(), np.frombuffer(source, dtype=np.uint8).copy()


def encode(p: np.ndarray, source: np.ndarray) -> tuple[bytes, bytes]:
    """A chunk's arrays in their stored form."""
    return np.ascontiguousarray(p, dtype=_P).tobytes(), np.ascontiguousarray(source, dtype=np.uint8).tobytes()


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
