"""The stated model of permissions given rules: a prior over rule sets and a likelihood.

One model serves the default learner (which looks for its most probable rule set) and the posterior
over rule sets (:mod:`ownctl.learn.posterior`):

* **Prior.** A rule set is a set of forbid rules (conjunctions of literals over the store's
  vocabulary, satisfiable and without implied literals). ``log P(R) = -sum over r in R of
  cost(len(r)) + const``, with ``cost(l) = rule_cost + literal_cost * l + count_weight * log N(l)``,
  where ``N(l)`` is the number of such rules of ``l`` literals: each rule pays for being one more
  rule and for its length (and, with ``count_weight`` 1, for which of the rules of its length it is,
  a description-length prior). The defaults (1.5, 1.0, 0) were chosen on tuning norm families and Table 3.
  Each negated literal costs ``negation_cost`` more (0.01: a tie-break between rules that say the
  same on the examples, in favour of positive literals, which forbid fewer other objects).
* **Likelihood.** Ownership atoms are independent per object, with the probabilities the caller
  gives (claims or predictions; the default learner reads them through the calibration of
  :mod:`ownctl.learn.calibration` first); the instructor states what the rules imply, except with
  probability ``noise`` where the permission is the opposite: ``P(t_i = 1 | R) = noise + (1 - 2
  noise) q_i(R)`` with ``q_i(R)`` the exact probability that some rule holds for object ``i``.
  Objects are independent given the rules, so ``log P(t | R)`` is a sum over objects.

The negative log of prior times likelihood (up to a constant) is the *objective* the learner
minimises.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from contextlib import nullcontext
from dataclasses import dataclass

import numpy as np

from ownctl.logic.rules import Literal, Rule, implies

LABEL_NOISE = 0.003
RULE_COST = 1.5
LITERAL_COST = 1.0
COUNT_WEIGHT = 0.0
NEGATION_COST = 0.01


@dataclass(frozen=True)
class Model:
    """Prior and noise of the stated model; ``counts[l]`` = N(l), the number of rules of l literals
    (counted only when ``count_weight`` uses them, else 0; one entry per length up to the longest)."""

    counts: tuple[int, ...]
    noise: float = LABEL_NOISE
    rule_cost: float = RULE_COST
    literal_cost: float = LITERAL_COST
    count_weight: float = COUNT_WEIGHT
    negation_cost: float = NEGATION_COST

    def cost(self, length: int) -> float:
        """``-log`` prior weight of one rule of ``length`` literals (see the module docstring)."""
        n = self.counts[length] if length < len(self.counts) else 0
        return self.rule_cost + self.literal_cost * length + self.count_weight * math.log(max(n, 1))

    def min_cost(self, length: int) -> float:
        """The least cost of a rule of at least ``length`` literals (within the counted lengths)."""
        lengths = range(length, len(self.counts))
        return min((self.cost(k) for k in lengths), default=math.inf)

    def cost_of(self, rule: Rule) -> float:
        """``-log`` prior weight of one rule: its length's cost plus ``negation_cost`` per negated
        literal (a ``not`` is one more word to say)."""
        return self.cost(len(rule.literals)) + self.negation_cost * sum(x.negated for x in rule.literals)

    def rules_cost(self, rules: Sequence[Rule]) -> float:
        """``-log`` prior weight of a rule set (up to the normalising constant)."""
        return sum(self.cost_of(r) for r in rules)

    def nll_terms(self, t: np.ndarray, q: np.ndarray) -> np.ndarray:
        """Per-example ``-log P(t_i | q_i)`` (broadcast over leading axes of ``q``)."""
        p = self.noise + (1 - 2 * self.noise) * q
        # with noise, 0 < p < 1: no logarithm of 0, and no error-state switch to pay for
        with nullcontext() if self.noise > 0 else np.errstate(divide="ignore"):
            out: np.ndarray = -(t * np.log(p) + (1 - t) * np.log1p(-p))
        return out

    def best_q(self, t: np.ndarray) -> np.ndarray:
        """The forbid probability that explains each permission best (its nll is convex in q)."""
        return np.clip((t - self.noise) / (1 - 2 * self.noise), 0.0, 1.0)


@functools.lru_cache(maxsize=256)
def compatible(atoms: tuple[Literal, ...]) -> np.ndarray:
    """``ok[x, y]``: literals ``x`` and ``y`` (index ``2j`` is atom ``j``, ``2j + 1`` its negation) may
    stand in one rule: different atoms, jointly satisfiable, neither implying the other. A rule is
    satisfiable and free of implied literals exactly when its literals are pairwise compatible."""
    lits = literal_list(atoms)
    ok = np.zeros((len(lits), len(lits)), dtype=bool)
    for x, a in enumerate(lits):
        for y, b in enumerate(lits):
            if a.atom == b.atom:
                continue
            one = Rule("find", (a,))
            ok[x, y] = one.admits(b) and not implies(a, b) and not implies(b, a)
    return ok


def literal_list(atoms: Sequence[Literal]) -> tuple[Literal, ...]:
    """Each atom then its negation: literal ``2j`` is atom ``j``, ``2j + 1`` its negation."""
    return tuple(x for a in atoms for x in (a, a.negate()))


def extensions(ok: np.ndarray, lits: tuple[int, ...], start: int) -> np.ndarray:
    """Indices of the literals that extend the rule ``lits`` canonically: literals of atoms from
    ``start`` on, compatible with every literal of the rule."""
    allowed: np.ndarray = np.asarray(ok[list(lits)].all(axis=0)) if lits else np.ones(len(ok), dtype=bool)
    allowed[: 2 * start] = False
    return np.flatnonzero(allowed)


@functools.lru_cache(maxsize=256)
def rule_counts(atoms: tuple[Literal, ...], max_length: int) -> tuple[int, ...]:
    """N(l) for l = 0..max_length: rules over ``atoms`` (positive atoms, each usable with either
    sign) that are satisfiable and carry no implied literal.

    Such a rule is a set of pairwise compatible literals (:func:`compatible`), so N(l) is the number
    of l-cliques of the compatibility graph, counted without listing them (with fifty agents there
    are millions of rules of four literals)."""
    later = np.triu(compatible(atoms), k=1)
    return tuple(_cliques(later, length) for length in range(max_length + 1))


def _cliques(later: np.ndarray, size: int) -> int:
    """The number of ``size``-cliques of the graph whose edges to later nodes are ``later[x, y]``
    (x < y; strictly upper triangular): a clique is counted once, from its first node."""
    if size <= 1:
        return 1 if size == 0 else int(len(later))
    if size == 2:
        return int(later.sum())
    if size == 3:  # edges (x, y) times their common later neighbours, in one product
        m = later.astype(np.float64)
        return int(round(float(((m @ m) * m).sum())))
    return sum(_cliques(later[np.ix_(row, row)], size - 1) for row in later if row.sum() >= size - 1)


def model_for(atoms: Sequence[Literal], max_length: int) -> Model:
    """The model over the vocabulary ``atoms`` with rules of at most ``max_length`` literals."""
    return _model(tuple(atoms), max_length, LABEL_NOISE, RULE_COST, LITERAL_COST, COUNT_WEIGHT, NEGATION_COST)


@functools.lru_cache(maxsize=256)
def _model(atoms: tuple[Literal, ...], max_length: int, noise: float, rule_cost: float, literal_cost: float,
           count_weight: float, negation_cost: float) -> Model:
    # N(l) enters the prior only through count_weight: without it, the rules are not enumerated
    # (with many agents there are hundreds of thousands of them)
    counts = rule_counts(atoms, max_length) if count_weight else (0,) * (max_length + 1)
    return Model(counts, noise, rule_cost, literal_cost, count_weight, negation_cost)
