"""Every command, through the CLI, on a temporary store with the clock pinned."""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from ownctl.cli.common import fmt

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl


def test_version_and_help(ownctl: Ownctl) -> None:
    assert ownctl("--version").stdout.startswith("ownctl ")
    for group in ("world", "agent", "object", "area", "claims", "rules", "perms", "db", "config"):
        assert "Usage" in ownctl(group, "--help").stdout
    for cmd in ("init", "claim", "forbid", "allow", "check", "owners", "log", "reset", "freeze", "batch"):
        assert "Usage" in ownctl(cmd, "--help").stdout


def test_init_is_idempotent(ownctl: Ownctl) -> None:
    data = ownctl.json("init")
    assert data["created"] is False and data["path"] == str(ownctl.path)


def test_agents(ownctl: Ownctl) -> None:
    ownctl("agent", "add", "alexis")
    ownctl("agent", "add", "xuan")
    assert [a["name"] for a in ownctl.json("agent", "list")] == ["alexis", "xuan"]
    assert "xuan" in ownctl("agent", "list").stdout
    ownctl("agent", "remove", "xuan")
    assert [a["name"] for a in ownctl.json("agent", "list")] == ["alexis"]
    assert ownctl("agent", "add", "bob", "--quiet").stdout == ""


def test_objects(ownctl: Ownctl) -> None:
    ownctl("object", "add", "wallet", "--color", "brown", "--pos", "0.1,0.2,0.3", "--category", "personal")
    ownctl("object", "add", "mug")
    listed = {o["name"]: o for o in ownctl.json("object", "list")}
    assert listed["wallet"]["position"] == [0.1, 0.2, 0.3]
    assert listed["wallet"]["categories"] == ["personal"] and listed["mug"]["color"] is None
    ownctl(
        "object", "set", "mug", "--color", "red", "--pos", "1,2", "--category", "kitchen", "--category", "cup"
    )
    mug = ownctl.json("object", "show", "mug")
    assert (
        mug["color"] == "red"
        and mug["position"] == [1.0, 2.0, 0.0]
        and mug["categories"] == ["cup", "kitchen"]
    )
    ownctl("object", "set", "mug", "--color", "none", "--pos", "none", "--category", "none")
    mug = ownctl.json("object", "show", "mug")
    assert mug["color"] is None and mug["position"] is None and mug["categories"] == []
    assert "wallet" in ownctl("object", "show", "wallet").stdout
    ownctl("object", "remove", "mug")
    assert [o["name"] for o in ownctl.json("object", "list")] == ["wallet"]


def test_agent_list_counts_the_objects_each_agent_touched(table_world: Ownctl) -> None:
    table_world("object", "touch", "wallet", "--by", "xuan")
    table_world("object", "touch", "mug", "--by", "xuan")
    table_world("object", "touch", "mug", "--by", "xuan", "--at", "400")  # the same object again
    table_world("object", "touch", "mug", "--by", "alexis")
    before = {a["name"]: a["touched"] for a in table_world.json("agent", "list")}
    table_world("object", "remove", "mug")
    after = {a["name"]: a["touched"] for a in table_world.json("agent", "list")}
    assert (before["xuan"], before["alexis"], after["xuan"], after["alexis"]) == (2, 1, 1, 0)


def test_touch_uses_absolute_store_time(table_world: Ownctl) -> None:
    table_world("object", "touch", "wallet", "--by", "xuan")
    table_world("object", "touch", "mug", "--by", "alexis", "--at", "400")
    objects = {o["name"]: o for o in table_world.json("object", "list")}
    assert objects["wallet"]["last_touch"] == {"xuan": 1000.0}
    assert objects["mug"]["last_touch"] == {"alexis": 400.0}


def test_areas(ownctl: Ownctl) -> None:
    ownctl("area", "add", "home", "--box", "-0.1,-0.1,0.1,0.1")
    assert ownctl.json("area", "list") == [{"name": "home", "box": [-0.1, -0.1, 0.1, 0.1]}]
    ownctl("area", "remove", "home")
    assert ownctl.json("area", "list") == []


def test_claims_trust_negation_and_exclusive(table_world: Ownctl) -> None:
    table_world("claim", "mug", "xuan", "--p", "0.75")
    table_world("config", "set", "trust", "0.8")
    table_world("claim", "pen", "xuan", "--not")
    claims = {(c["object"], c["agent"]): c for c in table_world.json("claims", "list")}
    assert claims[("wallet", "alexis")]["p"] == 1.0
    assert claims[("mug", "xuan")]["p"] == 0.75
    assert claims[("pen", "xuan")]["p"] == pytest.approx(1 - 0.8)
    table_world("config", "set", "trust", "1")
    table_world("claim", "wallet", "xuan", "--only", "--as", "xuan")
    owners = {o["agent"]: o for o in table_world.json("owners", "wallet")["owners"]}
    assert owners["xuan"]["p"] == 1.0 and owners["alexis"]["p"] == 0.0
    assert owners["alexis"]["source"] == "claim"


