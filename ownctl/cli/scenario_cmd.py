"""``ownctl scenario play FILE``: play a scripted scenario and check its expected outcomes."""

from __future__ import annotations

import io
import os
from contextlib import redirect_stderr, redirect_stdout
from typing import TYPE_CHECKING, Annotated, Any

import typer

from ownctl.cli.common import EXIT_FAILED, JsonOpt, QuietOpt, State, emit

if TYPE_CHECKING:
    from ownctl.app.context import AppContext
    from ownctl.world.scenario import Step


scenario = typer.Typer(
    help="Scripted scenarios: a world, steps (say, command, run) and expected outcomes (TOML).",
    no_args_is_help=True,
)


def run_line(ctx: AppContext, step: Step) -> tuple[int, str, str]:
    """Run a step's command line in-process on the scenario's store, at the scenario's time.

    Like a ``batch`` line: the same click command, a State bound to the scenario's AppContext; its
    output is captured. Returns (exit code, stdout, stderr).
    """
    from ownctl.cli.main import command

    state = State(db=ctx.db, now=ctx.now, interface="scenario", command=step.text,
                  prefix=f"step {step.number}: ", app=ctx)
    now, saved = ctx.now, os.environ.get("OWNCTL_NOW")
    out, err = io.StringIO(), io.StringIO()
    os.environ["OWNCTL_NOW"] = repr(now)  # the line runs at the scenario's time, not the wall clock's
    try:
        with redirect_stdout(out), redirect_stderr(err):
            try:
                code = command().main(args=list(step.words), prog_name="ownctl", standalone_mode=False,
                                      obj=state)
            except typer.TyperException as exc:  # a usage error of the line
                message = exc.format_message() if hasattr(exc, "format_message") else str(exc)
                typer.echo(f"ownctl: step {step.number}: {' '.join(message.split())}", err=True)
                code = getattr(exc, "exit_code", 2)
    finally:
        if saved is None:
            os.environ.pop("OWNCTL_NOW", None)
        else:
            os.environ["OWNCTL_NOW"] = saved
        ctx.now = now
    return int(code or 0), out.getvalue(), err.getvalue()


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
    file: Annotated[str, typer.Argument(help="The scenario: a TOML world file with steps.")],
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
    """Play a scenario: load its world, play its steps, check every expectation; exit 4 if one fails.

    Plays on a temporary store unless --db is given, here or before the command (OWNCTL_DB alone is not used, so a scenario never writes into the everyday store by accident).
    """  # noqa: E501
    from ownctl.app.scenario import play_file

    state = ctx.find_root().obj
    assert isinstance(state, State)
    human = not (json_out or quiet)

    def header(s: Any) -> None:
        if human:
            typer.echo(f"scenario: {s.name or s.source} ({s.source})")

    report = play_file(
        file, db or _global_db(ctx), state.now, physics=physics, render=render, run_command=run_line,
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
