"""What every command shares: the per-process state, option types, output and the one error handler.

Kept free of heavy imports: ``ownctl --help`` loads this module, typer and click, nothing else.
Commands import their ``ownctl.app`` module inside the function body.
"""

from __future__ import annotations

import json
import math
import os
import shlex
import sys
import time
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Annotated, Any

import typer
from typer.core import TyperGroup

from ownctl.cli.help import plain_values
from ownctl.errors import BadValue, OwnctlError
from ownctl.logic.names import composed

if TYPE_CHECKING:
    from ownctl.app.context import AppContext

JsonOpt = Annotated[bool, typer.Option("--json", help="Print exactly one JSON document on stdout.")]
QuietOpt = Annotated[bool, typer.Option("--quiet", "-q", help="Print nothing but errors.")]
ACTION_HELP = "An action: find, pickUp, putDown, release, goHome, moveTo, replace, wait, trash, collect."
ActionArg = Annotated[str, typer.Argument(metavar="ACTION", help=ACTION_HELP)]
ObjArg = Annotated[str, typer.Argument(metavar="OBJ", help="The object.")]

EXIT_FORBIDDEN = 3  # check (and a question) answered "forbidden", as grep answers "no match"
EXIT_FAILED = 4  # a task step or a scenario expectation failed


def clock(environ: Mapping[str, str] = os.environ) -> float:
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


@dataclass
class State:
    """Per-process CLI state (``ctx.obj``); ``batch`` hands the same one to every line.

    ``time_source`` gives each command line its store time when it starts: the process clock for
    the command line and ``batch`` lines, the scenario's clock for a scenario's command steps.
    """

    db: str | None
    now: float
    interface: str = "cli"
    command: str = ""
    prefix: str = ""  # put before error messages (batch: "FILE:LINE: ")
    app: AppContext | None = field(default=None, repr=False)
    time_source: Callable[[], float] = field(default=clock, repr=False)

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
    """Print ``data`` as JSON (times also as ISO 8601 strings), or the human form (a line, or a
    function that prints), or nothing."""
    if json_out:
        from ownctl.cli.render import with_iso

        typer.echo(json.dumps(with_iso(data), ensure_ascii=False))
    elif not quiet:
        if callable(human):
            human()
        else:
            typer.echo(human)


def wrote(path: Any, quiet: bool = False) -> None:
    """Say on stderr where a file was written (stdout stays one JSON document under --json)."""
    if path is not None and not quiet:
        typer.echo(f"wrote {path}", err=True)


def table(title: str | None, columns: Sequence[str], rows: Sequence[Sequence[Any]],
          whole: Collection[str] = ()) -> Callable[[], None]:
    """A function printing a rich table (``None`` cells show as blank, text is never markup).

    Cells of the ``whole`` columns (times) are kept on one line, never cut short.
    """

    def show() -> None:
        from rich.console import Console
        from rich.markup import escape
        from rich.table import Table

        cells = [["" if v is None else fmt(v) for v in row] for row in rows]
        grid = Table(title=title, show_lines=False)
        for i, column in enumerate(columns):
            if column in whole:
                widest = max([len(column), *(len(r[i]) for r in cells)])
                grid.add_column(column, no_wrap=True, min_width=widest)
            else:
                grid.add_column(column)
        for row in cells:
            grid.add_row(*(escape(cell) for cell in row))
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


#: pydantic's error types for a value that is not a number, and how ownctl says it
_NOT_A = {"int_parsing": "a whole number", "int_from_float": "a whole number", "int_type": "a whole number",
          "float_parsing": "a number", "float_type": "a number", "finite_number": "a finite number"}


def _param_name(param: Any) -> str:
    """How a parameter is named in an error: its option flags, or an argument's metavar."""
    if param.param_type_name == "option":
        return "/".join(param.opts)
    return param.metavar or (param.name or "value").upper()


