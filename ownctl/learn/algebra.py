"""Set algebra on rules: refinement, subtraction (``rule_diff``) and merging (``merge_rule``).

These are the paper's building blocks, made deterministic: every
iteration is over canonically ordered literals, never over hash order.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from ownctl.logic.rules import Literal, Rule, implies


def refine(rule: Rule, atoms: Sequence[Literal]) -> list[Rule]:
    """Every one-literal specialisation of ``rule``: per unused atom, ``rule and a``, ``rule and not a``."""
    used = {lit.atom for lit in rule.literals}
    out: list[Rule] = []
    for atom in atoms:
        if atom.atom in used:
            continue
        out.append(rule.with_literal(atom))
        out.append(rule.with_literal(atom.negate()))
    return out


def rule_diff(r1: Rule, r2: Rule) -> list[Rule]:
    """``r1 and not r2`` as a list of satisfiable rules: [r1] if the two are disjoint, empty if r1
    implies r2; otherwise ``r1 and not l`` for each literal ``l`` of r2 that r1 does not imply."""
    if any(not r1.admits(lit) for lit in r2.literals):
        return [r1]
    pieces = [r1.with_literal(lit.negate()) for lit in r2.literals
              if not any(implies(a, lit) for a in r1.literals)]
    return [p for p in pieces if p.is_satisfiable()]


def merge_pair(r1: Rule, r2: Rule) -> Rule | None:
    """``A and c`` with ``A and not c`` gives ``A``; None if the pair does not merge that way."""
    diff = r1.conditions ^ r2.conditions
    if len(diff) == 2:
        a, b = sorted(diff, key=Literal.sort_key)
        if a.negate() == b:
            return Rule(r1.action, tuple(r1.conditions & r2.conditions))
    return None


def merge_rule(
    rules: Sequence[Rule], new: Rule, covers: Callable[[Rule], np.ndarray] | None = None
) -> list[Rule]:
    """Add ``new`` to ``rules`` without redundancy (paper's mergeRule, fixed).

    Complementary pairs merge repeatedly; a rule that is syntactically more specific than another is
    dropped (the general one stays). When ``covers`` is given (rule -> bool mask of the stored
    examples it covers), a rule with at least as many literals as ``new`` whose covered examples
    are a strict subset of ``new``'s is also dropped (the paper's data-driven subsumption).
    """
    current = list(rules)
    changed = True
    while changed:
        changed = False
        for r in current:
            merged = merge_pair(r, new)
            if merged is not None:
                current.remove(r)
                new = merged
                changed = True
                break
    if any(r.conditions <= new.conditions for r in current):
        return current
    kept = [r for r in current if not new.conditions <= r.conditions]
    if covers is not None:
        mask_new = covers(new)

        def subsumed(r: Rule) -> bool:
            mask = covers(r)
            return bool(np.all(mask <= mask_new) and np.any(mask_new & ~mask))

        kept = [r for r in kept if not (len(new.literals) <= len(r.literals) and subsumed(r))]
    return [*kept, new]


def specialising(general: Sequence[Rule], rules: Sequence[Rule]) -> list[Rule]:
    """The ``rules`` that specialise (or equal) one of ``general`` (e.g. a given norm minus an allow norm)."""
    return [r for r in rules if any(g.action == r.action and g.conditions <= r.conditions for g in general)]
