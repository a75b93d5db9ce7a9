"""The Python API: the same instructions and answers as the command line, one transaction each."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from ownctl.api import Ownctl
from ownctl.cli.main import app
from ownctl.errors import OwnctlError

LOOP = '''
with Ownctl.open(db, create=True, clock=clock) as robot:
    for name in ("xuan", "jake"):
        robot.add_agent(name)
    for i, colour in enumerate(["red", "blue", "red"]):
        robot.add_object(f"block{i}", colour, (0.1 * i, 0.2, 0.0))
    robot.claim("block1", "xuan", exclusive=True)
    for block in ("block0", "block2"):
        for name in ("xuan", "jake"):
            robot.claim(block, name, negated=True)
    robot.forbid("trash", "if ownedBy any")
    for block in ("block0", "block1", "block2"):
        decision = robot.check("trash", block)
        done.append((block, decision.forbidden, decision.data["p_forbidden"]))
'''


def test_a_control_loop_checks_each_action_before_doing_it(tmp_path: Path) -> None:
    db, done = str(tmp_path / "r.db"), []
    ticks = iter(range(1000, 2000))
    exec(LOOP, {"Ownctl": Ownctl, "db": db, "clock": lambda: float(next(ticks)), "done": done})
    assert [b for b, forbidden, _ in done if forbidden] == ["block1"]
    # the command line sees the same store and gives the same answers
    runner = CliRunner()
    for block, forbidden, p in done:
        result = runner.invoke(app, ["--db", db, "check", "trash", block, "--json"])
        assert result.exit_code == (3 if forbidden else 0)
        assert json.loads(result.stdout)["p_forbidden"] == pytest.approx(p, abs=1e-12)


def test_errors_are_the_command_lines_and_write_nothing(tmp_path: Path) -> None:
    with Ownctl.open(str(tmp_path / "e.db"), create=True) as robot:
        robot.add_agent("xuan")
        with pytest.raises(OwnctlError, match="unknown object 'mug'"):
            robot.claim("mug", "xuan")
        with pytest.raises(OwnctlError):
            robot.forbid("thrash", "if ownedBy any")
        assert robot.rules() == []
        robot.add_object("mug", "red")
        robot.permit("trash", "mug", forbid=True)
        robot.check("trash", "mug")
        assert "forbidden" in robot.explain().text  # "why not?": the last refusal


def test_a_named_store_that_does_not_exist_is_not_created_by_accident(tmp_path: Path) -> None:
    with pytest.raises(OwnctlError):
        Ownctl.open(str(tmp_path / "typo.db"))
    assert not (tmp_path / "typo.db").exists()
