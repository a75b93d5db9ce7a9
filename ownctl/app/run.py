"""``ownctl run trashAll|collectAll``: the paper's tasks on the store's world, in MuJoCo or kinematically.

The robot's beliefs are loaded from the store into the in-memory Mind the experiments use, the
shared task loop (:func:`ownctl.experiment.task.run_task`) visits every object, and after every
object what the robot learned (permissions, claims, rules, beliefs) and where objects ended up are
written back, each object's attempt in its own transaction (docs/architecture.md, section 9). An empty
store (no object, no agent) first receives the paper's blocks world with its ground truth, so the
command works on a fresh machine.

Instructors: ``oracle`` plays the paper's simulated human from the store's ground truth (true norms
and owners); ``none`` lets the robot act on its own beliefs. Interrupts are utterances spoken when
the robot is about to act on an object ("No Baxter, that's mine!"); they are taught before the
instructor reacts, and a reprimand stops that attempt.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from ownctl.app.context import AppContext
from ownctl.app.mindstore import load as load_mind
from ownctl.app.worldfile import current_world, store_world
from ownctl.errors import BadValue, OwnctlError
from ownctl.experiment.task import Attempt, Execution, Instructor, Verdict, get_task, run_task
from ownctl.experiment.task_report import StepRecord, TaskReport
from ownctl.mind import Mind
from ownctl.world.model import Position, World

INSTRUCTORS = ("oracle", "none")
ARMS = ("auto", "left", "right")
GRASPS = ("weld", "friction")


def check_options(task: str, instructor: str, arm: str, grasp: str, render: str | None,
                  camera: str = "front") -> None:
    """Refuse bad options before anything is loaded, shown or written (names the valid values)."""
    get_task(task)
    for what, value, valid in (("instructor", instructor, INSTRUCTORS), ("arm", arm, ARMS),
                               ("grasp", grasp, GRASPS)):
        if value not in valid:
            raise BadValue(f"unknown {what} {value!r}; valid: {', '.join(valid)}", valid)
    if render and not render.endswith((".png", ".mp4")):
        raise BadValue(f"--render must name a .png or .mp4 file, got {render!r}")
    from sim.scene import check_camera

    check_camera(camera)
    if render:
        from sim.gl import ensure_rendering

        ensure_rendering()  # no working OpenGL: one line naming the package, before anything is written


def check_ask(ask: int) -> None:
    """Refuse a negative question budget (before anything is shown or written)."""
    if ask < 0:
        raise BadValue(f"--ask must be at least 0, got {ask}")


@dataclass(frozen=True)
class Interrupt:
    """``utterance`` said by ``speaker`` when the robot is about to do ``action`` on ``object``."""

    action: str
    object: str
    utterance: str
    speaker: str


@dataclass(frozen=True)
class RunReport:
    """A finished run: the task report plus timing and what the physics did."""

    report: TaskReport
    sim_seconds: float
    wall_seconds: float
    failed_steps: tuple[str, ...]
    loaded_world: bool
    questions: tuple[dict[str, Any], ...] = ()  # asked with --ask (docs/asking.md, section 4)

    @property
    def ok(self) -> bool:
        """False if some step failed in the physics (exit code 4)."""
        return not self.failed_steps

    def as_json(self) -> dict[str, Any]:
        """architecture section 7's ``run`` shape plus details."""
        rtf = self.sim_seconds / self.wall_seconds if self.wall_seconds > 0 else 0.0
        return {**self.report.as_dict(), "sim_seconds": self.sim_seconds, "wall_seconds": self.wall_seconds,
                "real_time_factor": rtf, "failed_steps": list(self.failed_steps),
                "loaded_world": self.loaded_world, "questions": list(self.questions)}


class PhysicsExecutor:
    """The task loop's executor backed by the MuJoCo Baxter (imported only when used)."""

    def __init__(self, world: World, seed: int, arm: str, grasp: str, render: str | None,
                 camera: str = "front") -> None:
        from sim.world import PhysicsWorld, SimArea, SimBlock

        blocks = [SimBlock(o.name, o.color, o.position) for o in world.objects]
        areas = [SimArea(a.name, a.box) for a in world.areas]
        video = render if render and render.endswith(".mp4") else None
        self.world = PhysicsWorld(blocks, areas, seed=seed, arm=arm, grasp=grasp, render=video, camera=camera)
        self.render = render
        self._failed: dict[tuple[str, str], str] = {}

    def perform(self, action: str, name: str) -> Execution:
        """Trash or collect ``name`` with the robot; a step that failed, and did not succeed when
        tried again, is remembered for exit code 4."""
        outcome = self.world.trash(name) if action == "trash" else self.world.collect(name)
        if outcome.ok:
            self._failed.pop((action, name), None)
        else:
            self._failed[action, name] = f"{action} {name}: {outcome.error}"
        return Execution(outcome.ok, outcome.error)

    @property
    def failed(self) -> list[str]:
        """The steps that failed and were not completed later, in the order they first failed."""
        return list(self._failed.values())

    def position(self, name: str) -> Position | None:
        """Where ``name`` is now, in workspace coordinates."""
        return self.world.position(name)

    @property
    def sim_time(self) -> float:
        """Seconds of simulated time so far."""
        return float(self.world.sim_time)

    def finish(self) -> None:
        """Write the requested picture or video and free the renderer."""
        if self.render and self.render.endswith(".mp4"):
            self.world.finish_video(self.render)
        elif self.render:
            self.world.render_png(self.render)
        self.world.close()


