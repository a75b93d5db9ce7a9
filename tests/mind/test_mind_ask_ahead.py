"""The look-ahead value of a question (``ownctl.mind.ask.mistakes_ahead``): the expected mistakes
once the instructor has taught the object being decided its permissions, against brute force
(docs/asking.md, section 4). The brute force is ``tests/mind/test_mind_ask.py``'s."""

from __future__ import annotations

import pytest

from ownctl.errors import BadValue
from ownctl.learn.model import LABEL_NOISE
from ownctl.logic.rules import ANY
from ownctl.mind import Mind
from ownctl.mind.ask import (
    MIN_OUTCOME,
    Answer,
    Question,
    apply_answer,
    best_questions,
    candidates,
    check_ahead,
    correction_agents,
    corrections,
    horizon,
    mistakes_ahead,
    outcomes,
    uncertain_examples,
    value_of_information,
)
from tests.mind.test_mind_ask import (
    STEPS,
    brute_action_answers,
    brute_answers,
    brute_em,
    brute_forbidden,
    owner_worlds,
    read_posterior,
    small_mind,
)


def brute_correction_agents(mind: Mind) -> tuple[str, ...]:
    """Every agent when some rule of some step's posterior says ``ownedBy any``, else those named."""
    lits = [lit for s in STEPS for rs in mind.rule_posterior(s).sets for r in rs for lit in r.literals
            if lit.pred == "ownedBy"]
    if any(lit.arg == ANY for lit in lits):
        return tuple(mind.agents)
    return tuple(a for a in mind.agents if a in {lit.arg for lit in lits})


def brute_corrections(mind: Mind, i: int, forbids: tuple[str, ...], temper: float = 1.0
                      ) -> list[tuple[tuple[tuple[str, float], ...], float]]:
    """What the instructor states after a mistake on object i, given the forbidden steps: every
    owner set by plain enumeration, weighted by P(owners) P(these answers | owners), grouped by
    what it says of the correction agents, the improbable ones dropped as the look-ahead drops them."""
    agents = brute_correction_agents(mind)
    if not agents:
        return [((), 1.0)]
    name = mind.objects[i].name
    open_steps = tuple(s for s in STEPS if mind.permission(s, name) is None)
    joint: dict[tuple[tuple[str, float], ...], float] = {}
    for owners, w in owner_worlds(read_posterior(mind)[i]):
        for s in open_steps:
            g = LABEL_NOISE + (1 - 2 * LABEL_NOISE) * brute_forbidden(mind, s, i, owners, temper)
            w *= g if s in forbids else 1 - g
        said = tuple((a, 1.0 if a in owners else 0.0) for a in agents)
        joint[said] = joint.get(said, 0.0) + w
    z = sum(joint.values())
    kept = [(c, p / z) for c, p in joint.items() if p / z >= MIN_OUTCOME]
    z = sum(p for _, p in kept)
    return [(c, p / z) for c, p in kept]


def brute_ahead(mind: Mind, objects: list[int], temper: float = 1.0) -> float:
    """P(wrong on the first object) plus, over every permission set of its steps without one (by
    plain enumeration, the improbable ones dropped as the look-ahead drops them) and, where the
    Mind's decision was wrong, over the owners the correcting instructor states, the brute-force
    expected mistakes on the others after teaching both to a fork."""
    first, rest = objects[0], objects[1:]
    name = mind.objects[first].name
    open_steps = tuple(s for s in STEPS if mind.permission(s, name) is None)
    if not rest or not open_steps:
        return brute_em(mind, objects, temper)
    q = Question("act", name, open_steps[-1], steps=open_steps)
    taught = [(a, p) for a, p in brute_action_answers(mind, q, temper) if p >= MIN_OUTCOME]
    z = sum(p for _, p in taught)
    total = brute_em(mind, [first], temper)
    decided, _ = mind.decide("trash", first, STEPS)
    held = any(g is not None and g.value >= 0.5 for g in (mind.permission(s, first) for s in STEPS))
    for answer, p in taught:
        assert answer.forbids is not None
        said = (brute_corrections(mind, first, answer.forbids, temper)
                if decided != (held or bool(answer.forbids)) else [((), 1.0)])
        for claims, c in said:
            fork = mind.fork()
            for agent, value in claims:
                fork.claim(first, agent, value)
            apply_answer(fork, answer)
            total += p / z * c * brute_em(fork, rest, temper)
    return total


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_mistakes_ahead_equal_brute_force(seed: int) -> None:
    mind = small_mind(seed, n=3)
    for objects in ([0, 1, 2], [2, 0, 1]):
        assert mistakes_ahead(mind, STEPS, objects) == pytest.approx(brute_ahead(mind, objects), abs=1e-9)


