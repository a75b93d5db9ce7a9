"""``ownctl scenario play``: every shipped scenario passes; failures, bad files and options behave."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path
from typing import TYPE_CHECKING

import pytest
from typer.testing import CliRunner

from tests.cli.conftest import NOW, Result, invoke

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"
PLAYED = sorted(p for p in SCENARIOS.glob("*.toml") if tomllib.loads(p.read_text()).get("steps"))


def play(*args: str, code: int | None = 0) -> Result:
    """``ownctl scenario play ARGS`` on a temporary store (no --db, OWNCTL_DB unset)."""
    result = invoke(CliRunner(), ["scenario", "play", *args], None, {"OWNCTL_NOW": NOW, "OWNCTL_DB": None})
    if code is not None:
        assert result.exit_code == code, (args, result.stdout, result.stderr)
    return result


def test_a_reprimand_during_a_run_teaches_its_norm_before_its_permission() -> None:
    """Otherwise one example would induce 'forbid trash' first and the norm would be dropped."""
    from ownctl.app.run import Interrupt, teach_utterance
    from ownctl.experiment.task import Attempt, get_task
    from ownctl.logic.rules import parse_rule
    from ownctl.mind import Mind
    from ownctl.world.model import ObjectSpec

    mind = Mind(("xuan",), [ObjectSpec("mug", "red", (0.0, 0.0, 0.0))], ())
    attempt = Attempt(get_task("trashAll"), 0, "mug", ("find", "pickUp", "trash"), True, ())
    teach_utterance(mind, Interrupt("trash", "mug", "No, that's mine!", "xuan"), attempt)
    assert mind.rules["trash"] == (parse_rule("forbid trash if ownedBy xuan"),)


@pytest.mark.parametrize(("utterance", "verdict"), [("Don't throw that away.", "skip"),
                                                    ("Never trash red things", "skip"),
                                                    ("It's Xuan's cup.", None), ("You can trash that", None)])
def test_an_interrupt_that_forbids_the_ongoing_action_stops_it(utterance: str, verdict: str | None) -> None:
    """A plain prohibition or a norm said while the robot acts is taught, and the robot, deciding
    again, stops; what leaves the action allowed lets it go on (no instructor to stop it here)."""
    from ownctl.app.run import Interrupt, Interrupting, teach_utterance
    from ownctl.experiment.task import Attempt, SilentInstructor, get_task
    from ownctl.mind import Mind
    from ownctl.world.model import ObjectSpec

    mind = Mind(("xuan",), [ObjectSpec("mug", "red", (0.0, 0.0, 0.0))], ())
    attempt = Attempt(get_task("trashAll"), 0, "mug", ("find", "pickUp", "trash"), True, ())
    said = [Interrupt("trash", "mug", utterance, "xuan")]
    teacher = Interrupting(SilentInstructor(), said, teach_utterance)
    assert teacher.react(attempt, mind).override == verdict


@pytest.mark.parametrize("path", PLAYED, ids=[p.stem for p in PLAYED])
def test_every_scenario_passes(path: Path) -> None:
    result = play(str(path), "--json", code=None)
    data = json.loads(result.stdout)
    failed = [(s["step"], e) for s in data["steps"] for e in s["expectations"] if not e["ok"]]
    errors = [(s["step"], s["error"]) for s in data["steps"] if s["error"]]
    assert data["passed"] and result.exit_code == 0, (failed, errors)
    assert data["steps_played"] == data["steps_total"] == len(tomllib.loads(path.read_text())["steps"])


def test_the_human_report_marks_each_expectation(tmp_path: Path) -> None:
    out = play(str(SCENARIOS / "demo3-induction.toml")).stdout
    assert out.startswith("scenario: demo 3: inducing a norm from examples")
    assert "step 9  say \"You can pick that up.\" (as xuan, about block4)" in out
    assert "✓ rule 'forbid pickUp if ownedBy any'" in out
    assert out.rstrip().splitlines()[-1].startswith("passed: 9/9 expectations held, 11/11 steps played")


WORLD = """\
name = "tiny"
agents = ["xuan"]

