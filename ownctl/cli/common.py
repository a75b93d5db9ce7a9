"""What every command shares: the per-process state, option types, output and the one error handler.

Kept free of heavy imports: ``ownctl --help`` loads this module, typer and click, nothing else.
Commands import their ``ownctl.app`` module inside the function body.
"""

from __future__ import annotations

import json
import math
import os
import shlex
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Annotated, Any

import typer
from typer.core import TyperGroup

from ownctl.errors import BadValue, OwnctlError

if TYPE_CHECKING:
    from ownctl.app.context import AppContext

JsonOpt = Annotated[bool, typer.Option("--json", help="Print exactly one JSON document on stdout.")]
QuietOpt = Annotated[bool, typer.Option("--quiet", "-q", help="Print nothing but errors.")]

EXIT_FORBIDDEN = 3  # check (and a question) answered "forbidden", as grep answers "no match"
EXIT_FAILED = 4  # a task step or a scenario expectation failed


@dataclass
class State:
    """Per-process CLI state (``ctx.obj``); ``batch`` hands the same one to every line."""

    db: str | None
    now: float
    interface: str = "cli"
    command: str = ""
    prefix: str = ""  # put before error messages (batch: "FILE:LINE: ")
    app: AppContext | None = field(default=None, repr=False)

    def context(self) -> AppContext:
        """The app-layer context for this instruction (one open store per process)."""
        from ownctl.app.context import AppContext

        if self.app is None:
            self.app = AppContext(self.db, self.now)
        self.app.now, self.app.interface, self.app.command = self.now, self.interface, self.command
        return self.app

    def close(self) -> None:
        """Close the store (SQLite checkpoints its WAL into the database file)."""
        if self.app is not None:
            self.app.close()


def clock(environ: dict[str, str] | os._Environ[str] = os.environ) -> float:
    """Store time: ``OWNCTL_NOW`` (a float) when set, else wall-clock seconds."""
    pinned = environ.get("OWNCTL_NOW")
    if pinned is None or pinned == "":
        return time.time()
    try:
        value = float(pinned)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise BadValue(f"OWNCTL_NOW must be a finite number of seconds, got {pinned!r}")
    return value


def command_text(args: Sequence[str]) -> str:
    """The instruction as typed, without the global ``--db`` option (for the event log)."""
    out, skip = [], False
    for arg in args:
        if skip:
            skip = False
        elif arg == "--db":
            skip = True
        elif not arg.startswith("--db="):
            out.append(arg)
    return shlex.join(out)


def app_ctx(ctx: typer.Context) -> AppContext:
    """The app context of the running command."""
    state = ctx.find_root().obj
    assert isinstance(state, State), "the ownctl callback did not run"
    return state.context()


def emit(data: Any, json_out: bool, quiet: bool, human: str | Callable[[], None]) -> None:
    """Print ``data`` as JSON, or the human form (a line, or a function that prints), or nothing."""
    if json_out:
        typer.echo(json.dumps(data, ensure_ascii=False))
    elif not quiet:
        if callable(human):
            human()
        else:
            typer.echo(human)


def wrote(path: Any, quiet: bool = False) -> None:
    """Say on stderr where a file was written (stdout stays one JSON document under --json)."""
    if path is not None and not quiet:
        typer.echo(f"wrote {path}", err=True)


def table(title: str | None, columns: Sequence[str], rows: Sequence[Sequence[Any]]) -> Callable[[], None]:
    """A function printing a rich table (``None`` cells show as blank)."""

    def show() -> None:
        from rich.console import Console
        from rich.table import Table

        grid = Table(title=title, show_lines=False)
        for column in columns:
            grid.add_column(column)
        for row in rows:
            grid.add_row(*("" if v is None else fmt(v) for v in row))
        Console().print(grid)

    return show


def fmt(value: Any) -> str:
    """A compact human form of a cell value."""
    if isinstance(value, float):
        return f"{value:.3g}" if abs(value) < 100 else f"{value:.1f}"
    if isinstance(value, list | tuple):
        return ", ".join(fmt(v) for v in value)
    if isinstance(value, dict):
        return ", ".join(f"{k}={fmt(v)}" for k, v in value.items())
    return str(value)


def report_error(ctx: Any, exc: OwnctlError) -> None:
    """One line on stderr; with ``--json`` also ``{"error", "valid"}`` on stdout."""
    state = ctx.find_root().obj
    prefix = state.prefix if isinstance(state, State) else ""
    message = " ".join(exc.message.split())  # one line, whatever the message holds
    if "--json" in ctx.meta.get("ownctl.args", ()):
        typer.echo(json.dumps({"error": message, "valid": exc.valid}, ensure_ascii=False))
    typer.echo(f"ownctl: {prefix}{message}", err=True)


class OwnctlGroup(TyperGroup):
    """The root group: records the arguments for the log and turns OwnctlError into exit codes."""

    def make_context(self, info_name: str | None, args: list[str], parent: Any = None, **extra: Any) -> Any:
        original = list(args)
        ctx = super().make_context(info_name, args, parent=parent, **extra)
        ctx.meta["ownctl.args"] = original
        return ctx

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except OwnctlError as exc:
            report_error(ctx, exc)
            raise typer.Exit(exc.exit_code) from None
