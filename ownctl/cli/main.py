"""The ``ownctl`` command: the root group, its global options, and every command registered.

Startup stays light: this module imports typer, click and the CLI modules only; every command
imports its ``ownctl.app`` module (and with it SQLAlchemy, numpy) when it runs.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Annotated, Any

import typer

from ownctl import __version__
from ownctl.cli import admin, ask_cmd, instruct, query, say_cmd, things
from ownctl.cli.batch import batch
from ownctl.cli.common import OwnctlGroup, State, clock, command_text
from ownctl.cli.experiment_cmd import experiment_app
from ownctl.cli.help import Group
from ownctl.cli.run_cmd import run as run_task
from ownctl.cli.scenario_cmd import scenario

app = Group(
    cls=OwnctlGroup,
    name="ownctl",
    help="A robot's ownership conscience: who owns what, which actions are forbidden, and why.",
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"ownctl {__version__}")
        raise typer.Exit()


@app.callback()
def main(
    ctx: typer.Context,
    db: Annotated[
        str | None,
        typer.Option(
            "--db",
            envvar="OWNCTL_DB",
            metavar="URL",
            help="The store: any SQLAlchemy URL or a SQLite file path (default: a file in the user data"
            " directory; ownctl db path prints it).",
        ),
    ] = None,
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version and exit.")
    ] = False,
) -> None:
    """Global options. The store clock is OWNCTL_NOW (seconds) when set, else the wall clock."""
    text = command_text(ctx.meta.get("ownctl.args", []))
    if isinstance(ctx.obj, State):  # a batch line or a scenario step: same store, the line's own time
        ctx.obj.now, ctx.obj.command = ctx.obj.time_source(), text
        return
    state = State(db=db or None, now=clock(), command=text)
    ctx.obj = state
    ctx.call_on_close(state.close)


app.add_typer(things.world, name="world")
app.add_typer(things.agent, name="agent")
app.add_typer(things.obj, name="object")
app.add_typer(things.area, name="area")
app.add_typer(instruct.claims, name="claims")
app.add_typer(query.rules, name="rules")
app.add_typer(query.perms, name="perms")
app.add_typer(admin.db, name="db")
app.add_typer(admin.config, name="config")
app.command("init")(admin.init)
app.command("claim")(instruct.claim)
app.command("forbid")(instruct.forbid)
app.command("allow")(instruct.allow)
app.command("check")(query.check)
app.command("owners")(query.owners)
app.command("log")(query.log)
app.command("reset")(admin.reset)
app.command("freeze")(admin.freeze)
app.command("unfreeze")(admin.unfreeze)
app.command("disable")(admin.disable)
app.command("enable")(admin.enable)
app.command("batch")(batch)
app.command("say")(say_cmd.say)
app.command("ask")(ask_cmd.ask)
app.command("explain")(say_cmd.explain)
app.add_typer(scenario, name="scenario")
app.command("run")(run_task)
app.add_typer(experiment_app, name="experiment")


@lru_cache(maxsize=1)
def command() -> Any:
    """The click command behind ``app``, built once for in-process callers (batch lines and
    scenario steps run on the root command of their own context instead)."""
    return typer.main.get_command(app)


def run() -> None:
    """Console-script entry point."""
    app(prog_name="ownctl")
