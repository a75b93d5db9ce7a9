"""Beam search from general to specific rules (the paper's ``ruleSearch``, reference 3.3).

Candidates are scored all at once: a scorer receives the candidates' (C, W, n) truth tables.
Ties keep refinement order (canonical literal order, positive before negated), so the search is
deterministic whatever the hash seed.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.learn.evidence import Evidence
from ownctl.logic.rules import Literal, Rule

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
) -> SearchResult:
    """Refine ``init`` literal by literal, keeping the ``beam`` best, until a rule scores <= threshold.

    With ``stop_at_success`` (the paper's behaviour) the first acceptable rule ends the search, which
    keeps rules general; otherwise the search runs to ``max_conditions`` and returns the best rule.
    """
    truth0 = ev.truth(init)[None]
    best, best_score = init, float(score(truth0, [init])[0])
    ok = all(bool(f(truth0, [init])[0]) for f in filters)
    success = ok and best_score <= threshold
    frontier = [init]
    depth = len(init.literals)
    while frontier and depth < max_conditions:
        if success and stop_at_success:
            break
        seen: set[Rule] = set()
        candidates: list[Rule] = []
        blocks: list[np.ndarray] = []
        for rule in frontier:
            used = {lit.atom for lit in rule.literals}
            lits = [x for a in atoms if a.atom not in used for x in (a, a.negate())]
            fresh = [(rule.with_literal(x), x) for x in lits]
            fresh = [(c, x) for c, x in fresh if c not in seen]
            if not fresh:
                continue
            seen.update(c for c, _ in fresh)
            candidates.extend(c for c, _ in fresh)
            blocks.append(ev.truth(rule)[None] & ev.literal_stack([x for _, x in fresh]))
        depth += 1
        if not candidates:
            break
        truths = np.concatenate(blocks)
        keep = np.ones(len(candidates), dtype=bool)
        for f in filters:
            keep &= f(truths, candidates)
        if not keep.any():
            break
        candidates = [c for c, k in zip(candidates, keep, strict=True) if k]
        truths = truths[keep]
        scores = np.asarray(score(truths, candidates), dtype=float)
        order = np.argsort(scores, kind="stable")
        frontier = [candidates[i] for i in order[:beam]]
        top = float(scores[order[0]])
        if top < best_score - 1e-12:
            best, best_score = candidates[order[0]], top
            success = best_score <= threshold
        elif not success and ok is False and top <= best_score + 1e-12 and top <= threshold:
            best, best_score, success = candidates[order[0]], top, True
    return SearchResult(best, best_score, success)
