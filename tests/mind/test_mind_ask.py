"""Expected mistakes and value of information (``ownctl.mind.ask``) against brute force.

The brute force lists every rule set of each step's posterior and every owner set of every object
(each agent one by one, nothing folded), evaluates the rules in plain Python on the objects'
percepts, and combines steps, objects and answers by plain sums and products. The simulation runs
the task loop on worlds whose true norms and owners are drawn from the posterior, with nobody
teaching the robot.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from ownctl.errors import BadValue
from ownctl.experiment.kinematic import KinematicExecutor
from ownctl.experiment.student import t_quantile
from ownctl.experiment.task import SilentInstructor, run_task
from ownctl.learn.calibration import CALIBRATIONS, IDENTITY, calibrate
from ownctl.learn.induce import calibrated_inducer
from ownctl.learn.model import LABEL_NOISE
from ownctl.logic.prob import rule_truth
from ownctl.logic.rules import ANY, Norm, Rule, parse_norm
from ownctl.logic.vocab import object_steps
from ownctl.mind import Mind
from ownctl.mind.ask import (
    Answer,
    Question,
    action_answer_probabilities,
    apply_answer,
    best_questions,
    candidates,
    expected_mistakes,
    horizon,
    owner_sets,
    rule_answer_probabilities,
    step_forbidden,
    task_reading,
    tempered,
    value_of_information,
    worlds_for,
)
from ownctl.world.model import Area, ObjectSpec, World

AGENTS = ("ann", "bob")
AREAS = (Area("home", (-0.1, -0.1, 0.1, 0.1)), Area("trash", (0.5, 0.5, 0.9, 0.9)))
STEPS = object_steps("trash")


def small_mind(seed: int, n: int = 4, perms: int = 3, allow: bool = False) -> Mind:
    """A few objects, two agents, random claims and permissions (and maybe an allow norm)."""
    rng = np.random.default_rng(seed)
    objects = []
    for i in range(n):
        x, y = rng.choice([0.0, 0.3]), rng.uniform(-0.05, 0.05)
        ages = {a: float(rng.choice([5.0, 500.0])) for a in AGENTS}
        objects.append(ObjectSpec(f"o{i}", str(rng.choice(["red", "blue"])), (float(x), float(y), 0.0),
                                  frozenset({"block"}), ages))
    mind = Mind(AGENTS, objects, list(AREAS))
    mind.claim("o0", "ann", 1.0)
    mind.claim("o0", "bob", 1.0, negated=True)
    for k in range(perms):
        step = STEPS[int(rng.integers(len(STEPS)))] if k else "trash"
        mind.permit(step, f"o{int(rng.integers(n))}", float(rng.integers(2)))
    if allow:
        mind.instruct(parse_norm("allow trash if isColored blue"))
    return mind


def facts(mind: Mind, i: int) -> tuple[str | None, set[str], frozenset[str]]:
    """Colour, areas and categories of object ``i`` (the crisp percepts)."""
    frame = mind.frame().take([i])
    areas = {a for a, member in frame.areas.items() if bool(member[0])}
    return frame.colors[0], areas, frame.categories[0]


def holds(rule: Rule, owners: frozenset[str], fact: tuple[str | None, set[str], frozenset[str]]) -> bool:
    """Plain truth of a rule for one object with a known owner set."""
    colour, areas, cats = fact
    for lit in rule.literals:
        if lit.pred == "ownedBy":
            value = bool(owners) if lit.arg == ANY else lit.arg in owners
        elif lit.pred == "isColored":
            value = colour is not None if lit.arg == ANY else colour == lit.arg
        elif lit.pred == "inArea":
            value = bool(areas) if lit.arg == ANY else lit.arg in areas
        else:
            value = bool(cats) if lit.arg == ANY else lit.arg in cats
        if value == lit.negated:
            return False
    return True


def owner_worlds(p: np.ndarray) -> list[tuple[frozenset[str], float]]:
    """Every owner set of one object with its probability (independent atoms, every agent)."""
    out = []
    for bits in itertools.product((0, 1), repeat=len(AGENTS)):
        weight = math.prod(q if b else 1 - q for q, b in zip(p, bits, strict=True))
        out.append((frozenset(a for a, b in zip(AGENTS, bits, strict=True) if b), weight))
    return out


def set_probabilities(mind: Mind, step: str, temper: float = 1.0) -> np.ndarray:
    """The step's rule-set probabilities, raised to ``temper`` from the log weights by hand."""
    rp = mind.rule_posterior(step)
    if temper == 1.0:
        return rp.probabilities
    w = np.exp(temper * (rp.log_weights - rp.log_weights.max()))
    return w / w.sum()