[[areas]]
name = "trash"
box = [-0.3, 0.6, 0.2, 1.1]

[[objects]]
name = "can"
color = "green"
position = [-0.4, 0.2, 0.0]

[[objects]]
name = "mug"
color = "red"
position = [0.4, -0.2, 0.0]
"""


def _scenario(tmp_path: Path, steps: str) -> str:
    path = tmp_path / "s.toml"
    path.write_text(WORLD + steps)
    return str(path)


def test_a_failed_expectation_exits_4_and_says_which(tmp_path: Path) -> None:
    path = _scenario(tmp_path, """
[[steps]]
command = "forbid trash on mug"
expect = ["check trash mug = permitted", "check trash mug = forbidden"]
""")
    result = play(path, code=4)
    assert "✗ check trash mug = permitted    (forbidden: trash is forbidden on mug by permission 1)" \
        in result.stdout
    assert "✓ check trash mug = forbidden" in result.stdout
    assert "FAILED: 1/2 expectations held" in result.stdout
    data = json.loads(play(path, "--json", code=4).stdout)
    assert data["passed"] is False and data["expectations"] == {"total": 2, "passed": 1, "failed": 1}


def test_a_failing_step_stops_the_scenario(tmp_path: Path) -> None:
    path = _scenario(tmp_path, """
[[steps]]
say = "Frobnicate the quux"
as = "xuan"
expect = ["moved mug"]

[[steps]]
command = "forbid trash on ghost"
""")
    data = json.loads(play(path, "--json", code=4).stdout)
    assert data["steps_played"] == 1 and data["steps"][0]["error"].startswith("I did not understand")
    assert data["steps"][0]["expectations"] == []


def test_a_failing_command_reports_its_error(tmp_path: Path) -> None:
    path = _scenario(tmp_path, """
[[steps]]
command = "forbid trash on ghost"
""")
    data = json.loads(play(path, "--json", code=4).stdout)
    assert data["steps"][0]["error"] == "ownctl: step 1: unknown object 'ghost'; known objects: can, mug"


def test_a_malformed_scenario_is_an_error_that_writes_nothing(tmp_path: Path, ownctl: Ownctl) -> None:
    path = _scenario(tmp_path, """
[[steps]]
say = "This is mine"
about = "mug"
expect = ["owner mug xuan >> 0.5"]
""")
    before = ownctl.digest()
    result = ownctl("scenario", "play", path, code=1)
    assert result.stderr.startswith(
        f"ownctl: {path}: step 1 expect: malformed expectation 'owner mug xuan >> 0.5'"
    )
    assert ownctl.digest() == before
    bad_key = _scenario(tmp_path, '\n[[steps]]\nsay = "hi"\nwhen = "now"\n')
    assert "unknown key 'when' in step 1; valid keys: say, as, about" in play(bad_key, code=1).stderr
    bad_task = _scenario(tmp_path, '\n[[steps]]\nrun = "tidyAll"\n')
    message = play(bad_task, code=1).stderr
    assert "step 1: unknown task 'tidyAll'; known tasks: collectAll, trashAll" in message


def test_commands_run_on_the_scenario_clock_and_db_keeps_the_result(tmp_path: Path, ownctl: Ownctl) -> None:
    path = _scenario(tmp_path, """
[[steps]]
say = "That's mine"
as = "xuan"
about = "mug"

[[steps]]
command = "claim can xuan --not --as xuan"
expect = ["owner can xuan < 0.1", "owner mug xuan > 0.9"]
""")
    out = ownctl.json("scenario", "play", path)
    assert out["passed"] and out["store"] == ownctl.url
    claims = {c["object"]: c["time"] for c in ownctl.json("claims", "list")}
    assert claims == {"mug": 1001.0, "can": 1002.0}  # one second per step after the world is loaded
    assert "already exists" in ownctl("scenario", "play", path, code=1).stderr  # the world is there


def test_a_run_step_with_an_interrupt(tmp_path: Path) -> None:
    path = _scenario(tmp_path, """
