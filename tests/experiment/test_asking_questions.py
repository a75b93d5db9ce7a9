"""The task loop's questions (``ownctl.experiment.asking``): the oracle's step-by-step answers to
"may I ACTION OBJ?", the first-permission gate, and the value a taught task gives permission
questions (docs/asking.md, section 4)."""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.experiment.asking import OracleAnswers, QuestionAsker
from ownctl.experiment.truth import TrueNorms
from ownctl.logic.vocab import object_steps
from ownctl.mind import Mind
from ownctl.mind.ask import ALL_KINDS, Question, best_questions, candidates
from ownctl.world.model import Area, ObjectSpec, World

AGENTS = ("ann", "bob")
AREAS = (Area("home", (-0.1, -0.1, 0.1, 0.1)), Area("trash", (0.5, 0.5, 0.9, 0.9)))
STEPS = object_steps("trash")


def world(seed: int) -> World:
    """Six objects, random colours and owners, norms on ownership and colour."""
    rng = np.random.default_rng(seed)
    objects = tuple(ObjectSpec(f"o{i}", str(rng.choice(["red", "blue"])),
                               (float(rng.choice([0.0, 0.3])), float(rng.uniform(-0.05, 0.05)), 0.0),
                               frozenset({"block"}), {a: float(rng.choice([5.0, 500.0])) for a in AGENTS})
                    for i in range(6))
    owners = {o.name: {a: 1.0 for a in AGENTS if rng.random() < 0.4} for o in objects}
    norms = ("forbid trash if ownedBy ann", "forbid pickUp if isColored red")
    return World("w", AGENTS, objects, AREAS, norms, owners)


def test_the_oracle_answers_may_i_act_step_by_step() -> None:
    for seed in range(4):
        w = world(seed)
        mind = Mind(w.agents, list(w.objects), list(w.areas))
        truth = TrueNorms(w)
        oracle = OracleAnswers(w)
        for i, obj in enumerate(w.objects):
            answer = oracle.answer(Question("act", obj.name, "trash", steps=STEPS), mind)
            values = truth.forbidden(i, obj, STEPS)
            assert answer.forbids == tuple(s for s in STEPS if values[s] >= 0.5)


@pytest.mark.slow
def test_ours_asks_after_the_first_permission_the_best_taught_question() -> None:
    w = world(1)
    mind = Mind(w.agents, list(w.objects), list(w.areas))
    asker = QuestionAsker(STEPS, "ours", budget=2, min_gain=0.0, answers=OracleAnswers(w), kinds=ALL_KINDS,
                          taught=True, temper=1.0, ahead=0)
    remaining = list(range(len(w.objects)))
    asker.before(mind, 0, remaining)
    assert asker.asked == []  # no permission yet: the posterior is only its prior
    mind.permit("trash", "o0", 1.0)
    mind.permit("pickUp", "o0", 0.0)
    remaining = remaining[1:]
    pool = candidates(mind, STEPS, remaining, ALL_KINDS, read=True)
    want = best_questions(mind, STEPS, remaining, top=1, questions=pool, taught=True, read=True)[0]
    given = best_questions(mind, STEPS, remaining, top=1, questions=pool, taught=True)[0]
    asker.before(mind, 1, remaining)
    assert [a.question for a in asker.asked] == [want.question]
    assert asker.asked[0].gain == want.gain  # valued with ownership read as the learner reads it
    assert want.gain != given.gain