def brute_forbidden(mind: Mind, step: str, i: int, owners: frozenset[str], temper: float = 1.0) -> float:
    """P(step forbidden on object i | its owner set), summing the step's rule sets one by one."""
    rp = mind.rule_posterior(step)
    fact = facts(mind, i)
    total = 0.0
    for rules, p in zip(rp.sets, set_probabilities(mind, step, temper), strict=True):
        if any(holds(r, owners, fact) for r in rules) and not any(holds(a, owners, fact) for a in rp.allows):
            total += float(p)
    return total


def read_posterior(mind: Mind, reading: tuple[float, float] = IDENTITY) -> np.ndarray:
    """The posterior ownership, each probability read through the calibration ``reading`` by hand."""
    post = mind.posterior()
    if reading == IDENTITY:
        return post
    confidence, shift = reading
    inner = (post > 0) & (post < 1)
    safe = np.where(inner, post, 0.5)
    return np.where(inner, 1 / (1 + np.exp(-(confidence * np.log(safe / (1 - safe)) + shift))), post)


def brute_em(mind: Mind, objects: list[int], temper: float = 1.0,
             reading: tuple[float, float] = IDENTITY) -> float:
    """Expected mistakes by listing, per object, every owner set and every step's rule sets."""
    post = read_posterior(mind, reading)
    total = 0.0
    for i in objects:
        p_forb = 0.0
        for owners, w in owner_worlds(post[i]):
            none = 1.0
            for s in STEPS:
                given = mind.permission(s, i)
                f = given.value if given is not None else brute_forbidden(mind, s, i, owners, temper)
                none *= 1 - f
            p_forb += w * (1 - none)
        refused, _ = mind.decide("trash", i, STEPS)
        total += 1 - p_forb if refused else p_forb
    return total


@pytest.mark.parametrize("seed", range(4))
def test_expected_mistakes_equal_brute_force(seed: int) -> None:
    mind = small_mind(seed, allow=seed == 3)
    objects = list(range(len(mind.objects)))
    exp = expected_mistakes(mind, STEPS, objects)
    assert exp.total == pytest.approx(brute_em(mind, objects), abs=1e-9)
    assert list(exp.decisions) == [mind.decide("trash", i, STEPS)[0] for i in objects]


@pytest.mark.slow
def test_a_step_marginal_equals_the_posterior_predictive() -> None:
    mind = small_mind(5, allow=True)
    frame = mind.frame()
    for s in STEPS:
        worlds = worlds_for(mind, [s], frame)
        marginal = (worlds.weights * step_forbidden(mind.rule_posterior(s), frame, worlds)).sum(axis=0)
        assert np.allclose(marginal, mind.rule_posterior(s).p_forbidden(frame), atol=1e-12)


