"""Every command's and group's ``--help`` reads like a Unix tool's: plain text (square brackets are
text, not markup), readable metavars, every option explained, one-line summaries that fit."""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

import pytest
from typer.testing import CliRunner

from ownctl.cli.main import command
from tests.cli.conftest import invoke

MARKUP = re.compile(r"\[/?(?:bold|dim|italic|green|yellow|red|blue|cyan|magenta|white|b|i|u)?\]")
TYPE_NAME = re.compile(r"<[a-z][a-z_\[\], ]*>")  # <str>, <bool>, <list[str]>


def _paths(cmd: Any, path: tuple[str, ...] = ()) -> Iterator[tuple[tuple[str, ...], Any]]:
    yield path, cmd
    for name, sub in getattr(cmd, "commands", {}).items():
        yield from _paths(sub, (*path, name))


PATHS = list(_paths(command()))


def _help(path: tuple[str, ...]) -> str:
    result = invoke(CliRunner(), [*path, "--help"], None, {})
    assert result.exit_code == 0 and result.stderr == "", result
    return result.stdout


def _squash(text: str) -> str:
    """Text without any whitespace, so wrapping (and a wrap after a hyphen) does not matter."""
    return re.sub(r"\s+", "", text)


def test_every_command_and_group_is_covered() -> None:
    names = {" ".join(p) for p, _ in PATHS}
    assert {"", "claim", "object add", "experiment norms", "scenario play", "world load"} <= names
    assert len(PATHS) > 40


@pytest.mark.parametrize(("path", "cmd"), PATHS, ids=lambda x: " ".join(x) if isinstance(x, tuple) else "")
def test_help_is_plain_complete_and_readable(path: tuple[str, ...], cmd: Any) -> None:
    text = _help(path)
    usage = text.splitlines()[0]
    assert usage.startswith(f"Usage: {' '.join(('ownctl', *path))} ")
    assert not MARKUP.search(text) and not TYPE_NAME.search(text), text
    assert "{" not in usage and "}" not in usage
    assert not set("╭╰│─") & set(text)  # no rich panels
    assert "DESIGN" not in text
    assert _squash(cmd.help or "") in _squash(text)  # the whole description, brackets included
    for param in cmd.params:
        if param.param_type_name == "option" or param.help is not None:
            assert param.help, f"{' '.join(path)}: {param.name} has no help"
            assert _squash(param.help) in _squash(text), (param.name, param.help)
        if param.param_type_name == "argument":
            assert re.fullmatch(r"[A-Z][A-Z.]*|[a-z]+(\|[a-z]+)+", param.metavar), param.metavar
            assert param.metavar in usage
        elif not param.is_flag:
            assert param.metavar and param.metavar == param.metavar.strip(), param.name


@pytest.mark.parametrize(("path", "cmd"), [(p, c) for p, c in PATHS if hasattr(c, "commands")],
                         ids=lambda x: " ".join(x) or "ownctl" if isinstance(x, tuple) else "")
def test_a_groups_summaries_fit_on_their_line(path: tuple[str, ...], cmd: Any) -> None:
    lines = _help(path).split("Commands:\n", 1)[1].splitlines()
    listed = {line.split()[0]: line.split(None, 1)[1] for line in lines if line.strip()}
    assert list(listed) == list(cmd.commands)  # one line each, no wrapped continuation
    for name, summary in listed.items():
        assert not summary.endswith("..."), (name, summary)  # not cut short
        assert summary == cmd.commands[name].get_short_help_str(limit=1000)


def test_brackets_survive_where_they_used_to_vanish() -> None:
    assert "trial t of condition c uses [seed, c, t]." in _help(("experiment", "norms"))
    assert "Seed for a [generator] section." in _help(("world", "load"))
    assert "Usage: ownctl claim [OPTIONS] OBJ AGENT\n" in _help(("claim",))
    assert "--p P " in _help(("claim",)) and "--not  " in _help(("claim",))
