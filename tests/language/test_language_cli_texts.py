"""Every understood instruction prints as a command line that `ownctl` itself accepts."""

from __future__ import annotations

import shlex

import pytest

from ownctl.cli.main import command
from tests.language.language_cases import TABLE

NOT_COMMANDS = ("skip ",)  # the robot stopping is an event of a task, not an ownctl command


def rest(ctx: object) -> list[str]:
    """The arguments a group context left for its subcommand."""
    return [*getattr(ctx, "_protected_args", []), *getattr(ctx, "args", [])]


def parses(line: str) -> None:
    """Parse ``line`` down to its leaf command without running it (raises on bad usage)."""
    cmd = command()
    ctx = cmd.make_context("ownctl", shlex.split(line), resilient_parsing=False)
    args = rest(ctx)
    while hasattr(cmd, "resolve_command"):
        name, sub, args = cmd.resolve_command(ctx, args)
        assert sub is not None, line
        ctx = sub.make_context(name or "", args, parent=ctx, resilient_parsing=False)
        cmd, args = sub, rest(ctx)


TEXTS = sorted({t for _, _, texts in TABLE for t in texts if not t.startswith(NOT_COMMANDS)})


@pytest.mark.parametrize("line", TEXTS)
def test_instruction_text_is_an_ownctl_command_line(line: str) -> None:
    parses(line)


def test_a_wrong_flag_would_be_caught() -> None:
    with pytest.raises(Exception, match="exclusive"):
        parses("claim wallet casey --exclusive")
