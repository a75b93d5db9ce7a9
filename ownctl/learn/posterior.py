"""The posterior over rule sets of one action, under the stated model of :mod:`ownctl.learn.model`.

``P(R | permissions) = P(R) P(permissions | R) / Z``: the prior favours fewer and shorter rules
(each rule costs ``Model.cost(len(rule))`` nats), the likelihood marginalises each object's
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
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from ownctl.config import LearnConfig
from ownctl.learn.distinct import distinct_rows, distinct_unions
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import calibrated_inducer, learning_inputs, subtract
from ownctl.learn.model import Model, compatible, extensions, literal_list, model_for
from ownctl.logic.frame import Frame
from ownctl.logic.kept import Kept
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import ANY, Literal, Rule, implies

MAX_RULES = 3  # rules per set beyond the given ones
POOL = 40  # candidate rules of :func:`rule_posterior`


@functools.lru_cache(maxsize=65536)
def rule_implies(a: Rule, b: Rule) -> bool:
    """Whether every object ``a`` holds for is one ``b`` holds for (each literal of ``b`` follows from
    a literal of ``a``)."""
    return all(any(implies(x, y) for x in a.literals) for y in b.literals)


@dataclass(frozen=True)
class RulePosterior:
    """A normalised posterior over rule sets: ``sets[k]`` has probability ``probabilities[k]``.

    Set ``k`` is ``rules[index[k]]`` (the distinct rules of the space, given rules first; -1 pads a
    smaller set). ``log_weights`` are the unnormalised log posteriors (log prior + log likelihood,
    up to one constant); ``log_evidence`` is their log-sum-exp. Each set includes the given rules.
    """

    action: str
    rules: tuple[Rule, ...]
    index: np.ndarray
    log_weights: np.ndarray
    probabilities: np.ndarray
    log_evidence: float
    allows: tuple[Rule, ...] = ()

    @functools.cached_property
    def sets(self) -> tuple[tuple[Rule, ...], ...]:
        """Every rule set, in the space's order."""
        return tuple(tuple(self.rules[i] for i in row if i >= 0) for row in self.index.tolist())

    def map(self) -> tuple[Rule, ...]:
        """The most probable rule set (the first, in enumeration order, on ties)."""
        row = self.index[int(np.argmax(self.log_weights))]
        return tuple(self.rules[i] for i in row if i >= 0)

    def rule_probabilities(self) -> dict[Rule, float]:
        """P(rule in the rule set) for every rule of some set with positive probability."""
        member = np.zeros((len(self.index), len(self.rules) + 1))
        np.put_along_axis(member, np.where(self.index >= 0, self.index, len(self.rules)), 1.0, axis=1)
        mass = self.probabilities @ member[:, :-1]
        occurs = np.asarray(member[:, :-1].any(axis=0)).tolist()
        return {r: float(m) for r, m, o in zip(self.rules, mass, occurs, strict=True) if o}

    def p_forbidden(self, frame: Frame) -> np.ndarray:
        """P(the action is forbidden) for every object of ``frame``, marginalised over rule sets
        (each set minus the allow norms), with the frame's ownership probabilities.

        Without allow norms, every rule's truth table over the frame's ownership worlds is built
        once and all sets' disjunctions are taken together, a block of objects at a time
        (:meth:`_p_forbidden_tables`); with them (or where a table would leave out some of the
        frame's agents), set by set with :func:`ownctl.logic.prob.p_forbidden`. Both are exact."""
        if not self.allows and frame.n:
            ev = Evidence(frame, np.zeros(frame.n))
            if len(ev.worlds.atoms) >= int((frame.own.sum(axis=0) > 0).sum()):
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
        out = np.zeros(frame.n)
        step = max(1, cells // max(1, len(self.index) * worlds))
        for lo in range(0, frame.n, step):
            part = frame.take(np.arange(lo, min(frame.n, lo + step)))
            ev = Evidence(part, np.zeros(part.n))
            shape = ev.worlds.weights.shape
            used, index = self._used
            none = np.zeros(shape, dtype=bool)  # -1 pads
            truth = np.stack([*(ev.truth(self.rules[k]) for k in used), none])
            joint, which = distinct_unions(truth, index)
            q = np.clip((joint * ev.worlds.weights).sum(axis=-2), 0.0, 1.0)
            out[lo : lo + part.n] = self.probabilities @ q[which]  # summed set by set, as decided
        return np.clip(out, 0.0, 1.0)

    @functools.cached_property
    def _used(self) -> tuple[list[int], np.ndarray]:
        """The rules some set holds (indices into ``rules``, ascending) and ``index`` renumbered
        into that list (-1 still pads): a window holds a few sets of a few rules, and the truth of
        the others need not be computed."""
        present = np.zeros(len(self.rules) + 1, dtype=bool)
        present[self.index] = True  # -1 marks the last slot, which is no rule
        used = np.flatnonzero(present[:-1])
        at = np.full(len(self.rules) + 1, -1, dtype=np.int64)
        at[used] = np.arange(len(used))
        return used.tolist(), at[self.index]

    def window(self, within: float) -> RulePosterior:
        """The rule sets whose log posterior is within ``within`` nats of the most probable one, each
        with the same probability: the sets the permissions cannot tell from the best by a likelihood
        ratio above e^within, given equal say (decisions ``decide.rules = window``,
        docs/norm-families.md). ``within`` 0 keeps the exact ties of the most probable set."""
        if not within >= 0.0:
            raise ValueError(f"within must be a number of nats of at least 0, got {within!r}")
        keep = np.flatnonzero(self.log_weights >= self.log_weights.max() - within)
        lw = self.log_weights[keep]
        return replace(self, index=self.index[keep], log_weights=lw,
                       probabilities=np.full(len(keep), 1.0 / len(keep)),
                       log_evidence=float(np.logaddexp.reduce(lw)))

    def support(self, rule: Rule, frame: Frame) -> float:
        """P(the rule set forbids every object ``rule`` forbids, in every ownership world of
        ``frame`` with positive weight): how sure the posterior is of what ``rule`` says, whichever
        rules say it (rules equal on these objects count alike). 1 - support is the uncertainty of
        a decision resting on ``rule``."""
        ev = Evidence(frame, np.zeros(frame.n))
        mine = ev.truth(rule) & (ev.worlds.weights > 0)
        if not mine.any():
            return min(float(self.probabilities.sum()), 1.0)
        where = np.nonzero(mine)  # the (world, object) cells the rule holds in
        used, index = self._used
        none = np.zeros(len(where[0]), dtype=bool)
        truth = np.stack([*(ev.truth(self.rules[k])[where] for k in used), none])
        joint, which = distinct_unions(truth, index)
        covered: np.ndarray = np.asarray(joint.all(axis=1))[which]
        return min(float(self.probabilities[covered].sum()), 1.0)


def window_p_forbidden(post: RulePosterior, own: Sequence[Rule], frame: Frame, within: float) -> np.ndarray:
    """P(the action is forbidden) for every object of ``frame`` under ``decide.rules = window``: the
    mean over the rule sets within ``within`` nats of the most probable (:meth:`RulePosterior.window`)
    and the learner's own set ``own`` (its rules with the allow norms subtracted), each set counted
    once. Where the near-best sets disagree on an object it is forbidden only as far as they agree,
    which keeps a rule resting on one or two examples from outvoting its equally likely rivals."""
    near = post.window(within)
    p = near.p_forbidden(frame)
    if _has_set(near, own):
        return p
    k = len(near.index)
    out: np.ndarray = (k * p + p_forbidden(list(own), frame)) / (k + 1)
    return out


def window_size(post: RulePosterior, own: Sequence[Rule], within: float) -> int:
    """How many rule sets :func:`window_p_forbidden` averages over."""
    near = post.window(within)
    return len(near.index) + (0 if _has_set(near, own) else 1)


def _has_set(post: RulePosterior, own: Sequence[Rule]) -> bool:
    """Whether some set of ``post``, its allow norms subtracted, is the set ``own``."""
    mine = frozenset(own)
    for rules in post.sets:
        kept = list(rules)
        for allow in post.allows:
            kept = subtract(kept, allow)
        if frozenset(kept) == mine:
            return True
    return False


@dataclass(frozen=True)
class RuleSpace:
    """Sets of at most ``max_rules`` rules of ``pool``, none implying another, plus ``given``."""

    pool: tuple[Rule, ...]
    max_rules: int = MAX_RULES
    given: tuple[Rule, ...] = ()

    def padded(self) -> np.ndarray:
        """Every set as a row of pool indices, -1 padding, by size then in lexicographic order
        (a read-only (K, max_rules) array)."""
        return _sets(self.pool, self.max_rules)


def implication_matrix(rules: Sequence[Rule]) -> np.ndarray:
    """``out[a, b]``: whether rule ``a`` implies rule ``b`` (:func:`rule_implies`), for every pair at
    once: ``a`` implies ``b`` iff each literal of ``b`` is implied by some literal of ``a``, so the
    literal-level relation is built once over the rules' distinct literals and combined by matrix
    products (a pool's 40 rules have 1,560 ordered pairs but rarely 30 distinct literals)."""
    lits = list(dict.fromkeys(x for r in rules for x in r.literals))
    at = {x: k for k, x in enumerate(lits)}
    member = np.zeros((len(rules), len(lits)), dtype=np.int64)
    for i, r in enumerate(rules):
        member[i, [at[x] for x in r.literals]] = 1
    lit_implies = np.zeros((len(lits), len(lits)), dtype=np.int64)
    for i, x in enumerate(lits):
        lit_implies[i] = [implies(x, y) for y in lits]
    reached = (member @ lit_implies) > 0  # reached[a, y]: some literal of a implies literal y
    missing = member @ (~reached).T.astype(np.int64)  # missing[b, a]: literals of b that a leaves open
    out: np.ndarray = (missing == 0).T
    return out


@functools.lru_cache(maxsize=512)
def _sets(pool: tuple[Rule, ...], max_rules: int) -> np.ndarray:
    """:meth:`RuleSpace.padded`, made once per pool (a pure function of the pool's rules)."""
    m = len(pool)
    imp = implication_matrix(pool)
    clash = (imp | imp.T) & ~np.eye(m, dtype=bool)
    width = max(1, max_rules)
    out = [np.full((1, width), -1, dtype=int)]
    level = np.zeros((1, 0), dtype=int)  # the sets of one size, as rows in lexicographic order
    above = np.arange(m)[None, :]
    for size in range(max_rules):
        last = level[:, -1:] if size else np.full((len(level), 1), -1)
        free = (above > last) & ~clash[level].any(axis=1) if size else (above > last)
        rows, cols = np.nonzero(free)  # row-major: each set's extensions in ascending order
        level = np.hstack([level[rows], cols[:, None]])
        out.append(np.hstack([level, np.full((len(level), width - size - 1), -1, dtype=int)]))
    table = np.vstack(out)
    table.setflags(write=False)
    return table


def every_rule(action: str, atoms: Sequence[Literal], max_length: int) -> tuple[Rule, ...]:
    """Every satisfiable rule without implied literals over ``atoms``, up to ``max_length`` literals,
    shortest first, then in canonical order."""
    lits = literal_list(tuple(atoms))
    return tuple(_rule_at(action, lits, row) for row in _every_rule(tuple(atoms), max_length))


def _rule_at(action: str, lits: Sequence[Literal], row: np.ndarray) -> Rule:
    """The rule whose literals are ``lits[row]`` (``row`` padded with -1)."""
    return Rule(action, tuple(lits[x] for x in row.tolist() if x >= 0))


@functools.lru_cache(maxsize=256)
def _made(action: str, atoms: tuple[Literal, ...], max_length: int) -> dict[int, Rule]:
    """The rules of ``action`` made so far from the rows of ``_every_rule(atoms, max_length)``, by
    row: candidates recur from one posterior to the next, and a rule is made once."""
    return {}


@functools.lru_cache(maxsize=256)
def _every_rule(atoms: tuple[Literal, ...], max_length: int) -> np.ndarray:
    """Each rule of :func:`every_rule` (of any action) as the indices of its literals in
    ``literal_list(atoms)``, padded with -1 to ``max_length`` columns (made once per vocabulary;
    the rules themselves are made only for the few that are chosen)."""
    ok = compatible(atoms)
    out: list[tuple[int, ...]] = [()]
    level: list[tuple[int, ...]] = [()]
    for _ in range(max_length):
        level = [(*s, int(x)) for s in level for x in extensions(ok, s, s[-1] // 2 + 1 if s else 0)]
        out += level
    index = np.full((len(out), max(1, max_length)), -1, dtype=int)
    for k, s in enumerate(out):
        index[k, : len(s)] = s
    index.setflags(write=False)
    return index


def _log_weights(ev: Evidence, model: Model, space: RuleSpace, sets: np.ndarray) -> np.ndarray:
    """Unnormalised log posterior of each set (log prior + log likelihood); ``sets`` padded with -1.
    Truth is kept only over the positive-weight pairs of the examples (:attr:`Evidence.pairs`)."""
    costs = np.array([*(model.cost_of(r) for r in space.pool), 0.0])
    prior: np.ndarray = -costs[sets].sum(axis=1)
    wi, ni, _, _ = ev.pairs
    if not len(ni):
        return prior
    truth = np.stack([*(ev.truth(r)[wi, ni] for r in space.pool), np.zeros(len(ni), dtype=bool)])
    base = ev.union(space.given)[wi, ni]
    joint, which = distinct_unions(truth, sets)  # each distinct disjunction's likelihood once
    out = np.empty(len(joint))
    block = max(1, (1 << 22) // len(ni))  # disjunctions per block, to bound memory
    for start in range(0, len(joint), block):
        q = ev.pair_prob(joint[start : start + block] | base)
        out[start : start + block] = -model.nll_terms(ev.t, q).sum(axis=-1)
    total: np.ndarray = out[which] + prior
    return total


def posterior(ev: Evidence, action: str, space: RuleSpace, model: Model,
              allows: Sequence[Rule] = ()) -> RulePosterior:
    """The exact posterior of the stated model over the rule sets of ``space``."""
    sets = space.padded()
    logw = _log_weights(ev, model, space, sets)
    top = float(logw.max())
    weights = np.exp(logw - top)
    z = float(weights.sum())
    every = (*space.given, *space.pool)
    g = len(space.given)
    index = np.hstack([np.broadcast_to(np.arange(g), (len(sets), g)), np.where(sets >= 0, sets + g, -1)])
    probabilities = weights / z
    for array in (index, logw, probabilities):  # shared by every holder of this posterior
        array.setflags(write=False)
    return RulePosterior(action, every, index, logw, probabilities, top + float(np.log(z)), tuple(allows))


def supported_rules(ev: Evidence, action: str, atoms: Sequence[Literal], model: Model, max_length: int,
                    size: int, around: Sequence[Rule] = (), cells: int = 1 << 22) -> tuple[Rule, ...]:
    """The ``size`` rules (up to ``max_length`` literals) whose addition most raises the posterior,
    alone or next to all but one of the rules ``around`` (so alternatives to each of them compete),
    with the rules ``around`` themselves; ties in canonical order.

    Candidates name only the agents the examples' ownership worlds name (a rule naming another
    agent forbids none of the examples, or exactly what the same rule without that literal
    forbids, at a higher cost: never better supported), and are scored a block of at most
    ``cells`` truth values at a time, so the work stays bounded however many agents a store knows."""
    named = set(ev.worlds.atoms)
    kept = tuple(a for a in atoms if a.pred != "ownedBy" or a.arg == ANY or a.arg in named)
    index = _every_rule(kept, max_length)
    lits = literal_list(kept)
    negated = np.r_[np.arange(len(lits)) % 2, 0]
    lengths = (index >= 0).sum(axis=1)
    costs = (np.array([model.cost(n) for n in range(max_length + 1)])[lengths]
             + model.negation_cost * negated[index].sum(axis=1))
    contexts = [()] + [tuple(x for x in around if x != r) for r in around]
    gains = np.zeros((len(contexts), len(index)))
    wi, ni, _, _ = ev.pairs  # truth is kept only over the positive-weight pairs
    if len(ni):
        table = np.concatenate([ev.pair_literals(lits), np.ones((1, len(ni)), dtype=bool)])  # -1: true
        bases = [ev.union(context)[wi, ni] for context in contexts]
        block = max(1, cells // len(ni))
        for lo in range(0, len(index), block):
            rows = index[lo : lo + block]
            truth = table[rows[:, 0]]
            for c in range(1, rows.shape[1]):
                truth = truth & table[rows[:, c]]
            first, which = distinct_rows(truth)  # each distinct truth scored once
            for k, base in enumerate(bases):
                q = ev.pair_prob(truth[first] | base[None])
                gains[k, lo : lo + len(rows)] = model.nll_terms(ev.t, q).sum(axis=-1)[which]
    gains += costs[None, :]
    chosen: dict[Rule, None] = {r: None for r in around}
    made = _made(action, kept, max_length)
    per = max(1, size // len(contexts))
    for gain in gains:
        taken = 0
        for k in np.argsort(gain, kind="stable"):
            if taken >= per:
                break
            rule = made.get(k)
            if rule is None:
                rule = made[k] = _rule_at(action, lits, index[k])
            if rule not in chosen:
                chosen[rule] = None
                taken += 1
    return tuple(chosen)


def rule_posterior(ev: Evidence, action: str, vocab: Vocabulary, cfg: LearnConfig,
                   rules: Sequence[Rule] = (), given: Sequence[Rule] = (), allows: Sequence[Rule] = (),
                   size: int = POOL, max_rules: int = MAX_RULES, max_length: int = 3) -> RulePosterior:
    """The posterior over rule sets for one action's stored permissions ``ev`` (prior ownership),
    on a pool of the ``size`` best supported rules around the current learned ``rules`` (the given
    norms are in every set). ``map()`` is then the most probable set of that space.

    The examples are read through the claim calibration the learner chooses for them
    (:func:`ownctl.learn.induce.calibrated_inducer`), so that the posterior and the learned rules
    rest on the same model.

    A pure function of its arguments' contents, so results are kept by content
    (:meth:`Evidence.content`): valuing questions builds many what-if Minds whose permissions are the
    same (about six in seven of a task's posteriors), and the same inputs give the very same
    (immutable) posterior."""
    key = (*learning_inputs(action, ev, vocab, cfg), tuple(rules), tuple(given), tuple(allows), size,
           max_rules, max_length)
    hit = _posteriors.get(key)
    if hit is not None:
        return hit
    return _posteriors.put(key, _rule_posterior(ev, action, vocab, cfg, rules, given, allows, size,
                                                max_rules, max_length))


POSTERIORS = 256  # posteriors kept by content, least recently used dropped first (each up to ~0.4 MB: a
# pool of 40 rules has ~10,000 sets; on a 4-question task, 128 would compute 20% more of them)
_posteriors: Kept[RulePosterior] = Kept(POSTERIORS)


def _rule_posterior(ev: Evidence, action: str, vocab: Vocabulary, cfg: LearnConfig, rules: Sequence[Rule],
                    given: Sequence[Rule], allows: Sequence[Rule], size: int, max_rules: int,
                    max_length: int) -> RulePosterior:
    """:func:`rule_posterior`, computed."""
    if cfg.learner == "ours":  # on the examples the learner learns from (Evidence.beyond)
        ev = calibrated_inducer(action, ev.beyond(allows)[0], vocab, cfg, tuple(given))[0].ev
    atoms = vocab.atoms()
    model = model_for(atoms, cfg.max_conditions)
    learned = [r for r in rules if r not in set(given)]
    pool = supported_rules(ev, action, atoms, model, min(max_length, cfg.max_conditions), size, learned)
    space = RuleSpace(tuple(r for r in pool if r not in set(given)), max_rules, tuple(given))
    return posterior(ev, action, space, model, allows)
