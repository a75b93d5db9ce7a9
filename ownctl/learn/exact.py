"""Exact search for the rule that most lowers the objective, and the re-induction built on it.

:func:`best_rule` is branch and bound over the refinement lattice (every satisfiable conjunction
without implied literals, up to ``max_length`` literals, each enumerated once in canonical atom
order): a rule's refinements cover, in every ownership world, a subset of what it covers, so the
objective of any refinement is bounded below by keeping the rule's covered forbid examples and
dropping its covered allow examples; subtrees whose bound cannot beat the prune threshold are cut.
A refinement that covers exactly what its parent covers is skipped (a shorter rule covers the same
for less). Ties go to the canonically first rule (shorter first, then vocabulary order).

:func:`reinduce` adds, greedily, the best rule while it lowers the objective, then drops rules that
no longer pay for themselves, and records every decision with its margin (a :class:`Trace`), so that
:func:`certify_greedy` can prove, for one more example, that re-running it would take the same decisions.
Examples are put in a canonical order first (:func:`canonical_order`), so every floating-point sum,
and so every decision, depends only on the set of examples, not on their arrival order.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.learn.calibration import uncertain
from ownctl.learn.evidence import Evidence
from ownctl.learn.model import Model, compatible, literal_list
from ownctl.logic.prob import atom_truth
from ownctl.logic.rules import Literal, Rule

SLACK = 1e-9  # decisions closer than this to their threshold are never certified
CAP = 0.25  # nats above the best (or above 0) within which subtrees are still explored, for margins


@dataclass(frozen=True)
class Best:
    """The result of :func:`best_rule`: the best rule (None if no candidate beats ``accept``), its
    score, a lower bound on every other candidate's score, and one on every candidate's score."""

    rule: Rule | None
    score: float
    runner_up: float
    lower: float
    twins: tuple[Rule, ...] = ()  # the best rule plus one literal, covering exactly what it covers


def example_digests(ev: Evidence) -> list[bytes]:
    """Each example's identity for the learner: its value, ownership, colour, areas and categories,
    as bytes (equal bytes, equal example)."""
    f = ev.frame
    areas = sorted(f.areas)
    member = np.array([np.asarray(f.areas[a], dtype=bool) for a in areas]).reshape(len(areas), ev.n)
    rows = np.concatenate([ev.t[:, None], np.asarray(f.own, dtype=np.float64), member.T.astype(float)],
                          axis=1)
    tail = [f"{c}|{','.join(sorted(k)) if k else ''}".encode()
            for c, k in zip(f.colors, f.categories, strict=True)]
    return [rows[i].tobytes() + tail[i] for i in range(ev.n)]


def canonical_order(ev: Evidence) -> tuple[Evidence, list[int], list[bytes]]:
    """The same examples sorted by digest (ties keep arrival order), the permutation, the digests."""
    digests = example_digests(ev)
    order = sorted(range(ev.n), key=lambda i: digests[i])
    if order == list(range(ev.n)):
        return ev, order, digests
    return ev.reordered(order), order, [digests[i] for i in order]


@dataclass(frozen=True)
class _Lattice:
    """What :func:`best_rule` needs of the vocabulary and the model, made once per pair: the
    literals, which may stand together, each rule length's prior cost and least cost, each literal's
    negation cost, ``after[x, y]`` (literal ``y``'s atom comes after literal ``x``'s), and the least
    prior cost of one more literal."""

    lits: tuple[Literal, ...]
    ok: np.ndarray
    cost: tuple[float, ...]
    min_cost: tuple[float, ...]
    neg_cost: np.ndarray
    after: np.ndarray
    min_step: float


@functools.lru_cache(maxsize=256)
def _lattice(atoms: tuple[Literal, ...], model: Model, max_length: int) -> _Lattice:
    """The :class:`_Lattice` of ``atoms`` under ``model`` for rules of up to ``max_length`` literals."""
    lits = literal_list(atoms)
    column = np.arange(len(lits))
    return _Lattice(lits, compatible(atoms), tuple(model.cost(k) for k in range(max_length + 1)),
                    tuple(model.min_cost(k) for k in range(max_length + 3)),
                    model.negation_cost * (column % 2),  # literal 2j + 1 is a negation
                    column[None, :] >= (2 * (column // 2 + 1))[:, None],
                    min((model.cost(k + 1) - model.cost(k) for k in range(max_length)), default=math.inf))


def best_rule(ev: Evidence, action: str, base: Sequence[Rule], atoms: Sequence[Literal], model: Model,
              max_length: int, accept: float = 0.0, weight: np.ndarray | None = None) -> Best:
    """The rule whose addition to ``base`` most lowers the objective (score = change of the
    objective, its own prior cost included), if that change is below ``accept``. ``weight``
    multiplies each example's likelihood term (default 1: the objective itself).

    Rules are searched as tuples of literal indices (:func:`ownctl.learn.model.literal_list`), level
    by level, every level's candidates scored at once.
    """
    lattice = _lattice(tuple(atoms), model, max_length)
    lits, ok, cost, min_cost = lattice.lits, lattice.ok, lattice.cost, lattice.min_cost
    neg_cost, after = lattice.neg_cost, lattice.after
    # only (world, example) pairs of positive weight matter: truth tables are kept over those pairs
    wi, ni, _, _ = ev.pairs
    table = ev.pair_literals(lits)  # (2A, P)
    base_truth = ev.union(base)[wi, ni]
    t = ev.t
    w = np.ones(ev.n) if weight is None else weight
    sign = np.where(t >= 0.5, 1.0, -1.0) if np.all((t == 0) | (t == 1)) else None

    def nll(q: np.ndarray) -> np.ndarray:
        """Weighted likelihood terms summed over examples, for each row of forbid probabilities."""
        if sign is None:
            total: np.ndarray = (w * model.nll_terms(t, q)).sum(axis=-1)
            return total
        p = model.noise + (1 - 2 * model.noise) * q
        signed: np.ndarray = -(w * np.log(np.where(sign > 0, p, 1.0 - p))).sum(axis=-1)
        return signed

    q0 = ev.pair_prob(base_truth[None])[0]
    base_nll = float(nll(q0[None])[0])
    qstar = model.best_q(t)
    n_lits = len(lits)
    negs = np.zeros(1)  # per node: the negation cost of its literals
    best_at: tuple[int, int] | None = None  # (level, node index) of the best rule
    best, second, pruned = math.inf, math.inf, math.inf
    twin_pruned = math.inf  # a bound on the refinements of twins, from their parents' bounds
    # per level: (level, parent, literal, score) arrays of the children covering what their parent covers
    twins: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]] = []
    levels: list[tuple[np.ndarray, np.ndarray]] = []  # per level: (parent index, added literal)
    allowed = np.ones((1, n_lits), dtype=bool)  # literals each node may still be extended with
    truths = np.ones((1, len(wi)), dtype=bool)
    for length in range(max_length + 1):
        q = ev.pair_prob(truths | base_truth[None])
        scores = nll(q) - base_nll + cost[length] + negs
        top_k = int(np.argmin(scores))  # the first of the lowest: canonical order among equal scores
        top = float(scores[top_k])
        if top < best:
            scores[top_k] = math.inf  # the lowest of the others, then the score back
            second = min(second, best, float(scores.min()))
            scores[top_k] = top
            best, best_at = top, (length, top_k)
        else:
            second = min(second, top)
        if length == max_length:
            break
        lo_nll = nll(np.minimum(np.maximum(qstar[None], q0[None]), q)) - base_nll  # clipped to [q0, q]
        bounds = lo_nll + min_cost[length + 1] + negs
        keep = bounds < min(best, accept) + CAP
        if not keep.all():
            pruned = min(pruned, float(bounds[~keep].min()))
        parents, added = np.nonzero(allowed & keep[:, None])  # in canonical (lexicographic) order
        if not len(added):
            break
        child = truths[parents] & table[added]
        same = (child == truths[parents]).all(axis=1)
        if same.any():  # covers what its parent covers, for a higher cost: never the best
            k_same = parents[same]
            twins.append((length, k_same, added[same],
                          scores[k_same] + cost[length + 1] - cost[length] + neg_cost[added[same]]))
            # a twin's refinements are refinements of its parent with two literals more
            twin_low = float((lo_nll[k_same] + negs[k_same]).min()) + min_cost[length + 2]
            twin_pruned = min(twin_pruned, twin_low)
            parents, added, child = parents[~same], added[~same], child[~same]
        if not len(added):
            break
        levels.append((parents, added))
        allowed = allowed[parents] & ok[added] & after[added]
        negs = negs[parents] + neg_cost[added]
        truths = child
    # a twin's refinement covers what its parent's refinement without the twin's literal covers, for
    # at least one literal's cost more, and no candidate scores below min(best, accept + CAP)
    # (subtrees were cut only above that): either bound holds
    pruned = min(pruned, max(twin_pruned, min(best, accept + CAP) + lattice.min_step))
    if best_at is None or best >= accept:
        lower = min(best, pruned, *(float(x[3].min()) for x in twins))
        return Best(None, best, lower, lower)
    level, k = best_at
    found: list[int] = []
    for parents, added in reversed(levels[:level]):
        found.append(int(added[k]))
        k = int(parents[k])
    rule = Rule(action, tuple(lits[x] for x in reversed(found)))
    mine: list[int] = []
    others = math.inf
    for lv, k_same, added_same, values in twins:
        of_best = (k_same == best_at[1]) if lv == best_at[0] else np.zeros(len(k_same), dtype=bool)
        mine += [int(x) for x in added_same[of_best]]
        if not of_best.all():
            others = min(others, float(values[~of_best].min()))
    return Best(rule, best, min(second, pruned, others), min(best, pruned),
                tuple(rule.with_literal(lits[x]) for x in mine))

@dataclass(frozen=True)
class Step:
    """One greedy addition: to ``before`` the learner added ``rule`` with ``score`` (< 0); every
    other candidate scored at least ``score + margin``."""

    before: tuple[Rule, ...]
    rule: Rule
    score: float
    margin: float  # over every candidate but the twins
    twins: tuple[tuple[Rule, float], ...] = ()  # the chosen rule's twins and their scores


@dataclass(frozen=True)
class Drop:
    """One pruning decision on ``rule`` within ``current``: ``value`` = objective change of
    removing it (removed when <= 0)."""

    current: tuple[Rule, ...]
    rule: Rule
    value: float


@dataclass(frozen=True)
class Trace:
    """Every decision of one re-induction, enough to certify it for one more example."""

    steps: tuple[Step, ...]
    stop: tuple[tuple[Rule, ...], float] | None  # (rules, lower bound of every candidate's score)
    drops: tuple[Drop, ...]
    result: tuple[Rule, ...]
    allow_weight: float = 1.0  # the weight of allow examples in the greedy scoring
    objective: float = 0.0  # of the result (likelihood and prior, unweighted)
    swaps: tuple[Step, ...] = ()  # each learned rule, in turn, replaced by the best rule beside the others


def _objective_nll(model: Model, ev: Evidence, rules: Sequence[Rule]) -> float:
    return float(model.nll_terms(ev.t, ev.q(rules)).sum())


def _weights(ev: Evidence, allow_weight: float) -> np.ndarray:
    """Scoring weight per example: ``allow_weight`` for an allow (value 0), 1 for a forbid."""
    return 1.0 + (allow_weight - 1.0) * (1.0 - ev.t)


def objective(model: Model, ev: Evidence, rules: Sequence[Rule]) -> float:
    """``-log`` (likelihood x prior) of ``rules`` for the examples, up to a constant."""
    return _objective_nll(model, ev, rules) + model.rules_cost(rules)


def reinduce_greedy(ev: Evidence, action: str, given: Sequence[Rule], atoms: Sequence[Literal],
                    model: Model, max_length: int, max_rules: int, allow_weight: float = 1.0,
                    known: Partial | None = None) -> Trace:
    """Greedy covering around the ``given`` rules (kept as they are), traced: add the rule that most
    lowers the objective, with allow examples weighted ``allow_weight`` in that choice, while it
    lowers it; then, when it learned several rules, replace each, in turn, by the best rule beside
    the others (up to :data:`SWAP_PASSES` passes, so that an early greedy choice can give way); then
    drop, in turn, each learned rule whose removal does not raise the objective.
    ``known``: decisions already proved for these examples (:func:`certify_greedy`), not searched again."""
    weight = _weights(ev, allow_weight)
    steps: list[Step] = list(known.steps) if known else []
    current = (*steps[-1].before, steps[-1].rule) if steps else tuple(given)
    stop = known.stop if known else None
    while stop is None and len(steps) < max_rules:
        found = best_rule(ev, action, current, atoms, model, max_length, weight=weight)
        if found.rule is None:
            stop = (current, found.lower)
            break
        steps.append(_step(model, current, found))
        current = (*current, found.rule)
    fixed = tuple(r for r in current if r in given)
    learned = [r for r in current if r not in given]
    swaps: list[Step] = []
    for _ in range(SWAP_PASSES if len(learned) >= 2 else 0):  # alone, a rule is the best one already
        changed, k = False, 0
        while k < len(learned):
            others = (*fixed, *learned[:k], *learned[k + 1:])
            found = best_rule(ev, action, others, atoms, model, max_length, math.inf, weight)
            assert found.rule is not None  # every rule is accepted
            swaps.append(_step(model, others, found))
            if found.rule in others:  # the others do without it
                learned.pop(k)
                changed = True
                continue
            if found.rule != learned[k]:
                learned[k] = found.rule
                changed = True
            k += 1
        if not changed:
            break
    current = (*fixed, *learned)
    drops: list[Drop] = []
    for rule in [r for r in current if r not in given]:
        rest = tuple(r for r in current if r != rule)
        value = _objective_nll(model, ev, rest) - _objective_nll(model, ev, current) - model.cost_of(rule)
        drops.append(Drop(current, rule, value))
        if value <= 0:
            current = rest
    return Trace(tuple(steps), stop, tuple(drops), current, allow_weight, objective(model, ev, current),
                 tuple(swaps))


SWAP_PASSES = 2  # passes replacing each learned rule by the best rule beside the others


def _step(model: Model, before: tuple[Rule, ...], found: Best) -> Step:
    """The record of choosing ``found.rule`` beside ``before``, with its margin and twins."""
    assert found.rule is not None
    own = model.cost_of(found.rule)
    return Step(before, found.rule, found.score, found.runner_up - found.score,
                tuple((r, found.score + model.cost_of(r) - own) for r in found.twins))


@dataclass(frozen=True)
class Partial:
    """The decisions of a trace proved to stand with one more example: a prefix of its steps, and
    its stop when every step stands."""

    steps: tuple[Step, ...]
    stop: tuple[tuple[Rule, ...], float] | None = None


#: Allow-example weights of the greedy runs: 1 (the objective), then precision-minded runs that
#: avoid covering allowed examples first, mildly (2) and strictly (16). The objective's greedy order
#: can cover a disjunction with one over-general rule or, with uncertain ownership, with one rule
#: that hedges over uncertain owners where a colour rule and an ownership rule say it better; a run
#: that first covers the examples it can cover cleanly finds those. Every run after the first is
#: made when the first gets some example wrong with certainty (:func:`_overcovers`); one below
#: :data:`STRICT` also whenever some example's ownership is uncertain, since no example is then
#: wrong with certainty and a hedging first rule cannot be told that way. Measured on tuning norm
#: families (``docs/learning.md``): the mild run finds a better rule set most often; the strict
#: one made on every uncertain example set too gains little more for twice the time.
ALLOW_WEIGHTS = (1.0, 2.0, 16.0)
STRICT = 16.0  # from this allow weight on, a run is made only when the first run misfits with certainty


@dataclass(frozen=True)
class Choice:
    """The greedy runs of one re-induction and the one chosen (the lowest objective, first on ties)."""

    runs: tuple[Trace | None, ...]  # None: a run not needed (see :func:`reinduce`)
    chosen: int

    @property
    def result(self) -> tuple[Rule, ...]:
        """The chosen run's rules."""
        run = self.runs[self.chosen]
        assert run is not None
        return run.result