def test_a_kept_step_marginal_is_the_one_computed_afresh() -> None:
    """step_forbidden keeps its results by content: the same posterior asked about other objects,
    or about the same objects read through another ownership, gets their own values (each the sum
    over the posterior's rule sets, set by set), and a kept value cannot be changed in place."""
    mind = small_mind(2, n=5, perms=4)
    full = mind.rule_posterior("trash")
    near = full.window(3.0)
    frames = [mind.frame().take([i]) for i in range(5)]
    frames.append(frames[0].with_own(calibrate(frames[0].own, *CALIBRATIONS[1])))
    first: list[np.ndarray] = []
    for round_ in range(2):  # the second round is served from what the first kept
        for k, frame in enumerate(frames):
            rp = full if k == 0 else near  # the whole posterior once, then a few of its sets
            worlds = worlds_for(mind, ["trash"], frame)
            expected = sum(p * rule_truth(list(s), frame, worlds) for s, p in zip(rp.sets, rp.probabilities,
                                                                                   strict=True))
            got = step_forbidden(rp, frame, worlds)
            assert np.allclose(got, np.clip(expected, 0.0, 1.0), rtol=0.0, atol=1e-12)
            if round_:
                assert np.array_equal(got, first[k])
            else:
                first.append(got)
            with pytest.raises(ValueError):
                got[0, 0] = 0.5


def brute_answers(mind: Mind, q: Question, temper: float = 1.0,
                  reading: tuple[float, float] = IDENTITY) -> list[tuple[Answer, float]]:
    """The answers' probabilities by plain enumeration."""
    post = read_posterior(mind, reading)
    if q.kind == "whose":
        i = mind.obj(q.object)
        return [(Answer(q, owners=tuple(sorted(o))), w) for o, w in owner_worlds(post[i])]
    if q.kind == "may":
        i = mind.obj(q.object)
        f = sum(w * brute_forbidden(mind, q.action, i, o, temper) for o, w in owner_worlds(post[i]))
        p = LABEL_NOISE + (1 - 2 * LABEL_NOISE) * f
        return [(Answer(q, forbid=True), p), (Answer(q, forbid=False), 1 - p)]
    if q.kind == "act":
        return brute_action_answers(mind, q, temper, reading)
    probs = brute_rule_answers(mind, q.rule, temper, reading)
    return [(Answer(q, holds=h), p) for h, p in probs.items()]


def brute_action_answers(mind: Mind, q: Question, temper: float = 1.0,
                         reading: tuple[float, float] = IDENTITY) -> list[tuple[Answer, float]]:
    """P(each set of forbidden steps): every owner set of the object, each step's answer true with
    its probability under that owner set and flipped with the instructor noise."""
    i = mind.obj(q.object)
    post = read_posterior(mind, reading)
    out = []
    for bits in itertools.product((False, True), repeat=len(q.steps)):
        total = 0.0
        for owners, w in owner_worlds(post[i]):
            for s, b in zip(q.steps, bits, strict=True):
                g = LABEL_NOISE + (1 - 2 * LABEL_NOISE) * brute_forbidden(mind, s, i, owners, temper)
                w *= g if b else 1 - g
            total += w
        out.append((Answer(q, forbids=tuple(s for s, b in zip(q.steps, bits, strict=True) if b)), total))
    return out


def brute_rule_answers(mind: Mind, rule: Rule, temper: float = 1.0,
                       reading: tuple[float, float] = IDENTITY) -> dict[str, float]:
    """P(yes/no/partly) over every rule set and every joint owner assignment of all objects."""
    rp = mind.rule_posterior(rule.action)
    post = read_posterior(mind, reading)
    n = len(mind.objects)
    per = [owner_worlds(post[i]) for i in range(n)]
    fact = [facts(mind, i) for i in range(n)]
    out = {"yes": 0.0, "no": 0.0, "partly": 0.0}
    for rules, p in zip(rp.sets, set_probabilities(mind, rule.action, temper), strict=True):
        if p < 1e-15:
            continue
        for combo in itertools.product(*per):
            w = p * math.prod(x[1] for x in combo)
            covered = [holds(rule, combo[i][0], fact[i]) for i in range(n)]
            forb = [any(holds(r, combo[i][0], fact[i]) for r in rules)
                    and not any(holds(a, combo[i][0], fact[i]) for a in rp.allows) for i in range(n)]
            hits = [f for c, f in zip(covered, forb, strict=True) if c]
            out["yes" if all(hits) else "no" if not any(hits) else "partly"] += w
    return out


