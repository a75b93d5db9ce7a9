"""The in-memory Mind's additions (moves, snapshots, lazy prediction) and the shared task loop."""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.kinematic import KinematicExecutor
from ownctl.experiment.oracle import OracleInstructor
from ownctl.experiment.task import SilentInstructor, StepRecord, get_task, inside, run_task
from ownctl.experiment.truth import TrueNorms
from ownctl.logic.rules import parse_norm
from ownctl.mind import Mind, Switches
from ownctl.world.generator import paper_blocks_world
from ownctl.world.model import Area, ObjectSpec, World


def paper(seed: int = 0) -> World:
    return paper_blocks_world(np.random.default_rng([seed, 99]))


def mind_of(world: World, **switches: bool) -> Mind:
    return Mind(world.agents, list(world.objects), world.areas, switches=Switches(**switches))


def test_lazy_prediction_equals_refitting_after_every_claim() -> None:
    world = paper()
    truth = world.true_ownership()
    lazy, eager = mind_of(world), mind_of(world)
    for i in (0, 1, 2, 5, 6):
        for j, agent in enumerate(world.agents):
            lazy.claim(i, agent, truth[i, j])
            eager.claim(i, agent, truth[i, j])
            _ = eager.prior  # force the refit now
    assert np.array_equal(lazy.prior, eager.prior)
    assert not np.allclose(lazy.prior, lazy.settings.predict.base_rate)  # predictions were made


def test_move_changes_areas_but_examples_keep_the_state_they_were_given_in() -> None:
    home = Area("home", (-0.1, -0.1, 0.1, 0.1))
    objs = [ObjectSpec("a", "red", (0.5, 0.5, 0.0)), ObjectSpec("b", "red", (0.6, 0.5, 0.0))]
    mind = Mind(("x",), objs, (home,), switches=Switches(prediction=False))
    mind.permit("collect", 0, 0.0)
    mind.move(0, (0.0, 0.0, 0.0))
    mind.move(1, (0.0, 0.0, 0.0))
    assert mind.frame().areas["home"].tolist() == [True, True]  # decisions see where objects are
    ev, idx = mind.evidence("collect")
    assert idx == [0] and ev.frame.areas["home"].tolist() == [False]  # the example: where it was
    mind.permit("collect", 1, 1.0)  # a permission given now describes the object now
    ev, idx = mind.evidence("collect")
    assert ev.frame.areas["home"].tolist() == [False, True]


def test_instructed_true_rules_decide_like_the_truth_with_true_owners() -> None:
    world = paper()
    mind = mind_of(world, inference=False, prediction=False)
    mind.claims[:] = world.true_ownership()
    for text in world.norms:
        mind.instruct(parse_norm(text))
    truth = TrueNorms(world)
    for i, obj in enumerate(world.objects):
        steps = ("find", "pickUp", "trash")
        assert mind.decide("trash", i, steps)[0] == truth.violated(i, obj, steps)


def test_referenced_agents_follow_the_true_rules_of_the_steps() -> None:
    truth = TrueNorms(paper())
    assert truth.referenced_agents(("find", "pickUp", "collect")) == ("agent2",)
    assert truth.referenced_agents(("find", "pickUp", "trash")) == ("agent1", "agent2", "agent3")


def test_kinematic_executor_puts_objects_on_distinct_spots_inside_the_area() -> None:
    world = paper()
    ex = KinematicExecutor(world)
    home = next(a for a in world.areas if a.name == "home")
    for obj in world.objects:
        assert ex.perform("collect", obj.name).ok
    spots = np.array([ex.position(o.name)[:2] for o in world.objects])
    assert all(inside(home, ex.position(o.name)) for o in world.objects)
    gaps = np.hypot(*(spots[:, None, :] - spots[None, :, :]).transpose(2, 0, 1))
    assert gaps[np.triu_indices(len(spots), 1)].min() > 0.03
    assert not ex.perform("trash", "no-such").ok
    with pytest.raises(UnknownName):
        ex.perform("wave", world.objects[0].name)


def test_silent_instructor_run_delivers_everything_allowed_and_counts_violations() -> None:
    world = paper(1)
    mind = mind_of(world)
    seen: list[StepRecord] = []
    report = run_task(mind, world, "trashAll", KinematicExecutor(world), SilentInstructor(), seen.append)
    assert [r.name for r in seen] == [o.name for o in world.objects]
    truth = TrueNorms(world)
    owned = world.true_ownership().max(axis=1) >= 0.5
    trash = next(a for a in world.areas if a.name == "trash")
    start_inside = [inside(trash, o.position) for o in world.objects]
    expected = sum(owned[i] and not start_inside[i] for i in range(len(world.objects)))
    assert len(report.violations) == expected == report.mistakes  # nothing known: all allowed
    assert len(report.delivered) == sum(not s for s in start_inside)
    assert all(r.outcome == "done" for r, s in zip(seen, start_inside, strict=True) if s)
    assert not any(mind.rules.values())  # nobody taught it anything
    assert truth.rules.keys() == report.rules.keys()


