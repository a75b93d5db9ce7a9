"""Scenario files: steps and expectation lines parse into typed objects, or fail naming file, step, key."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from ownctl.errors import BadValue
from ownctl.world.scenario import (
    CheckExpectation,
    OwnerExpectation,
    PlaceExpectation,
    RuleExpectation,
    parse_expectation,
    scenario_from_dict,
)

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"


@pytest.mark.parametrize(
    ("line", "expected"),
    [
        ("check trash wallet = forbidden",
         CheckExpectation("check trash wallet = forbidden", "trash", "wallet", True)),
        ("check pickUp b1=permitted", CheckExpectation("check pickUp b1=permitted", "pickUp", "b1", False)),
        ("rule 'forbid trash if isColored red and ownedBy agent1'",
         RuleExpectation("rule 'forbid trash if isColored red and ownedBy agent1'",
                         "forbid trash if ownedBy agent1 and isColored red", True)),
        ('no rule "forbid trash"', RuleExpectation('no rule "forbid trash"', "forbid trash", False)),
        ("owner wallet agent1 > 0.9",
         OwnerExpectation("owner wallet agent1 > 0.9", "wallet", "agent1", True, 0.9)),
        ("owner wallet agent1 < 0.1",
         OwnerExpectation("owner wallet agent1 < 0.1", "wallet", "agent1", False, 0.1)),
        ("moved can", PlaceExpectation("moved can", "can", True)),
        ("  left can ", PlaceExpectation("left can", "can", False)),
    ],
)
def test_expectations_parse(line: str, expected: object) -> None:
    assert parse_expectation(line) == expected


@pytest.mark.parametrize(
    ("line", "why"),
    [
        ("check trash wallet = maybe", ""),
        ("check thrash wallet = forbidden", "unknown action 'thrash'"),
        ("rule forbid trash", ""),
        ("rule 'forbid trash if isBig yes'", "isBig"),
        ("rule 'allow trash if isColored red'", "forbid rules"),
        ("owner wallet agent1 > 1.5", "not a probability"),
        ("owner wallet agent1 = 0.5", ""),
        ("moved", ""),
        ("moved two things", ""),
        ("left 9lives", "not a valid object name"),
    ],
)
def test_malformed_expectations_name_the_file_step_and_forms(line: str, why: str) -> None:
    with pytest.raises(BadValue) as err:
        parse_expectation(line, "demo.toml", "step 3 expect")
    message = err.value.message
    assert message.startswith(f"demo.toml: step 3 expect: malformed expectation {line!r}")
    assert why in message
    assert "expectations are: check ACTION OBJ = forbidden|permitted; rule 'TEXT'; no rule 'TEXT'" in message
    assert "moved OBJ; left OBJ" in message


def _steps(*steps: dict[str, object]) -> dict[str, object]:
    return {"name": "t", "steps": list(steps)}


@pytest.mark.parametrize(
    ("steps", "message"),
    [
        (_steps({"say": "hi", "sya": "x"}),
         "f.toml: unknown key 'sya' in step 1; valid keys: say, as, about, command, run, instructor, "
         "interrupt, expect"),
        (_steps({"say": "hi"}, {"say": "a", "command": "claim a b"}),
         "f.toml: step 2 must have exactly one of say, command, run, got say, command"),
        (_steps({"expect": ["moved a"]}),
         "f.toml: step 1 must have exactly one of say, command, run, got none"),
        (_steps({"command": "claim a b", "as": "x"}),
         "f.toml: step 1: key 'as' does not go with command; a command step takes command, expect"),
        (_steps({"run": "trashAll", "interrupt": [{"before": "trash a", "say": "No!"}]}),
         "f.toml: step 1 interrupt 1 needs as"),
        (_steps({"run": "trashAll", "interrupt": [{"before": "thrash a", "say": "No!", "as": "x"}]}),
         "f.toml: step 1 interrupt 1: before must be 'ACTION OBJECT'"),
        (_steps({"run": "trashAll",
                 "interrupt": [{"before": "trash a", "say": "No!", "as": "x", "expect": []}]}),
         "f.toml: unknown key 'expect' in step 1 interrupt 1; valid keys: before, say, as"),
        (_steps({"command": "--db other.db claim a b"}), "a scenario cannot run"),
        (_steps({"command": "ownctl init"}), "a scenario cannot run"),
        (_steps({"command": "claim 'a b"}), "cannot split command"),
        (_steps({"say": ""}), "f.toml: step 1: say must be a non-empty string"),
        (_steps({"say": "hi", "expect": "moved a"}), "f.toml: step 1: expect must be a list of strings"),
        (_steps({"run": "trashAll", "instructor": "god"}),
         "unknown instructor 'god'; valid instructors: none, oracle"),
        ({"steps": {"say": "hi"}}, "f.toml: steps must be an array of tables"),
    ],
)
def test_malformed_steps_name_the_file_step_and_valid_keys(steps: dict[str, object], message: str) -> None:
    with pytest.raises(BadValue) as err:
        scenario_from_dict(steps, "f.toml")
    assert message in err.value.message


def test_a_step_in_full() -> None:
    data = tomllib.loads('''
[[steps]]
run = "trashAll"
instructor = "oracle"
expect = ["moved can"]
[[steps.interrupt]]
before = "trash wallet"
say = "No Baxter, that's mine!"
as = "xuan"

[[steps]]
command = "ownctl forbid trash if ownedBy xuan  # a comment"
''')
    run, command = scenario_from_dict(data, "f.toml").steps
    assert (run.kind, run.text, run.instructor, run.number) == ("run", "trashAll", "oracle", 1)
    assert [(i.action, i.object, i.utterance, i.speaker) for i in run.interrupts] == [
        ("trash", "wallet", "No Baxter, that's mine!", "xuan")
    ]
    assert run.describe() == 'run trashAll with the oracle instructor; before trash wallet, xuan: ' \
                             '"No Baxter, that\'s mine!"'
    assert command.words == ("forbid", "trash", "if", "ownedBy", "xuan")


def test_the_shipped_scenarios_parse() -> None:
    files = sorted(SCENARIOS.glob("*.toml"))
    assert len([f for f in files if f.name.startswith("demo")]) >= 4
    for path in files:
        scenario_from_dict(tomllib.loads(path.read_text()), str(path))