QUESTIONS = {"whose": Question("whose", "o1"), "may": Question("may", "o2", "pickUp"),
             "act": Question("act", "o2", "trash", steps=STEPS),
             "rule": Question("rule", action="trash", rule=parse_norm("forbid trash if isColored red").rule)}


@pytest.mark.parametrize(("seed", "kind", "temper"), [
    (0, "may", 1.0), (0, "whose", 1.0),
    *[pytest.param(s, k, t, marks=pytest.mark.slow) for s, k, t in
      [(0, "may", 0.5), (1, "act", 1.0), (0, "rule", 1.0), (0, "act", 1.0), (2, "act", 1.0), (1, "may", 1.0),
       (1, "whose", 1.0), (1, "rule", 1.0), (2, "may", 1.0), (2, "whose", 1.0), (2, "rule", 1.0),
       (1, "act", 0.5), (1, "whose", 0.3), (2, "rule", 0.5)]],
])
def test_value_of_information_equals_brute_force(seed: int, kind: str, temper: float) -> None:
    mind = small_mind(seed, n=3)
    objects = list(range(3))
    before = brute_em(mind, objects, temper)
    for q in [QUESTIONS[kind]]:
        scored = value_of_information(mind, q, STEPS, objects, temper=temper)
        brute = brute_answers(mind, q, temper)
        if q.kind in ("whose", "act"):
            brute = [(a, p) for a, p in brute if p >= 1e-4]
        z = sum(p for _, p in brute)
        after = 0.0
        for a, p in brute:
            fork = mind.fork()
            apply_answer(fork, a)
            after += p / z * brute_em(fork, objects, temper)
        assert scored.before == pytest.approx(before, abs=1e-9)
        assert scored.gain == pytest.approx(before - after, abs=1e-9), q.text()
        assert sum(p for _, p, _ in scored.answers) == pytest.approx(1.0)


def learner_calibration(mind: Mind, step: str) -> tuple[float, float]:
    """The calibration the learner read the step's permissions through (matched on its examples)."""
    ev, _ = mind.evidence(step)
    read = calibrated_inducer(step, ev, mind.vocab, mind.settings.learn, tuple(mind.given(step)))[0].ev
    return next(c for c in CALIBRATIONS if np.allclose(calibrate(ev.frame.own, *c), read.frame.own))


def test_the_task_reading_of_one_step_is_the_learners_calibration() -> None:
    chosen = set()
    for seed in range(6):
        mind = small_mind(seed, n=5, perms=4)
        for s in STEPS:
            if mind.perms[s]:
                assert task_reading(mind, [s]) == learner_calibration(mind, s), (seed, s)
                chosen.add(task_reading(mind, [s]))
        assert task_reading(mind, STEPS) in CALIBRATIONS
    assert chosen == set(CALIBRATIONS)  # both readings occur: the comparison is not empty
    exact = small_mind(0)
    for i in range(len(exact.objects)):
        for agent in AGENTS:
            exact.claim(i, agent, 1.0, negated=i % 2 == 0)
    assert task_reading(exact, STEPS) == IDENTITY


