"""The posterior over rule sets of one action, under the stated model of :mod:`ownctl.learn.model`.

``P(R | permissions) = P(R) P(permissions | R) / Z``: the prior favours fewer and shorter rules
(each rule costs ``Model.cost_of(rule)`` nats), the likelihood marginalises each object's
uncertain ownership exactly (independent atoms, as in :mod:`ownctl.logic.prob`) and allows for
instructor noise (``Model.noise``). The default learner's rule set is this model's most probable
one as found by search (:mod:`ownctl.learn.exact`); here the model is normalised over a space of
candidate rule sets and summed, so each rule and each decision gets a probability.

The space (:class:`RuleSpace`): every set of at most ``max_rules`` rules from a pool of candidate
rules, no rule in a set implying another (such a set says what the smaller one says), the given
rules (stated norms) added to every set. :func:`posterior` enumerates it exactly. The pool is
either every rule of the vocabulary up to a length (:func:`every_rule`: the whole model, feasible
for small vocabularies) or the rules the permissions support best (:func:`supported_rules`), whose
truncation error can be measured by widening the pool (``benchmarks/posterior.py``).

API: :func:`rule_posterior` (pool from the data, the learner's rules included) returns a
:class:`RulePosterior` with the most probable rule set (:meth:`RulePosterior.map`), each rule's
posterior probability (:meth:`RulePosterior.rule_probabilities`) and P(forbidden) per object
marginalised over rule sets (:meth:`RulePosterior.p_forbidden`).
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.config import LearnConfig
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import subtract
from ownctl.learn.model import Model, compatible, extensions, literal_list, model_for
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import Literal, Rule, implies

MAX_RULES = 3  # rules per set beyond the given ones
POOL = 40  # candidate rules of :func:`rule_posterior`


def rule_implies(a: Rule, b: Rule) -> bool:
    """Whether every object ``a`` holds for is one ``b`` holds for (each literal of ``b`` follows from
    a literal of ``a``)."""
    return all(any(implies(x, y) for x in a.literals) for y in b.literals)


@dataclass(frozen=True)
class RulePosterior:
    """A normalised posterior over rule sets: ``sets[k]`` has probability ``probabilities[k]``.

    ``log_weights`` are the unnormalised log posteriors (log prior + log likelihood, up to one
    constant); ``log_evidence`` is their log-sum-exp. Each set includes the given rules.
    """

    action: str
    sets: tuple[tuple[Rule, ...], ...]
    log_weights: np.ndarray
    probabilities: np.ndarray
    log_evidence: float
    allows: tuple[Rule, ...] = ()

    def map(self) -> tuple[Rule, ...]:
        """The most probable rule set (the first, in enumeration order, on ties)."""
        return self.sets[int(np.argmax(self.log_weights))]

    def rule_probabilities(self) -> dict[Rule, float]:
        """P(rule in the rule set) for every rule of some set with positive probability."""
        out: dict[Rule, float] = {}
        for rules, p in zip(self.sets, self.probabilities, strict=True):
            for r in rules:
                out[r] = out.get(r, 0.0) + float(p)
        return out

    def p_forbidden(self, frame: Frame) -> np.ndarray:
        """P(the action is forbidden) for every object of ``frame``, marginalised over rule sets
        (each set minus the allow norms), with the frame's ownership probabilities.

        Without allow norms, every rule's truth table over the frame's ownership worlds is built
        once and the sets' disjunctions are taken together, a block of objects at a time
        (:meth:`_p_forbidden_tables`); with them (or beyond the agents a table enumerates), set by
        set with :func:`ownctl.logic.prob.p_forbidden`. Both are exact."""
        if not self.allows and frame.n:
            ev = Evidence(frame, np.zeros(frame.n))
            if len(ev.worlds.atoms) >= sum(1 for m in frame.own.sum(axis=0) if m > 0):
                return self._p_forbidden_tables(frame, len(ev.worlds.bits))
        out = np.zeros(frame.n)
        for rules, p in zip(self.sets, self.probabilities, strict=True):
            if p > 0:
                kept = list(rules)
                for allow in self.allows:
                    kept = subtract(kept, allow)
                out += p * p_forbidden(kept, frame)
        return np.clip(out, 0.0, 1.0)

    def _p_forbidden_tables(self, frame: Frame, worlds: int, cells: int = 1 << 23) -> np.ndarray:
        """:meth:`p_forbidden` from truth tables (``worlds``: at most that many ownership worlds per
        object); ``cells`` bounds the (sets, worlds, objects) block held at once."""
        rules = list(dict.fromkeys(r for s in self.sets for r in s))
        index = {r: k for k, r in enumerate(rules)}
        by_size: dict[int, list[int]] = {}
        for k, s in enumerate(self.sets):
            by_size.setdefault(len(s), []).append(k)
        out = np.zeros(frame.n)
        step = max(1, cells // max(1, len(self.sets) * worlds))
        for lo in range(0, frame.n, step):
            part = frame.take(np.arange(lo, min(frame.n, lo + step)))
            ev = Evidence(part, np.zeros(part.n))
            shape = ev.worlds.weights.shape
            truth = np.stack([ev.truth(r) for r in rules]) if rules else np.zeros((0, *shape), dtype=bool)
            for size, ks in by_size.items():
                union = np.zeros((len(ks), *shape), dtype=bool)
                for c in range(size):
                    union |= truth[np.array([index[self.sets[k][c]] for k in ks], dtype=int)]
                q = np.clip((union * ev.worlds.weights).sum(axis=-2), 0.0, 1.0)
                out[lo:lo + part.n] += self.probabilities[ks] @ q
        return np.clip(out, 0.0, 1.0)

    def support(self, rule: Rule, frame: Frame) -> float:
        """P(the rule set forbids every object ``rule`` forbids, in every ownership world of
        ``frame`` with positive weight): how sure the posterior is of what ``rule`` says, whichever
        rules say it (rules equal on these objects count alike). 1 - support is the uncertainty of
        a decision resting on ``rule``."""
        ev = Evidence(frame, np.zeros(frame.n))
        mine = ev.truth(rule) & (ev.worlds.weights > 0)
        total = 0.0
        for rules, p in zip(self.sets, self.probabilities, strict=True):
            if p > 0 and not (mine & ~ev.union(rules)).any():
                total += float(p)
        return min(total, 1.0)


@dataclass(frozen=True)
class RuleSpace:
    """Sets of at most ``max_rules`` rules of ``pool``, none implying another, plus ``given``."""

    pool: tuple[Rule, ...]
    max_rules: int = MAX_RULES
    given: tuple[Rule, ...] = ()

    def sets(self) -> list[tuple[int, ...]]:
        """Every set as pool indices, by size then in lexicographic order."""
        m = len(self.pool)
        clash = np.zeros((m, m), dtype=bool)
        for i, j in itertools.combinations(range(m), 2):
            a, b = self.pool[i], self.pool[j]
            clash[i, j] = clash[j, i] = rule_implies(a, b) or rule_implies(b, a)
        free = ~clash & np.triu(np.ones((m, m), dtype=bool), 1)  # free[i, j]: i < j may stand together
        out: list[tuple[int, ...]] = [()]
        level = np.zeros((1, 0), dtype=int)
        for _ in range(self.max_rules):
            if not len(level) or not m:
                break
            # extend each set by every later index free with all of its members (lexicographic)
            ok = np.ones((len(level), m), dtype=bool)
            if level.shape[1]:
                ok &= np.arange(m)[None, :] > level[:, -1:]
                for c in range(level.shape[1]):
                    ok &= free[level[:, c]]
            rows, cols = np.nonzero(ok)
            level = np.concatenate([level[rows], cols[:, None]], axis=1)
            out += [tuple(int(x) for x in s) for s in level]
        return out


def every_rule(action: str, atoms: Sequence[Literal], max_length: int) -> tuple[Rule, ...]:
    """Every satisfiable rule without implied literals over ``atoms``, up to ``max_length`` literals,
    shortest first, then in canonical order."""
    return _every_rule(action, tuple(atoms), max_length)


@functools.lru_cache(maxsize=64)
def _every_rule(action: str, atoms: tuple[Literal, ...], max_length: int) -> tuple[Rule, ...]:
    lits = literal_list(atoms)
    return tuple(Rule(action, tuple(lits[x] for x in s)) for s in _rule_indices(atoms, max_length))


@functools.lru_cache(maxsize=64)
def _rule_indices(atoms: tuple[Literal, ...], max_length: int) -> tuple[tuple[int, ...], ...]:
    """:func:`every_rule` as tuples of indices into ``literal_list(atoms)``."""
    ok = compatible(atoms)
    out: list[tuple[int, ...]] = [()]
    level: list[tuple[int, ...]] = [()]
    for _ in range(max_length):
        level = [(*s, int(x)) for s in level for x in extensions(ok, s, s[-1] // 2 + 1 if s else 0)]
        out += level
    return tuple(out)


@functools.lru_cache(maxsize=64)
def _rule_costs(model: Model, atoms: tuple[Literal, ...], max_length: int) -> np.ndarray:
    """``model.cost_of`` of every rule of :func:`every_rule` (literal ``2j + 1`` is a negation)."""
    index = _rule_indices(atoms, max_length)
    return np.array([model.cost(len(s)) + model.negation_cost * sum(x % 2 for x in s) for s in index])


def every_rule_truth(ev: Evidence, atoms: Sequence[Literal], max_length: int) -> np.ndarray:
    """(R, W, n) truth of every rule of :func:`every_rule` on the examples, one conjunction of
    literal tables per literal position for all rules at once."""
    atoms = tuple(atoms)
    index = _rule_indices(atoms, max_length)
    lits = literal_list(atoms)
    stack = ev.literal_stack(lits)
    padded = np.concatenate([stack, np.ones((1, *stack.shape[1:]), dtype=bool)])
    columns = np.full((len(index), max(max_length, 1)), len(lits), dtype=int)
    for k, s in enumerate(index):
        columns[k, : len(s)] = s
    out: np.ndarray = padded[columns[:, 0]]
    for c in range(1, columns.shape[1]):
        out &= padded[columns[:, c]]
    return out


def _log_weights(ev: Evidence, model: Model, space: RuleSpace, sets: Sequence[tuple[int, ...]]
                 ) -> np.ndarray:
    """Unnormalised log posterior of each set (log prior + log likelihood), vectorised by size."""
    shape = ev.worlds.weights.shape
    truth = np.stack([ev.truth(r) for r in space.pool]) if space.pool else np.zeros((0, *shape), dtype=bool)
    base = ev.union(space.given)
    costs = np.array([model.cost_of(r) for r in space.pool])
    out = np.empty(len(sets))
    by_size: dict[int, list[int]] = {}
    for k, s in enumerate(sets):
        by_size.setdefault(len(s), []).append(k)
    for size, ks in by_size.items():
        index = np.array([sets[k] for k in ks], dtype=int).reshape(len(ks), size)
        union = np.broadcast_to(base, (len(ks), *base.shape)).copy()
        for c in range(size):
            union |= truth[index[:, c]]
        q = np.clip((union * ev.worlds.weights).sum(axis=-2), 0.0, 1.0)
        nll = model.nll_terms(ev.t, q).sum(axis=-1)
        out[ks] = -nll - costs[index].sum(axis=1)
    return out


def posterior(ev: Evidence, action: str, space: RuleSpace, model: Model,
              allows: Sequence[Rule] = ()) -> RulePosterior:
    """The exact posterior of the stated model over the rule sets of ``space``."""
    sets = space.sets()
    logw = _log_weights(ev, model, space, sets)
    top = float(logw.max())
    weights = np.exp(logw - top)
    z = float(weights.sum())
    rules = tuple(tuple((*space.given, *(space.pool[i] for i in s))) for s in sets)
    return RulePosterior(action, rules, logw, weights / z, top + float(np.log(z)), tuple(allows))


def supported_rules(ev: Evidence, action: str, atoms: Sequence[Literal], model: Model, max_length: int,
                    size: int, around: Sequence[Rule] = ()) -> tuple[Rule, ...]:
    """The ``size`` rules (up to ``max_length`` literals) whose addition most raises the posterior,
    alone or next to all but one of the rules ``around`` (so alternatives to each of them compete),
    with the rules ``around`` themselves; ties in canonical order."""
    pool = every_rule(action, atoms, max_length)
    truth = every_rule_truth(ev, atoms, max_length)
    costs = _rule_costs(model, tuple(atoms), max_length)
    chosen: dict[Rule, None] = {r: None for r in around}
    contexts = [()] + [tuple(x for x in around if x != r) for r in around]
    per = max(1, size // len(contexts))
    for context in contexts:
        base = ev.union(context)
        q = np.clip(((truth | base[None]) * ev.worlds.weights).sum(axis=-2), 0.0, 1.0)
        gain = model.nll_terms(ev.t, q).sum(axis=-1) + costs
        taken = 0
        for k in np.argsort(gain, kind="stable"):
            if taken >= per:
                break
            if pool[k] not in chosen:
                chosen[pool[k]] = None
                taken += 1
    return tuple(chosen)


def rule_posterior(ev: Evidence, action: str, vocab: Vocabulary, cfg: LearnConfig,
                   rules: Sequence[Rule] = (), given: Sequence[Rule] = (), allows: Sequence[Rule] = (),
                   size: int = POOL, max_rules: int = MAX_RULES, max_length: int = 3) -> RulePosterior:
    """The posterior over rule sets for one action's stored permissions ``ev`` (prior ownership),
    on a pool of the ``size`` best supported rules around the current learned ``rules`` (the given
    norms are in every set). ``map()`` is then the most probable set of that space."""
    atoms = vocab.atoms()
    model = model_for(atoms, cfg.max_conditions)
    learned = [r for r in rules if r not in set(given)]
    pool = supported_rules(ev, action, atoms, model, min(max_length, cfg.max_conditions), size, learned)
    space = RuleSpace(tuple(r for r in pool if r not in set(given)), max_rules, tuple(given))
    return posterior(ev, action, space, model, allows)
