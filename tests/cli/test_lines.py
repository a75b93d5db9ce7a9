"""One command line run in-process (``batch`` lines, scenario command steps): the exit code and the
captured output, at the caller's store and clock, without touching the environment."""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from ownctl.app.context import AppContext
from ownctl.cli.common import State
from ownctl.cli.lines import run_words
from ownctl.cli.main import command

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl


class GuardedEnviron(dict):
    """os.environ that fails the test if anything sets or removes one of ownctl's variables."""

    def _check(self, key: str) -> None:
        if key.startswith("OWNCTL_"):
            raise AssertionError(f"os.environ[{key!r}] was changed")

    def __setitem__(self, key: str, value: Any) -> None:
        self._check(key)
        super().__setitem__(key, value)

    def __delitem__(self, key: str) -> None:
        self._check(key)
        super().__delitem__(key)

    def pop(self, key: str, *default: Any) -> Any:
        self._check(key)
        return super().pop(key, *default)


@pytest.fixture
def state(ownctl: Ownctl) -> Iterator[State]:
    app = AppContext(ownctl.url, 5000.0)
    yield State(db=ownctl.url, now=5000.0, interface="scenario", prefix="step 7: ", app=app,
                time_source=lambda: 5000.0)
    app.close()


def test_a_line_runs_at_the_callers_clock_and_leaves_the_environment_alone(
    state: State, ownctl: Ownctl, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(os, "environ", GuardedEnviron(os.environ))
    done = run_words(command(), ["agent", "add", "bob", "--json"], state)
    assert (done.code, json.loads(done.stdout), done.stderr) == (0, {"agent": "bob"}, "")
    user = run_words(command(), ["claim", "ghost", "bob"], state)
    assert user.code == 1 and user.stdout == ""
    assert user.stderr.startswith("ownctl: step 7: unknown object 'ghost'") and user.stderr.count("\n") == 1
    usage = run_words(command(), ["claim", "ghost", "bob", "--p", "often"], state)
    assert usage.code == 2 and usage.stderr.startswith("ownctl: step 7: invalid value for --p: 'often'")
    monkeypatch.undo()
    (event,) = [e for e in ownctl.json("log") if e["command"] == "agent add bob --json"]
    assert (event["time"], event["interface"]) == (5000.0, "scenario")


def test_a_scenario_command_step_runs_at_the_scenario_clock(ownctl: Ownctl, tmp_path: Path) -> None:
    scenario = tmp_path / "steps.toml"
    scenario.write_text('name = "clock"\nagents = ["alexis"]\n[[objects]]\nname = "wallet"\n'
                        '[[steps]]\ncommand = "agent add bob"\n[[steps]]\ncommand = "claim wallet bob"\n')
    before = dict(os.environ)
    report = ownctl.json("scenario", "play", str(scenario))
    assert report["passed"] is True and dict(os.environ) == before
    times = {e["command"]: e["time"] for e in ownctl.json("log")}
    assert times["agent add bob"] == 1001.0 and times["claim wallet bob"] == 1002.0  # start + step number
