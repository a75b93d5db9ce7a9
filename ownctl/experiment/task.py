"""The task loop shared by the in-memory experiments and the MuJoCo runner (reference 7.5, 8.1).

A task (``collectAll``, ``trashAll``) visits every object in ascending order. An object already in
the task's target area is done (checked when it is dequeued, so earlier moves count). Otherwise
the :class:`~ownctl.mind.Mind` decides the action's object-targeted steps (``find``,
``pickUp``, then ``trash`` or ``collect``): a step's permission decides it when there is one, else
its rules on the posterior at the obedience threshold. The :class:`Instructor` may then teach the
Mind and override the decision (stop an allowed action, force a refused one); the
:class:`Executor` performs what is finally allowed and reports where objects are afterwards.

Ground truth (the world's true norms and owners) is read only by the oracle instructor and by the
report's metrics, never by the Mind.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np

from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.metrics import ownership_scores, rule_scores
from ownctl.experiment.task_report import StepRecord, TaskReport
from ownctl.experiment.truth import TrueNorms
from ownctl.logic.prob import p_forbidden
from ownctl.logic.vocab import object_steps
from ownctl.mind import Mind
from ownctl.world.model import Area, Position, World

MOVE_TOLERANCE = 0.01  # metres: a smaller displacement is not a move (architecture section 11, "left OBJ")


@dataclass(frozen=True)
class Task:
    """A whole-workspace task: apply ``action`` to every object not yet in ``area``."""

    name: str
    action: str
    area: str


TASKS: dict[str, Task] = {
    "collectAll": Task("collectAll", "collect", "home"),
    "trashAll": Task("trashAll", "trash", "trash"),
}


def get_task(name: str) -> Task:
    """The task called ``name``; UnknownName listing the tasks otherwise."""
    try:
        return TASKS[name]
    except KeyError:
        raise UnknownName("task", name, TASKS) from None


@dataclass(frozen=True)
class Execution:
    """What an executor reports for one action: success, or the error that stopped it."""

    ok: bool
    error: str | None = None


class Outcome(Protocol):
    """What :meth:`Executor.perform` returns: :class:`Execution`, or anything with ``ok`` and
    ``error`` (``sim.world.StepOutcome`` qualifies, so a physics executor is a thin wrapper)."""

    @property
    def ok(self) -> bool: ...

    @property
    def error(self) -> str | None: ...


class Executor(Protocol):
    """Performs object actions (``trash``, ``collect``) and reports object positions.

    A physics executor: ``perform = lambda action, name: getattr(physics_world, action)(name)``
    and ``position = physics_world.position``.
    """

    def perform(self, action: str, name: str) -> Outcome:
        """Do ``action`` on object ``name``."""
        ...

    def position(self, name: str) -> Position | None:
        """Where object ``name`` is now (None if unknown)."""
        ...


@dataclass(frozen=True)
class Attempt:
    """The Mind's decision on one object, as the instructor sees it before the robot acts."""

    task: Task
    obj: int
    name: str
    steps: tuple[str, ...]
    allowed: bool
    forbidding: tuple[str, ...]  # the steps the Mind believes forbidden


@dataclass(frozen=True)
class Verdict:
    """The instructor's reaction: ``override`` is ``"skip"``, ``"force"`` or None (let it be)."""

    override: str | None = None


class Instructor(Protocol):
    """Reacts to each attempt: may teach ``mind`` (permissions, claims) and override the decision."""

    def react(self, attempt: Attempt, mind: Mind) -> Verdict:
        """Teach and judge one attempt."""
        ...


class Asker(Protocol):
    """Asks questions before the robot acts on an object (docs/asking.md, section 4)."""

    def before(self, mind: Mind, obj: int, remaining: Sequence[int]) -> None:
        """Ask (and have answered) questions before acting on ``obj``; ``remaining`` are the
        objects the task will still attempt, ``obj`` first."""
        ...


class SilentInstructor:
    """No instructor: the robot acts on its own decisions and learns nothing."""

    def react(self, attempt: Attempt, mind: Mind) -> Verdict:
        """Never teaches, never overrides."""
        return Verdict()


def area_named(areas: Sequence[Area], name: str) -> Area:
    """The area called ``name``; BadValue listing the areas otherwise (a task needs its area)."""
    for area in areas:
        if area.name == name:
            return area
    raise BadValue(f"the task needs an area {name!r}; the world's areas: "
                   f"{', '.join(a.name for a in areas) or '(none)'}", [a.name for a in areas])


def inside(area: Area, position: Position | None) -> bool:
    """Whether ``position`` lies in ``area`` (no position: nowhere)."""
    return position is not None and bool(area.contains(np.array(position[:2]))[0])


def run_task(
    mind: Mind,
    world: World,
    task: Task | str,
    executor: Executor,
    instructor: Instructor,
    on_step: Callable[[StepRecord], None] | None = None,
    asker: Asker | None = None,
) -> TaskReport:
    """Run ``task`` over every object of ``mind`` (whose objects are the world's, in order);
    ``asker`` may ask questions before each attempt."""
    task = get_task(task) if isinstance(task, str) else task
    truth = TrueNorms(world)
    records = run_objects(mind, truth, task, executor, instructor, on_step=on_step, asker=asker)
    return _report(mind, truth, task, object_steps(task.action), records)