def test_owners_by_agent(table_world: Ownctl) -> None:
    table_world("claim", "mug", "alexis", "--p", "0.6")
    table_world("claim", "pen", "alexis", "--p", "0.2")
    rows = table_world.json("owners", "--agent", "alexis")
    assert [r["object"] for r in rows] == ["wallet", "mug"]
    assert [r["object"] for r in table_world.json("owners", "--agent", "alexis", "--min", "0")][-1] == "pen"
    table_world("owners", code=2)


def test_permissions(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "on", "wallet")
    table_world("allow", "pickUp", "on", "mug")
    table_world("forbid", "trash", "on", "wallet", "--p", "0.7")  # overwrites
    perms = table_world.json("perms", "list")
    assert [(p["text"], p["value"]) for p in perms] == [
        ("forbid trash on wallet", 0.7),
        ("allow pickUp on mug", 0.0),
    ]
    table_world("perms", "remove", str(perms[0]["id"]))
    assert len(table_world.json("perms", "list")) == 1


def test_rules_given_and_listed_canonically(table_world: Ownctl) -> None:
    out = table_world.json("forbid", "pickUp", "if", "not", "isColored", "red", "and", "ownedBy", "xuan")
    assert out["text"] == "forbid pickUp if ownedBy xuan and not isColored red" and out["stored"]
    again = table_world.json("forbid", "pickUp", "if", "ownedBy", "xuan", "and", "not", "isColored", "red")
    assert again["stored"] is False and again["id"] == out["id"]
    table_world("forbid", "trash", "if", "ownedBy", "any", "and", "inArea", "desk")
    rules = table_world.json("rules", "list")
    assert {r["text"] for r in rules} == {
        "forbid pickUp if ownedBy xuan and not isColored red",
        "forbid trash if ownedBy any and inArea desk",
    }
    assert set(rules[0]) >= {"id", "text", "action", "origin", "accuracy"}
    assert rules[0]["origin"] == "given"
    table_world("rules", "remove", str(out["id"]))
    assert len(table_world.json("rules", "list")) == 1


def test_allow_norm_is_subtracted_from_the_forbid_rules(table_world: Ownctl) -> None:
    out = table_world.json("allow", "trash", "if", "isColored", "red")
    assert out["stored"] is False and out["rules"] == []
    assert table_world.json("log")[-1]["command"] == "allow trash if isColored red --json"
    table_world("forbid", "trash", "if", "ownedBy", "any")
    texts = [r["text"] for r in table_world.json("rules", "list")]
    assert texts == ["forbid trash if ownedBy any and not isColored red", "allow trash if isColored red"]


def test_rule_accuracy_against_permissions(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "if", "ownedBy", "any")
    table_world("forbid", "trash", "on", "wallet")
    table_world("allow", "trash", "on", "mug")
    (rule,) = table_world.json("rules", "list")
    # as the conflict gate measures it: on prior ownership (wallet claimed; mug predicted)
    none_owns_mug = 1.0
    for owner in table_world.json("owners", "mug")["owners"]:
        none_owns_mug *= 1.0 - (owner["claim"] if owner["claim"] is not None else owner["prior"])
    assert rule["accuracy"] == pytest.approx((1.0 + none_owns_mug) / 2, abs=1e-12)
    assert rule["set_accuracy"] == rule["accuracy"]


def test_check_shape_and_exit_codes(table_world: Ownctl) -> None:
    data = table_world.json("check", "trash", "wallet")
    assert data["decision"] == "permitted" and data["decided_by"] == "none"
    assert [s["action"] for s in data["steps"]] == ["find", "pickUp", "trash"]
    table_world("forbid", "trash", "if", "ownedBy", "any")
    data = table_world.json("check", "trash", "wallet", code=3)
    assert set(data) >= {
        "action",
        "object",
        "decision",
        "p_forbidden",
        "threshold",
        "decided_by",
        "steps",
        "atoms",
    }
    assert data["decision"] == "forbidden" and data["decided_by"] == "rules" and data["p_forbidden"] == 1.0
    step = data["steps"][-1]
    assert set(step) >= {"action", "decision", "decided_by", "p_forbidden", "permission", "rules"}
    assert step["rules"][0]["text"] == "forbid trash if ownedBy any"
    assert {"agent": "alexis", "p": 1.0, "source": "claim"} in data["atoms"]
    assert "forbidden" in table_world("check", "trash", "wallet", code=3).stdout
    table_world("allow", "trash", "on", "wallet")
    assert table_world.json("check", "trash", "wallet")["decided_by"] == "permission"


