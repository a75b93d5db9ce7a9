"""``rule_search``: the beam search from general to specific rules.

Scorers here are small tables over a rule's literal set, so each test states exactly which rule the
search must find: the beam keeps a second-best rule that greedy search would drop, the depth bound is
``max_conditions`` (the original allowed one more), ties keep refinement order, and the search is a
pure function of its inputs.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.search import rule_search
from ownctl.logic.frame import Frame
from ownctl.logic.rules import ANY, Literal, Rule

RED, BLUE, HOME = Literal("isColored", "red"), Literal("isColored", "blue"), Literal("inArea", "home")
OWNED = Literal("ownedBy", ANY)


def evidence() -> Evidence:
    frame = Frame(("alexis", "xuan"), np.array([[1.0, 0.0], [0.0, 0.5], [0.2, 0.0], [0.0, 0.0]]),
                  ("red", "blue", "red", None), {"home": np.array([True, False, False, True])})
    return Evidence(frame, [1.0, 0.0, 1.0, 0.0])


def atoms() -> list[Literal]:
    return Vocabulary(("alexis", "xuan"), ("blue", "red"), ("home",)).atoms()


def table(scores: dict[frozenset[Literal], float], default: float = 5.0):  # type: ignore[no-untyped-def]
    """A scorer: the score of a candidate is looked up by its literal set."""

    def score(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
        assert truths.shape[0] == len(cands)
        return np.array([scores.get(c.conditions, default) for c in cands])

    return score


def test_the_beam_keeps_a_second_best_rule_that_greedy_search_drops() -> None:
    ev, start = evidence(), Rule("trash")
    score = table({
        frozenset({RED}): 1.0,                  # best first step, a dead end
        frozenset({HOME}): 2.0,                 # second best first step ...
        frozenset({HOME, BLUE.negate()}): 0.0,  # ... that leads to the only acceptable rule
    })
    greedy = rule_search(ev, start, atoms(), score, 0.0, beam=1)
    assert not greedy.success and greedy.rule == Rule("trash", (RED,)) and greedy.score == 1.0
    wide = rule_search(ev, start, atoms(), score, 0.0, beam=2)
    assert wide.success and wide.rule == Rule("trash", (HOME, BLUE.negate())) and wide.score == 0.0


def longer_is_better(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
    return -np.array([len(c.literals) for c in cands], dtype=float)


def test_rules_never_exceed_max_conditions() -> None:
    ev = evidence()
    for max_conditions in (0, 1, 2, 4):
        result = rule_search(ev, Rule("trash"), atoms(), longer_is_better, -99.0, beam=3,
                             max_conditions=max_conditions, stop_at_success=False)
        assert len(result.rule.literals) == max_conditions  # the original reached max + 1
    start = Rule("trash", (OWNED,))
    result = rule_search(ev, start, atoms(), longer_is_better, -99.0, max_conditions=3, stop_at_success=False)
    assert len(result.rule.literals) == 3 and start.conditions <= result.rule.conditions


def test_stop_at_success_returns_the_first_acceptable_rule() -> None:
    ev = evidence()
    first = rule_search(ev, Rule("trash"), atoms(), longer_is_better, 0.0, stop_at_success=True)
    assert first.success and first.rule == Rule("trash")  # the empty rule already scores <= 0
    best = rule_search(ev, Rule("trash"), atoms(), longer_is_better, 0.0, stop_at_success=False)
    assert best.success and len(best.rule.literals) == 4 and best.score == -4.0


def test_ties_keep_refinement_order() -> None:
    ev = evidence()
    # vocabulary order first: ownedBy before isColored
    tie = table({frozenset({RED}): 0.0, frozenset({OWNED}): 0.0})
    assert rule_search(ev, Rule("trash"), atoms(), tie, 0.0).rule == Rule("trash", (OWNED,))
    # positive before negated
    tie = table({frozenset({RED.negate()}): 0.0, frozenset({RED}): 0.0})
    assert rule_search(ev, Rule("trash"), atoms(), tie, 0.0).rule == Rule("trash", (RED,))
    # `any` before a specific argument
    tie = table({frozenset({Literal("ownedBy", "xuan")}): 0.0, frozenset({OWNED}): 0.0})
    assert rule_search(ev, Rule("trash"), atoms(), tie, 0.0).rule == Rule("trash", (OWNED,))
    # a later candidate must be strictly better to replace the best so far
    flat = table({}, default=1.0)
    result = rule_search(ev, Rule("trash"), atoms(), flat, 0.0)
    assert result.rule == Rule("trash") and not result.success


def test_filters_remove_candidates_before_scoring() -> None:
    ev = evidence()
    score = table({frozenset({RED}): 0.0, frozenset({HOME}): 0.5})

    def no_red(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
        return np.array([RED not in c.conditions for c in cands])

    result = rule_search(ev, Rule("trash"), atoms(), score, 0.5, filters=(no_red,))
    assert result.success and result.rule == Rule("trash", (HOME,))

    def nothing(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
        return np.zeros(len(cands), dtype=bool)

    assert not rule_search(ev, Rule("trash"), atoms(), score, 0.5, filters=(nothing,)).success


def test_scorers_see_exact_truth_tables_of_the_candidates() -> None:
    """The (C, W, n) truth tables handed to the scorer are the candidates' own truth tables."""
    ev = evidence()
    seen: list[tuple[Rule, np.ndarray]] = []

    def spy(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
        seen.extend(zip(cands, truths, strict=True))
        return np.ones(len(cands))

    rule_search(ev, Rule("trash"), atoms(), spy, 0.0, beam=2, max_conditions=2)
    assert len(seen) > 20
    for rule, tab in seen:
        assert np.array_equal(tab, ev.truth(rule)), rule


def test_search_is_a_pure_function_of_its_inputs() -> None:
    rng = np.random.default_rng(3)
    for _ in range(30):
        weights = {frozenset(c.conditions): float(rng.integers(0, 4)) for c in
                   [Rule("trash", (a,)) for a in atoms()] + [Rule("trash", (a.negate(),)) for a in atoms()]}
        score = table(weights, default=3.0)
        thr = float(rng.integers(0, 3))
        runs = {rule_search(evidence(), Rule("trash"), atoms(), score, thr, beam=int(b))
                for b in (3, 3, 3) for _ in range(2)}
        assert len(runs) == 1


def test_excluded_rules_are_never_candidates() -> None:
    ev = evidence()
    score = table({frozenset({RED}): 0.0, frozenset({HOME}): 0.5})
    result = rule_search(ev, Rule("trash"), atoms(), score, 0.5, exclude=[Rule("trash", (RED,))])
    assert result.success and result.rule == Rule("trash", (HOME,))
    # an excluded starting rule is not acceptable either, however well it scores
    start = Rule("trash", (OWNED,))
    flat = table({}, default=0.0)
    result = rule_search(ev, start, atoms(), flat, 0.0, exclude=[start])
    assert result.rule != start and start.conditions < result.rule.conditions and result.success
