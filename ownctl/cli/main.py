"""The ``ownctl`` command: the root group, its global options, and every command registered.

Startup stays light: this module imports typer and the CLI's common pieces only. The root group
knows its commands by name (:data:`COMMANDS`) and imports a command's CLI module, and builds its
click command, the first time that command is asked for, so ``ownctl check`` builds ``check``
alone; ``ownctl --help`` lists (and so builds) them all. Every command imports its ``ownctl.app``
module (and with it SQLAlchemy, numpy) when it runs.

Leaving is light too: when the command is done (its store closed, its output written), the
console script freezes the heap (``gc.freeze``), so the interpreter's last garbage collection at
exit does not walk the hundreds of thousands of objects SQLAlchemy, numpy and the command made,
which would cost more than all of ownctl's own start-up (``benchmarks/cli_startup.py``).
"""

from __future__ import annotations

import gc
import importlib
from collections.abc import Iterator, MutableMapping
from functools import lru_cache
from typing import Annotated, Any

import typer

from ownctl import __version__
from ownctl.cli.common import OwnctlGroup, State, clock, command_text
from ownctl.cli.help import Group

#: Every command and command group of ``ownctl`` in the order help lists them: name -> (module,
#: attribute), a command function or a :class:`~ownctl.cli.help.Group` of subcommands.
COMMANDS: dict[str, tuple[str, str]] = {
    "init": ("ownctl.cli.admin", "init"),
    "claim": ("ownctl.cli.instruct", "claim"),
    "forbid": ("ownctl.cli.instruct", "forbid"),
    "allow": ("ownctl.cli.instruct", "allow"),
    "check": ("ownctl.cli.query", "check"),
    "owners": ("ownctl.cli.query", "owners"),
    "log": ("ownctl.cli.query", "log"),
    "reset": ("ownctl.cli.admin", "reset"),
    "freeze": ("ownctl.cli.admin", "freeze"),
    "unfreeze": ("ownctl.cli.admin", "unfreeze"),
    "disable": ("ownctl.cli.admin", "disable"),
    "enable": ("ownctl.cli.admin", "enable"),
    "batch": ("ownctl.cli.batch", "batch"),
    "say": ("ownctl.cli.say_cmd", "say"),
    "ask": ("ownctl.cli.ask_cmd", "ask"),
    "explain": ("ownctl.cli.say_cmd", "explain"),
    "run": ("ownctl.cli.run_cmd", "run"),
    "world": ("ownctl.cli.things", "world"),
    "agent": ("ownctl.cli.things", "agent"),
    "object": ("ownctl.cli.things", "obj"),
    "area": ("ownctl.cli.things", "area"),
    "claims": ("ownctl.cli.instruct", "claims"),
    "rules": ("ownctl.cli.query", "rules"),
    "perms": ("ownctl.cli.query", "perms"),
    "db": ("ownctl.cli.admin", "db"),
    "config": ("ownctl.cli.admin", "config"),
    "scenario": ("ownctl.cli.scenario_cmd", "scenario"),
    "experiment": ("ownctl.cli.experiment_cmd", "experiment_app"),
}


def build(name: str) -> Any:
    """The click command ``ownctl NAME``, made from its module's function or group."""
    module, attribute = COMMANDS[name]
    target = getattr(importlib.import_module(module), attribute)
    made: Any
    if isinstance(target, typer.Typer):
        made = typer.main.get_group(target)  # a group even when it has one subcommand
    else:  # a command function: a Typer app of one command gives that command
        single = Group(help="")
        single.command(name)(target)
        made = typer.main.get_command(single)
    made.name = name
    return made


class Commands(MutableMapping[str, Any]):
    """The root group's commands: every name of :data:`COMMANDS`, each built when first looked up."""

    def __init__(self) -> None:
        self.built: dict[str, Any] = {}

    def __getitem__(self, name: str) -> Any:
        if name not in self.built:
            if name not in COMMANDS:
                raise KeyError(name)
            self.built[name] = build(name)
        return self.built[name]

    def __setitem__(self, name: str, command: Any) -> None:
        self.built[name] = command

    def __delitem__(self, name: str) -> None:
        del self.built[name]

    def __iter__(self) -> Iterator[str]:
        return iter([*COMMANDS, *(n for n in self.built if n not in COMMANDS)])

    def __len__(self) -> int:
        return len(set(COMMANDS) | set(self.built))


class Root(OwnctlGroup):
    """``ownctl`` itself: an :class:`~ownctl.cli.common.OwnctlGroup` whose commands are built on demand."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.commands = Commands()

    def list_commands(self, ctx: Any) -> list[str]:
        """The command names, in help order, without building any command."""
        return list(self.commands)


app = Group(
    cls=Root,
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


@lru_cache(maxsize=1)
def command() -> Any:
    """The click command behind ``app``, built once for in-process callers (batch lines and
    scenario steps run on the root command of their own context instead)."""
    return typer.main.get_command(app)


def run() -> None:
    """Console-script entry point (the process ends when it returns, see the module docstring)."""
    try:
        app(prog_name="ownctl")
    finally:
        gc.freeze()  # what is left is the process's to drop at exit, not the collector's to walk
