"""``scenario play FILE``: load a scenario's world into a store, play its steps, check its expectations.

A scenario (architecture section 11; parsed by :mod:`ownctl.world.scenario`) is validated whole before
any store is touched: a malformed file is an error (exit 1) that writes nothing. Playing then

1. loads the world with its ground truth into the store (a temporary one unless ``db`` is given),
   and notes every object's position (``moved``/``left`` compare with it);
2. plays the steps in order on the scenario clock (the start time plus one second per step):
   ``say`` through :func:`ownctl.app.say.say`, ``command`` through the ``run_command`` callback the
   CLI provides (the line runs in-process like a ``batch`` line), ``run`` through the task runner of
   :mod:`ownctl.app.run` with the step's interruptions, kinematically unless ``physics``;
3. after each step checks the step's expectations.

A step that fails (an error, a physics failure) stops the scenario; the report says which step and
why. The scenario passes iff every step ran and every expectation held.
"""

from __future__ import annotations

import math
import tempfile
import time
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ownctl.app.context import AppContext
from ownctl.errors import BadValue, OwnctlError, UnknownName
from ownctl.humanize import plural
from ownctl.world.model import World
from ownctl.world.scenario import (
    CheckExpectation,
    Expectation,
    OwnerExpectation,
    PlaceExpectation,
    RuleExpectation,
    Scenario,
    Step,
    scenario_from_dict,
)

MOVE_TOLERANCE = 0.01  # metres: "left OBJ" means within 1 cm of where it was when the world was loaded

#: Runs one command line (its words) on the scenario's store; returns (exit code, stdout, stderr).
CommandRunner = Callable[[AppContext, Step], tuple[int, str, str]]


@dataclass(frozen=True)
class Checked:
    """One expectation after its step: did it hold, and what was found."""

    text: str
    ok: bool
    actual: str


@dataclass
class StepResult:
    """One played step: its output for people, its data, its expectations."""

    step: Step
    ok: bool = True
    error: str | None = None
    output: list[str] = field(default_factory=list)
    result: Any = None
    checked: list[Checked] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        """The step ran and all its expectations held."""
        return self.ok and all(c.ok for c in self.checked)

    @property
    def data(self) -> dict[str, Any]:
        """JSON form."""
        s = self.step
        return {
            "step": s.number, "kind": s.kind, "text": s.text, "speaker": s.speaker, "about": s.about,
            "ok": self.ok, "error": self.error, "output": self.output, "result": self.result,
            "expectations": [{"expect": c.text, "ok": c.ok, "actual": c.actual} for c in self.checked],
        }


@dataclass
class ScenarioReport:
    """The outcome of playing a scenario."""

    scenario: Scenario
    store: str | None
    steps: list[StepResult] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def checked(self) -> list[Checked]:
        """Every expectation checked so far."""
        return [c for s in self.steps for c in s.checked]

    @property
    def passed(self) -> bool:
        """Every step was played, ran, and every expectation held."""
        return len(self.steps) == len(self.scenario.steps) and all(s.passed for s in self.steps)

    @property
    def data(self) -> dict[str, Any]:
        """``{"scenario", "file", "passed", "expectations": {"total", "passed", "failed"}, "steps"}``."""
        held = sum(c.ok for c in self.checked)
        return {
            "scenario": self.scenario.name,
            "file": self.scenario.source,
            "passed": self.passed,
            "expectations": {"total": len(self.checked), "passed": held, "failed": len(self.checked) - held},
            "steps_played": len(self.steps),
            "steps_total": len(self.scenario.steps),
            "store": self.store,
            "seconds": self.seconds,
            "steps": [s.data for s in self.steps],
        }


