"""A fresh store per test, and a helper that runs ownctl against it in-process (CliRunner)."""

from __future__ import annotations

import hashlib
import json
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from ownctl.cli.main import command

NOW = "1000"


@dataclass
class Result:
    """What a run printed and its exit code."""

    stdout: str
    stderr: str
    exit_code: int


def invoke(runner: CliRunner, args: list[str], input: str | None, env: dict[str, str | None]) -> Result:
    """Run the (once-built) ownctl command in-process like CliRunner.invoke; exceptions propagate.

    typer's CliRunner.invoke rebuilds the click command from the Typer app on every call, which
    costs more than most commands.
    """
    with runner.isolation(input=input, env=env) as (out, err, _):
        try:
            command().main(args=args, prog_name="ownctl")
            code = 0
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 1
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
        return Result(out.getvalue().decode(), err.getvalue().decode(), code)


class Ownctl:
    """Runs ``ownctl --db URL ARGS...`` with OWNCTL_NOW pinned; fails the test on a traceback."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.url = f"sqlite:///{path}"
        self.runner = CliRunner()

    def __call__(self, *args: str, code: int | None = 0, input: str | None = None, now: str = NOW) -> Result:
        result = invoke(self.runner, ["--db", self.url, *args], input, {"OWNCTL_NOW": now, "OWNCTL_DB": None})
        if code is not None:
            assert result.exit_code == code, (args, result.exit_code, result.stdout, result.stderr)
        return result

    def json(self, *args: str, code: int | None = 0) -> Any:
        """Run with --json and parse the single JSON document on stdout."""
        return json.loads(self(*args, "--json", code=code).stdout)

    def digest(self) -> str:
        """SHA-256 of the database file."""
        return hashlib.sha256(self.path.read_bytes()).hexdigest()


def build_template(factory: pytest.TempPathFactory, commands: Sequence[Sequence[str]]) -> bytes:
    """The bytes of a store after ``init`` and ``commands`` (built once, copied into each test)."""
    run = Ownctl(factory.mktemp("template") / "store.db")
    run("init")
    for args in commands:
        run(*args)
    return run.path.read_bytes()


def from_template(path: Path, template: bytes) -> Ownctl:
    """A store at ``path`` holding a copy of ``template``."""
    path.write_bytes(template)
    return Ownctl(path)


@pytest.fixture(scope="session")
def _empty_store(tmp_path_factory: pytest.TempPathFactory) -> bytes:
    return build_template(tmp_path_factory, [])


@pytest.fixture(scope="session")
def _table_store(tmp_path_factory: pytest.TempPathFactory) -> bytes:
    return build_template(tmp_path_factory, TABLE_WORLD)


@pytest.fixture
def ownctl(tmp_path: Path, _empty_store: bytes) -> Ownctl:
    """An initialised, empty store."""
    return from_template(tmp_path / "store.db", _empty_store)


@pytest.fixture
def table_world(tmp_path: Path, _table_store: bytes) -> Ownctl:
    """Two agents, an area, three objects, one claim (see TABLE_WORLD)."""
    return from_template(tmp_path / "store.db", _table_store)


TABLE_WORLD: list[tuple[str, ...]] = [
    ("agent", "add", "alexis"),
    ("agent", "add", "xuan"),
    ("area", "add", "desk", "--box", "0,0,0.5,0.5"),
    ("object", "add", "wallet", "--color", "brown", "--pos", "0.1,0.1,0"),
    ("object", "add", "mug", "--color", "red", "--pos", "0.8,0.8,0", "--category", "kitchen"),
    ("object", "add", "pen"),
    ("claim", "wallet", "alexis"),
]


#: A world file of three blocks (one owned), two agents and the paper's trash norm, for the task commands.
SMALL_WORLD = """
name = "three blocks"
agents = ["alexis", "xuan"]
norms = ["forbid trash if ownedBy any"]

[[areas]]
name = "home"
box = [-0.1, -0.1, 0.1, 0.1]

[[areas]]
name = "trash"
box = [-0.3, 0.6, 0.2, 1.1]

[[objects]]
name = "wallet"
color = "red"
position = [0.5, 0.3, 0.0]
owners = { alexis = 1.0 }

[[objects]]
name = "cup"
color = "blue"
position = [0.4, -0.4, 0.0]

[[objects]]
name = "can"
color = "green"
position = [-0.5, 0.2, 0.0]
"""