@pytest.mark.slow
def test_expected_mistakes_read_through_a_calibration_equal_brute_force() -> None:
    mind = small_mind(1, n=3)
    objects = list(range(3))
    for reading in CALIBRATIONS:
        exp = expected_mistakes(mind, STEPS, objects, reading=reading)
        assert exp.total == pytest.approx(brute_em(mind, objects, reading=reading), abs=1e-9)
    assert expected_mistakes(mind, STEPS, objects, reading=(4.0, -1.0)).total != pytest.approx(
        expected_mistakes(mind, STEPS, objects).total, abs=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize(("seed", "kind"), [(1, "whose"), (0, "may"), (2, "act")])
def test_values_with_the_learners_reading_equal_brute_force(seed: int, kind: str) -> None:
    mind = small_mind(seed, n=3)
    objects = list(range(3))
    q = QUESTIONS[kind]
    now = task_reading(mind, STEPS)
    scored = value_of_information(mind, q, STEPS, objects, read=True)
    brute = [(a, p) for a, p in brute_answers(mind, q, reading=now) if p >= 1e-4]
    z = sum(p for _, p in brute)
    after = 0.0
    for a, p in brute:
        fork = mind.fork()
        apply_answer(fork, a)
        after += p / z * brute_em(fork, objects, reading=task_reading(fork, STEPS))
    assert scored.before == pytest.approx(brute_em(mind, objects, reading=now), abs=1e-9)
    assert scored.gain == pytest.approx(scored.before - after, abs=1e-9)


@pytest.mark.slow
def test_rule_answers_equal_brute_force() -> None:
    mind = small_mind(2, n=3)
    for text in ("forbid trash if isColored red", "forbid trash if ownedBy ann", "forbid pickUp"):
        rule = parse_norm(text).rule
        got = rule_answer_probabilities(mind, rule)
        want = brute_rule_answers(mind, rule)
        for h in want:
            assert got[h] == pytest.approx(want[h], abs=1e-9), (text, h)


@pytest.mark.slow
def test_action_answers_equal_brute_force_and_sum_to_one() -> None:
    for seed in (1, 3):
        mind = small_mind(seed, allow=seed == 3)
        q = Question("act", "o1", "trash", steps=STEPS)
        got = dict(action_answer_probabilities(mind, STEPS, "o1"))
        want = {a.forbids: p for a, p in brute_action_answers(mind, q)}
        assert set(got) == set(want) and len(got) == 2 ** len(STEPS)
        for b, p in want.items():
            assert got[b] == pytest.approx(p, abs=1e-9), b
        assert sum(got.values()) == pytest.approx(1.0, abs=1e-12)


def test_candidates_include_the_object_about_to_be_acted_on() -> None:
    mind = small_mind(0)
    for first in range(len(mind.objects)):
        objects = [first, *[i for i in range(len(mind.objects)) if i != first]]
        pool = candidates(mind, STEPS, objects, kinds=("act", "may", "whose"), top_objects=1)
        name = mind.objects[first].name
        open_steps = tuple(s for s in STEPS if mind.permission(s, name) is None)
        assert all(Question("may", name, s) in pool for s in open_steps)
        assert (Question("act", name, "trash", steps=open_steps) in pool) == (len(open_steps) > 1)


def test_rule_questions_are_about_steps_holding_a_permission() -> None:
    mind = small_mind(0, perms=0)
    objects = list(range(len(mind.objects)))
    assert candidates(mind, STEPS, objects, kinds=("rule",)) == []  # every posterior is the prior
    mind.permit("trash", "o1", 1.0)
    asked = candidates(mind, STEPS, objects, kinds=("rule",))
    assert {q.action for q in asked} == {"trash"}

    for seed in range(1, 4):  # whose posteriors hold rules no object satisfies ("not isColored any")
        mind = small_mind(seed, perms=1)
        post = mind.posterior()
        asked = candidates(mind, STEPS, objects, kinds=("rule",))
        for q in asked:  # a rule no object may satisfy would surely be answered "yes"
            assert q.rule is not None and any(holds(q.rule, owners, facts(mind, i)) for i in objects
                                              for owners, w in owner_worlds(post[i]) if w > 0), q


@pytest.mark.slow
def test_taught_permission_questions_count_the_decisions_up_to_their_object() -> None:
    mind = small_mind(2, n=4)
    objects = [3, 1, 0, 2]
    names = [mind.objects[i].name for i in objects]
    assert horizon(Question("act", "o0", "trash", steps=STEPS), names) == 3
    assert horizon(Question("may", "o3", "find"), names) == 1
    assert horizon(Question("whose", "o3"), names) == 4
    pool = [Question("act", "o1", "trash", steps=STEPS), Question("may", "o0", "pickUp"),
            Question("whose", "o2")]
    ranked = best_questions(mind, STEPS, objects, top=3, questions=pool, taught=True)
    for scored in ranked:
        cut = objects[: horizon(scored.question, names)]
        direct = value_of_information(mind, scored.question, STEPS, cut)
        assert scored.gain == pytest.approx(direct.gain, abs=1e-12)
        assert scored.before == pytest.approx(brute_em(mind, cut), abs=1e-9)


def test_owner_sets_are_the_posterior_product() -> None:
    mind = small_mind(1)
    sets = dict(owner_sets(mind, "o2"))
    for owners, w in owner_worlds(mind.posterior()[2]):
        assert sets.get(tuple(sorted(owners)), 0.0) == pytest.approx(w, abs=1e-4)


def test_answers_go_through_the_ordinary_instructions() -> None:
    base = small_mind(0)
    cases = [
        (Answer(Question("whose", "o2"), owners=("bob",)),
         lambda m: (m.claim("o2", "ann", 1.0, negated=True), m.claim("o2", "bob", 1.0, negated=False))),
        (Answer(Question("may", "o3", "trash"), forbid=True), lambda m: m.permit("trash", "o3", 1.0)),
        (Answer(Question("act", "o3", "trash", steps=STEPS), forbids=("pickUp",)),
         lambda m: [m.permit(s, "o3", 1.0 if s == "pickUp" else 0.0) for s in STEPS]),
        (Answer(Question("rule", action="trash", rule=parse_norm("forbid trash if ownedBy ann").rule),
                holds="yes"), lambda m: m.instruct(parse_norm("forbid trash if ownedBy ann"))),
        (Answer(Question("rule", action="trash", rule=parse_norm("forbid trash if isColored red").rule),
                holds="no"),
         lambda m: m.instruct(Norm("allow", parse_norm("forbid trash if isColored red").rule))),
    ]
    for answer, by_hand in cases:
        a, b = base.fork(), base.fork()
        apply_answer(a, answer)
        by_hand(b)
        assert np.array_equal(a.claims, b.claims, equal_nan=True)
        assert a.perms == {k: {n: g for n, g in v.items()} for k, v in b.perms.items()}
        assert a.rules == b.rules and a.allows == b.allows
        assert np.allclose(a.posterior(), b.posterior())
    partly = base.fork()
    apply_answer(partly, Answer(cases[3][0].question, holds="partly"))
    assert partly.rules == base.rules and partly.perms == base.perms


def test_a_fork_is_independent_and_keeps_other_actions_posteriors() -> None:
    mind = small_mind(4)
    before = {s: mind.rule_posterior(s) for s in STEPS}
    fork = mind.fork()
    fork.permit("pickUp", "o1", 1.0)
    fork.claim("o3", "bob", 1.0)
    assert mind.permission("pickUp", "o1") is None or mind.permission("pickUp", "o1").value != 1.0 \
        or before["pickUp"] is mind.rule_posterior("pickUp")
    assert np.isnan(mind.claims[3, 1])
    other = small_mind(4)
    other.permit("pickUp", "o1", 1.0)
    kept = other.rule_posterior("trash")  # carried over from before the permission
    fresh = small_mind(4)
    fresh.permit("pickUp", "o1", 1.0)
    fresh._changed()
    assert np.allclose(kept.probabilities, fresh.rule_posterior("trash").probabilities)


@pytest.mark.slow
def test_best_questions_are_ranked_and_ties_ordered() -> None:
    mind = small_mind(0)
    objects = list(range(len(mind.objects)))
    ranked = best_questions(mind, STEPS, objects, top=50)
    assert len(ranked) == len(candidates(mind, STEPS, objects))
    names = [mind.objects[i].name for i in objects]
    keys = [(-round(s.gain, 9), s.question.sort_key(names)) for s in ranked]
    assert keys == sorted(keys)


@pytest.mark.slow
def test_progress_counts_every_value_of_information_and_changes_nothing() -> None:
    mind = small_mind(1)
    objects = list(range(len(mind.objects)))
    told: list[tuple[int, int]] = []
    ranked = best_questions(mind, STEPS, objects, top=50, ahead=2, progress=lambda d, t: told.append((d, t)))
    assert [d for d, _ in told] == list(range(1, len(told) + 1))  # one report per value, in order
    pool = len(candidates(mind, STEPS, objects))
    assert told[0][1] == pool and told[-1][0] == told[-1][1] > pool  # the look-ahead's values added
    quiet = best_questions(mind, STEPS, objects, top=50, ahead=2)
    assert [(s.question, s.gain) for s in ranked] == [(s.question, s.gain) for s in quiet]


def test_equal_gains_are_ordered_by_kind_then_task_order() -> None:
    names = ["o10", "o2", "o1"]
    qs = [Question("whose", "o1"), Question("may", "o1", "trash"), Question("may", "o2", "trash"),
          Question("may", "o10", "trash"), Question("rule", action="trash",
                                                    rule=parse_norm("forbid trash if isColored red").rule)]
    got = sorted(qs, key=lambda q: q.sort_key(names))
    assert [(q.kind, q.object) for q in got] == [("may", "o10"), ("may", "o2"), ("may", "o1"),
                                                 ("whose", "o1"), ("rule", None)]


def test_a_tempered_posterior_is_the_power_posterior() -> None:
    mind = small_mind(1)
    rp = mind.rule_posterior("trash")
    assert tempered(rp, 1.0) is rp
    for t in (0.7, 0.3):
        got = tempered(rp, t).probabilities
        assert got == pytest.approx(set_probabilities(mind, "trash", t), abs=1e-12)
        assert got.sum() == pytest.approx(1.0)
        entropy = [-(p[p > 0] * np.log(p[p > 0])).sum() for p in (rp.probabilities, got)]
        assert entropy[1] > entropy[0]  # flatter: the sets the examples favour less keep more weight
    objects = list(range(len(mind.objects)))
    assert expected_mistakes(mind, STEPS, objects, 0.5).total == pytest.approx(brute_em(mind, objects, 0.5),
                                                                               abs=1e-9)
    for bad in (0.0, -1.0, 1.5):
        with pytest.raises(BadValue, match=r"\(0, 1\]"):
            best_questions(mind, STEPS, objects, temper=bad)


def draw_world(mind: Mind, rng: np.random.Generator) -> World:
    """True norms (a rule set per step from its posterior) and owners (from the posterior)."""
    norms = []
    for s in STEPS:
        rp = mind.rule_posterior(s)
        k = int(rng.choice(len(rp.sets), p=rp.probabilities / rp.probabilities.sum()))
        norms += [r.text() for r in rp.sets[k]]
    post = mind.posterior()
    owners = {o.name: {a: 1.0 for j, a in enumerate(mind.agents) if rng.random() < post[i, j]}
              for i, o in enumerate(mind.objects)}
    return World("drawn", mind.agents, tuple(mind.objects), tuple(mind.areas), tuple(dict.fromkeys(norms)),
                 owners)


@pytest.mark.slow
def test_expected_mistakes_match_simulated_tasks() -> None:
    mind = small_mind(7, n=6, perms=4)
    objects = [i for i in range(6) if not AREAS[1].contains(np.array(mind.objects[i].position[:2]))[0]]
    em = expected_mistakes(mind, STEPS, objects).total
    rng = np.random.default_rng(11)
    counts = []
    for _ in range(600):
        world = draw_world(mind, rng)
        report = run_task(mind.fork(), world, "trashAll", KinematicExecutor(world), SilentInstructor())
        counts.append(report.mistakes)
    x = np.array(counts, dtype=float)
    half = t_quantile(0.975, len(x) - 1) * x.std(ddof=1) / math.sqrt(len(x))
    assert abs(x.mean() - em) <= half, (x.mean(), em, half)
