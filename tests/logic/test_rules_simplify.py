"""Simplification drops only implied literals: the simplified rule forbids exactly the same."""

from __future__ import annotations

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import ANY, Literal, Rule, implies

AGENTS = ("a", "b")
COLOURS = ("red", "blue")
ATOMS = [Literal("ownedBy", x) for x in (ANY, *AGENTS, "c")]
ATOMS += [Literal("isColored", x) for x in (ANY, *COLOURS)]


def random_rule(rng: np.random.Generator) -> Rule:
    k = int(rng.integers(0, 4))
    picked = rng.choice(len(ATOMS), size=k, replace=False)
    return Rule("trash", tuple(ATOMS[i] if rng.random() < 0.5 else ATOMS[i].negate() for i in picked))


def random_frame(rng: np.random.Generator, n: int = 12) -> Frame:
    own = rng.choice([0.0, 0.3, 0.5, 1.0], size=(n, len(AGENTS)))
    colours = tuple(rng.choice([None, *COLOURS]) for _ in range(n))
    return Frame(AGENTS, own, colours)


def test_simplified_rules_forbid_exactly_the_same() -> None:
    rng = np.random.default_rng(7)
    changed = 0
    for _ in range(600):
        rule, frame = random_rule(rng), random_frame(rng)
        simple = rule.simplified()
        changed += simple != rule
        assert len(simple.literals) <= len(rule.literals)
        assert np.allclose(p_forbidden([rule], frame), p_forbidden([simple], frame), atol=1e-12), rule.text()
    assert changed > 50  # the generator does produce redundant rules


def test_implication_holds_on_every_object() -> None:
    rng = np.random.default_rng(3)
    lits = [*ATOMS, *(a.negate() for a in ATOMS)]
    colours = tuple(rng.choice([None, *COLOURS]) for _ in range(200))
    frame = Frame(AGENTS, rng.choice([0.0, 1.0], size=(200, 2)), colours)
    for a in lits:
        for b in lits:
            if implies(a, b):  # wherever a holds (crisp ownership), b holds
                both = p_forbidden([Rule("trash", (a, b.negate()))], frame) if a != b else np.zeros(200)
                assert not both.any(), (a.text(), b.text())
    assert implies(Literal("ownedBy", "a"), Literal("ownedBy", ANY))
    assert implies(Literal("isColored", "red"), Literal("isColored", "blue", True))
    assert not implies(Literal("ownedBy", ANY), Literal("ownedBy", "a"))