def _choose(runs: Sequence[Trace | None]) -> int:
    """The run with the lowest objective, the first of those within SLACK of it: a certified run's
    objective is a sum taken in another order than a search's, so exact ties differ by rounding."""
    values = [math.inf if r is None else r.objective for r in runs]
    least = min(values)
    return next(k for k, v in enumerate(values) if v <= least + SLACK)


def reinduce(ev: Evidence, action: str, given: Sequence[Rule], atoms: Sequence[Literal], model: Model,
             max_length: int, max_rules: int, earlier: Choice | None = None, new: int | None = None
             ) -> Choice:
    """The most probable rule set around the ``given`` rules found by the greedy runs of
    :data:`ALLOW_WEIGHTS` that are needed (see there), traced. ``ev`` should be in canonical order
    (:func:`canonical_order`) for the result to depend on the set of examples only.

    ``earlier``: the result of this function on the same examples but example ``new``; each of its
    runs that :func:`certify_greedy` proves unchanged is kept instead of being searched again.
    """
    runs: list[Trace | None] = []
    hedged = uncertain(ev)
    misfit: bool | None = None  # whether the first run gets some example wrong with certainty, once asked
    for k, weight in enumerate(ALLOW_WEIGHTS):
        run = None
        if k and not (hedged and weight < STRICT):
            if misfit is None:
                misfit = _overcovers(ev, runs[0].result if runs[0] else ())
            if not misfit:
                runs.append(None)
                continue
        known = None
        previous = earlier.runs[k] if earlier is not None else None
        if previous is not None and new is not None:
            proved = certify_greedy(previous, ev, new, model)
            if isinstance(proved, Trace):
                run = proved
            else:
                known = proved
        if run is None:
            run = reinduce_greedy(ev, action, given, atoms, model, max_length, max_rules, weight, known)
        runs.append(run)
    return Choice(tuple(runs), _choose(runs))


