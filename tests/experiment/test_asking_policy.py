"""The task asker's policy (``ownctl.experiment.asking``): question kinds and the tempered rule-set
posterior it values questions on, and the task loop run from an object on (docs/asking.md, section 4)."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from ownctl.app.settings import ASK_AHEAD, ASK_KINDS, ASK_MIN_GAIN, ASK_READ, ASK_TEMPER
from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.asking import (
    DEFAULT_MIN_GAIN,
    TASK_AHEAD,
    TASK_KINDS,
    TASK_READ,
    TASK_TEMPER,
    OracleAnswers,
    Policy,
    QuestionAsker,
    parse_kinds,
)
from ownctl.experiment.kinematic import KinematicExecutor
from ownctl.experiment.oracle import OracleInstructor
from ownctl.experiment.task import get_task, run_objects, run_task
from ownctl.experiment.truth import TrueNorms
from ownctl.logic.vocab import object_steps
from ownctl.mind import Mind
from ownctl.mind.ask import best_questions, candidates, value_of_information
from ownctl.world.generator import paper_blocks_world
from ownctl.world.model import World

STEPS = object_steps("trash")


def test_kinds_are_parsed_and_checked() -> None:
    assert parse_kinds(" act, whose ,act") == ("act", "whose")
    assert "rule" not in TASK_KINDS and Policy().kinds == TASK_KINDS
    with pytest.raises(UnknownName, match="unknown question kind 'why'"):
        parse_kinds("act,why")
    with pytest.raises(BadValue, match="at least one question kind"):
        parse_kinds(" , ")
    with pytest.raises(BadValue, match=r"\(0, 1\]"):
        QuestionAsker(STEPS, temper=0.0)
    with pytest.raises(UnknownName, match="question kind"):
        Policy(kinds=("whence",))


def test_the_store_settings_default_to_the_task_askers_policy() -> None:
    assert (ASK_MIN_GAIN, ASK_KINDS, ASK_TEMPER, ASK_READ, ASK_AHEAD) == (
        DEFAULT_MIN_GAIN, TASK_KINDS, TASK_TEMPER, TASK_READ, TASK_AHEAD)
    assert Policy() == Policy(ASK_MIN_GAIN, ASK_KINDS, ASK_TEMPER, read=ASK_READ, ahead=ASK_AHEAD)
    assert QuestionAsker(STEPS).read == TASK_READ and QuestionAsker(STEPS).ahead == TASK_AHEAD
    with pytest.raises(BadValue, match="look-ahead"):
        QuestionAsker(STEPS, ahead=-1)
    with pytest.raises(BadValue, match="look-ahead"):
        Policy(ahead=-2)


@pytest.mark.slow
def test_the_task_loop_resumes_from_any_object_as_if_never_stopped() -> None:
    world = paper_blocks_world(np.random.default_rng([3, 1, 0]))
    whole = Mind(world.agents, list(world.objects), world.areas)
    full = run_task(whole, world, "trashAll", KinematicExecutor(world), OracleInstructor(world)).records
    mind = Mind(world.agents, list(world.objects), world.areas)
    truth, task, executor = TrueNorms(world), get_task("trashAll"), KinematicExecutor(world)
    head = run_objects(mind, truth, task, executor, OracleInstructor(world), attempts=4)
    assert sum(r.outcome != "done" for r in head) == 4
    ahead = run_objects(mind.fork(), truth, task, copy.deepcopy(executor), OracleInstructor(world),
                        start=len(head))  # a look-ahead on a fork leaves the run as it was
    tail = run_objects(mind, truth, task, executor, OracleInstructor(world), start=len(head))
    assert [*head, *tail] == list(full)
    assert ahead == tail


def _first_taught(seed: int, trash: float) -> tuple[World, Mind]:
    """A paper world of ``seed`` whose Mind was taught its first object's permissions (``trash``
    forbidden or not, ``pickUp`` allowed), as the task asker sees it before the second object."""
    world = paper_blocks_world(np.random.default_rng(seed))
    mind = Mind(world.agents, list(world.objects), world.areas)
    mind.permit("trash", 0, trash)
    mind.permit("pickUp", 0, 0.0)
    return world, mind


@pytest.mark.slow
def test_ours_asks_the_best_question_on_the_tempered_posterior() -> None:
    world, mind = _first_taught([0, 1, 2], 0.0)
    remaining = list(range(1, 5))
    asker = QuestionAsker(STEPS, "ours", budget=1, min_gain=0.0, answers=OracleAnswers(world), temper=0.5,
                          ahead=0)
    pool = candidates(mind, STEPS, remaining, TASK_KINDS, temper=0.5)
    assert all(q.kind in TASK_KINDS for q in pool)
    want = best_questions(mind, STEPS, remaining, top=1, questions=pool, temper=0.5)[0]
    exact = best_questions(mind, STEPS, remaining, top=1, questions=pool)[0]
    assert want.gain == pytest.approx(value_of_information(mind, want.question, STEPS, remaining,
                                                           temper=0.5).gain, abs=1e-12)
    assert want.before != pytest.approx(exact.before)  # the tempered posterior expects other mistakes
    asker.before(mind, 1, remaining)
    assert [a.question for a in asker.asked] == [want.question]


@pytest.mark.slow
def test_ours_asks_the_best_question_looking_ahead() -> None:
    world, mind = _first_taught([0, 1, 3], 1.0)
    remaining = list(range(1, 6))
    asker = QuestionAsker(STEPS, "ours", budget=1, min_gain=0.0, answers=OracleAnswers(world))
    assert asker.ahead == TASK_AHEAD > 0  # the task asker looks ahead by default
    pool = candidates(mind, STEPS, remaining, TASK_KINDS, temper=TASK_TEMPER, read=TASK_READ)
    want = best_questions(mind, STEPS, remaining, top=1, questions=pool, temper=TASK_TEMPER, read=TASK_READ,
                          ahead=TASK_AHEAD)[0]
    myopic = best_questions(mind, STEPS, remaining, top=1, questions=pool, temper=TASK_TEMPER,
                            read=TASK_READ)[0]
    assert want.before != pytest.approx(myopic.before)  # the value counts the permissions taught next
    asker.before(mind, 1, remaining)
    assert [a.question for a in asker.asked] == [want.question]
    assert asker.asked[0].gain == pytest.approx(want.gain, abs=1e-12)


@pytest.mark.parametrize("decide", ["map", "window"])
def test_budget_zero_is_table_3s_trial_under_any_decision_mode(decide: str) -> None:
    """With no question the asking run is Table 3's trial [seed, c, t], decided as ``decide`` says."""
    from ownctl.experiment.asking import Unit, ask_run
    from ownctl.experiment.online import TASK_CONDITIONS, task_trial

    seed, c, t = 3, 1, 2
    mistakes, asked = ask_run(Unit(c, t, "ours", 0), seed, Policy(decide=decide))
    rng = np.random.default_rng([seed, c, t])
    table3 = task_trial(paper_blocks_world, TASK_CONDITIONS[c], "ours", rng, decide)
    assert asked == 0 and mistakes == table3.counts["mistakes"] > 0


def test_an_unknown_decision_mode_is_refused() -> None:
    with pytest.raises(UnknownName, match="known decision modes: map, posterior, window"):
        Policy(decide="vote")