def load_scenario(path: str, seed: int = 0) -> tuple[Scenario, World]:
    """Read and validate a scenario file: its world and its steps (task names included)."""
    import numpy as np

    from ownctl.experiment.task import TASKS
    from ownctl.world.spec import world_from_dict

    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        why = getattr(exc, "strerror", None) or exc
        raise OwnctlError(f"cannot read scenario file {path}: {why}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise BadValue(f"{path}: not valid TOML: {exc}") from None
    world = world_from_dict(data, str(path), np.random.default_rng(seed))
    scenario = scenario_from_dict(data, str(path))
    for step in scenario.steps:
        if step.kind == "run" and step.text not in TASKS:
            raise BadValue(f"{path}: step {step.number}: unknown task {step.text!r}; known tasks: "
                           f"{', '.join(TASKS)}", TASKS)
    return scenario, world


# -- expectations ----------------------------------------------------------------------------------

def _positions(ctx: AppContext) -> dict[str, tuple[float, float, float] | None]:
    with ctx.read() as tx:
        return {o.name: None if o.x is None or o.y is None else (o.x, o.y, o.z or 0.0)
                for o in tx.things.objects()}


def check_expectation(ctx: AppContext, expect: Expectation,
                      start: dict[str, tuple[float, float, float] | None]) -> Checked:
    """Evaluate one expectation on the store as it is now."""
    from ownctl.app.decide import check

    try:
        if isinstance(expect, CheckExpectation):
            report = check(ctx, expect.action, expect.object, record=False)
            ok = report.forbidden == expect.forbidden
            return Checked(expect.text, ok, f"{report.data['decision']}: {report.reason}")
        if isinstance(expect, RuleExpectation):
            with ctx.read() as tx:
                texts = [r.text for r in tx.knowledge.rules()]
            action = expect.rule.split()[1]
            mine = [t for t in texts if t.split()[1] == action]
            ok = (expect.rule in texts) == expect.present
            return Checked(expect.text, ok, f"rules of {action}: {'; '.join(mine) or '(none)'}")
        if isinstance(expect, OwnerExpectation):
            return _owner(ctx, expect)
        return _place(ctx, expect, start)
    except OwnctlError as exc:
        return Checked(expect.text, False, f"error: {exc.message}")


def _owner(ctx: AppContext, expect: OwnerExpectation) -> Checked:
    from ownctl.app.query import owners

    with ctx.read() as tx:
        tx.world.agent(expect.agent)  # an unknown agent is an error naming the known ones
    rows = {o["agent"]: o for o in owners(ctx, expect.object)["owners"]}
    row = rows[expect.agent]
    p = row["p"]
    ok = p > expect.p if expect.above else p < expect.p
    return Checked(expect.text, ok, f"p={p:.3g} ({row['source']})")


def _place(ctx: AppContext, expect: PlaceExpectation,
           start: dict[str, tuple[float, float, float] | None]) -> Checked:
    now = _positions(ctx)
    if expect.object not in now:
        raise UnknownName("object", expect.object, now)
    if expect.object not in start:
        raise BadValue(f"{expect.object!r} was not in the scenario's world when it was loaded")
    before, after = start[expect.object], now[expect.object]
    if before is None or after is None:
        distance = 0.0 if before == after else math.inf
    else:
        distance = math.dist(before, after)
    moved = distance > MOVE_TOLERANCE
    where = "no position" if after is None else f"at ({after[0]:.3f}, {after[1]:.3f})"
    return Checked(expect.text, moved == expect.moved, f"moved {distance:.3f} m, now {where}")


# -- steps -------------------------------------------------------------------------------------------

def _say(ctx: AppContext, step: Step, physics: bool, result: StepResult) -> None:
    from ownctl.app.say import say

    report = say(ctx, step.text, step.speaker, step.about, physics=physics)
    result.output = [f"{r['instruction']}: {r['message']}" for r in report.results]
    result.output.append(f"robot: {report.reply}")
    result.result = report.data


def _command(ctx: AppContext, step: Step, runner: CommandRunner | None, result: StepResult) -> None:
    if runner is None:
        raise OwnctlError("command steps need a command runner (play scenarios with ownctl scenario play)")
    code, out, err = runner(ctx, step)
    result.output = [line for line in out.splitlines() if line.strip()]
    result.result = {"exit_code": code, "stdout": out}
    if code not in (0, 3):  # 3: a check answered "forbidden", an answer, not a failure
        result.ok, result.error = False, " ".join(err.split()) or f"exit code {code}"


def _video(render: str | None, step: Step, first: bool) -> str | None:
    if render is None or first:
        return render
    path = Path(render)
    return str(path.with_name(f"{path.stem}-step{step.number}{path.suffix}"))


def _run(ctx: AppContext, step: Step, physics: bool, render: str | None, result: StepResult) -> None:
    from ownctl.app.run import Interrupt
    from ownctl.app.say import run_function
    from ownctl.experiment.task import get_task

    interrupts = [Interrupt(i.action, i.object, i.utterance, i.speaker) for i in step.interrupts]
    with ctx.read() as tx:
        names = {o.name for o in tx.things.objects()}
    unknown = sorted({i.object for i in interrupts} - names)
    if unknown:
        raise BadValue(f"unknown object {unknown[0]!r} in an interrupt; known objects: "
                       f"{', '.join(sorted(names))}", names)
    kwargs: dict[str, Any] = {"instructor": step.instructor, "physics": physics, "interrupts": interrupts}
    if render is not None:
        kwargs["render"] = render
    report = run_function()(ctx, step.text, **kwargs)
    data = report.as_json()
    with ctx.write(None) as tx:
        tx.meta.converse(action=get_task(step.text).action)
    moved = ", ".join(data["delivered"]) or "nothing"
    left = ", ".join(f"{s['object']} ({s['reason']})" for s in data["skipped"]) or "nothing"
    result.output = [f"delivered: {moved}", f"left: {left}",
                     f"{plural(data['mistakes'], 'mistake')}, "
                     f"{plural(len(data['violations']), 'norm violation')}"]
    if render is not None:
        result.output.append(f"wrote {render}")
    result.result = data
    attempted = {s["object"] for s in data["steps"] if s["outcome"] != "done"}
    unsaid = [i for i in step.interrupts if i.object not in attempted]
    if not report.ok:
        result.ok, result.error = False, "task step failed: " + "; ".join(report.failed_steps)
    elif unsaid:
        result.ok = False
        result.error = "; ".join(f"the robot never went to {i.action} {i.object}, so {i.speaker} never said "
                                 f"{i.utterance!r}" for i in unsaid)


def play(
    ctx: AppContext,
    scenario: Scenario,
    world: World,
    *,
    physics: bool = False,
    render: str | None = None,
    run_command: CommandRunner | None = None,
    on_step: Callable[[StepResult], None] | None = None,
) -> ScenarioReport:
    """Load ``world`` into ``ctx``'s store and play ``scenario`` on it (see the module docstring)."""
    from ownctl.app.worldfile import keep_name, store_world

    if render is not None and not physics:
        raise BadValue("--render needs --physics (a kinematic run has nothing to film)")
    if render is not None and not render.endswith((".mp4", ".png")):
        raise BadValue(f"--render must name a .mp4 or .png file, got {render!r}")
    if render is not None:
        from sim.gl import ensure_rendering

        ensure_rendering()  # no working OpenGL: one line naming the package, before anything is written
    started, t0 = time.perf_counter(), ctx.now
    report = ScenarioReport(scenario, ctx.db)
    ctx.interface, ctx.command = "scenario", f"scenario play {scenario.source}"
    with ctx.write({"op": "world.load", "file": scenario.source, "world": world.name}) as tx:
        store_world(tx, world, ctx.now)
        keep_name(tx, world.name)
    start = _positions(ctx)
    runs = 0
    for step in scenario.steps:
        ctx.now = t0 + step.number
        ctx.command = step.describe()
        result = StepResult(step)
        try:
            if step.kind == "say":
                _say(ctx, step, physics, result)
            elif step.kind == "command":
                _command(ctx, step, run_command, result)
            else:
                _run(ctx, step, physics, _video(render, step, runs == 0), result)
                runs += 1
        except OwnctlError as exc:
            result.ok, result.error = False, exc.message
        if result.ok:
            result.checked = [check_expectation(ctx, e, start) for e in step.expect]
        report.steps.append(result)
        if on_step is not None:
            on_step(result)
        if not result.ok:
            break
    report.seconds = time.perf_counter() - started
    return report


def play_file(
    path: str,
    db: str | None,
    now: float,
    *,
    physics: bool = False,
    render: str | None = None,
    run_command: CommandRunner | None = None,
    on_step: Callable[[StepResult], None] | None = None,
    before: Callable[[Scenario], None] | None = None,
) -> ScenarioReport:
    """Validate ``path``, then play it on the store ``db`` (None: a new temporary store).

    ``before`` is called with the parsed scenario once it is known to be valid.
    """
    from ownctl.app.admin import init

    scenario, world = load_scenario(path)
    if before is not None:
        before(scenario)
    with tempfile.TemporaryDirectory(prefix="ownctl-scenario-") as tmp:
        ctx = AppContext(db if db is not None else str(Path(tmp) / "scenario.db"), now)
        try:
            if db is None:
                init(ctx)
            report = play(ctx, scenario, world, physics=physics, render=render,
                          run_command=run_command, on_step=on_step)
        finally:
            ctx.close()
    if db is None:
        report.store = None
    return report


__all__: Sequence[str] = ("Checked", "ScenarioReport", "StepResult", "load_scenario", "play", "play_file")
