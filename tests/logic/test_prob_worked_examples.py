"""Hand-computed values of p_forbidden (docs/architecture.md, section 3)."""

from __future__ import annotations

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.logic.prob import each_rule_truth, enumerate_worlds, p_forbidden, rule_truth
from ownctl.logic.rules import parse_rule

EXACT = 1e-12


def rules(*texts: str):
    return [parse_rule(t) for t in texts]


def frame(agents, own, colours, areas=None, categories=()):
    return Frame(tuple(agents), np.array(own, dtype=float), tuple(colours), areas or {}, tuple(categories))


def test_wallet_owned_by_alexis() -> None:
    wallet = frame(["alexis"], [[0.75]], [None])
    got = p_forbidden(rules("forbid trash if ownedBy any"), wallet)
    assert abs(got[0] - 0.75) < EXACT
    assert abs(p_forbidden(rules("forbid trash if ownedBy alexis"), wallet)[0] - 0.75) < EXACT
    assert abs(p_forbidden(rules("forbid trash if not ownedBy any"), wallet)[0] - 0.25) < EXACT


def test_complementary_rules_cover_every_world() -> None:
    # {ownedBy a and c} or {not ownedBy a and c} is just c: exactly 1 when c holds, 0 otherwise.
    f = frame(["a", "b"], [[0.7, 0.2], [0.7, 0.2], [0.3, 0.9]], ["red", "blue", "red"])
    rs = rules("forbid trash if ownedBy a and isColored red",
               "forbid trash if not ownedBy a and isColored red")
    got = p_forbidden(rs, f)
    assert abs(got[0] - 1.0) < EXACT and abs(got[2] - 1.0) < EXACT
    assert got[1] == 0.0
    assert abs(got[0] - 0.7) > 0.1  # not the old decomposition's answer


def test_shared_atoms_are_not_double_counted() -> None:
    f = frame(["a", "b"], [[0.6, 0.5]], ["red"])
    # The second rule is subsumed by the first: P = P(a), not a noisy-or of the two rules.
    got = p_forbidden(rules("forbid trash if ownedBy a", "forbid trash if ownedBy a and ownedBy b"), f)
    assert abs(got[0] - 0.6) < EXACT
    # a or b = 1 - 0.4 * 0.5
    got = p_forbidden(rules("forbid trash if ownedBy a", "forbid trash if ownedBy b"), f)
    assert abs(got[0] - 0.8) < EXACT
    # any and not a = P(b and not a) = 0.4 * 0.5
    got = p_forbidden(rules("forbid trash if ownedBy any and not ownedBy a"), f)
    assert abs(got[0] - 0.2) < EXACT


def test_empty_rule_set_forbids_nothing() -> None:
    f = frame(["a"], [[1.0], [0.5]], ["red", None])
    got = p_forbidden([], f)
    assert got.shape == (2,) and np.all(got == 0.0)


def test_empty_rule_forbids_always() -> None:
    f = frame(["a"], [[1.0], [0.5], [0.0]], ["red", None, "blue"])
    got = p_forbidden(rules("forbid trash"), f)
    assert np.all(np.abs(got - 1.0) < EXACT)


def test_owned_by_any_is_a_noisy_or() -> None:
    f = frame(["a1", "a2", "a3"], [[0.5, 0.5, 0.5], [0.0, 0.0, 0.0], [0.2, 0.0, 1.0]], ["red"] * 3)
    got = p_forbidden(rules("forbid trash if ownedBy any"), f)
    assert np.all(np.abs(got - [0.875, 0.0, 1.0]) < EXACT)
    # Naming one agent splits it from the folded rest; the answer must not change.
    got = p_forbidden(rules("forbid trash if ownedBy any", "forbid trash if ownedBy a2 and ownedBy a3"), f)
    assert np.all(np.abs(got - [0.875, 0.0, 1.0]) < EXACT)


def test_agent_absent_from_the_frame() -> None:
    f = frame(["a"], [[0.9]], ["red"])
    assert p_forbidden(rules("forbid trash if ownedBy ghost"), f)[0] == 0.0
    assert abs(p_forbidden(rules("forbid trash if not ownedBy ghost"), f)[0] - 1.0) < EXACT
    assert abs(p_forbidden(rules("forbid trash if ownedBy any and not ownedBy ghost"), f)[0] - 0.9) < EXACT


def test_crisp_any_arguments() -> None:
    f = frame(
        ["a"], [[0.0]] * 3, ["red", None, "blue"],
        {"home": np.array([True, False, False]), "desk": np.array([False, False, True])},
        [frozenset({"cup"}), frozenset(), frozenset()],
    )
    assert p_forbidden(rules("forbid trash if isColored any"), f).tolist() == [1.0, 0.0, 1.0]
    assert p_forbidden(rules("forbid trash if not isColored any"), f).tolist() == [0.0, 1.0, 0.0]
    assert p_forbidden(rules("forbid trash if inArea any"), f).tolist() == [1.0, 0.0, 1.0]
    assert p_forbidden(rules("forbid trash if inCategory any"), f).tolist() == [1.0, 0.0, 0.0]
    assert p_forbidden(rules("forbid trash if inArea nowhere"), f).tolist() == [0.0, 0.0, 0.0]
    got = p_forbidden(rules("forbid trash if not isColored red and inArea any"), f)
    assert got.tolist() == [0.0, 0.0, 1.0]


def test_each_rule_truth_is_worked_out_literal_by_literal_and_rule_truth_is_their_union() -> None:
    colours = ["red", "blue", None]
    f = frame(["a", "b"], [[0.6, 0.5], [0.1, 0.9], [0.0, 0.0]], colours)
    rs = rules("forbid trash if ownedBy a and isColored red", "forbid trash if not ownedBy any",
               "forbid trash if ownedBy b and not isColored blue", "forbid trash if isColored blue")
    worlds = enumerate_worlds(f, ("a",), with_other=True)  # atoms: a, and b folded into the other atom

    def holds(k: int, w: int, i: int) -> bool:  # by hand: each literal read off world w and object i
        a, other = (bool(x) for x in worlds.bits[w])
        truth = [[a and colours[i] == "red"], [not (a or other)], [False], [colours[i] == "blue"]][k]
        return all(truth)  # "ownedBy b" is not an atom of these worlds: b owns nothing in them

    each = each_rule_truth(rs, f, worlds)
    assert each.shape == (len(rs), len(worlds.bits), 3)
    for k in range(len(rs)):
        for w in range(len(worlds.bits)):
            for i in range(3):
                assert each[k, w, i] == holds(k, w, i)
    union = rule_truth(rs, f, worlds)
    assert all(union[w, i] == any(holds(k, w, i) for k in range(len(rs)))
               for w in range(len(worlds.bits)) for i in range(3))
    assert rule_truth([], f, worlds).shape == (len(worlds.bits), 3) and not rule_truth([], f, worlds).any()
