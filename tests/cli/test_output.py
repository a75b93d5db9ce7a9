"""Human output reads right: ISO 8601 local times (JSON keeps the numbers and adds the ISO strings),
counted nouns, nothing said twice, a run's events under one log row; speakers are names."""

from __future__ import annotations

import json
from datetime import datetime
from typing import TYPE_CHECKING

import pytest

from ownctl.humanize import iso, plural

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

NOW = 1000.0  # the store time tests/cli/conftest.py pins


def test_iso_is_local_iso_8601_that_reads_back_as_the_same_second() -> None:
    for seconds in (0.0, NOW, 1796122900.7, 4102444800.0):
        text = iso(seconds)
        parsed = datetime.fromisoformat(text)
        assert parsed.tzinfo is not None and parsed.timestamp() == int(seconds)
        assert parsed.utcoffset() == datetime.fromtimestamp(seconds).astimezone().utcoffset()
    assert iso(float("nan")) == "nan" and iso(1e300) == "1e+300"  # stored junk still prints


def test_plural() -> None:
    assert [plural(n, "instruction") for n in (0, 1, 2)] == ["0 instructions", "1 instruction",
                                                             "2 instructions"]
    assert plural(2, "body", "bodies") == "2 bodies"


def test_times_print_as_iso_and_json_adds_iso_next_to_the_numbers(table_world: Ownctl) -> None:
    assert table_world("object", "touch", "wallet", "--by", "xuan").stdout == (
        f"xuan touched wallet at {iso(NOW)}\n")
    table_world("object", "touch", "mug", "--by", "alexis", "--at", "400")
    objects = {o["name"]: o for o in table_world.json("object", "list")}
    assert objects["mug"]["last_touch"] == {"alexis": 400.0}
    assert objects["mug"]["last_touch_iso"] == {"alexis": iso(400.0)}
    claim = table_world.json("claims", "list")[0]
    assert claim["time"] == NOW and claim["time_iso"] == iso(NOW)
    assert iso(NOW) in table_world("claims", "list").stdout
    assert f"alexis {iso(400.0)}" in table_world("object", "list").stdout
    assert iso(400.0) in table_world("object", "show", "mug").stdout
    event = table_world.json("log")[-1]
    assert event["time_iso"] == iso(event["time"])
    assert iso(NOW) in table_world("log").stdout
    table_world("forbid", "trash", "on", "wallet")
    assert f"at {iso(NOW)}" in table_world("explain", "trash", "wallet").stdout
    shown = (("log",), ("claims", "list"), ("explain", "trash", "mug"))
    for out in (table_world(*args).stdout for args in shown):
        assert "e+09" not in out and "t=" not in out


def test_counts_are_singular_for_one(ownctl: Ownctl) -> None:
    out = ownctl("batch", "-", input="agent add a1\n").stdout
    assert out.endswith("batch: ran 1 instruction from stdin\n")
    assert "forgot 0 permissions, 0 rules, 0 claims" in ownctl("reset", "all", "--yes").stdout
    ownctl("object", "add", "pen")
    ownctl("claim", "pen", "a1")
    assert "forgot 1 claim" in ownctl("reset", "claims", "--yes").stdout


def test_why_not_says_its_explanation_once(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "on", "wallet", "--as", "alexis")
    table_world("check", "trash", "wallet", code=3)
    out = table_world("say", "Why not?", "--as", "xuan").stdout
    assert out.count("trash is forbidden on wallet") == 1
    assert out.splitlines()[0].strip() == "explain" and out.splitlines()[-1].startswith("robot: ")


def test_a_runs_events_are_one_log_row_with_its_actor(ownctl: Ownctl) -> None:
    run = ownctl.json("run", "collectAll", "--kinematic")
    ownctl("agent", "add", "zed")
    rows = [line for line in ownctl("log").stdout.splitlines() if line.strip()]
    assert len(rows) == 3  # init, the run, agent add
    first, last = 2, 2 + len(run["steps"])  # the generated world, then one event per step
    assert rows[1].split()[:4] == [f"{first}-{last}", iso(NOW), "robot", "cli"]
    fates = f"{len(run['delivered'])} delivered"
    assert f"run collectAll --kinematic --json  (world.generate; {len(run['steps'])} steps: " in rows[1]
    assert fates in rows[1] and plural(run["mistakes"], "mistake") in rows[1]
    assert ownctl("log", "-n", "2").stdout.splitlines()[0] == rows[1]  # -n counts instructions
    events = ownctl.json("log", "-n", "2")  # --json keeps every event of those instructions
    assert [e["id"] for e in events] == [*range(first, last + 1), last + 1]


def test_run_summary_and_table_use_the_same_words(ownctl: Ownctl) -> None:
    result = ownctl("run", "trashAll", "--kinematic")
    data = ownctl.json("run", "trashAll", "--kinematic")  # the table is done: nothing left to move
    assert data["delivered"] == []
    assert "delivered" in result.stderr and "moved" not in result.stderr  # the live table
    assert " delivered, " in result.stdout and "moved" not in result.stdout


SPEAKERS = ["x" * 65, "-\u00e9", "\u0430gent", "Xuan Tan", "9lives", "any", "", "a" * 10_000]


@pytest.mark.parametrize("speaker", SPEAKERS, ids=lambda s: repr(s[:12]))
def test_a_speaker_obeys_the_naming_rule_on_every_command(table_world: Ownctl, speaker: str) -> None:
    before = table_world.digest()
    for args in (("claim", "wallet", "alexis"), ("forbid", "trash", "on", "wallet"),
                 ("allow", "trash", "if", "isColored", "red"), ("say", "No, that's mine!", "--about", "mug")):
        result = table_world(*args, "--as", speaker, code=1)
        assert result.stderr.startswith("ownctl: ") and result.stderr.count("\n") == 1
        assert "speaker name" in result.stderr or "reserved" in result.stderr
        assert table_world.digest() == before
    error = json.loads(table_world("claim", "wallet", "alexis", "--as", speaker, "--json", code=1).stdout)
    assert error["error"].startswith(("invalid speaker name", "speaker name"))