CERTAIN = 0.999


def _overcovers(ev: Evidence, rules: Sequence[Rule]) -> bool:
    """Whether the rules get some example wrong with certainty (an allowed one forbidden, or a
    forbidden one not forbidden): then every precision-minded run is tried."""
    q = ev.q(rules)
    return bool(np.any(q[ev.t < 0.5] >= CERTAIN) or np.any(q[ev.t >= 0.5] <= 1.0 - CERTAIN))


class _Example:
    """One example's truth per ownership world, for the few rule sets a certificate looks at."""

    def __init__(self, ev: Evidence, i: int, model: Model) -> None:
        self.ev, self.i, self.model = ev, i, model
        self.weights = ev.worlds.weights[:, i]
        self.t = np.array(ev.t[i])
        self._lits: dict[Literal, np.ndarray] = {}
        self._rules: dict[Rule, np.ndarray] = {}
        self._q: dict[tuple[Rule, ...], float] = {}  # the rule sets of a trace recur: each is done once
        self._nll: dict[tuple[Rule, ...], float] = {}

    def _truth(self, rule: Rule) -> np.ndarray:
        """Whether ``rule`` holds in each world of this example."""
        holds = self._rules.get(rule)
        if holds is None:
            holds = np.ones(len(self.weights), dtype=bool)
            for lit in rule.literals:
                col = self._lits.get(lit)
                if col is None:
                    atom = atom_truth(lit, self.ev.frame, self.ev.worlds)
                    col = atom[:, self.i] if atom.shape[1] > 1 else atom[:, 0]
                    col = self._lits[lit] = np.broadcast_to(~col if lit.negated else col, self.weights.shape)
                holds &= col
            self._rules[rule] = holds
        return holds

    def q(self, rules: Sequence[Rule]) -> float:
        """P(some rule holds) for this example."""
        key = tuple(rules)
        got = self._q.get(key)
        if got is None:
            out = np.zeros(len(self.weights), dtype=bool)
            for rule in key:
                out |= self._truth(rule)
            got = self._q[key] = min(max(float((out * self.weights).sum()), 0.0), 1.0)
        return got

    def nll(self, rules: Sequence[Rule]) -> float:
        """This example's likelihood term under ``rules``."""
        key = tuple(rules)
        got = self._nll.get(key)
        if got is None:
            got = self._nll[key] = float(self.model.nll_terms(self.t, np.array(self.q(key))))
        return got

    def nll_lo(self, rules: Sequence[Rule]) -> tuple[float, float]:
        """(the term under ``rules``, the least term any superset of ``rules`` could give)."""
        q = self.q(rules)
        lo = float(np.clip(self.model.best_q(self.t), q, 1.0))
        terms = self.model.nll_terms(self.t, np.array([q, lo]))
        return float(terms[0]), float(terms[1])