def run_objects(mind: Mind, truth: TrueNorms, task: Task, executor: Executor, instructor: Instructor,
                start: int = 0, attempts: int | None = None,
                on_step: Callable[[StepRecord], None] | None = None,
                asker: Asker | None = None) -> list[StepRecord]:
    """The task loop from object ``start`` on, stopped after ``attempts`` attempted objects (None:
    to the end): one record per object visited (what :func:`run_task` reports on). A question's
    look-ahead runs it on a fork of the Mind (docs/asking.md, section 4)."""
    target = area_named(mind.areas, task.area)
    steps = object_steps(task.action)
    records: list[StepRecord] = []
    tried = 0
    for i in range(start, len(mind.objects)):
        name = mind.objects[i].name
        if inside(target, mind.objects[i].position):
            record = StepRecord(i, name, "done", reason=f"already in {task.area}")
        elif attempts is not None and tried >= attempts:
            break
        else:
            if asker is not None:
                asker.before(mind, i, remaining(mind, target, i))
            record = _attempt(mind, truth, task, steps, i, executor, instructor)
            _sync(mind, executor)
            tried += 1
        records.append(record)
        if on_step is not None:
            on_step(record)
    if attempts is None:
        _retry_failed(mind, task, steps, executor, records, on_step)
    return records


FAILED = "failed: "  # the reason of an object whose action the executor could not complete
RETRIED = "delivered on a later try"


def _retry_failed(mind: Mind, task: Task, steps: tuple[str, ...], executor: Executor,
                  records: list[StepRecord], on_step: Callable[[StepRecord], None] | None) -> None:
    """Act again, once every object was visited, on those whose action failed: a block that lay
    under another, or too close to its neighbours, is often free by then. Passes in task order
    repeat while one delivers (a pile comes down one block per pass at worst). Nothing is decided
    or taught again, but an object the Mind now believes forbidden is left alone unless the
    instructor forced it. ``records`` is updated in place; ``on_step`` sees each delivery."""
    progress = True
    while progress:
        progress = False
        for k, record in enumerate(records):
            if record.outcome != "skipped" or not record.reason.startswith(FAILED):
                continue
            if not record.forced and mind.decide(task.action, record.obj, steps)[0]:
                continue
            done = executor.perform(task.action, record.name)
            _sync(mind, executor)
            if done.ok:
                records[k] = replace(record, outcome="delivered", reason=RETRIED)
                progress = True
                if on_step is not None:
                    on_step(records[k])


def remaining(mind: Mind, target: Area, start: int) -> list[int]:
    """The objects from ``start`` on that are not yet in the task's area (those it will attempt)."""
    return [k for k in range(start, len(mind.objects)) if not inside(target, mind.objects[k].position)]


def _attempt(mind: Mind, truth: TrueNorms, task: Task, steps: tuple[str, ...], i: int,
             executor: Executor, instructor: Instructor) -> StepRecord:
    name = mind.objects[i].name
    forbidden, bad = mind.decide(task.action, i, steps)
    allowed = not forbidden
    violated = truth.violated(i, mind.objects[i], steps)
    mistake = allowed == violated
    verdict = instructor.react(Attempt(task, i, name, steps, allowed, tuple(bad)), mind)
    act, forced = allowed, False
    reason = "" if allowed else "refused: " + ", ".join(f"{s} forbidden" for s in bad)
    if verdict.override == "skip" and allowed:
        act, reason = False, "stopped by the instructor"
    elif verdict.override == "force" and not allowed:
        act, forced, reason = True, True, ""
    outcome = "skipped"
    if act:
        done = executor.perform(task.action, name)
        outcome = "delivered" if done.ok else "skipped"
        reason = "" if done.ok else f"{FAILED}{done.error or 'unknown error'}"
    return StepRecord(i, name, outcome, allowed, violated, mistake, forced, reason, tuple(bad))


def _sync(mind: Mind, executor: Executor) -> None:
    """Let the Mind perceive every object that moved by more than MOVE_TOLERANCE."""
    for i, obj in enumerate(list(mind.objects)):
        new = executor.position(obj.name)
        old = obj.position
        if new is None or (old is not None and np.linalg.norm(np.subtract(new, old)) < MOVE_TOLERANCE):
            continue
        mind.move(i, tuple(float(v) for v in new))  # type: ignore[arg-type]


def _report(mind: Mind, truth: TrueNorms, task: Task, steps: tuple[str, ...],
            records: list[StepRecord]) -> TaskReport:
    frame = truth.frame(mind.objects)
    rules = {a: rule_scores(p_forbidden(r, frame), p_forbidden(mind.rules[a], frame))
             for a, r in truth.rules.items()}
    post = mind.posterior()
    owners = truth.ownership
    ownership = {a: ownership_scores(owners[:, j], post[:, j]) for j, a in enumerate(mind.agents)}
    relevant = tuple(s for s in steps if s in truth.rules)
    return TaskReport(task.name, tuple(records), rules, relevant, ownership)
