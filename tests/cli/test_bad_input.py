"""Bad input: one clear line on stderr, exit 1 (2 for usage errors), ``{"error", "valid"}`` with --json,
and the store file byte-for-byte unchanged."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from tests.cli.conftest import TABLE_WORLD, build_template, from_template

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

HOSTILE = ["x'; DROP TABLE agents;--", 'quo"te', "bell\x07", "new\nline", "two words", "9lives", "", "a" * 65]

USER_ERRORS: list[tuple[str, ...]] = [
    *(("agent", "add", name) for name in HOSTILE),
    ("agent", "add", "any"),
    ("agent", "add", "alexis"),
    ("agent", "remove", "ghost"),
    ("agent", "remove", "xuan"),  # a rule names xuan
    ("object", "add", "wallet"),
    ("object", "add", "cup", "--pos", "1,2,x"),
    ("object", "add", "cup", "--pos", "nan,0,0"),
    ("object", "add", "cup", "--pos", "1,2,3,4"),
    ("object", "add", "cup", "--color", "re d"),
    ("object", "add", "cup", "--category", "DROP TABLE"),
    ("object", "set", "ghost", "--color", "red"),
    ("object", "set", "wallet"),
    ("object", "show", "ghost"),
    ("object", "remove", "ghost"),
    ("object", "touch", "wallet", "--by", "ghost"),
    ("object", "touch", "wallet", "--by", "alexis", "--at", "nan"),
    ("area", "add", "desk", "--box", "0,0,1,1"),
    ("area", "add", "flipped", "--box", "1,1,0,0"),
    ("area", "add", "short", "--box", "0,0,1"),
    ("claim", "ghost", "alexis"),
    ("claim", "wallet", "ghost"),
    ("claim", "wallet", "alexis", "--p", "1.5"),
    ("claim", "wallet", "alexis", "--p", "-0.1"),
    ("claim", "wallet", "alexis", "--p", "nan"),
    ("claim", "wallet", "alexis", "--only", "--not"),
    ("forbid", "thrash", "on", "wallet"),
    ("forbid", "trash", "on", "ghost"),
    ("forbid", "trash", "on"),
    ("forbid", "trash", "on", "wallet", "mug"),
    ("forbid", "trash", "on", "wallet", "--p", "2"),
    ("forbid", "trash", "wallet"),
    ("forbid", "trash", "if"),
    ("forbid", "trash", "if", "ownedBy", "ghost"),
    ("forbid", "trash", "if", "inArea", "nowhere"),
    ("forbid", "trash", "if", "isColored"),
    ("forbid", "trash", "if", "isBig", "yes"),
    ("forbid", "trash", "if", "ownedBy", "any", "or", "isColored", "red"),
    ("forbid", "trash", "if", "isColored", "red", "and", "not", "isColored", "red"),
    ("allow", "trash", "if", "ownedBy", "ghost"),
    ("check", "thrash", "wallet"),
    ("check", "trash", "ghost"),
    ("owners", "ghost"),
    ("owners", "--agent", "ghost"),
    ("owners", "--agent", "alexis", "--min", "2"),
    ("rules", "remove", "99"),
    ("perms", "remove", "99"),
    ("config", "set", "threshold", "1.5"),
    ("config", "set", "threshold", "nan"),
    ("config", "set", "threshold.thrash", "0.5"),
    ("config", "set", "nope", "1"),
    ("config", "set", "frozen.perms", "maybe"),
    ("config", "get", "nope"),
    ("reset", "perms"),
    ("log", "--limit", "0"),
    ("world", "load", "missing.toml"),
]

USAGE_ERRORS: list[tuple[str, ...]] = [
    ("claim", "wallet"),
    ("frobnicate",),
    ("reset", "nothing", "--yes"),
    ("freeze", "claims"),
    ("check", "trash", "wallet", "--bogus"),
    ("owners",),
    ("rules", "remove", "one"),
    ("claim", "wallet", "alexis", "--p", "0x1"),
    ("world", "load", "x.toml", "--seed", "abc"),
    ("log", "--limit", "1.5"),
    ("object",),
    (),
    ("explain", "trash"),
]


@pytest.fixture(scope="module")
def _world_store(tmp_path_factory: pytest.TempPathFactory) -> bytes:
    extra = [("forbid", "pickUp", "if", "ownedBy", "xuan"), ("forbid", "trash", "on", "wallet")]
    return build_template(tmp_path_factory, [*TABLE_WORLD, *extra])


@pytest.fixture
def world(tmp_path: Path, _world_store: bytes) -> Ownctl:
    """The table world with a rule naming xuan and a permission."""
    return from_template(tmp_path / "store.db", _world_store)


@pytest.mark.parametrize("args", USER_ERRORS, ids=lambda a: " ".join(a)[:40])
def test_user_error_is_one_line_exit_1_and_writes_nothing(world: Ownctl, args: tuple[str, ...]) -> None:
    before = world.digest()
    result = world(*args, code=1)
    assert result.stdout == ""
    assert result.stderr.startswith("ownctl: ") and result.stderr.count("\n") == 1, result.stderr
    assert world.digest() == before
    as_json = world(*args, "--json", code=1)
    error = json.loads(as_json.stdout)
    assert set(error) == {"error", "valid"} and error["error"]
    assert world.digest() == before


def test_hostile_names_are_refused_with_the_rule(world: Ownctl) -> None:
    result = world("agent", "add", "x'; DROP TABLE agents;--", code=1)
    assert "a letter, then letters, digits" in result.stderr
    assert [a["name"] for a in world.json("agent", "list")] == ["alexis", "xuan"]


def test_unknown_names_list_the_valid_ones(world: Ownctl) -> None:
    error = world.json("claim", "wallet", "ghost", code=1)
    assert error["valid"] == ["alexis", "xuan"] and "known agents: alexis, xuan" in error["error"]
    assert "trash" in world.json("check", "thrash", "wallet", code=1)["valid"]


@pytest.mark.parametrize("args", USAGE_ERRORS, ids=lambda a: " ".join(a) or "nothing")
def test_usage_error_is_one_line_exit_2_and_writes_nothing(world: Ownctl, args: tuple[str, ...]) -> None:
    before = world.digest()
    result = world(*args, code=2)
    assert result.stderr.startswith("ownctl: ") and result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.rstrip().endswith("--help)")  # and says where the help is
    assert world.digest() == before


def test_a_bad_number_is_named_with_what_it_should_be(world: Ownctl) -> None:
    assert world("claim", "wallet", "alexis", "--p", "0x1", code=2).stderr == (
        "ownctl: invalid value for --p: '0x1' is not a number (see: ownctl claim --help)\n")
    assert "'abc' is not a whole number" in world("log", "-n", "abc", code=2).stderr
    assert "commands: add, set, list, show, remove, touch" in world("object", code=2).stderr


def test_bad_world_file_names_file_and_key(world: Ownctl, tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text('agents = ["a1"]\n[[objects]]\nname = "cup"\ncolour = "red"\n')
    before = world.digest()
    error = world.json("world", "load", str(bad), code=1)
    assert str(bad) in error["error"] and "'colour'" in error["error"] and "color" in error["valid"]
    assert world.digest() == before


def test_bad_clock_is_refused(world: Ownctl) -> None:
    before = world.digest()
    result = world("agent", "add", "bob", code=1, now="soon")
    assert "OWNCTL_NOW" in result.stderr
    assert world.digest() == before


def test_failing_batch_line_reports_its_number(world: Ownctl, tmp_path: Path) -> None:
    script = tmp_path / "bad.txt"
    script.write_text("# a comment\n\nclaim wallet ghost\nagent add bob\n")
    before = world.digest()
    result = world("batch", str(script), code=1)
    assert result.stderr.startswith(f"ownctl: {script}:3: unknown agent 'ghost'")
    assert result.stderr.count("\n") == 1
    assert world.digest() == before