[[steps]]
run = "trashAll"
expect = ["left mug", "moved can", "owner mug xuan > 0.9"]
[[steps.interrupt]]
before = "trash mug"
say = "Stop, that's mine!"
as = "xuan"
""")
    data = json.loads(play(path, "--json").stdout)
    run = data["steps"][0]["result"]
    assert run["delivered"] == ["can"] and run["skipped"] == [{"object": "mug", "reason": "stopped by the "
                                                                                          "instructor"}]


def test_an_interrupt_that_never_comes_fails_the_step(tmp_path: Path) -> None:
    path = _scenario(tmp_path, """
[[steps]]
command = "forbid trash on mug"

[[steps]]
run = "trashAll"
[[steps.interrupt]]
before = "trash ghost"
say = "No!"
as = "xuan"
""")
    data = json.loads(play(path, "--json", code=4).stdout)
    assert data["steps"][1]["error"].startswith("unknown object 'ghost' in an interrupt")


def test_render_needs_physics(tmp_path: Path) -> None:
    path = _scenario(tmp_path, '\n[[steps]]\nsay = "hi"\n')
    assert "--render needs --physics" in play(path, "--render", str(tmp_path / "v.mp4"), code=1).stderr


@pytest.mark.slow
def test_a_scenario_plays_in_physics(tmp_path: Path) -> None:
    data = json.loads(play(str(SCENARIOS / "demo4-shared-desk.toml"), "--physics", "--json").stdout)
    assert data["passed"], data["steps"][-1]
    assert data["steps"][-1]["result"]["sim_seconds"] > 0


def test_ownctl_db_alone_does_not_pick_the_store_but_db_does(tmp_path: Path, ownctl: Ownctl) -> None:
    path = _scenario(tmp_path, '\n[[steps]]\nsay = "That\'s mine"\nas = "xuan"\nabout = "mug"\n')
    before = ownctl.digest()
    env = {"OWNCTL_NOW": NOW, "OWNCTL_DB": ownctl.url}
    result = invoke(CliRunner(), ["scenario", "play", path, "--json"], None, env)
    assert result.exit_code == 0 and json.loads(result.stdout)["store"] is None
    assert ownctl.digest() == before
    result = invoke(CliRunner(), ["scenario", "play", path, "--db", ownctl.url, "-q"], None, env)
    assert result.exit_code == 0 and ownctl.json("claims", "list")[0]["object"] == "mug"


def test_a_scenario_names_people_and_things_in_any_script_however_typed(tmp_path: Path) -> None:
    """A world and its steps written with combining accents (docs/architecture.md, section 2)."""
    path = tmp_path / "unicode.toml"
    path.write_text("""
name = "cocina"
agents = ["Jose\\u0301", "\\u0414\\u0438\\u043c\\u0430"]

[[objects]]
name = "ta\\u0301za"
color = "red"
position = [0.3, 0.1, 0.0]

[[steps]]
say = "The ta\\u0301za is mine."
as = "Jose\\u0301"
expect = ["owner t\\u00e1za Jos\\u00e9 > 0.9", "owner ta\\u0301za \\u0414\\u0438\\u043c\\u0430 < 0.5"]

[[steps]]
say = "Don't throw away Jose\\u0301's things."
as = "\\u0414\\u0438\\u043c\\u0430"
expect = ["check trash ta\\u0301za = forbidden", "rule 'forbid trash if ownedBy Jose\\u0301'"]
""", encoding="utf-8")
    data = json.loads(play(str(path), "--json").stdout)
    assert data["passed"] is True and data["expectations"] == {"total": 4, "passed": 4, "failed": 0}
