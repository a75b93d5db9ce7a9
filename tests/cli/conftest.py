"""A fresh store per test, and a helper that runs ownctl against it in-process (CliRunner)."""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner, Result

from ownctl.cli.main import app

NOW = "1000"


class Ownctl:
    """Runs ``ownctl --db URL ARGS...`` with OWNCTL_NOW pinned; fails the test on a traceback."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.url = f"sqlite:///{path}"
        self.runner = CliRunner()

    def __call__(self, *args: str, code: int | None = 0, input: str | None = None, now: str = NOW) -> Result:
        result = self.runner.invoke(
            app, ["--db", self.url, *args], input=input, env={"OWNCTL_NOW": now, "OWNCTL_DB": None}
        )
        if result.exception is not None and not isinstance(result.exception, SystemExit):
            raise result.exception
        if code is not None:
            assert result.exit_code == code, (args, result.exit_code, result.stdout, result.stderr)
        return result

    def json(self, *args: str, code: int | None = 0) -> Any:
        """Run with --json and parse the single JSON document on stdout."""
        return json.loads(self(*args, "--json", code=code).stdout)

    def digest(self) -> str:
        """SHA-256 of the database file."""
        return hashlib.sha256(self.path.read_bytes()).hexdigest()


@pytest.fixture
def ownctl(tmp_path: Path) -> Ownctl:
    """An initialised, empty store."""
    run = Ownctl(tmp_path / "store.db")
    run("init")
    return run


@pytest.fixture
def table_world(ownctl: Ownctl) -> Ownctl:
    """Two agents, an area, three objects, one claim."""
    for args in (
        ("agent", "add", "alexis"),
        ("agent", "add", "xuan"),
        ("area", "add", "desk", "--box", "0,0,0.5,0.5"),
        ("object", "add", "wallet", "--color", "brown", "--pos", "0.1,0.1,0"),
        ("object", "add", "mug", "--color", "red", "--pos", "0.8,0.8,0", "--category", "kitchen"),
        ("object", "add", "pen"),
        ("claim", "wallet", "alexis"),
    ):
        ownctl(*args)
    return ownctl


Run = Callable[..., Result]
