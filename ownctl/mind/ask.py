"""Expected mistakes of a task and the question that most reduces them (docs/asking.md).

Pure core: no I/O. :func:`expected_mistakes` is the expected number of wrong decisions the
:class:`~ownctl.mind.Mind` makes acting on its current beliefs, without further learning, on a list
of objects for one action's object steps (acting where a step is forbidden, refusing where every
step is allowed), exactly from the posterior over ownership (independent atoms) and the posterior
over each step's rule sets (:meth:`Mind.rule_posterior`). Rule sets of different actions are
independent given the permissions; within one object the steps share its ownership atoms, so each
object's P(forbidden) is computed on the joint enumeration of its atoms (docs/asking.md, section 1).

A :class:`Question` is ``whose OBJ``, ``may STEP OBJ`` or ``rule RULE``; its possible answers
(:func:`answers`) carry their predicted probability; :func:`apply_answer` teaches an answer to a Mind
through the same instructions as any claim, permission or norm. :func:`value_of_information` is
``EM(now) - sum_a P(a) EM(after a)``, each ``after a`` on a fork of the Mind; :func:`best_questions`
ranks the candidates (docs/asking.md, sections 2-3).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from ownctl.errors import BadValue
from ownctl.learn.calibration import CALIBRATIONS, IDENTITY, calibrate
from ownctl.learn.distinct import distinct_unions
from ownctl.learn.induce import calibration_objectives
from ownctl.learn.model import LABEL_NOISE
from ownctl.learn.posterior import RulePosterior
from ownctl.logic.frame import Frame
from ownctl.logic.kept import Kept
from ownctl.logic.prob import (
    OTHER,
    Worlds,
    describes_some,
    each_rule_truth,
    enumerate_worlds,
    relevant_atoms,
    rule_truth,
)
from ownctl.logic.rules import Norm, Rule
from ownctl.mind.core import PERMISSION_CUT, Mind

KINDS = ("may", "whose", "rule")  # the kinds ``ownctl ask`` scores (a speaker can answer each)
#: every kind, in tie order; ``act`` ("may I ACTION OBJ?", answered step by step) is asked during tasks
ALL_KINDS = ("act", *KINDS)
HOLDS = ("yes", "no", "partly")
#: candidate pruning (docs/asking.md, section 3)
TOP_OBJECTS = 3  # objects asked about: the most likely wrong decisions among those still to visit
TOP_RULES = 2  # rules asked about per step: the most uncertain rules of its posterior
TOP_EXAMPLES = 2  # objects already permitted asked "whose" about: those of most uncertain ownership
MAX_OWNER_AGENTS = 4  # owner sets of at most this many uncertain agents are enumerated
SURE = 0.01  # an agent with posterior within SURE of 0 or 1 is taken as known in owner sets
MIN_ANSWER = 1e-4  # answers less probable than this are dropped (the rest renormalised)
EXACT_AGENTS = 6  # up to this many agents, corrections enumerate every owner set (2**6 = 64)
MIN_OUTCOME = 0.01  # permissions about to be taught less probable than this are not looked ahead on
EXACT = 1.0  # the temper of the stated model's own posterior (docs/asking.md, section 2)


@dataclass(frozen=True)
class Question:
    """``whose`` OBJ (answered with its owner set), ``may`` STEP OBJ (a permission), ``act`` ACTION
    OBJ over ``steps`` (a permission per step) or ``rule`` RULE (yes: the rule is stated; no: its
    allow norm is stated; partly: nothing is taught)."""

    kind: str
    object: str | None = None
    action: str | None = None
    rule: Rule | None = None
    steps: tuple[str, ...] = ()

    def text(self) -> str:
        """The question as the robot asks it."""
        if self.kind == "whose":
            return f"Whose is {self.object}?"
        if self.kind in ("may", "act"):
            return f"May I {self.action} {self.object}?"
        assert self.rule is not None
        return f"Does '{self.rule.text()}' hold?"

    def as_dict(self) -> dict[str, str | None]:
        """``{"kind", "object", "action", "rule", "text"}``."""
        return {"kind": self.kind, "object": self.object, "action": self.action,
                "rule": self.rule.text() if self.rule else None, "text": self.text()}

    def sort_key(self, order: Sequence[str] = ()) -> tuple[int, int, str, str, str]:
        """Deterministic order of questions of equal gain: kind (act, may, whose, rule), then the
        object's place in ``order`` (the task's objects: the one decided soonest first; objects not
        in it after them), then object name, action and rule text."""
        names = list(order)
        place = names.index(self.object) if self.object is not None and self.object in names else len(names)
        return (ALL_KINDS.index(self.kind), place, self.object or "", self.action or "",
                self.rule.text() if self.rule else "")


@dataclass(frozen=True)
class Answer:
    """One possible answer: ``owners`` (whose), ``forbid`` (may), ``forbids`` (act: the steps that
    are forbidden, the question's other steps allowed) or ``holds`` (rule)."""

    question: Question
    owners: tuple[str, ...] | None = None
    forbid: bool | None = None
    holds: str | None = None
    forbids: tuple[str, ...] | None = None

    def text(self) -> str:
        """The answer in words."""
        q = self.question
        if q.kind == "whose":
            return f"{q.object} belongs to {' and '.join(self.owners)}" if self.owners else "nobody's"
        if q.kind == "may":
            return "no, you may not" if self.forbid else "yes, you may"
        if q.kind == "act":
            assert self.forbids is not None
            return f"no, you may not {' or '.join(self.forbids)} it" if self.forbids else "yes, you may"
        return str(self.holds)


@dataclass(frozen=True)
class Expectation:
    """Per object of the task: the decision (forbidden), P(forbidden) and P(the decision is wrong)."""

    objects: tuple[str, ...]
    decisions: np.ndarray
    p_forbidden: np.ndarray
    p_wrong: np.ndarray

    @property
    def total(self) -> float:
        """The expected number of mistakes: the sum of the per-object probabilities."""
        return float(self.p_wrong.sum())


@dataclass(frozen=True)
class Scored:
    """A question with its value of information and its answers' probabilities and outcomes."""

    question: Question
    gain: float
    before: float
    answers: tuple[tuple[Answer, float, float], ...]  # (answer, P(answer), expected mistakes after)

    def as_dict(self) -> dict[str, object]:
        """The ``ask --json`` row: the question, its gain and each answer."""
        return {**self.question.as_dict(), "gain": self.gain, "expected_mistakes": self.before,
                "answers": [{"answer": a.text(), "p": p, "expected_mistakes": em}
                            for a, p, em in self.answers]}


def binary_entropy(p: np.ndarray) -> np.ndarray:
    """H(p) in bits, elementwise (0 at 0 and 1)."""
    q = np.clip(p, 1e-12, 1 - 1e-12)
    out: np.ndarray = -(q * np.log2(q) + (1 - q) * np.log2(1 - q))
    return out


def ownership_entropy(mind: Mind, rows: Sequence[int]) -> np.ndarray:
    """Per object of ``rows``, the sum over agents of the binary entropy of its posterior ownership
    (bits): how uncertain its owners are."""
    out: np.ndarray = binary_entropy(mind.posterior_rows(list(rows))).sum(axis=1)
    return out


def uncertain_examples(mind: Mind, steps: Sequence[str], exclude: Sequence[str] = (),
                       top: int = TOP_EXAMPLES) -> list[str]:
    """The ``top`` objects holding a permission of one of ``steps`` whose ownership is most
    uncertain (largest sum over agents of the posterior's binary entropy; ties: task order), not
    in ``exclude`` and not already known (entropy above 0.01 bit): their owners explain the
    permissions the rules are learned from, so "whose" about them can change what is learned
    (docs/asking.md, section 3)."""
    rows = [i for i in mind.permitted() if any(mind.permission(s, i) is not None for s in steps)
            and mind.objects[i].name not in exclude]
    if not rows or top <= 0:
        return []
    h = ownership_entropy(mind, rows)
    order = sorted(range(len(rows)), key=lambda k: (-round(float(h[k]), 12), rows[k]))
    return [mind.objects[rows[k]].name for k in order[:top] if h[k] > 0.01]


# -- the joint of one step's rule sets and the ownership worlds -----------------------------------
@dataclass(frozen=True)
class _Layout:
    """The rule sets of one posterior as indices into its distinct rules (-1 pads a smaller set)."""

    pool: tuple[Rule, ...]
    index: np.ndarray  # (K, max set size)
    named: tuple[str, ...]  # agents any rule or allow norm names


_LAYOUTS: dict[int, tuple[RulePosterior, _Layout]] = {}


def _layout(rp: RulePosterior) -> _Layout:
    """The layout of ``rp``'s sets (kept for the last few posteriors seen; a pure function)."""
    hit = _LAYOUTS.get(id(rp))
    if hit is not None and hit[0] is rp:
        return hit[1]
    if rp.index is not None:
        pool, index = rp.rules, rp.index
    else:
        pool = tuple(dict.fromkeys(r for s in rp.sets for r in s))
        where = {r: k for k, r in enumerate(pool)}
        width = max((len(s) for s in rp.sets), default=0)
        index = np.full((len(rp.sets), max(1, width)), -1, dtype=int)
        for k, s in enumerate(rp.sets):
            index[k, : len(s)] = [where[r] for r in s]
    named, _ = relevant_atoms([pool, rp.allows])
    out = _Layout(pool, index, named)
    if len(_LAYOUTS) >= 64:
        _LAYOUTS.pop(next(iter(_LAYOUTS)))
    _LAYOUTS[id(rp)] = (rp, out)
    return out


def _set_rules(rp: RulePosterior) -> tuple[Rule, ...]:
    """The distinct rules of ``rp``'s rule sets (not its allow norms), from its layout."""
    lay = _layout(rp)
    return tuple(lay.pool[k] for k in np.unique(lay.index[lay.index >= 0]))


def _named(posteriors: Sequence[RulePosterior]) -> tuple[str, ...]:
    return tuple(sorted({a for rp in posteriors for a in _layout(rp).named}))


_TEMPERED: dict[tuple[int, float], tuple[RulePosterior, RulePosterior]] = {}


def tempered(rp: RulePosterior, temper: float = EXACT) -> RulePosterior:
    """``rp`` with its probabilities raised to the power ``temper`` and renormalised (a power
    posterior, from the log weights): 1 is ``rp`` itself; below 1 the rule sets the examples
    favour less keep more weight (docs/asking.md, section 4). Kept for the last few posteriors."""
    if temper == EXACT:
        return rp
    key = (id(rp), float(temper))
    hit = _TEMPERED.get(key)
    if hit is not None and hit[0] is rp:
        return hit[1]
    w = rp.log_weights * temper
    p = np.exp(w - w.max())
    out = dataclasses.replace(rp, probabilities=p / p.sum())
    if len(_TEMPERED) >= 64:
        _TEMPERED.pop(next(iter(_TEMPERED)))
    _TEMPERED[key] = (rp, out)
    return out


def check_temper(temper: float) -> float:
    """``temper`` if it is in (0, 1]; BadValue naming it otherwise."""
    if not 0.0 < temper <= 1.0:
        raise BadValue(f"the temper of the rule-set posterior must be in (0, 1] (1: the stated model's "
                       f"own posterior), got {temper!r}")
    return temper


def _posterior(mind: Mind, step: str, temper: float) -> RulePosterior:
    return tempered(mind.rule_posterior(step), temper)


Reading = tuple[float, float]  # a claim calibration (confidence, shift) of ownctl.learn.calibration


def task_reading(mind: Mind, steps: Sequence[str]) -> Reading:
    """The claim calibration through which the task's truth reads uncertain ownership
    (docs/asking.md, section 1): the one of ``CALIBRATIONS`` under which the permissions of all of
    ``steps`` together are most probable, as each step's learner measures it (its most probable
    rule set's prior times likelihood, summed over the steps; the identity first on ties). A step
    whose permissions do not depend on ownership scores every calibration alike, so the steps that
    found evidence decide. The identity with the paper's learner, which reads claims as they are."""
    if mind.settings.learn.learner != "ours":
        return IDENTITY
    totals = dict.fromkeys(CALIBRATIONS, 0.0)
    for step in steps:
        ev, _ = mind.evidence(step)
        if ev.n == 0:
            continue
        options = calibration_objectives(step, ev, mind.vocab, mind.settings.learn, mind.given(step))
        for cal in CALIBRATIONS:  # with no uncertain ownership, every calibration reads as the identity
            totals[cal] += options.get(cal, options[IDENTITY])
    return min(CALIBRATIONS, key=lambda cal: (round(totals[cal], 9), CALIBRATIONS.index(cal)))


def _frame(mind: Mind, idx: Sequence[int], reading: Reading) -> Frame:
    """The frame of the objects at ``idx`` with their posterior ownership read through ``reading``."""
    frame = mind.frame().take(list(idx))
    return frame if reading == IDENTITY else frame.with_own(calibrate(frame.own, *reading))


def _set_tables(rp: RulePosterior, frame: Frame, worlds: Worlds) -> tuple[np.ndarray, np.ndarray]:
    """The (U, W, n) truth in every world of each distinct disjunction of ``rp``'s rule sets (minus
    its allow norms), and which one each set's is (K,): set ``k``'s truth is ``out[which[k]]``. A
    posterior's ~10,000 sets have some hundreds of distinct disjunctions on a task's objects
    (:func:`ownctl.learn.distinct.distinct_unions`), so the sums over sets are taken over those."""
    lay = _layout(rp)
    shape = (len(worlds.bits), frame.n)
    table = np.concatenate([each_rule_truth(lay.pool, frame, worlds),
                            np.zeros((1, *shape), dtype=bool)])  # row -1: no rule
    out, which = distinct_unions(table, lay.index)
    for allow in rp.allows:  # a set minus an allow norm forbids what it forbids outside the norm
        out &= ~rule_truth([allow], frame, worlds)[None]
    return out, which


def step_forbidden(rp: RulePosterior, frame: Frame, worlds: Worlds) -> np.ndarray:
    """(W, n): P(the step is forbidden | ownership world w) for each object, marginalised over the
    rule sets of ``rp`` (the posterior of one action).

    Kept for the last few thousand calls (read-only results), by the posterior itself (posteriors
    are kept by content, :func:`ownctl.learn.posterior.rule_posterior`, so equal inputs share one)
    and the content of the frame and worlds: valuing a question asks for the same posterior on the
    same objects and worlds about three times in four."""
    key = (id(rp), frame.content(), worlds.atoms, worlds.bits.tobytes(), worlds.weights.tobytes())
    hit = _FORBIDDEN.get(key)
    if hit is not None and hit[0] is rp:
        return hit[1]
    table, which = _set_tables(rp, frame, worlds)
    mass = np.bincount(which, rp.probabilities, len(table))  # each distinct disjunction's probability
    # einsum casts the boolean table in its buffers: the same sums, without a float copy of the
    # (U, W, n) table (which, on a store of 2,000 objects, took most of `ownctl ask`'s time)
    out: np.ndarray = np.clip(np.einsum("u,uwn->wn", mass, table), 0.0, 1.0)
    out.setflags(write=False)
    _FORBIDDEN.put(key, (rp, out))
    return out


#: marginals kept: a few thousand on a task's 20 objects; at most 256 MiB of them on a large store
_FORBIDDEN: Kept[tuple[RulePosterior, np.ndarray]] = Kept(4096, 256 << 20, lambda kept: kept[1].nbytes)


def worlds_for(mind: Mind, steps: Sequence[str], frame: Frame) -> Worlds:
    """Every assignment of the ownership atoms any rule set of the steps names (and the folded atom)."""
    named = _named([mind.rule_posterior(s) for s in steps])
    return enumerate_worlds(frame, named, with_other=True)


def decisions(mind: Mind, steps: Sequence[str], idx: Sequence[int]) -> np.ndarray:
    """The Mind's decision (True: forbidden) for each object of ``idx``: some step forbidden by its
    permission, else by the rules at the step's threshold (as :meth:`Mind.decide`, vectorised)."""
    frame = mind.frame().take(list(idx))
    out = np.zeros(len(idx), dtype=bool)
    for s in steps:
        bad = mind.p_rules_on(s, frame) >= mind.settings.threshold_for(s)
        for k, value in permissions_at(mind, s, idx):
            bad[k] = value >= PERMISSION_CUT
        out |= bad
    return out


def permissions_at(mind: Mind, step: str, idx: Sequence[int]) -> list[tuple[int, float]]:
    """``(k, value)`` for each position ``k`` of ``idx`` whose object holds a permission of ``step``:
    read off the step's permissions, which are few, rather than looked up for each of the objects,
    which on a large store are many."""
    where: dict[int, list[int]] = {}
    for k, i in enumerate(idx):
        where.setdefault(int(i), []).append(k)
    return [(k, given.value) for name, given in mind.perms[step].items()
            for k in where.get(mind.index[name], ())]


def expected_mistakes(mind: Mind, steps: Sequence[str], objects: Sequence[int | str],
                      temper: float = EXACT, reading: Reading = IDENTITY) -> Expectation:
    """The expected number of mistakes of deciding ``steps`` on ``objects`` on current beliefs.

    Truth per object: each step is forbidden by its permission's value when the object has one
    (the instructor said so), else by a rule set drawn from the step's posterior; ownership atoms are
    drawn from the posterior. P(forbidden) = 1 - E_w[prod_s (1 - f_s(w))], f_s(w) the step's
    probability of being forbidden in ownership world w (docs/asking.md, section 1). ``temper``:
    the rule-set posteriors' power (:func:`tempered`; 1, the default, is the stated model's);
    ``reading``: the calibration the truth reads ownership through (:func:`task_reading`; the
    decisions read it as it is, as the Mind decides).
    """
    idx = [mind.obj(o) for o in objects]
    names = tuple(mind.objects[i].name for i in idx)
    if not idx:
        empty = np.zeros(0)
        return Expectation(names, empty.astype(bool), empty, empty)
    frame = _frame(mind, idx, reading)
    worlds = worlds_for(mind, steps, frame)
    allowed = np.ones_like(worlds.weights)  # (W, n): P(no step forbidden | w)
    for s in steps:
        f = step_forbidden(_posterior(mind, s, temper), frame, worlds).copy()
        for k, value in permissions_at(mind, s, idx):
            f[:, k] = value
        allowed *= 1.0 - f
    p_forb = np.clip(1.0 - (worlds.weights * allowed).sum(axis=0), 0.0, 1.0)
    dec = decisions(mind, steps, idx)
    wrong = np.where(dec, 1.0 - p_forb, p_forb)
    return Expectation(names, dec, p_forb, wrong)


# -- questions and their answers ------------------------------------------------------------------
def owner_sets(mind: Mind, obj: int | str, reading: Reading = IDENTITY, exact: bool = False
               ) -> list[tuple[tuple[str, ...], float]]:
    """The possible owner sets of an object with their posterior probability (independent atoms).

    Agents within SURE of 0 or 1 are taken as known; at most MAX_OWNER_AGENTS of the others (the
    most uncertain) are enumerated, the rest taken at their likelier value; answers below
    MIN_ANSWER are dropped and the rest renormalised (docs/asking.md, section 3). ``exact``: every
    owner set, nothing taken as known or dropped, for at most EXACT_AGENTS agents (beyond, the
    pruned list).
    """
    i = mind.obj(obj)
    p = calibrate(mind.posterior_rows([i])[0], *reading)
    agents = mind.agents
    if exact and len(agents) <= EXACT_AGENTS:
        unsure = list(range(len(agents)))
    else:
        exact = False
        unsure = [j for j in range(len(agents)) if SURE < p[j] < 1 - SURE]
        unsure = sorted(sorted(unsure, key=lambda j: (abs(p[j] - 0.5), j))[:MAX_OWNER_AGENTS])
    fixed = [j for j in range(len(agents)) if j not in unsure and p[j] >= 0.5]
    out: list[tuple[tuple[str, ...], float]] = []
    for bits in range(2 ** len(unsure)):
        chosen = [unsure[k] for k in range(len(unsure)) if bits >> k & 1]
        prob = float(np.prod([p[j] if j in chosen else 1 - p[j] for j in unsure]))
        owners = tuple(agents[j] for j in sorted([*fixed, *chosen]))
        out.append((owners, prob))
    return out if exact else _normalised(out)


T = TypeVar("T")


def _normalised(items: Sequence[tuple[T, float]], floor: float = MIN_ANSWER) -> list[tuple[T, float]]:
    """The items at least ``floor`` probable, their probabilities renormalised."""
    kept = [(a, p) for a, p in items if p >= floor]
    z = sum(p for _, p in kept)
    return [(a, p / z) for a, p in kept] if z > 0 else []


def p_permission(mind: Mind, step: str, obj: int | str, temper: float = EXACT,
                 reading: Reading = IDENTITY) -> float:
    """P(an instructor forbids ``step`` on the object): the posterior predictive P(forbidden),
    with the stated model's instructor noise."""
    frame = _frame(mind, [mind.obj(obj)], reading)
    worlds = worlds_for(mind, [step], frame)
    q = float((worlds.weights * step_forbidden(_posterior(mind, step, temper), frame, worlds)).sum())
    return LABEL_NOISE + (1 - 2 * LABEL_NOISE) * min(max(q, 0.0), 1.0)


def action_answer_probabilities(mind: Mind, steps: Sequence[str], obj: int | str, temper: float = EXACT,
                                reading: Reading = IDENTITY) -> list[tuple[tuple[str, ...], float]]:
    """P(each set of forbidden steps) for "may I ACTION OBJ?" answered step by step: the steps
    share the object's ownership worlds, their rule sets are independent given them, and each
    step's answer carries the stated model's instructor noise (docs/asking.md, section 2):
    ``P(B) = sum_w P(w) prod_s (g_s(w) if s in B else 1 - g_s(w))``, ``g_s = noise + (1 - 2 noise) f_s``."""
    return _forbidden_sets(mind, steps, _frame(mind, [mind.obj(obj)], reading), temper)


def _forbidden_sets(mind: Mind, steps: Sequence[str], frame: Frame,
                    temper: float) -> list[tuple[tuple[str, ...], float]]:
    """:func:`action_answer_probabilities` on the one object of ``frame`` as it reads ownership."""
    worlds = worlds_for(mind, steps, frame)
    g = [LABEL_NOISE + (1 - 2 * LABEL_NOISE)
         * np.clip(step_forbidden(_posterior(mind, s, temper), frame, worlds)[:, 0], 0.0, 1.0) for s in steps]
    out = []
    for bits in range(2 ** len(steps)):
        chosen = tuple(s for k, s in enumerate(steps) if bits >> k & 1)
        joint = np.ones_like(worlds.weights[:, 0])
        for k, s in enumerate(steps):
            joint = joint * (g[k] if s in chosen else 1.0 - g[k])
        out.append((chosen, float((worlds.weights[:, 0] * joint).sum())))
    return out


def correction_agents(mind: Mind, steps: Sequence[str]) -> tuple[str, ...]:
    """The agents whose ownership of an object a correcting instructor states after a mistake on
    it, as the Mind can foresee them: those an ``ownedBy`` literal of some rule set of the steps'
    posteriors names, every agent when one says ``ownedBy any`` (docs/asking.md, section 4)."""
    named, uses_any = relevant_atoms([_set_rules(mind.rule_posterior(s)) for s in steps])
    return tuple(mind.agents) if uses_any else tuple(a for a in mind.agents if a in named)


Claims = tuple[tuple[str, float], ...]  # (agent, 1.0 owns / 0.0 does not) stated about one object


def corrections(mind: Mind, steps: Sequence[str], obj: int | str, forbids: Sequence[str],
                temper: float = EXACT, reading: Reading = IDENTITY) -> list[tuple[Claims, float]]:
    """The ownership a correcting instructor may state about ``obj`` after a mistake on it, given
    that the instructor forbids ``forbids`` of ``steps`` (docs/asking.md, section 4): each owner
    set of the object (every one, up to EXACT_AGENTS agents), restricted to
    :func:`correction_agents`, with its probability given that answer (Bayes:
    ``P(o | B) ~ P(o) P(B | o)``, ``P(B | o)`` on the object with owners ``o``); sets below
    MIN_OUTCOME dropped and the rest renormalised. ``[((), 1.0)]`` when no agent would be named."""
    agents = correction_agents(mind, steps)
    if not agents:
        return [((), 1.0)]
    i = mind.obj(obj)
    frame = _frame(mind, [i], reading)
    joint: dict[Claims, float] = {}
    for owners, prior in owner_sets(mind, i, reading, exact=True):
        row = np.array([[1.0 if a in owners else 0.0 for a in mind.agents]])
        likely = dict(_forbidden_sets(mind, steps, frame.with_own(row), temper))
        said = tuple((a, 1.0 if a in owners else 0.0) for a in agents)
        joint[said] = joint.get(said, 0.0) + prior * likely.get(tuple(forbids), 0.0)
    z = sum(joint.values())
    if z <= 0:
        return [((), 1.0)]
    return _normalised([(c, p / z) for c, p in joint.items()], MIN_OUTCOME)


def rule_answer_probabilities(mind: Mind, rule: Rule, temper: float = EXACT,
                              reading: Reading = IDENTITY) -> dict[str, float]:
    """P(yes), P(no), P(partly) for "does RULE hold?" on the Mind's objects: yes when every object
    the rule describes is forbidden, no when none is, partly otherwise (rule sets from the action's
    posterior, ownership atoms independent per object)."""
    frame = _frame(mind, range(len(mind.objects)), reading)
    rp = _posterior(mind, rule.action, temper)
    named, _ = relevant_atoms([[rule], *rp.sets, rp.allows])
    worlds = enumerate_worlds(frame, named, with_other=True)
    table, which = _set_tables(rp, frame, worlds)  # (U, W, n), (K,)
    covered = rule_truth([rule], frame, worlds)[None]  # (1, W, n)
    # per distinct disjunction (sets sharing one share their answers), summed in einsum's buffers
    some_allowed = np.einsum("wn,uwn->un", worlds.weights, covered & ~table)  # P(covered and allowed)
    some_forbidden = np.einsum("wn,uwn->un", worlds.weights, covered & table)
    mass = np.bincount(which, rp.probabilities, len(table))  # each distinct disjunction's probability
    p_yes = float(mass @ np.prod(np.clip(1 - some_allowed, 0, 1), axis=1))
    p_no = float(mass @ np.prod(np.clip(1 - some_forbidden, 0, 1), axis=1))
    if not covered.any():  # it describes nothing here: "yes" and "no" are both true; count it "yes"
        return {"yes": 1.0, "no": 0.0, "partly": 0.0}
    return {"yes": p_yes, "no": p_no, "partly": max(0.0, 1.0 - p_yes - p_no)}


def answers(mind: Mind, question: Question, temper: float = EXACT,
            reading: Reading = IDENTITY) -> list[tuple[Answer, float]]:
    """The possible answers to ``question`` with their predicted probabilities (summing to 1);
    ``temper``: the rule-set posteriors' power (:func:`tempered`); ``reading``: the calibration the
    truth reads ownership through (:func:`task_reading`)."""
    if question.kind == "whose":
        assert question.object is not None
        return [(Answer(question, owners=o), p) for o, p in owner_sets(mind, question.object, reading)]
    if question.kind == "may":
        assert question.object is not None and question.action is not None
        p = p_permission(mind, question.action, question.object, temper, reading)
        return _normalised([(Answer(question, forbid=True), p), (Answer(question, forbid=False), 1 - p)])
    if question.kind == "act":
        assert question.object is not None
        return _normalised([(Answer(question, forbids=b), p)
                            for b, p in action_answer_probabilities(mind, question.steps, question.object,
                                                                    temper, reading)])
    assert question.rule is not None
    probs = rule_answer_probabilities(mind, question.rule, temper, reading)
    return _normalised([(Answer(question, holds=h), probs[h]) for h in HOLDS])


def apply_answer(mind: Mind, answer: Answer, speaker: str | None = None) -> None:
    """Teach ``answer`` to ``mind`` by the ordinary instructions: an owner set is a claim per agent
    (owners claimed, every other agent "not theirs"); a permission is :meth:`Mind.permit`, and an
    answer to ``act`` one permission per step, in the question's step order; "yes" to a rule is the
    forbid norm, "no" its allow norm, "partly" teaches nothing."""
    q = answer.question
    if q.kind == "whose":
        assert q.object is not None and answer.owners is not None
        for agent in mind.agents:
            mind.claim(q.object, agent, 1.0, negated=agent not in answer.owners, speaker=speaker)
    elif q.kind == "may":
        assert q.object is not None and q.action is not None
        mind.permit(q.action, q.object, 1.0 if answer.forbid else 0.0, speaker)
    elif q.kind == "act":
        assert q.object is not None and answer.forbids is not None
        for s in q.steps:
            mind.permit(s, q.object, 1.0 if s in answer.forbids else 0.0, speaker)
    elif answer.holds in ("yes", "no"):
        assert q.rule is not None
        mind.instruct(Norm("forbid" if answer.holds == "yes" else "allow", q.rule), speaker)


def outcomes(mind: Mind, steps: Sequence[str], obj: int | str, temper: float = EXACT,
             reading: Reading = IDENTITY) -> list[tuple[Answer, float]]:
    """What the task's instructor is about to teach on ``obj``, the object being decided: the
    permission of each of its ``steps`` without one, as an answer to "may I ACTION OBJ?" over those
    steps with its predicted probability (:func:`action_answer_probabilities`); outcomes less
    probable than MIN_OUTCOME are dropped and the rest renormalised (docs/asking.md, section 4).
    Empty when every step has its permission already (nothing is left to teach)."""
    open_steps = tuple(s for s in steps if mind.permission(s, obj) is None)
    if not open_steps:
        return []
    name = mind.objects[mind.obj(obj)].name
    question = Question("act", name, open_steps[-1], steps=open_steps)
    probs = action_answer_probabilities(mind, open_steps, obj, temper, reading)
    return _normalised([(Answer(question, forbids=b), p) for b, p in probs], MIN_OUTCOME)


def mistakes_ahead(mind: Mind, steps: Sequence[str], objects: Sequence[int | str], temper: float = EXACT,
                   read: bool = False, reading: Reading | None = None) -> float:
    """The expected mistakes of a task whose instructor teaches the first object's permissions
    right after its decision (docs/asking.md, section 4): P(wrong on ``objects[0]``) on current
    beliefs, plus, over the permissions the instructor is about to give it (:func:`outcomes`) and,
    where they show the decision wrong, over the owners it then states (:func:`corrections`), the
    expected mistakes on the other objects once the Mind has learned from them (each on a fork).
    ``read``: each state reads ownership through its own :func:`task_reading`; ``reading``:
    ``mind``'s, when the caller has it already."""
    if not objects:
        return 0.0
    if reading is None:
        reading = task_reading(mind, steps) if read else IDENTITY
    first, rest = objects[:1], list(objects[1:])
    taught = outcomes(mind, steps, first[0], temper, reading) if rest else []
    if not taught:
        return expected_mistakes(mind, steps, objects, temper, reading).total
    total = expected_mistakes(mind, steps, first, temper, reading).total
    decided = bool(decisions(mind, steps, [mind.obj(first[0])])[0])
    given = [mind.permission(s, first[0]) for s in steps]
    held = any(g is not None and g.value >= PERMISSION_CUT for g in given)  # forbidden already
    for answer, p in taught:
        assert answer.forbids is not None
        wrong = decided != (held or bool(answer.forbids))
        said = (corrections(mind, answer.question.steps, first[0], answer.forbids, temper, reading)
                if wrong else [((), 1.0)])
        for claims, q in said:
            fork = mind.fork()
            for agent, value in claims:  # the instructor states ownership first, as it corrects
                fork.claim(first[0], agent, value)
            apply_answer(fork, answer)
            then = task_reading(fork, steps) if read else IDENTITY
            total += p * q * expected_mistakes(fork, steps, rest, temper, then).total
    return total


def value_of_information(mind: Mind, question: Question, steps: Sequence[str],
                         objects: Sequence[int | str], before: float | None = None,
                         temper: float = EXACT, read: bool = False, ahead: bool = False) -> Scored:
    """EM(now) - sum over answers of P(answer) EM(after teaching the answer to a fork of ``mind``),
    answers and mistakes on the rule-set posteriors raised to ``temper`` (1: the stated model's);
    ``read``: the truth reads ownership through :func:`task_reading` (now, and on each fork after
    its answer), as the learner does; off, as it is given. ``ahead``: EM is
    :func:`mistakes_ahead`, which also counts what the Mind learns from the permissions the
    instructor gives the first object right after its decision (docs/asking.md, section 4)."""
    reading = task_reading(mind, steps) if read else IDENTITY

    def measure(state: Mind, how: Reading) -> float:
        if ahead:
            return mistakes_ahead(state, steps, objects, temper, read, how)
        return expected_mistakes(state, steps, objects, temper, how).total

    now = measure(mind, reading) if before is None else before
    rows = []
    for answer, p in answers(mind, question, temper, reading):
        fork = mind.fork()
        apply_answer(fork, answer)
        then = task_reading(fork, steps) if read else IDENTITY
        rows.append((answer, p, measure(fork, then)))
    after = sum(p * em for _, p, em in rows)
    return Scored(question, now - after, now, tuple(rows))


def candidates(mind: Mind, steps: Sequence[str], objects: Sequence[int | str],
               kinds: Sequence[str] = KINDS, top_objects: int = TOP_OBJECTS,
               top_rules: int = TOP_RULES, action: str | None = None, temper: float = EXACT,
               read: bool = False) -> list[Question]:
    """The questions worth scoring (docs/asking.md, section 3), on the first object of ``objects``
    (the one about to be acted on) and the ``top_objects`` objects whose decisions are most likely
    wrong (ties: task order): ``may`` for each step without a permission, ``act`` (``action``,
    default the last step) over those steps when there are two or more, and ``whose``; and
    ``rule`` on the ``top_rules`` rules of each step's posterior whose probability is nearest 1/2
    (not yet stated, not certain, holding for some of the objects; only for steps holding a
    permission); probabilities on the rule-set posteriors raised to ``temper``, ownership read
    through :func:`task_reading` with ``read``."""
    reading = task_reading(mind, steps) if read else IDENTITY
    exp = expected_mistakes(mind, steps, objects, temper, reading)
    order = sorted(range(len(exp.objects)), key=lambda k: (-round(float(exp.p_wrong[k]), 12), k))
    top = [exp.objects[k] for k in order[:top_objects] if exp.p_wrong[k] > 0]
    chosen = list(dict.fromkeys([*exp.objects[:1], *top]))
    out: list[Question] = []
    if "whose" in kinds:
        out += [Question("whose", name) for name in uncertain_examples(mind, steps, chosen)
                if len(owner_sets(mind, name, reading)) > 1]
    for name in chosen:
        open_steps = tuple(s for s in steps if mind.permission(s, name) is None)
        if "act" in kinds and len(open_steps) > 1:
            out.append(Question("act", name, action or steps[-1], steps=open_steps))
        if "may" in kinds:
            out += [Question("may", name, s) for s in open_steps]
        if "whose" in kinds and len(owner_sets(mind, name, reading)) > 1:
            out.append(Question("whose", name))
    if "rule" in kinds:
        frame = mind.frame_of([mind.obj(o) for o in objects])
        for s in steps:
            if not mind.perms[s]:  # its posterior is still the prior over the cheapest rules
                continue
            given = set(mind.given(s))
            probs = [(r, p) for r, p in _posterior(mind, s, temper).rule_probabilities().items()
                     if r not in given and 0.01 < p < 0.99 and describes_some(r, frame)]
            probs.sort(key=lambda rp: (abs(rp[1] - 0.5), len(rp[0].literals), rp[0].text()))
            out += [Question("rule", action=s, rule=r) for r, _ in probs[:top_rules]]
    return out


def horizon(question: Question, names: Sequence[str]) -> int:
    """How many of the task's objects (``names``, in task order) a question's answer can change the
    decisions of when every attempted object's permissions are taught right after its decision
    (docs/asking.md, section 4): a permission question (``may``, ``act``) on an object is answered
    anyway when that object is attempted, so only the decisions up to and including it count;
    any other question counts the whole remaining task."""
    obj = question.object
    if question.kind in ("may", "act") and obj is not None and obj in names:
        return list(names).index(obj) + 1
    return len(names)


def best_questions(mind: Mind, steps: Sequence[str], objects: Sequence[int | str], top: int = 3,
                   kinds: Sequence[str] = KINDS, questions: Sequence[Question] | None = None,
                   taught: bool = False, temper: float = EXACT, read: bool = False,
                   ahead: int = 0, progress: Progress | None = None) -> list[Scored]:
    """The ``top`` questions of largest value of information, best first; equal gains (to 1e-9) in
    :meth:`Question.sort_key` order over ``objects``' order. ``taught``: the objects' permissions
    will be taught as each is attempted, so a permission question's value counts only the
    decisions up to its object (:func:`horizon`). ``temper``: value on the rule-set posteriors
    raised to that power (:func:`tempered`; 1 is the stated model's posterior, exact). ``read``: the
    truth reads ownership as the learner does (:func:`task_reading`). ``ahead``: value the
    questions as the task's instructor teaches, which implies ``taught``: the ``ahead`` best of
    them and every question about the first object (the one being decided) are valued again
    with the look-ahead over the permissions the instructor gives that object next
    (:func:`mistakes_ahead`), and ranked on it (docs/asking.md, section 4); 0: no look-ahead.
    ``progress`` is told (valued, to value) after each value of information."""
    check_temper(temper)
    taught = taught or check_ahead(ahead) > 0
    pool = (candidates(mind, steps, objects, kinds, temper=temper, read=read) if questions is None
            else list(questions))
    objs = list(objects)
    names = [mind.objects[mind.obj(o)].name for o in objs]
    tick = _Ticker(progress, len(pool))
    scored = _ranked(mind, steps, objs, names, pool, taught, temper, read, ahead=False, tick=tick)
    if ahead and scored:
        first = names[0]
        chosen = [s.question for s in scored[:ahead]]
        chosen += [s.question for s in scored[ahead:] if s.question.object == first]
        tick.total += len(chosen)
        scored = _ranked(mind, steps, objs, names, chosen, taught, temper, read, ahead=True, tick=tick)
    return scored[:top]


Progress = Callable[[int, int], None]  # told (done, total) as work goes on


class _Ticker:
    """Counts the values of information computed and tells ``progress``, if any."""

    def __init__(self, progress: Progress | None, total: int) -> None:
        self.progress, self.total, self.done = progress, total, 0

    def __call__(self) -> None:
        self.done += 1
        if self.progress is not None:
            self.progress(self.done, self.total)


SAVES_NOTHING = 1e-9  # expected mistakes: a gain this small is a tie with no question (ranking's tolerance)


def worth_asking(gain: float, min_gain: float) -> bool:
    """Whether a question of expected gain ``gain`` is worth putting when a question must save at
    least ``min_gain`` expected mistakes (setting ``ask.min_gain``): the one test both ``run --ask``
    and ``ask --put`` apply (docs/asking.md, sections 4-5). A question that saves nothing (gain
    within :data:`SAVES_NOTHING` of 0) is never worth putting, even with ``ask.min_gain 0``."""
    return gain > SAVES_NOTHING and gain >= min_gain


def _ranked(mind: Mind, steps: Sequence[str], objs: Sequence[int | str], names: Sequence[str],
            pool: Sequence[Question], taught: bool, temper: float, read: bool, ahead: bool,
            tick: Callable[[], None] | None = None) -> list[Scored]:
    """Every question of ``pool`` scored (see :func:`best_questions`), best first; the value now is
    computed once per horizon (with ``taught``, questions sharing one share it)."""
    now: dict[int, float] = {}
    scored = []
    for q in pool:
        cut = list(objs[: horizon(q, names)] if taught else objs)
        scored.append(value_of_information(mind, q, steps, cut, now.get(len(cut)), temper, read, ahead))
        now[len(cut)] = scored[-1].before
        if tick is not None:
            tick()
    scored.sort(key=lambda s: (-round(s.gain, 9), s.question.sort_key(names)))
    return scored


def check_ahead(ahead: int) -> int:
    """``ahead`` if it is a whole number of questions, at least 0; BadValue naming it otherwise."""
    if isinstance(ahead, bool) or not isinstance(ahead, int) or ahead < 0:
        raise BadValue(f"the number of questions re-valued with the look-ahead must be a whole number "
                       f"of at least 0 (0: none), got {ahead!r}")
    return ahead


__all__ = ["ALL_KINDS", "HOLDS", "IDENTITY", "KINDS", "MIN_OUTCOME", "OTHER", "Answer", "Expectation",
           "Question", "Scored", "action_answer_probabilities", "answers", "apply_answer", "best_questions",
           "binary_entropy", "candidates", "check_ahead", "check_temper", "correction_agents", "corrections",
           "decisions", "expected_mistakes", "horizon", "mistakes_ahead", "outcomes", "owner_sets",
           "ownership_entropy", "p_permission", "permissions_at", "rule_answer_probabilities",
           "step_forbidden", "task_reading", "tempered", "uncertain_examples", "value_of_information",
           "worlds_for"]
