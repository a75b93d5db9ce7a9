"""Exact probability that a rule set forbids an action, under independent ownership atoms.

Possible-worlds semantics (as in ProbLog): ownership atoms ``ownedBy(o, a)`` are independent
Bernoulli variables; the probability that an action is forbidden is the total weight of the worlds
in which at least one rule's conjunction holds. Only agents a rule set names matter one by one; all
other agents fold into one "owned by some other agent" atom, whose probability is their noisy-or.
So a rule set naming k agents and using ``any`` costs 2^(k+1) worlds per object, vectorised over
objects (docs/architecture.md, section 3).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.logic.rules import ANY, Literal, Rule

OTHER = "*"  # the folded atom "owned by an agent no rule names"


@dataclass(frozen=True)
class Worlds:
    """All assignments of the relevant ownership atoms with their weights per object.

    ``bits[w, k]``: atom k true in world w; ``weights[w, i]``: P(world w) for object i;
    ``atoms[k]``: an agent name, or OTHER for the folded atom.
    """

    atoms: tuple[str, ...]
    bits: np.ndarray
    weights: np.ndarray
    probs: np.ndarray  # (K, n): P(atom k) per object


def relevant_atoms(rule_sets: Iterable[Sequence[Rule]]) -> tuple[tuple[str, ...], bool]:
    """The agents named by the rules (sorted) and whether any rule says ``ownedBy any``."""
    named: set[str] = set()
    uses_any = False
    for rules in rule_sets:
        for rule in rules:
            for lit in rule.literals:
                if lit.pred == "ownedBy":
                    if lit.arg == ANY:
                        uses_any = True
                    else:
                        named.add(lit.arg)
    return tuple(sorted(named)), uses_any


def noisy_or(p: np.ndarray | Sequence[float], axis: int = -1) -> np.ndarray:
    """P(at least one holds) of independent ownership atoms with probabilities ``p`` along ``axis``:
    what ``ownedBy any`` means under independent atoms (0 over no atom)."""
    out: np.ndarray = 1.0 - np.prod(1.0 - np.asarray(p, dtype=float), axis=axis)
    return out


def other_probability(frame: Frame, named: Iterable[str]) -> np.ndarray:
    """Noisy-or over the agents not in ``named``: P(owned by some unnamed agent), per object."""
    named = set(named)
    keep = [j for j, a in enumerate(frame.agents) if a not in named]
    if not keep:
        return np.zeros(frame.n)
    return noisy_or(frame.own[:, keep], axis=1)


def enumerate_worlds(frame: Frame, named: Sequence[str], with_other: bool) -> Worlds:
    """Every assignment of the named agents' atoms (and the folded atom) with its weight per object."""
    atoms = (*named, OTHER) if with_other else tuple(named)
    probs = [frame.agent_column(a) for a in named]
    if with_other:
        probs.append(other_probability(frame, named))
    k = len(atoms)
    p = np.array(probs).reshape(k, frame.n)
    bits = ((np.arange(2**k)[:, None] >> np.arange(k)[None, :]) & 1).astype(bool)  # (W, K)
    weights = np.ones((2**k, frame.n))
    for j in range(k):
        weights *= np.where(bits[:, j : j + 1], p[j][None, :], 1.0 - p[j][None, :])
    return Worlds(atoms, bits, weights, p)


def atom_truth(lit: Literal, frame: Frame, worlds: Worlds) -> np.ndarray:
    """Truth of a literal's atom (its sign ignored), broadcastable to (W, n).

    ``ownedBy AGENT`` is that agent's bit in each world ((W, 1)); ``ownedBy any`` is true in every
    world where some atom is (the folded atom included); an agent the worlds do not name owns
    nothing; crisp predicates are the objects' percepts ((1, n)).
    """
    if lit.pred != "ownedBy":
        return frame.crisp(lit)[None, :]
    width = len(worlds.bits)
    if lit.arg == ANY:
        some: np.ndarray = np.asarray(worlds.bits.any(axis=1))
        return some[:, None] if worlds.atoms else np.zeros((width, 1), dtype=bool)
    if lit.arg in worlds.atoms:
        return worlds.bits[:, worlds.atoms.index(lit.arg)][:, None]
    return np.zeros((width, 1), dtype=bool)


def each_rule_truth(rules: Sequence[Rule], frame: Frame, worlds: Worlds) -> np.ndarray:
    """(R, W, n) bool: does rule r's conjunction hold in world w for object i, for each of
    ``rules``; each atom's truth is computed once for them all."""
    width = len(worlds.bits)
    out = np.ones((len(rules), width, frame.n), dtype=bool)
    atoms: dict[tuple[str, str], np.ndarray] = {}
    for k, rule in enumerate(rules):
        for lit in rule.literals:
            if lit.atom not in atoms:
                atoms[lit.atom] = atom_truth(lit, frame, worlds)
            value = atoms[lit.atom]
            out[k] &= ~value if lit.negated else value
    return out


def rule_truth(rules: Sequence[Rule], frame: Frame, worlds: Worlds) -> np.ndarray:
    """(W, n) bool: does some rule's conjunction hold in world w for object i."""
    out: np.ndarray = np.any(each_rule_truth(rules, frame, worlds), axis=0)
    return out


def p_forbidden(rules: Sequence[Rule], frame: Frame) -> np.ndarray:
    """Exact P(some rule holds) for every object of ``frame`` (length n, in [0, 1])."""
    if not rules:
        return np.zeros(frame.n)
    named, uses_any = relevant_atoms([rules])
    worlds = enumerate_worlds(frame, named, uses_any)
    truth = rule_truth(rules, frame, worlds)
    out: np.ndarray = np.clip((worlds.weights * truth).sum(axis=0), 0.0, 1.0)
    return out


def describes_some(rule: Rule, frame: Frame) -> bool:
    """Whether ``rule`` may hold for some object of ``frame``. One that holds for none ("forbid find
    if not inArea any" where every object is in an area, "ownedBy ana and not isColored any" where
    every object has a colour) says nothing about these objects."""
    return bool((p_forbidden([rule], frame) > 0).any())