def usage_message(exc: typer.TyperException) -> tuple[str, list[str]]:
    """A usage error (typer's copy of click's UsageError) as one line naming the bad value, and the
    valid values when there is a list of them.

    A value typer could not convert names the value and what it should be; a group run without
    a command, or with an unknown one, lists the commands; every message points to ``--help``.
    """
    ctx, param = getattr(exc, "ctx", None), getattr(exc, "param", None)
    errors = getattr(exc.__cause__, "errors", None)  # pydantic's ValidationError behind a conversion
    if param is not None and callable(errors) and errors():
        first = errors()[0]
        value, kind = first.get("input"), str(first.get("type", ""))
        detail = str(first.get("msg", "")).removeprefix("Value error, ").removesuffix(".")
        if kind in _NOT_A:
            detail = f"{value!r} is not {_NOT_A[kind]}"
        elif repr(value) not in detail:
            detail = f"{value!r}: {detail[:1].lower()}{detail[1:]}"
        message = f"invalid value for {_param_name(param)}: {detail}"
    else:
        text = " ".join(exc.format_message().split()).removesuffix(".")
        message = text[:1].lower() + text[1:]
    group = ctx.command if ctx is not None else None
    commands = getattr(group, "list_commands", None)
    valid: list[str] = []
    if callable(commands) and message.startswith(("missing command", "no such command")):
        valid = list(commands(ctx))
        message += f"; commands: {', '.join(valid)}"
    if ctx is not None:
        message += f" (see: {ctx.command_path} --help)"
    return message, valid


class OwnctlGroup(TyperGroup):
    """The root group: records the arguments for the log, turns OwnctlError into exit codes, and
    reports usage errors as one line on stderr (exit 2), in every mode.

    ``main`` returns the exit code when ``standalone_mode`` is false (a batch line, a scenario
    step) and exits with it otherwise.
    """

    def main(  # type: ignore[override]  # click declares main with overloads on standalone_mode
        self, args: Sequence[str] | None = None, prog_name: str | None = None,
        complete_var: str | None = None, standalone_mode: bool = True, **extra: Any,
    ) -> Any:
        state = extra.get("obj")
        prefix = state.prefix if isinstance(state, State) else ""
        # one spelling per name: "José" typed with a combining accent is the José of the store
        args = [composed(a) for a in (sys.argv[1:] if args is None else args)]
        try:
            result = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
            code = result if isinstance(result, int) and not isinstance(result, bool) else 0
        except typer.TyperException as exc:  # click's UsageError and its kin, in typer's copy of click
            message, valid = usage_message(exc)
            if "--json" in (args or ()):  # like every error: the document on stdout, the line on stderr
                typer.echo(json.dumps({"error": message, "valid": valid}, ensure_ascii=False))
            typer.echo(f"ownctl: {prefix}{message}", err=True)
            code = int(getattr(exc, "exit_code", 2))
        except typer.Abort:
            typer.echo(f"ownctl: {prefix}aborted", err=True)
            code = 1
        if standalone_mode:
            raise SystemExit(code)
        return code

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        plain_values(self.params)  # --db: no pydantic on the way to a command

    def get_help_option(self, ctx: Any) -> Any:
        option = super().get_help_option(ctx)
        plain_values([] if option is None else [option])
        return option

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


class ProgressBar:
    """A rich progress bar on stderr, shown from the first report of progress on (so option errors
    print alone), and only on a terminal; call it with (done, total)."""

    def __init__(self, progress: Any, description: str) -> None:
        self.progress, self.description = progress, description
        self.task: Any = None

    def __call__(self, done: int, total: int) -> None:
        if self.task is None:
            self.progress.start()
            self.task = self.progress.add_task(self.description, total=total)
        self.progress.update(self.task, completed=done, total=total)

    def stop(self) -> None:
        """Remove the bar (it is transient), if it was shown."""
        if self.task is not None:
            self.progress.stop()


def progress_bar(description: str) -> ProgressBar | None:
    """A :class:`ProgressBar` for long work (an experiment, valuing questions), or None when stderr
    is not a terminal."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    console = Console(stderr=True)
    if not console.is_terminal:
        return None
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    return ProgressBar(Progress(*columns, console=console, transient=True), description)
