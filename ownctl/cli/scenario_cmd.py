"""``ownctl scenario play FILE``: play a scripted scenario and check its expected outcomes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Annotated, Any

import typer

from ownctl.cli.common import EXIT_FAILED, JsonOpt, QuietOpt, State, emit
from ownctl.cli.help import Group
from ownctl.cli.lines import run_words

if TYPE_CHECKING:
    from ownctl.app.context import AppContext
    from ownctl.world.scenario import Step


scenario = Group(
    help="Play scripted scenarios and check their outcomes.\n\nA scenario is a world file with steps "
    "(say, command, run) and what each step expects.")


def _step_runner(root: Any) -> Callable[[AppContext, Step], tuple[int, str, str]]:
    """Run a command step's line in-process on the scenario's store, at the scenario's time.

    Like a ``batch`` line (:func:`ownctl.cli.lines.run_words`), with a State bound to the
    scenario's AppContext and its clock. Returns (exit code, stdout, stderr).
    """

    def run_step(app: AppContext, step: Step) -> tuple[int, str, str]:
        now, interface, command = app.now, app.interface, app.command
        state = State(db=app.db, now=now, interface="scenario", command=step.text,
                      prefix=f"step {step.number}: ", app=app, time_source=lambda: now)
        try:
            done = run_words(root, step.words, state)
        finally:
            app.now, app.interface, app.command = now, interface, command
        return done.code, done.stdout, done.stderr

    return run_step


def _global_db(ctx: typer.Context) -> str | None:
    """The global --db when given on the command line (OWNCTL_DB alone does not pick the store)."""
    root = ctx.find_root()
    source = root.get_parameter_source("db")  # an enum of typer's own copy of click
    if source is not None and source.name == "COMMANDLINE":
        return root.params.get("db")
    return None


def _show_step(result: Any) -> None:
    step = result.step
    typer.echo(f"step {step.number}  {step.describe()}")
    for line in result.output:
        typer.echo(f"        {line}")
    if result.error:
        typer.echo(f"        ✗ failed: {result.error}")
    for c in result.checked:
        typer.echo(f"        {'✓' if c.ok else '✗'} {c.text}    ({c.actual})")


@scenario.command("play")
def play(
    ctx: typer.Context,
    file: Annotated[str, typer.Argument(metavar="FILE", help="The scenario: a TOML world file with steps.")],
    physics: Annotated[
        bool, typer.Option("--physics", help="Run tasks in MuJoCo (default: kinematically, instantly).")
    ] = False,
    render: Annotated[
        str | None, typer.Option("--render", metavar="FILE", help="With --physics: film the run to FILE.mp4.")
    ] = None,
    db: Annotated[
        str | None,
        typer.Option("--db", metavar="URL", help="Play on this existing store (default: a temporary store)."),
    ] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Play a scenario and check every expectation; exit 4 if one fails.

    Loads the scenario's world, plays its steps (say, command, run) and checks what each step
    expects. Plays on a temporary store unless --db is given, here or before the command
    (OWNCTL_DB alone is not used, so a scenario never writes into the everyday store by accident).
    """
    from ownctl.app.scenario import play_file

    state = ctx.find_root().obj
    assert isinstance(state, State)
    human = not (json_out or quiet)

    def header(s: Any) -> None:
        if human:
            typer.echo(f"scenario: {s.name or s.source} ({s.source})")

    report = play_file(
        file, db or _global_db(ctx), state.now, physics=physics, render=render,
        run_command=_step_runner(ctx.find_root().command),
        on_step=_show_step if human else None, before=header,
    )
    data = report.data
    counts = data["expectations"]
    verdict = "passed" if report.passed else "FAILED"
    summary = (f"{verdict}: {counts['passed']}/{counts['total']} expectations held, "
               f"{data['steps_played']}/{data['steps_total']} steps played in {data['seconds']:.2f} s")
    emit(data, json_out, quiet, summary)
    if not report.passed:
        if not human:
            typer.echo(f"ownctl: scenario {file}: {summary}", err=True)
        raise typer.Exit(EXIT_FAILED)
