"""``ownctl batch FILE|-``: many instructions, one process, one open store.

Each non-blank line (``#`` starts a comment) is an ownctl command line without the ``ownctl``
word, e.g. ``claim wallet alexis --p 0.75``. Lines run in order, each in its own transaction, so the
lines before a failing one stay done. The first failing line stops the batch: its error is printed
as ``ownctl: FILE:LINE: message`` and the batch exits with that line's code (1 user error, 2 usage
error). A ``check`` answering "forbidden" (exit 3) is an answer, not a failure: the batch goes on.
With ``--json`` the batch prints exactly one document: every line's output (its own JSON document
when it printed one), and on a failure the failing line with its error.
"""

from __future__ import annotations

import contextlib
import io
import json
import shlex
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Annotated

import typer

from ownctl.cli.common import EXIT_FORBIDDEN, JsonOpt, QuietOpt, State, emit
from ownctl.errors import OwnctlError


def _lines(file: str) -> list[str]:
    if file == "-":
        return sys.stdin.read().splitlines()
    try:
        return Path(file).read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise OwnctlError(f"cannot read batch file {file}: {getattr(exc, 'strerror', None) or exc}") from None


def _words(line: str, where: str) -> list[str]:
    try:
        words = shlex.split(line, comments=True)
    except ValueError as exc:
        raise OwnctlError(f"{where}: cannot split the line into words: {exc}") from None
    if words and words[0] == "ownctl":
        words = words[1:]
    if words and words[0].startswith("--db"):
        raise OwnctlError(f"{where}: --db is not allowed inside a batch (give it to the batch command)")
    if words and words[0] == "batch":
        raise OwnctlError(f"{where}: a batch cannot run another batch")
    return words


def batch(
    ctx: typer.Context,
    file: Annotated[str, typer.Argument(help="The instructions, one per line; - reads stdin.")],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Run one instruction per line, in one process.

    Each line is its own transaction; the first failing line stops the batch (exit 1, or 2 for a
    usage error) and is named as FILE:LINE. Blank lines and # comments are skipped.
    """
    from ownctl.cli.main import command

    state = ctx.find_root().obj
    assert isinstance(state, State)
    name = "stdin" if file == "-" else file
    ran = 0
    results: list[dict[str, object]] = []
    for number, line in enumerate(_lines(file), start=1):
        where = f"{name}:{number}"
        words = _words(line, where)
        if not words:
            continue
        state.interface, state.prefix = "batch", f"{where}: "
        out, err = io.StringIO(), io.StringIO()
        try:
            with _captured(json_out, out, err):
                code = _run_line(command(), words, state, where)
        finally:
            state.interface, state.prefix = "cli", ""
            if json_out:
                sys.stderr.write(err.getvalue())
        if json_out:
            results.append({"line": number, "command": line.strip(), "exit": code or 0,
                            "output": _parsed(out.getvalue())})
        if code not in (None, 0, EXIT_FORBIDDEN):
            if json_out:
                lines = [x for x in err.getvalue().splitlines() if x.strip()]
                typer.echo(json.dumps({"file": name, "ran": ran, "failed": number, "exit": code,
                                       "error": lines[-1] if lines else "", "valid": [], "lines": results}))
            raise typer.Exit(code)
        ran += 1
    summary = {"file": name, "ran": ran, **({"lines": results} if json_out else {})}
    emit(summary, json_out, quiet, f"batch: ran {ran} instructions from {name}")


def _run_line(group: typer.main.TyperGroup, words: list[str], state: State, where: str) -> int | None:
    """Run one line's command in-process; a usage error of the line is reported as FILE:LINE."""
    try:
        return group.main(args=words, prog_name="ownctl", standalone_mode=False, obj=state)
    except typer.TyperException as exc:  # a usage error of the line (click's, vendored by typer)
        message = exc.format_message() if hasattr(exc, "format_message") else str(exc)
        typer.echo(f"ownctl: {where}: {' '.join(message.split())}", err=True)
        return int(getattr(exc, "exit_code", 2))


@contextlib.contextmanager
def _captured(on: bool, out: io.StringIO, err: io.StringIO) -> Iterator[None]:
    """With --json, keep each line's own output out of stdout (it goes into the one document)."""
    if not on:
        yield
        return
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        yield


def _parsed(text: str) -> object:
    """A line's output: its JSON document when it printed one, else its text."""
    try:
        return json.loads(text)
    except ValueError:
        return text.strip()