def certify_greedy(trace: Trace, ev: Evidence, i: int, model: Model) -> Trace | Partial:
    """The trace of :func:`reinduce_greedy` on ``ev`` if ``trace`` (made on ``ev`` without example
    ``i``) provably takes the same decisions with example ``i`` added; otherwise the decisions that
    provably stand (:class:`Partial`), from which the search goes on.

    Adding example ``i`` shifts each candidate's score by the change of that example's term alone:
    the chosen rule's shift is known, every other candidate's is at least the least shift any rule
    could give (its term at the best reachable forbid probability); a decision stands when that
    cannot close its margin. Margins in the returned trace are the guaranteed (smaller) ones.
    """
    w = float(_weights(ev, trace.allow_weight)[i])
    one = _Example(ev, i, model)
    steps: list[Step] = []
    for st in trace.steps:
        got = _certify_step(st, one, w, improving=True)
        if got is None:
            return Partial(tuple(steps))
        steps.append(got)
    stop = trace.stop
    if stop is not None:
        now, lo = one.nll_lo(stop[0])
        lower = stop[1] + w * (lo - now)
        if lower < SLACK:
            return Partial(tuple(steps))
        stop = (stop[0], lower)
    swaps = []
    for st in trace.swaps:
        got = _certify_step(st, one, w, improving=False)
        if got is None:
            return Partial(tuple(steps), stop)
        swaps.append(got)
    drops = []
    for d in trace.drops:
        rest = tuple(r for r in d.current if r != d.rule)
        value = d.value + one.nll(rest) - one.nll(d.current)
        if abs(value) < SLACK or (value <= 0) != (d.value <= 0):
            return Partial(tuple(steps), stop)
        drops.append(Drop(d.current, d.rule, value))
    value = trace.objective + one.nll(trace.result)
    return Trace(tuple(steps), stop, tuple(drops), trace.result, trace.allow_weight, value, tuple(swaps))


def _certify_step(st: Step, one: _Example, w: float, improving: bool) -> Step | None:
    """``st`` with its scores and margin shifted by the new example, if the choice provably stands
    (and, when ``improving``, still lowers the objective); None otherwise."""
    now, lo = one.nll_lo(st.before)
    shift = w * (one.nll((*st.before, st.rule)) - now)
    gap = shift - w * (lo - now)
    score = st.score + shift
    # the new margin is at least ``margin - gap``; a choice that was (or may become) a tie within
    # SLACK was settled by the search's order among equal scores, which one more example can change
    if (improving and score >= -SLACK) or st.margin - gap < SLACK:
        return None
    twins = []
    for twin, value in st.twins:  # each twin's shift is known exactly
        value += w * (one.nll((*st.before, twin)) - now)
        if value < score + SLACK:
            return None
        twins.append((twin, value))
    return Step(st.before, st.rule, score, st.margin - gap, tuple(twins))