def test_the_outcomes_are_the_open_steps_permissions_and_sum_to_one() -> None:
    mind = small_mind(2, n=3)
    for i in range(3):
        name = mind.objects[i].name
        open_steps = tuple(s for s in STEPS if mind.permission(s, name) is None)
        got = outcomes(mind, STEPS, i)
        assert all(a.question.steps == open_steps and p >= MIN_OUTCOME for a, p in got)
        assert sum(p for _, p in got) == pytest.approx(1.0) if open_steps else got == []
    mind.permit("find", "o0", 0.0)
    mind.permit("pickUp", "o0", 0.0)
    mind.permit("trash", "o0", 1.0)
    assert outcomes(mind, STEPS, "o0") == []  # nothing left to teach: no look-ahead
    assert mistakes_ahead(mind, STEPS, [0, 1, 2]) == pytest.approx(brute_em(mind, [0, 1, 2]), abs=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize(("kind", "question"), [("whose", Question("whose", "o0")),
                                                ("may", Question("may", "o1", "pickUp"))])
def test_the_look_ahead_value_equals_brute_force(kind: str, question: Question) -> None:
    mind = small_mind(0, n=3)
    objects = [0, 1, 2]
    scored = value_of_information(mind, question, STEPS, objects, ahead=True)
    before = brute_ahead(mind, objects)
    brute = [(a, p) for a, p in brute_answers(mind, question) if p >= 1e-4]
    z = sum(p for _, p in brute)
    after = 0.0
    for a, p in brute:
        fork = mind.fork()
        apply_answer(fork, a)
        after += p / z * brute_ahead(fork, objects)
    assert scored.before == pytest.approx(before, abs=1e-9)
    assert scored.gain == pytest.approx(before - after, abs=1e-9), kind


@pytest.mark.slow
def test_asking_what_the_instructor_teaches_next_saves_that_decision_less_its_correction() -> None:
    """"May I trash OBJ?" over every step of the object being decided is answered a moment later
    anyway: looking ahead, its value is the mistake it prevents on that object, less what the
    correction of that mistake would have taught (the owners the instructor states) on the rest."""
    mind = small_mind(3, n=3)
    objects = [1, 0, 2]
    name = mind.objects[1].name
    open_steps = tuple(s for s in STEPS if mind.permission(s, name) is None)
    q = Question("act", name, "trash", steps=open_steps)
    scored = value_of_information(mind, q, STEPS, objects, ahead=True)
    answered = [(a, p) for a, p, _ in scored.answers]
    if any(p < MIN_OUTCOME for _, p in answered):  # the look-ahead drops what the answers keep
        pytest.skip("an improbable permission set: the two enumerations differ by design")
    prevented = brute_em(mind, [1]) - sum(p * brute_em(_taught(mind, a), [1]) for a, p in answered)
    decided, _ = mind.decide("trash", 1, STEPS)
    forgone = 0.0
    for a, p in answered:
        assert a.forbids is not None
        if decided == bool(a.forbids):
            continue
        taught = _taught(mind, a)
        corrected = 0.0
        for claims, c in brute_corrections(mind, 1, a.forbids):
            fork = mind.fork()
            for agent, value in claims:
                fork.claim(1, agent, value)
            corrected += c * brute_em(_taught(fork, a), [0, 2])
        forgone += p * (brute_em(taught, [0, 2]) - corrected)
    assert scored.gain == pytest.approx(prevented - forgone, abs=1e-9)


def _taught(mind: Mind, answer: Answer) -> Mind:
    fork = mind.fork()
    apply_answer(fork, answer)
    return fork


@pytest.mark.slow
def test_best_questions_look_ahead_on_the_best_and_the_first_objects() -> None:
    mind = small_mind(1, n=3)
    objects = [2, 0, 1]
    pool = candidates(mind, STEPS, objects, kinds=("act", "may", "whose"))
    myopic = best_questions(mind, STEPS, objects, top=len(pool), questions=pool, taught=True)
    ranked = best_questions(mind, STEPS, objects, top=len(pool), questions=pool, ahead=1)
    first = mind.objects[2].name
    expected = {myopic[0].question} | {s.question for s in myopic if s.question.object == first}
    assert {s.question for s in ranked} == expected
    names = [mind.objects[i].name for i in objects]
    for s in ranked:  # as the instructor teaches: a permission question counts up to its object
        cut = objects[: horizon(s.question, names)]
        direct = value_of_information(mind, s.question, STEPS, cut, ahead=True)
        assert s.gain == pytest.approx(direct.gain, abs=1e-12)
    assert [s.gain for s in ranked] == sorted((s.gain for s in ranked), reverse=True)


def test_the_look_ahead_count_is_checked() -> None:
    assert check_ahead(0) == 0 and check_ahead(3) == 3
    for bad in (-1, 1.5, True):
        with pytest.raises(BadValue, match="look-ahead"):
            check_ahead(bad)  # type: ignore[arg-type]


def test_corrections_state_the_owners_the_rules_could_name_given_the_answer() -> None:
    mind = small_mind(1, n=3)
    agents = correction_agents(mind, STEPS)
    assert agents == brute_correction_agents(mind)
    open_steps = tuple(s for s in STEPS if mind.permission(s, 2) is None)
    assert open_steps
    for forbids in ((), open_steps[-1:]):
        said = corrections(mind, open_steps, 2, forbids)
        assert sum(p for _, p in said) == pytest.approx(1.0)
        assert all(tuple(a for a, _ in claims) == agents for claims, _ in said)
        expected = dict(brute_corrections(mind, 2, forbids))
        assert dict(said) == pytest.approx(expected, abs=1e-9)


def test_the_uncertain_examples_are_permitted_objects_of_unknown_owners() -> None:
    mind = small_mind(4, n=4)
    got = uncertain_examples(mind, STEPS)
    permitted = {mind.objects[i].name for i in mind.permitted()}
    assert set(got) <= permitted - {"o0"}  # o0's owners were claimed
    assert len(got) <= 2
    assert uncertain_examples(mind, STEPS, exclude=got) == [
        n for n in uncertain_examples(mind, STEPS, top=4) if n not in got][:2]
