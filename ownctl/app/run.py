"""``ownctl run trashAll|collectAll``: the paper's tasks on the store's world, in MuJoCo or kinematically.

The robot's beliefs are loaded from the store into the in-memory Mind the experiments use, the
shared task loop (:func:`ownctl.experiment.task.run_task`) visits every object, and after every
object what the robot learned (permissions, claims, rules, beliefs) and where objects ended up are
written back, each object's attempt in its own transaction (DESIGN section 9). A store with no
objects first receives the paper's blocks world with its ground truth, so the command works on a
fresh machine.

Instructors: ``oracle`` plays the paper's simulated human from the store's ground truth (true norms
and owners); ``none`` lets the robot act on its own beliefs. Interrupts are utterances spoken when
the robot is about to act on an object ("No Baxter, that's mine!"); they are taught before the
instructor reacts, and a reprimand stops that attempt.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from ownctl.app.context import AppContext
from ownctl.app.mindstore import mind_from_store, save_mind
from ownctl.app.worldfile import current_world, store_world
from ownctl.errors import BadValue, OwnctlError
from ownctl.experiment.mind import Mind
from ownctl.experiment.task import Attempt, Execution, Instructor, Verdict, get_task, run_task
from ownctl.experiment.task_report import StepRecord, TaskReport
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

    @property
    def ok(self) -> bool:
        """False if some step failed in the physics (exit code 4)."""
        return not self.failed_steps

    def as_json(self) -> dict[str, Any]:
        """DESIGN section 7's ``run`` shape plus details."""
        rtf = self.sim_seconds / self.wall_seconds if self.wall_seconds > 0 else 0.0
        return {**self.report.as_dict(), "sim_seconds": self.sim_seconds, "wall_seconds": self.wall_seconds,
                "real_time_factor": rtf, "failed_steps": list(self.failed_steps),
                "loaded_world": self.loaded_world}


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
        self.failed: list[str] = []

    def perform(self, action: str, name: str) -> Execution:
        """Trash or collect ``name`` with the robot; a failed step is remembered for exit code 4."""
        outcome = self.world.trash(name) if action == "trash" else self.world.collect(name)
        if not outcome.ok:
            self.failed.append(f"{action} {name}: {outcome.error}")
        return Execution(outcome.ok, outcome.error)

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
        """Speak the matching interrupts; a reprimand (skip) ends the attempt there."""
        hits = [i for i in self.pending if i.object == attempt.name and i.action in attempt.steps]
        for hit in hits:
            self.pending.remove(hit)
        skip = any([self.teach(mind, hit, attempt) for hit in hits])
        if skip and attempt.allowed:
            return Verdict("skip")
        return self.base.react(attempt, mind)


def teach_utterance(mind: Mind, hit: Interrupt, attempt: Attempt) -> bool:
    """Apply an utterance's instructions to the Mind; True if it asks the robot to stop."""
    from ownctl.language import Claim, Context, NormInstruction, Permission, Skip, teaching_order, understand

    ctx = Context(speaker=hit.speaker, about=hit.object, action=attempt.task.action,
                  agents=frozenset(mind.agents), objects=frozenset(o.name for o in mind.objects))
    stop = False
    for _, ins in teaching_order(understand(hit.utterance, ctx).instructions):
        if isinstance(ins, Claim):
            mind.claim(mind.index[ins.object], ins.agent, ins.probability, exclusive=ins.exclusive)
        elif isinstance(ins, Permission):
            mind.permit(ins.action, mind.index[ins.object], 1.0 if ins.forbid else 0.0)
        elif isinstance(ins, NormInstruction):
            mind.instruct(ins.norm)
        elif isinstance(ins, Skip):
            stop = True
    return stop


def _ensure_world(ctx: AppContext, seed: int, layout_seed: int | None) -> bool:
    """Load the paper's blocks world into an empty store, or a new layout beside the old one."""
    import numpy as np

    from ownctl.world.generator import paper_blocks_world

    with ctx.read() as tx:
        empty = not tx.objects()
        agents = tuple(a.name for a in tx.agents())
        norms = tuple(tx.truth_norms())
        base_seed = tx.settings().get("world.seed")
    if not empty and layout_seed is None:
        return False
    rng = np.random.default_rng(seed if layout_seed is None else layout_seed)
    if empty:
        world = paper_blocks_world(rng)
    else:
        if not norms:
            raise OwnctlError("--layout-seed needs a store whose world has true norms (load a world file)")
        places = None if base_seed is None else np.random.default_rng(int(base_seed))
        world = paper_blocks_world(rng, agents=agents or ("agent1", "agent2", "agent3"), norms=norms,
                                   prefix=f"l{layout_seed}-block", places=places)
    with ctx.write({"op": "world.generate", "seed": seed, "layout_seed": layout_seed}) as tx:
        store_world(tx, world, ctx.now, skip_existing_areas=True)
        if empty:
            tx.set_setting("world.seed", seed)
    return True


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
) -> RunReport:
    """Play ``task`` on the store's world; persist every object's attempt as it happens."""
    check_options(task, instructor, arm, grasp, render, camera)
    chosen = get_task(task)
    loaded = _ensure_world(ctx, seed, layout_seed)
    world = current_world(ctx)
    from ownctl.experiment.oracle import OracleInstructor
    from ownctl.experiment.task import SilentInstructor

    with ctx.read() as tx:
        mind = mind_from_store(tx, world)
    base: Instructor = OracleInstructor(world) if instructor == "oracle" else SilentInstructor()
    teacher = Interrupting(base, interrupts, teach_utterance) if interrupts else base
    if physics:
        executor: Any = PhysicsExecutor(world, seed, arm, grasp, render, camera)
    else:
        from ownctl.experiment.kinematic import KinematicExecutor

        executor = KinematicExecutor(world)

    def persist(record: StepRecord) -> None:
        payload = {"op": "run.step", "task": chosen.name, "object": record.name, "outcome": record.outcome,
                   "reason": record.reason, "mistake": record.mistake}
        with ctx.write(payload) as tx:
            save_mind(tx, mind, ctx.now, [record.obj])
            refusal = None if record.allowed else {"action": chosen.action, "object": record.name,
                                                   "steps": list(record.forbidding), "at": ctx.now}
            tx.converse(target=record.name, action=chosen.action, refusal=refusal)
        if on_step is not None:
            on_step(record)

    start = time.perf_counter()
    try:
        report = run_task(mind, world, chosen, executor, teacher, on_step=persist)
    finally:
        if physics:
            executor.finish()
    wall = time.perf_counter() - start
    sim_seconds = executor.sim_time if physics else 0.0
    failed = tuple(executor.failed) if physics else ()
    return RunReport(report, sim_seconds, wall, failed, loaded)
