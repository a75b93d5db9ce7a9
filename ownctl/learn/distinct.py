"""Computing once per distinct truth.

Scoring candidate rules and rule sets is a function of their truth over the examples' ownership
worlds alone, and most candidates share their truth with others: on one action's examples the
~2,900 rules of the blocks world's vocabulary up to three literals have a few hundred distinct
truths, and a pool of 40 rules a handful, so a space of ~10,000 rule sets has some hundreds of
distinct disjunctions. :func:`distinct_rows` and :func:`distinct_unions` find them, so that a
likelihood or a probability per object is computed once for each and read back for every
candidate: the very same numbers, in a fraction of the time.
"""

from __future__ import annotations

import numpy as np

DENSE_KINDS = 16  # up to this many kinds of truth, distinct kind sets are found in a 2^kinds table


def distinct_rows(table: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct rows of a boolean ``(R, ...)`` array: ``(first, which)`` with ``table[first]``
    the distinct rows (each at its first occurrence, in an order of their bits) and
    ``table[first][which] == table``. Rows are packed into 64-bit words and sorted as such."""
    flat = np.packbits(table.reshape(len(table), -1), axis=1)
    width = -(-flat.shape[1] // 8)
    words = np.zeros((len(flat), 8 * width), dtype=np.uint8)
    words[:, : flat.shape[1]] = flat
    keys = words.view(np.uint64)
    order = np.lexsort(keys.T[::-1]) if width else np.arange(len(keys))  # stable: first occurrence first
    ranked = keys[order]
    new = np.ones(len(order), dtype=bool)
    new[1:] = (ranked[1:] != ranked[:-1]).any(axis=1)
    which = np.empty(len(order), dtype=np.int64)
    which[order] = np.cumsum(new) - 1
    return order[new], which


def unions(truth: np.ndarray, index: np.ndarray) -> np.ndarray:
    """(K, ...) disjunction of the rows ``index[k]`` of ``truth``, whose last row is all false (so
    that -1 pads a smaller set)."""
    if not index.shape[1]:
        return np.zeros((len(index), *truth.shape[1:]), dtype=bool)
    out: np.ndarray = truth[index[:, 0]]  # a copy (fancy indexing), then or-ed in place
    for c in range(1, index.shape[1]):
        out |= truth[index[:, c]]
    return out


def distinct_unions(truth: np.ndarray, index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The disjunctions of :func:`unions`, one per distinct set of truths, and which one each
    set's is: ``(U, ...)`` and ``(K,)`` with ``unions(truth, index) == out[which]``.

    Each set is reduced to the set of kinds of truth (:func:`distinct_rows`) of its rules, coded as
    one integer; sets with the same code have the same disjunction (two codes may still give equal
    disjunctions, which is only a little work done twice)."""
    first, of = distinct_rows(truth)
    kinds = truth[first]
    ids = of[index]
    code = _kind_sets(ids, int(of[-1]), len(kinds))  # of[-1]: the all-false last row, which pads
    if len(kinds) <= DENSE_KINDS:  # the codes are bit masks below 2^len(kinds): no sort needed
        seen = np.zeros(1 << len(kinds), dtype=bool)
        seen[code] = True
        one = np.empty(len(seen), dtype=np.int64)
        one[code] = np.arange(len(code))  # some set with each code (whichever is written last)
        chosen = one[seen]
        which = (np.cumsum(seen) - 1)[code]
    else:
        chosen, which = np.unique(code, return_index=True, return_inverse=True)[1:]
    return unions(kinds, ids[chosen]), which.reshape(-1)


def _kind_sets(ids: np.ndarray, none: int, radix: int) -> np.ndarray:
    """One integer per row of ``ids`` (kinds in ``range(radix)``), equal for two rows exactly when
    they hold the same kinds other than ``none``: a bit mask while the kinds fit in 63 bits, else the
    sorted, duplicate-free kinds in base ``radix``, renumbered densely before they could overflow."""
    if radix <= 63:
        bits = np.left_shift(np.int64(1), np.arange(radix, dtype=np.int64))
        bits[none] = 0
        out: np.ndarray = np.bitwise_or.reduce(bits[ids], axis=1)
        return out
    ids = np.sort(ids, axis=1)
    if ids.shape[1] > 1:
        later = ids[:, 1:]
        later[later == ids[:, :-1]] = none  # a kind twice says what it says once
        ids.sort(axis=1)
    code = np.zeros(len(ids), dtype=np.int64)
    bound = 1
    for col in ids.T:
        if bound * radix >= 1 << 62:
            code = np.unique(code, return_inverse=True)[1].reshape(-1)
            bound = int(code.max()) + 1
        code = code * radix + col
        bound *= radix
    return code
