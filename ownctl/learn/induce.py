"""Incremental dual-mode norm induction: the paper's Algorithms 1-4 and the conflict gate.

* ``cover_example``: a forbid permission the rules do not explain -> search a new rule from the
  empty rule that covers it without covering (many) allowed examples.
* ``uncover_example``: an allow permission the rules forbid -> specialise each covering rule so it
  excludes the example and subtract the specialisation.
* ``cover_rule``: a given forbid norm -> specialise it against the allowed examples (Gricean), add.
* ``uncover_rule``: a given allow norm -> specialise it against the forbidden examples, subtract it
  (the paper's; ours subtracts the norm as said and re-induces under it, as every later
  permission does).

Two learners share the entry points (``LearnConfig.learner``):

* ``paper``: the original system's counts and thresholds (crisp false-positive counts with one error
  tolerated for examples, soft false/true-positive values for given rules), with the conflict gate;
* ``ours``: after every permission, the most probable rule set of all stored permissions under the
  stated model of :mod:`ownctl.learn.model` (uncertain ownership counts in proportion to its
  probability), found by :mod:`ownctl.learn.exact`; given norms go through cover/uncover rule.

Everything is deterministic: canonical literal order, stable sorts, ordered example sweeps.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.config import LearnConfig
from ownctl.learn import calibration, exact
from ownctl.learn.algebra import merge_rule, rule_diff, specialising
from ownctl.learn.calibration import calibrated
from ownctl.learn.calibration import candidates as calibration_candidates
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.model import Model, model_for
from ownctl.learn.search import Filter, rule_search
from ownctl.logic.frame import Frame
from ownctl.logic.kept import Kept
from ownctl.logic.prob import describes_some
from ownctl.logic.rules import ANY, Norm, Rule

MAX_RULES = 5  # ours: rules re-induction may add to the given ones
SURELY = 1.0 - 1e-12  # a rule this probable on an example holds there in every ownership world
TRACES = 4096  # ours: re-induction traces kept for certification (a memo: results never depend on it)
_traces: Kept[exact.Choice] = Kept(TRACES)


@dataclass(frozen=True)
class Outcome:
    """Result of one instruction: the new rule set, whether induction ran, the gate's accuracy."""

    rules: tuple[Rule, ...]
    induced: bool
    accuracy: float
    given: tuple[Rule, ...] = ()  # after a norm: the rules that stand for what instructors said
    excepted: bool = False  # the permission lies under a stated allow norm: an exception, not learned from