def test_check_prerequisite_and_threshold(table_world: Ownctl) -> None:
    table_world("claim", "mug", "xuan", "--p", "0.4")
    table_world("forbid", "pickUp", "if", "ownedBy", "xuan")
    assert table_world.json("check", "trash", "mug")["decision"] == "permitted"
    table_world("config", "set", "threshold.pickUp", "0.3")
    data = table_world.json("check", "trash", "mug", code=3)
    assert data["decided_by"] == "prerequisite" and data["p_forbidden"] == pytest.approx(0.4)
    table_world("forbid", "release", "on", "pen")  # a target-less step is checked when it has a permission
    pen = table_world.json("check", "trash", "pen", code=3)
    assert [s["action"] for s in pen["steps"]] == ["find", "pickUp", "release", "trash"]
    assert pen["decided_by"] == "prerequisite"


def test_config(ownctl: Ownctl) -> None:
    assert ownctl.json("config", "get")["threshold"] == 0.5
    ownctl("config", "set", "threshold.trash", "0.7")
    assert ownctl.json("config", "get", "threshold.trash") == {"threshold.trash": 0.7}
    ownctl("config", "set", "threshold.trash", "default")
    assert "threshold.trash" not in ownctl.json("config", "get")


def test_freeze_and_disable(table_world: Ownctl) -> None:
    table_world("freeze", "perms")
    assert "frozen" in table_world("forbid", "trash", "on", "wallet", code=1).stderr
    table_world("unfreeze", "perms")
    table_world("forbid", "trash", "on", "wallet")
    table_world("freeze", "rules")
    table_world("forbid", "trash", "if", "ownedBy", "any", code=1)
    table_world("unfreeze", "rules")
    table_world("disable", "inference")
    table_world("disable", "prediction")
    settings = table_world.json("config", "get")
    assert settings["disabled.inference"] and settings["disabled.prediction"] and not settings["frozen.rules"]
    table_world("enable", "inference")
    assert table_world.json("config", "get")["disabled.inference"] is False


def test_reset(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "on", "wallet")
    table_world("forbid", "trash", "if", "ownedBy", "any")
    table_world("reset", "perms", code=1)  # needs --yes
    assert table_world.json("reset", "perms", "--yes")["permissions"] == 1
    table_world("reset", "all", "--yes")
    assert table_world.json("rules", "list") == [] and table_world.json("claims", "list") == []
    assert len(table_world.json("object", "list")) == 3  # the world stays


def test_log_records_instructions(table_world: Ownctl) -> None:
    events = table_world.json("log")
    assert events[0]["command"] == "init"
    assert events[-1]["command"] == "claim wallet alexis" and events[-1]["interface"] == "cli"
    assert events[-1]["payload"]["op"] == "claim" and events[-1]["time"] == 1000.0
    assert len(table_world.json("log", "--limit", "2")) == 2


def test_db_commands(ownctl: Ownctl) -> None:
    assert ownctl("db", "path").stdout.strip() == str(ownctl.path)
    current = ownctl.json("db", "current")
    assert current["current"] and current["revision"] == current["head"]
    assert ownctl.json("db", "upgrade")["to"] == current["head"]


def test_the_store_can_use_the_papers_learner(table_world: Ownctl) -> None:
    assert table_world.json("config", "get")["learner"] == "ours"
    table_world("config", "set", "learner", "paper")
    assert "valid learners: ours, paper" in table_world("config", "set", "learner", "magic", code=1).stderr
    table_world("forbid", "trash", "on", "wallet")  # the paper's first example: the always-rule
    assert [r["text"] for r in table_world.json("rules", "list")] == ["forbid trash"]


def test_rules_list_shows_each_rules_posterior_as_its_json_does(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "on", "wallet")  # wallet is alexis's: a rule is learned
    rule = table_world.json("rules", "list")[0]
    assert rule["origin"] == "learned" and 0.0 < rule["posterior"] <= 1.0
    lines = table_world("rules", "list").stdout.splitlines()
    header = next(line for line in lines if "accuracy" in line)
    assert header.rstrip(" ┃").split("┃")[-1].strip() == "posterior"
    first = next(line for line in lines if line.startswith("│ ") and rule["text"].split()[0] in line)
    assert first.rstrip(" │").split("│")[-1].strip() == fmt(rule["posterior"])