def test_oracle_run_is_consistent_and_learns() -> None:
    world = paper(2)
    mind = mind_of(world)
    report = run_task(mind, world, "collectAll", KinematicExecutor(world), OracleInstructor(world))
    records = [r for r in report.records if r.outcome != "done"]
    for r in records:
        assert r.mistake == (r.allowed == r.violated)
        # the oracle corrects every mistake: violations are never executed, refusals of allowed
        # actions are forced
        if r.mistake:
            assert (r.outcome == "skipped") == r.violated and r.forced == (not r.allowed)
    assert report.violations == []
    assert report.mistakes < 8.75  # the allow-everything baseline of the paper
    assert report.relevant == ("pickUp", "collect")
    for r in records:  # the oracle gave the true permission of every step of every attempt
        assert all(mind.permission(s, r.obj) is not None for s in ("find", "pickUp", "collect"))
    assert report.rule_average().accuracy > 0.9


def test_task_needs_its_area_and_a_known_name() -> None:
    world = paper()
    bare = World("bare", world.agents, world.objects, (), world.norms, world.owners)
    with pytest.raises(BadValue, match="area 'home'"):
        run_task(mind_of(bare), bare, "collectAll", KinematicExecutor(bare), SilentInstructor())
    with pytest.raises(UnknownName, match="collectAll, trashAll"):
        get_task("tidyAll")


def test_report_json_has_the_run_shape() -> None:
    world = paper(3)
    report = run_task(mind_of(world), world, "trashAll", KinematicExecutor(world), OracleInstructor(world))
    doc = report.as_dict()
    assert {"task", "delivered", "skipped", "mistakes", "violations", "rule", "ownership"} <= set(doc)
    assert doc["task"] == "trashAll" and doc["mistakes"] == report.mistakes
    assert set(doc["rule"]) >= {"accuracy", "f1"} and set(doc["ownership"]) >= {"accuracy", "f1"}
    assert len(doc["steps"]) == len(world.objects)
    assert all(s["reason"] for s in doc["skipped"])


def test_failed_actions_are_skipped_with_their_reason() -> None:
    from dataclasses import dataclass

    @dataclass
    class Outcome:  # any object with ok and error will do (e.g. sim.world.StepOutcome)
        ok: bool
        error: str | None

    world = paper(4)

    class Slippery(KinematicExecutor):
        def perform(self, action: str, name: str) -> Outcome:  # type: ignore[override]
            if name == "block1":
                return Outcome(False, "the grasp slipped")
            super().perform(action, name)
            return Outcome(True, None)

    report = run_task(mind_of(world), world, "trashAll", Slippery(world), SilentInstructor())
    assert ("block1", "failed: the grasp slipped") in report.skipped
    assert "block1" not in report.delivered and report.delivered


class Piled(KinematicExecutor):
    """A kinematic executor on which each block of ``under`` cannot be moved while the block named
    for it is not yet trashed (it lies on top), and which counts the attempts per block."""

    def __init__(self, world: World, under: dict[str, str]) -> None:
        super().__init__(world)
        self.under, self.tries = under, {o.name: 0 for o in world.objects}

    def perform(self, action: str, name: str):  # type: ignore[no-untyped-def]
        from ownctl.experiment.task import Execution

        self.tries[name] += 1
        top = self.under.get(name)
        if top is not None and not inside(get_area(self.world, "trash"), self.position(top)):
            return Execution(False, f"{top} lies on top of it")
        return super().perform(action, name)


def get_area(world: World, name: str) -> Area:
    return next(a for a in world.areas if a.name == name)


def test_a_failed_action_is_tried_again_once_the_block_on_top_is_gone() -> None:
    from ownctl.experiment.task import RETRIED, run_objects

    world = paper(4)
    pile = Piled(world, {"block1": "block2", "block2": "block3"})  # block3 on block2 on block1
    seen: list[tuple[str, str]] = []
    records = run_objects(mind_of(world), TrueNorms(world), get_task("trashAll"), pile, SilentInstructor(),
                          on_step=lambda r: seen.append((r.name, r.outcome)))
    fate = {r.name: (r.outcome, r.reason) for r in records}
    assert fate["block1"] == fate["block2"] == ("delivered", RETRIED)
    assert pile.tries["block1"] == 3 and pile.tries["block2"] == 2  # one pass per block of the pile
    assert all(n == 1 for name, n in pile.tries.items() if name not in ("block1", "block2"))
    assert seen[-2:] == [("block2", "delivered"), ("block1", "delivered")]  # each delivery reported


def test_a_block_that_stays_covered_or_is_now_forbidden_is_not_delivered() -> None:
    from ownctl.experiment.task import run_objects

    world = paper(4)
    mind = mind_of(world, frozen_rules=True)  # permissions decide their objects alone
    trash = get_area(world, "trash")
    last = [o.name for o in world.objects if not inside(trash, o.position)][-1]
    pile = Piled(world, {"block1": last, "block2": "block1", "block3": "block4"})
    mind.permit("trash", "block4", 1.0)  # block4 stays where it is, on block3

    def forbid_block2_at_the_end(record: StepRecord) -> None:
        if record.name == last:
            mind.permit("trash", "block2", 1.0)

    records = run_objects(mind, TrueNorms(world), get_task("trashAll"), pile, SilentInstructor(),
                          on_step=forbid_block2_at_the_end)
    fate = {r.name: (r.outcome, r.reason) for r in records}
    assert fate["block1"][0] == "delivered"  # freed when the last block went
    assert fate["block2"] == ("skipped", "failed: block1 lies on top of it")
    assert pile.tries["block2"] == 1  # forbidden by then: not tried again
    assert fate["block3"] == ("skipped", "failed: block4 lies on top of it")
    assert pile.tries["block3"] == 3  # tried in each pass, the last delivering nothing