class Inducer:
    """The four entry points over one action's stored examples."""

    def __init__(self, action: str, ev: Evidence, vocab: Vocabulary, cfg: LearnConfig) -> None:
        self.action, self.ev, self.cfg = action, ev, cfg
        self.ours = cfg.learner == "ours"
        # agents the examples' worlds leave out (no ownership among the examples, or beyond the
        # enumeration limit) cannot be told apart there: the paper's search does not name them;
        # ours searches the whole vocabulary (such literals cover nothing, or what their rule
        # covers, and are never chosen), so its hypothesis space does not depend on the examples
        self.atoms = [a for a in vocab.atoms()
                      if self.ours or a.pred != "ownedBy" or a.arg == ANY or a.arg in ev.worlds.atoms]
        self.model: Model = model_for(vocab.atoms(), cfg.max_conditions)

    # -- helpers -------------------------------------------------------------------------------
    def _covers(self, rule: Rule) -> np.ndarray:
        return self.ev.prob(self.ev.truth(rule)) >= self.cfg.cover_threshold

    def _merge(self, rules: Sequence[Rule], new: Rule) -> list[Rule]:
        """Add ``new`` without its implied literals, and without redundancy (merge_rule)."""
        return merge_rule(rules, new.simplified(), None if self.ours else self._covers)

    def _search(self, init: Rule, score, threshold: float, filters=(), exclude=()):  # type: ignore[no-untyped-def]
        return rule_search(self.ev, init, self.atoms, score, threshold, filters, self.cfg.beam,
                           self.cfg.max_conditions, stop_at_success=not self.ours, exclude=exclude)

    # -- Algorithm 1 (paper) -----------------------------------------------------------------
    def cover_example(self, rules: list[Rule], i: int) -> list[Rule]:
        """Add a rule covering forbid example ``i`` (unless no acceptable rule exists)."""
        neg = ~self.ev.positives
        covers_new = lambda tr, c: self.ev.prob(tr)[:, i] >= self.cfg.cover_threshold  # noqa: E731

        def score(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
            counts: np.ndarray = (self.ev.prob(truths)[:, neg] >= self.cfg.cover_threshold).sum(axis=1)
            return counts.astype(float)

        thr = max(1.0, self.cfg.example_tolerance * neg.sum())
        result = self._search(Rule(self.action), score, thr, (covers_new,), rules)
        return self._merge(rules, result.rule) if result.success else rules

    # -- Algorithm 2 (paper) -----------------------------------------------------------------
    def uncover_example(self, rules: list[Rule], i: int) -> list[Rule]:
        """Specialise every rule that covers allow example ``i`` and subtract the specialisation."""
        current = list(rules)
        for r in [r for r in rules if self._covers(r)[i]]:
            if r not in current:
                continue
            keeps_neg = lambda tr, c: self.ev.prob(tr)[:, i] >= self.cfg.cover_threshold  # noqa: E731
            pos = self.ev.positives & self._covers(r)

            def score(truths: np.ndarray, cands: Sequence[Rule], pos: np.ndarray = pos) -> np.ndarray:
                covered: np.ndarray = self.ev.prob(truths)[:, pos] >= self.cfg.cover_threshold
                counts: np.ndarray = covered.sum(axis=1).astype(float)
                return counts

            thr = max(1.0, self.cfg.example_tolerance * pos.sum())
            result = self._search(r, score, thr, (keeps_neg,))
            if result.success:
                current.remove(r)
                for piece in rule_diff(r, result.rule):
                    current = self._merge(current, piece)
        return current

    # -- re-induction (ours) ------------------------------------------------------------------
    def reinduce(self, given: Sequence[Rule], allows: Sequence[Rule], trace: exact.Choice | None = None
                 ) -> list[Rule]:
        """Ours: the most probable rule set for all stored examples, kept around the given rules.

        Greedy, with an exact search for each rule (:func:`ownctl.learn.exact.reinduce`), on the
        examples in canonical order, then the allow norms are subtracted: the result depends only on
        the set of examples, not on the order they arrived in. ``trace``: a certified trace of this
        very computation (:func:`ownctl.learn.exact.certify_greedy`), used instead of searching again.
        """
        if trace is None:
            canon, _, _ = exact.canonical_order(self.ev)
            trace = exact.reinduce(canon, self.action, given, self.atoms, self.model,
                                   self.cfg.max_conditions, MAX_RULES)
        current = list(trace.result)
        for allow in allows:
            current = subtract(current, allow, self._merge)
        return current

    def traced(self, given: Sequence[Rule], new: int | None = None) -> exact.Choice:
        """The re-induction trace for the stored examples: the memoised one if these very examples
        were re-induced before; else certified from the trace of the same examples without example
        ``new`` when one is known and the certificate holds; else computed."""
        canon, order, digests = exact.canonical_order(self.ev)
        truncated = self.ev.worlds.atoms if self.ev.folded else None
        key = (self.action, tuple(given), tuple(self.atoms), truncated, self.model, self.cfg.max_conditions,
               MAX_RULES)
        full = (key, tuple(digests))
        known = _traces.get(full)
        if known is not None:
            return known
        earlier = None
        if new is not None:
            earlier = _traces.peek((key, tuple(d for k, d in enumerate(digests) if order[k] != new)))
        trace = exact.reinduce(canon, self.action, given, self.atoms, self.model, self.cfg.max_conditions,
                               MAX_RULES, earlier, None if new is None else order.index(new))
        return _traces.put(full, trace)

    # -- Algorithms 3 and 4 ------------------------------------------------------------------
    def cover_rule(self, rules: list[Rule], given: Rule, world: Frame | None = None) -> list[Rule]:
        """Add a given forbid rule, specialised against the allowed examples, never into a rule that
        holds for none of ``world``'s objects (:func:`somewhere`). Ours specialises it only against
        the allowed examples it surely covers: where it covers one only if that object's uncertain
        owners are who they may be, the permission is explained by who they are (inference), as a
        permission the rules explain by a likely ownership teaches no rule."""
        if any(r.conditions <= given.conditions for r in rules):
            return rules
        neg = ~self.ev.positives

        def score(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
            covered = self.ev.prob(truths)[:, neg]
            if self.ours:  # an allowed example the norm covers only if its owners are who they may be
                covered = np.where(covered >= SURELY, covered, 0.0)  # is left to inference to explain
            excess: np.ndarray = np.maximum(covered - self.ev.t[neg], 0).sum(axis=1)
            return excess

        threshold = self.cfg.rule_tolerance * neg.sum()
        result = rule_search(self.ev, given, self.atoms, score, threshold, somewhere(given, world),
                             self.cfg.beam, self.cfg.max_conditions, stop_at_success=True)
        if result.success:
            return self._merge(rules, result.rule)
        # ours trusts the instructor: a norm no specialisation reconciles with the examples is kept as said
        return self._merge(rules, given) if self.ours else rules

    def uncover_rule(self, rules: list[Rule], given: Rule, world: Frame | None = None) -> list[Rule]:
        """The paper's: subtract a given allow rule, first specialised against the forbidden
        examples, never into a rule that holds for none of ``world``'s objects (:func:`somewhere`)."""
        pos = self.ev.positives

        def score(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
            kept: np.ndarray = np.minimum(self.ev.prob(truths)[:, pos], self.ev.t[pos]).sum(axis=1)
            return kept

        result = self._search(given, score, self.cfg.rule_tolerance * pos.sum(), somewhere(given, world))
        return subtract(rules, result.rule, self._merge) if result.success else rules


def somewhere(said: Rule, world: Frame | None) -> tuple[Filter, ...]:
    """The search filter that keeps the specialisations of a stated norm ``said`` that may still
    hold for some object of ``world`` (the robot's objects). Without it, a norm the examples
    contradict is "specialised" into one that describes nothing: "forbid pickUp if ownedBy ana"
    became "... and not isColored any" where every object has a colour, which satisfies the
    examples by forbidding nothing. None when ``world`` is unknown, or when ``said`` itself
    holds for none of its objects (a norm about things the robot has not met yet)."""
    if world is None or not describes_some(said, world):
        return ()

    def keep(truths: np.ndarray, cands: Sequence[Rule]) -> np.ndarray:
        return np.array([describes_some(c, world) for c in cands], dtype=bool)

    return (keep,)


def calibration_choices(action: str, ev: Evidence, vocab: Vocabulary, cfg: LearnConfig,
                        given: Sequence[Rule], new: int | None = None
                        ) -> dict[tuple[float, float], tuple[Inducer, exact.Choice, float]]:
    """Per claim calibration worth trying on ``ev`` (:mod:`ownctl.learn.calibration`; the identity
    alone when no ownership is uncertain), in order: the inducer over the examples so read, its
    re-induction trace around the ``given`` rules, and the objective of that trace's most probable
    rule set. Each calibration's trace is certified from, and memoised beside, the same
    calibration's trace without example ``new``; the objectives are those of the examples in
    canonical order, so they depend only on the set of permissions."""
    out: dict[tuple[float, float], tuple[Inducer, exact.Choice, float]] = {}
    for reading in calibration_candidates(ev):
        ind = Inducer(action, calibrated(ev, reading), vocab, cfg)
        choice = ind.traced(given, new)
        run = choice.runs[choice.chosen]
        assert run is not None
        out[reading] = (ind, choice, run.objective)
    return out


def calibration_objectives(action: str, ev: Evidence, vocab: Vocabulary, cfg: LearnConfig,
                           given: Sequence[Rule]) -> dict[tuple[float, float], float]:
    """The objectives of :func:`calibration_choices`, per calibration worth trying (in order).

    A pure function of its arguments' contents, so kept by content (:meth:`Evidence.content`, least
    recently used dropped first): valuing a question asks it of many what-if Minds whose
    permissions and ownership are the same (docs/asking.md, section 1)."""
    key = (*learning_inputs(action, ev, vocab, cfg), tuple(given), MAX_RULES)
    kept = _objectives.get(key)
    if kept is None:
        kept = _objectives.put(key, {cal: option[2] for cal, option in
                                     calibration_choices(action, ev, vocab, cfg, given).items()})
    return dict(kept)


def learning_inputs(action: str, ev: Evidence, vocab: Vocabulary, cfg: LearnConfig) -> tuple[object, ...]:
    """What every result of learning from ``ev`` depends on, as a hashable value: the examples'
    content (:meth:`Evidence.content`), the action, vocabulary and settings, the stated model and the
    claim calibrations; the key of results kept by content (here and :mod:`ownctl.learn.posterior`)."""
    return (ev.content(), action, vocab, cfg, model_for(vocab.atoms(), cfg.max_conditions),
            calibration.CALIBRATIONS)


OBJECTIVES = 4096  # calibration objectives kept by content (a few floats each)
_objectives: Kept[dict[tuple[float, float], float]] = Kept(OBJECTIVES)


def calibrated_inducer(action: str, ev: Evidence, vocab: Vocabulary, cfg: LearnConfig,
                       given: Sequence[Rule], new: int | None = None) -> tuple[Inducer, exact.Choice]:
    """Ours: the inducer and trace of :func:`calibration_choices` whose rule set makes the stored
    permissions most probable (the first calibration on ties)."""
    ind, choice, _ = min(calibration_choices(action, ev, vocab, cfg, given, new).values(),
                         key=lambda option: option[2])
    return ind, choice


def subtract(rules: Sequence[Rule], allow: Rule, merge=None) -> list[Rule]:  # type: ignore[no-untyped-def]
    """Every rule minus ``allow`` (rules disjoint from it are kept as they are)."""
    merge = merge or (lambda rs, r: merge_rule(rs, r))
    out: list[Rule] = []
    for r in rules:
        pieces = rule_diff(r, allow)
        if pieces == [r]:
            out = merge(out, r)
            continue
        for piece in pieces:
            out = merge(out, piece)
    return out


def learn_permission(
    action: str, rules: Sequence[Rule], allows: Sequence[Rule], ev: Evidence, new: int,
    vocab: Vocabulary, cfg: LearnConfig, given: Sequence[Rule] = (),
) -> Outcome:
    """Induction after permission ``new`` was stored with the others in ``ev``.

    ``paper``: the conflict gate, then cover/uncover example for ``new`` and then every misclassified
    example, while the rules agree with less than ``cfg.accuracy_gate`` of the stored permissions
    (soft accuracy); otherwise the permission is only stored and used for inference.

    ``ours``: the most probable rule set for all stored permissions around the given rules
    (:meth:`Inducer.reinduce`), after every permission; a permission the rules explain by a likely
    ownership changes nothing (the stated model weighs it), and the result depends only on the set of
    permissions, not on their order. Most permissions are settled by certifying the previous
    re-induction (:func:`ownctl.learn.exact.certify_greedy`) instead of searching again. ``induced`` says
    whether the rules changed. Examples on which a stated allow norm surely holds are left out
    (:meth:`Evidence.beyond`: under every rule set minus the allow norms they are allowed), so a
    permission that contradicts an allow norm is an exception (``excepted``), never the seed of a rule.
    """
    accuracy = ev.soft_accuracy(rules)
    if cfg.learner == "ours":
        examples, kept = ev.beyond(allows)
        at = np.flatnonzero(kept == new)
        excepted = not len(at)
        if examples.n == 0:
            return Outcome(tuple(rules), False, accuracy, excepted=excepted)
        ind, trace = calibrated_inducer(action, examples, vocab, cfg, given, None if excepted else int(at[0]))
        learned = tuple(ind.reinduce(given, allows, trace))
        return Outcome(learned, learned != tuple(rules), accuracy, excepted=excepted)
    if accuracy >= cfg.accuracy_gate:
        return Outcome(tuple(rules), False, accuracy)
    ind = Inducer(action, ev, vocab, cfg)
    current = list(rules)
    for j in [new, *(j for j in range(ev.n) if j != new)]:
        q = float(ev.q(current)[j])
        if ev.t[j] >= cfg.cover_threshold and q < cfg.cover_threshold:
            current = ind.cover_example(current, j)
        elif ev.t[j] < cfg.cover_threshold and q >= cfg.cover_threshold:
            current = ind.uncover_example(current, j)
    return Outcome(tuple(current), True, accuracy)


def learn_norm(
    norm: Norm, rules: Sequence[Rule], ev: Evidence, vocab: Vocabulary, cfg: LearnConfig,
    allows: Sequence[Rule] = (), given: Sequence[Rule] = (), world: Frame | None = None,
) -> Outcome:
    """One-shot instruction of a forbid (cover rule) or allow (uncover rule) norm; ``world``: the
    robot's objects, which a stated norm is never specialised into describing none of.

    ``given`` are the current rules that instructors stated (or their pieces). The ``ours`` learner
    lets a given forbid norm replace guesses: the norm is added (specialised only as far as the
    examples demand) to the given rules, and the learned rules are re-induced around them, so a rule
    learned from one example ("forbid trash" after one forbidden trash) gives way to the norm that
    explains it. An allow norm is subtracted from the given rules as said and joins the allow norms
    the learned rules are re-induced under, exactly as every later permission re-induces them, so
    the rules do not depend on whether the norm came before or after the permissions (a forbidden
    example it covers is an exception). Earlier allow norms stay in force. The paper's learner
    ignores a norm an active rule already covers, and specialises an allow norm against the
    forbidden examples before subtracting it.
    """
    accuracy = ev.soft_accuracy(rules)
    ind = Inducer(norm.rule.action, ev, vocab, cfg)
    stated = [r for r in rules if r in set(given)]
    if ind.ours:
        if norm.sign == "forbid":
            said, allowing = ind.cover_rule(stated, norm.rule, world), list(allows)
        else:
            said = subtract(stated, norm.rule, ind._merge)
            allowing = list(dict.fromkeys([*allows, norm.rule]))
        best, trace = calibrated_inducer(norm.rule.action, ev.beyond(allowing)[0], vocab, cfg, said)
        current = best.reinduce(said, allowing, trace)
        return Outcome(tuple(current), True, accuracy, tuple(specialising(said, current)))
    if norm.sign == "forbid":
        current = ind.cover_rule(list(rules), norm.rule, world)
        fresh = [r for r in current if r not in rules]
        return Outcome(tuple(current), True, accuracy, tuple([*stated, *fresh]))
    current = ind.uncover_rule(list(rules), norm.rule, world)
    return Outcome(tuple(current), True, accuracy, tuple(specialising(stated, current)))