class Interrupting:
    """Teaches the interrupts' utterances before the base instructor reacts."""

    def __init__(self, base: Instructor, interrupts: Sequence[Interrupt], teach: Callable[..., bool]) -> None:
        self.base, self.pending, self.teach = base, list(interrupts), teach

    def react(self, attempt: Attempt, mind: Mind) -> Verdict:
        """Speak the matching interrupts; a reprimand (skip) ends the attempt there, and so does
        anything taught that makes the robot, deciding again, refuse it ("Don't throw that away"
        said as it does: the permission now forbids the step it is doing)."""
        hits = [i for i in self.pending if i.object == attempt.name and i.action in attempt.steps]
        for hit in hits:
            self.pending.remove(hit)
        skip = any([self.teach(mind, hit, attempt) for hit in hits])
        if hits and not skip and attempt.allowed:
            skip = mind.decide(attempt.task.action, attempt.obj, attempt.steps)[0]
        if skip and attempt.allowed:
            return Verdict("skip")
        return self.base.react(attempt, mind)


def _teach_claim(mind: Mind, ins: Any, speaker: str) -> bool:
    mind.claim(ins.object, ins.agent, ins.p, negated=ins.negated, exclusive=ins.exclusive, speaker=speaker)
    return False


def _teach_permission(mind: Mind, ins: Any, speaker: str) -> bool:
    mind.permit(ins.action, ins.object, 1.0 if ins.forbid else 0.0, speaker)
    return False


def _teach_norm(mind: Mind, ins: Any, speaker: str) -> bool:
    mind.instruct(ins.norm, speaker)
    return False


def _stop(mind: Mind, ins: Any, speaker: str) -> bool:
    return True


def teaching() -> dict[type, Callable[[Mind, Any, str], bool]]:
    """Which Mind instruction an understood instruction becomes during a run (True: stop the
    attempt). Questions and introductions are not taught during a run."""
    from ownctl.language import Claim, NormInstruction, Permission, Skip

    return {Claim: _teach_claim, Permission: _teach_permission, NormInstruction: _teach_norm, Skip: _stop}


def teach_utterance(mind: Mind, hit: Interrupt, attempt: Attempt) -> bool:
    """Apply an utterance's instructions to the Mind; True if it asks the robot to stop."""
    from ownctl.language import Context, teaching_order, understand

    ctx = Context(speaker=hit.speaker, about=hit.object, action=attempt.task.action,
                  agents=frozenset(mind.agents), objects=frozenset(o.name for o in mind.objects))
    table = teaching()
    stops = [table[type(ins)](mind, ins, hit.speaker)
             for _, ins in teaching_order(understand(hit.utterance, ctx).instructions) if type(ins) in table]
    return any(stops)


def _new_world(ctx: AppContext, seed: int, layout_seed: int | None) -> tuple[World | None, bool]:
    """The world a run adds (the paper's blocks world for an empty store, a new layout beside the old
    objects for ``layout_seed``), or None; and whether the store was empty (no object and no agent:
    a store whose world has agents but no objects keeps its world, and a task finds nothing to do).
    Nothing is written."""
    import numpy as np

    from ownctl.world.generator import paper_blocks_world

    with ctx.read() as tx:
        agents = tuple(a.name for a in tx.world.agents())
        empty = not tx.things.objects() and not agents  # a world of its own, even with no objects
        norms = tuple(tx.knowledge.truth_norms())
        base_seed = tx.meta.settings().get("world.seed")
    if not empty and layout_seed is None:
        return None, False
    rng = np.random.default_rng(seed if layout_seed is None else layout_seed)
    if empty:
        world = paper_blocks_world(rng)
    else:
        if not norms:
            raise OwnctlError("--layout-seed needs a store whose world has true norms (load a world file)")
        places = None if base_seed is None else np.random.default_rng(int(base_seed))
        world = paper_blocks_world(rng, agents=agents or ("agent1", "agent2", "agent3"), norms=norms,
                                   prefix=f"l{layout_seed}-block", places=places)
    return world, empty


