"""One ownctl command line run inside this process: how ``batch`` lines and scenario command steps run.

The line goes through the same root command as the command line itself (so it parses, fails and
reports exactly as ``ownctl WORDS`` would), with a :class:`~ownctl.cli.common.State` that carries
the store, the clock and the error prefix. Nothing is read from or written to the environment.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from contextlib import redirect_stderr, redirect_stdout
from dataclasses import dataclass
from typing import Any

from ownctl.cli.common import State


@dataclass(frozen=True)
class LineResult:
    """What one command line did: its exit code and everything it printed."""

    code: int
    stdout: str
    stderr: str


def run_words(root: Any, words: Sequence[str], state: State) -> LineResult:
    """Run ``ownctl WORDS`` on ``root`` (the root click command) with ``state``, capturing its output.

    Errors, usage errors included, come back as the exit code and one line of stderr that starts
    with ``ownctl: `` and ``state.prefix``.
    """
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = root.main(args=list(words), prog_name="ownctl", standalone_mode=False, obj=state)
    return LineResult(int(code or 0), out.getvalue(), err.getvalue())
