"""``ownctl batch FILE|-``: many instructions, one process, one open store.

Each non-blank line (``#`` starts a comment) is an ownctl command line without the ``ownctl``
word, e.g. ``claim wallet alexis --p 0.75``. Lines run in order, each in its own transaction, so the
lines before a failing one stay done. The first failing line stops the batch: its error is printed
as ``ownctl: FILE:LINE: message`` and the batch exits with that line's code (1 user error, 2 usage
error). A ``check`` answering "forbidden" (exit 3) is an answer, not a failure: the batch goes on.
With ``--json`` the batch prints exactly one document: every line's output (its own JSON document
when it printed one), and on a failure the failing line with its error.

Nothing is kept between lines but the open store: every line loads what it needs in its own
transaction, so a long-running batch (``batch -`` reads stdin line by line) sees what other writers
taught between its lines (docs/architecture.md, section 6).
"""

from __future__ import annotations

import json
import shlex
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Annotated

import typer

from ownctl.cli.common import EXIT_FORBIDDEN, JsonOpt, QuietOpt, State, emit
from ownctl.cli.lines import run_words
from ownctl.errors import OwnctlError
from ownctl.humanize import plural


def _lines(file: str) -> Iterator[str]:
    """The batch's lines: a file's all at once; stdin's one at a time as they arrive, so that a batch
    fed by another program answers each line before the next is written."""
    if file == "-":
        return (line.rstrip("\r\n") for line in iter(sys.stdin.readline, ""))
    try:
        return iter(Path(file).read_text(encoding="utf-8").splitlines())
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
    file: Annotated[
        str, typer.Argument(metavar="FILE", help="The instructions, one per line; - reads stdin.")
    ],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Run one instruction per line, in one process.

    Each line is its own transaction; the first failing line stops the batch (exit 1, or 2 for a
    usage error) and is named as FILE:LINE. Blank lines and # comments are skipped.
    """
    state = ctx.find_root().obj
    assert isinstance(state, State)
    root = ctx.find_root().command
    name = "stdin" if file == "-" else file
    ran = 0
    results: list[dict[str, object]] = []
    for number, line in enumerate(_lines(file), start=1):
        where = f"{name}:{number}"
        words = _words(line, where)
        if not words:
            continue
        state.interface, state.prefix = "batch", f"{where}: "
        try:
            done = run_words(root, words, state)
        finally:
            state.interface, state.prefix = "cli", ""
        sys.stderr.write(done.stderr)
        if json_out:
            results.append({"line": number, "command": line.strip(), "exit": done.code,
                            "output": _parsed(done.stdout)})
        else:
            sys.stdout.write(done.stdout)
            sys.stdout.flush()  # whoever feeds the lines sees each answer before sending the next
        if done.code not in (0, EXIT_FORBIDDEN):
            if json_out:
                errors = [x for x in done.stderr.splitlines() if x.strip()]
                typer.echo(json.dumps({"file": name, "ran": ran, "failed": number, "exit": done.code,
                                       "error": errors[-1] if errors else "", "valid": [],
                                       "lines": results}, ensure_ascii=False))
            raise typer.Exit(done.code)
        ran += 1
    summary = {"file": name, "ran": ran, **({"lines": results} if json_out else {})}
    emit(summary, json_out, quiet, f"batch: ran {plural(ran, 'instruction')} from {name}")


def _parsed(text: str) -> object:
    """A line's output: its JSON document when it printed one, else its text."""
    try:
        return json.loads(text)
    except ValueError:
        return text.strip()
