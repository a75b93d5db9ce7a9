"""Beam search from general to specific rules (the paper's ``ruleSearch``, reference 3.3).

Candidates are scored all at once: a scorer receives the candidates' (C, W, n) truth tables.
Ties keep refinement order (canonical literal order, positive before negated), so the search is
deterministic whatever the hash seed.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.learn.evidence import Evidence
from ownctl.logic.rules import Literal, Rule, implies

#: scores (C,) of candidates given their stacked truth tables (C, W, n); lower is better
Scorer = Callable[[np.ndarray, Sequence[Rule]], np.ndarray]
#: keep-mask (C,) of candidates given their truth tables
Filter = Callable[[np.ndarray, Sequence[Rule]], np.ndarray]


@dataclass(frozen=True)
class SearchResult:
    """The best rule found, its score, and whether it met the threshold and filters."""

    rule: Rule
    score: float
    success: bool


class Candidates(Sequence[Rule]):
    """The refinements of one search round, built as rules only when looked at.

    Entry ``k`` is ``parents[pairs[k][0]]`` refined by ``lits[pairs[k][1]]``; every candidate of a
    round has the same number of literals (``size``).
    """

    def __init__(
        self, parents: Sequence[Rule], lits: Sequence[Literal], pairs: list[tuple[int, int]]
    ) -> None:
        self.parents, self.lits, self.pairs = parents, lits, pairs
        self.size = len(parents[0].literals) + 1 if parents else 0

    def __len__(self) -> int:
        return len(self.pairs)

    def __getitem__(self, k):  # type: ignore[no-untyped-def]
        if isinstance(k, slice):
            return [self[i] for i in range(*k.indices(len(self)))]
        parent, lit = self.pairs[k]
        return self.parents[parent].with_literal(self.lits[lit])

    def select(self, keep: np.ndarray) -> Candidates:
        """The candidates where ``keep`` is true, in order."""
        return Candidates(self.parents, self.lits, [p for p, k in zip(self.pairs, keep, strict=True) if k])


def sizes(cands: Sequence[Rule]) -> np.ndarray:
    """Number of literals of each candidate, without building rules when they are Candidates."""
    if isinstance(cands, Candidates):
        return np.full(len(cands), cands.size, dtype=float)
    return np.array([len(c.literals) for c in cands], dtype=float)


@functools.lru_cache(maxsize=1 << 16)
def _open(rule: Rule, lits: tuple[Literal, ...]) -> tuple[int, ...]:
    """Indices of the literals that refine ``rule`` into a different, satisfiable rule: an unused
    atom, admitted by the rule (:meth:`Rule.admits`) and not already implied by it. Rules recur
    across searches, so the answer is kept."""
    used = {lit.atom for lit in rule.literals}
    return tuple(
        j for j, x in enumerate(lits)
        if x.atom not in used and rule.admits(x) and not any(implies(a, x) for a in rule.literals)
    )


def _round(ev: Evidence, frontier: list[Rule], lits: list[Literal], exclude: frozenset[Rule]
           ) -> tuple[Candidates, np.ndarray]:
    """Every new one-literal refinement of the frontier (no duplicates, none in ``exclude``).

    A refinement ``parent and x`` repeats an earlier parent's refinement exactly when that parent
    differs from this one by one literal each way, and it is excluded exactly when an excluded rule
    is this parent plus ``x``; both are found with a few set operations per parent.
    """
    table = ev.literal_stack(lits)
    banned = [r.conditions for r in exclude]
    pairs: list[tuple[int, int]] = []
    blocks: list[np.ndarray] = []
    for p, rule in enumerate(frontier):
        base = rule.conditions
        skip: set[Literal] = set()
        for other in [q.conditions for q in frontier[:p]]:  # same size: one literal differs each way
            extra = other - base
            if len(extra) == 1 and len(base - other) == 1:
                skip |= extra
        for other in banned:  # one literal more than this parent, and containing it
            if len(other) == len(base) + 1 and base <= other:
                skip |= other - base
        js = [j for j in _open(rule, tuple(lits)) if lits[j] not in skip]
        if not js:
            continue
        pairs.extend((p, j) for j in js)
        blocks.append(ev.truth(rule)[None] & table[js])
    truths = np.concatenate(blocks) if blocks else np.zeros((0, *ev.worlds.weights.shape), dtype=bool)
    return Candidates(frontier, lits, pairs), truths


def rule_search(
    ev: Evidence,
    init: Rule,
    atoms: Sequence[Literal],
    score: Scorer,
    threshold: float,
    filters: Sequence[Filter] = (),
    beam: int = 3,
    max_conditions: int = 4,
    stop_at_success: bool = True,
    exclude: Sequence[Rule] = (),
) -> SearchResult:
    """Refine ``init`` literal by literal, keeping the ``beam`` best, until a rule scores <= threshold.

    With ``stop_at_success`` (the paper's behaviour) the first acceptable rule ends the search, which
    keeps rules general; otherwise the search runs to ``max_conditions`` and returns the best rule.
    Rules in ``exclude`` are never candidates (the paper's "not already in the rule set" filter).
    """
    banned = frozenset(exclude)
    lits = [x for a in atoms for x in (a, a.negate())]
    truth0 = ev.truth(init)[None]
    best, best_score = init, float(score(truth0, [init])[0])
    ok = init not in banned and all(bool(f(truth0, [init])[0]) for f in filters)
    success = ok and best_score <= threshold
    if not ok:  # a rejected start is no standard: the first acceptable candidate may score worse
        best_score = np.inf
    frontier = [init]
    depth = len(init.literals)
    while frontier and depth < max_conditions:
        if success and stop_at_success:
            break
        candidates, truths = _round(ev, frontier, lits, banned)
        depth += 1
        if not len(candidates):
            break
        keep = np.ones(len(candidates), dtype=bool)
        for f in filters:
            keep &= f(truths, candidates)
        if not keep.any():
            break
        if not keep.all():
            candidates, truths = candidates.select(keep), truths[keep]
        scores = np.asarray(score(truths, candidates), dtype=float)
        order = np.argsort(scores, kind="stable")
        frontier = [candidates[int(i)] for i in order[:beam]]
        top = float(scores[order[0]])
        if top < best_score - 1e-12:
            best, best_score = frontier[0], top
            success = best_score <= threshold
    return SearchResult(best, best_score, success)