def _joined(old: World, new: World) -> World:
    """The store's world with ``new``'s objects and areas after its own (as storing would order them)."""
    areas = {a.name: a for a in (*old.areas, *new.areas)}
    agents = tuple(sorted({*old.agents, *new.agents}))
    return replace(old, agents=agents, objects=(*old.objects, *new.objects),
                   areas=tuple(areas[n] for n in sorted(areas)), norms=old.norms or new.norms,
                   owners={**old.owners, **new.owners})


def run(
    ctx: AppContext,
    task: str,
    *,
    instructor: str = "oracle",
    physics: bool = True,
    seed: int = 0,
    layout_seed: int | None = None,
    arm: str = "auto",
    grasp: str = "weld",
    render: str | None = None,
    camera: str = "front",
    interrupts: Sequence[Interrupt] = (),
    on_step: Callable[[StepRecord], None] | None = None,
    ask: int = 0,
) -> RunReport:
    """Play ``task`` on the store's world; persist every object's attempt as it happens. With
    ``ask``, up to that many questions are asked before objects (docs/asking.md, section 4): the
    oracle answers them, ``instructor="none"`` only lists them."""
    check_options(task, instructor, arm, grasp, render, camera)
    check_ask(ask)
    from ownctl.experiment.runner import check_seed

    check_seed(seed)
    if layout_seed is not None:
        check_seed(layout_seed, "--layout-seed")
    chosen = get_task(task)
    fresh, empty = _new_world(ctx, seed, layout_seed)
    world = current_world(ctx) if fresh is None else _joined(current_world(ctx), fresh)
    from ownctl.experiment.oracle import OracleInstructor
    from ownctl.experiment.task import SilentInstructor

    # the scene is built (every block placed) before anything is written: a layout that cannot be
    # placed leaves the store as it was
    if physics:
        executor: Any = PhysicsExecutor(world, seed, arm, grasp, render, camera)
    else:
        from ownctl.experiment.kinematic import KinematicExecutor

        executor = KinematicExecutor(world)
    if fresh is not None:
        try:
            with ctx.write({"op": "world.generate", "seed": seed, "layout_seed": layout_seed}) as tx:
                store_world(tx, fresh, ctx.now, skip_existing_areas=True)
                if empty:
                    tx.meta.set_setting("world.seed", seed)
        except BaseException:
            if physics:
                executor.world.close()
            raise
        world = current_world(ctx)
    with ctx.read() as tx:
        stored = load_mind(tx, ctx.now)
    mind = stored.mind
    base: Instructor = OracleInstructor(world) if instructor == "oracle" else SilentInstructor()
    teacher = Interrupting(base, interrupts, teach_utterance) if interrupts else base

    def persist(record: StepRecord) -> None:
        payload = {"op": "run.step", "task": chosen.name, "object": record.name, "outcome": record.outcome,
                   "reason": record.reason, "mistake": record.mistake}
        refusal = None if record.allowed else {"action": chosen.action, "object": record.name,
                                               "steps": list(record.forbidding), "at": ctx.now}

        def write() -> None:
            before = stored.base
            try:
                with ctx.write(payload) as tx:
                    stored.save(tx)
                    tx.meta.converse(target=record.name, action=chosen.action, refusal=refusal)
            except BaseException:
                stored.base = before  # nothing was written: the next try compares with the store again
                raise

        ctx.retrying(write)
        if on_step is not None:
            on_step(record)

    start = time.perf_counter()
    done: list[str] = []

    def saved(record: StepRecord) -> None:
        persist(record)
        done.append(record.name)

    asker = None
    if ask:
        from ownctl.app.settings import asking
        from ownctl.experiment.asking import OracleAnswers, QuestionAsker
        from ownctl.logic.vocab import object_steps

        with ctx.read() as tx:
            min_gain, kinds, temper, read, ahead = asking(tx.meta.settings())
        answers = OracleAnswers(world) if instructor == "oracle" else None
        asker = QuestionAsker(object_steps(chosen.action), "ours", ask, min_gain, answers, kinds=kinds,
                              temper=temper, read=read, ahead=ahead)
    try:
        report = run_task(mind, world, chosen, executor, teacher, on_step=saved, asker=asker)
    except OwnctlError as exc:
        kept = (f"the {len(done)} object{'s' if len(done) != 1 else ''} attempted before were saved, "
                "each in its own transaction" if done else "nothing of the run was saved")
        stopped = OwnctlError(f"{exc} (the run stopped; {kept})")
        stopped.exit_code = exc.exit_code
        raise stopped from None
    finally:
        if physics:
            executor.finish()
    wall = time.perf_counter() - start
    sim_seconds = executor.sim_time if physics else 0.0
    failed = tuple(executor.failed) if physics else ()
    asked = tuple(a.as_dict() for a in asker.asked) if asker is not None else ()
    return RunReport(report, sim_seconds, wall, failed, fresh is not None, asked)
