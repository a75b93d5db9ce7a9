"""``ownctl say``: an utterance becomes its instructions, applied in one transaction, in context."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

CASEYS = ["skip wallet", "claim wallet casey", "forbid trash on wallet", "forbid trash if ownedBy casey"]


def _rules(store: Ownctl) -> list[str]:
    return [r["text"] for r in store.json("rules", "list")]


def test_a_reprimand_is_a_claim_a_permission_and_a_norm(table_world: Ownctl) -> None:
    table_world("agent", "add", "casey")
    table_world("check", "trash", "wallet")  # the robot's current action: trash, on the wallet
    out = table_world.json("say", "Don't, that's Casey's!", "--as", "xuan")
    assert out["intent"] == "reprimand"
    assert out["instructions"] == CASEYS
    assert [r["instruction"] for r in out["results"]] == CASEYS
    assert out["reply"].startswith("Sorry about that.")
    assert "forbid trash if ownedBy casey" in _rules(table_world)
    assert "forbid trash" not in _rules(table_world)  # the example agrees with the norm given with it
    claims = {(c["object"], c["agent"]): c for c in table_world.json("claims", "list")}
    assert claims["wallet", "casey"]["p"] == 1.0 and claims["wallet", "casey"]["speaker"] == "xuan"
    perms = table_world.json("perms", "list")
    assert [(p["text"], p["speaker"]) for p in perms] == [("forbid trash on wallet", "xuan")]
    log = table_world.json("log", "-n", "5")
    # one event for the utterance, then one per instruction in the order applied: the norm before the
    # permission it explains
    assert log[0]["payload"] == {"op": "say", "utterance": "Don't, that's Casey's!", "speaker": "xuan",
                                 "about": "wallet", "instructions": CASEYS}
    assert [e["command"] for e in log[1:]] == [
        "skip wallet", "claim wallet casey", "forbid trash if ownedBy casey", "forbid trash on wallet"
    ]
    assert {e["interface"] for e in log[1:]} == {"say"} and {e["actor"] for e in log} == {"xuan"}


def test_the_human_output_lists_the_instructions_and_the_reply(table_world: Ownctl) -> None:
    out = table_world("say", "This is mine", "--as", "xuan", "--about", "mug").stdout
    assert "claim mug xuan" in out
    assert "robot: Noted: mug belongs to xuan." in out


def test_an_utterance_that_fails_half_way_writes_nothing(table_world: Ownctl) -> None:
    table_world("freeze", "rules")
    table_world("check", "trash", "wallet")
    before = table_world.digest()
    result = table_world("say", "No, that's mine!", "--as", "xuan", code=1)
    assert "rules are frozen" in result.stderr
    assert table_world.digest() == before  # the claim made before the refused norm is rolled back
    assert ("wallet", "xuan") not in {(c["object"], c["agent"]) for c in table_world.json("claims", "list")}


def test_an_utterance_not_understood_writes_nothing_and_shows_examples(table_world: Ownctl) -> None:
    before = table_world.digest()
    result = table_world("say", "Frobnicate the quux", "--as", "xuan", code=1)
    assert "did not understand" in result.stderr and "try for example" in result.stderr
    assert table_world.digest() == before
    error = json.loads(table_world("say", "Frobnicate the quux", "--json", code=1).stdout)
    assert error["valid"]  # the examples


def test_unknown_speaker_or_object_is_an_error_naming_the_known_ones(table_world: Ownctl) -> None:
    before = table_world.digest()
    assert "known agents: alexis, xuan" in table_world("say", "Whose is this?", "--as", "ghost",
                                                       "--about", "mug", code=1).stderr
    assert "known objects:" in table_world("say", "This is mine", "--as", "xuan", "--about", "ghost",
                                           code=1).stderr
    assert table_world.digest() == before


def test_this_without_a_target_asks_for_one(table_world: Ownctl) -> None:
    result = table_world("say", "That's mine", "--as", "xuan", code=1)
    assert "--about" in result.stderr


def test_speaker_and_target_carry_over_between_utterances(table_world: Ownctl) -> None:
    table_world("say", "This is mine", "--as", "xuan", "--about", "mug")
    out = table_world.json("say", "This is mine too")  # same speaker, same target
    assert out["instructions"] == ["claim mug xuan"]
    out = table_world.json("say", "That's Alexis's", "--about", "pen")
    assert out["instructions"] == ["claim pen alexis"] and out["speaker"] == "xuan"
    assert table_world.json("say", "Whose is this?")["instructions"] == ["owners pen"]


def test_no_thats_mine_refers_to_the_last_checked_action(table_world: Ownctl) -> None:
    table_world("check", "collect", "mug")
    out = table_world.json("say", "No, that's mine!", "--as", "xuan")
    assert out["instructions"] == ["skip mug", "claim mug xuan", "forbid collect on mug",
                                   "forbid collect if ownedBy xuan"]


def test_a_question_is_answered_from_what_the_utterance_just_taught(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "if", "ownedBy", "xuan")
    out = table_world.json("say", "This is mine. Can you throw it away?", "--as", "xuan", "--about", "mug",
                           code=3)
    assert out["instructions"] == ["claim mug xuan", "check trash mug"]
    assert out["forbidden"] is True
    assert "Sorry, I may not throw away mug" in out["reply"]
    assert out["results"][1]["data"]["decision"] == "forbidden"


def test_can_you_answers_like_check(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "if", "ownedBy", "alexis")
    refused = table_world("say", "Can you throw this away?", "--as", "xuan", "--about", "wallet", code=3)
    assert "robot: Let me check whether I may throw away wallet. Sorry, I may not" in refused.stdout
    assert "Yes, I may throw away mug" in table_world("say", "Can you throw the mug away?").stdout


def test_why_not_explains_the_last_refusal(table_world: Ownctl) -> None:
    assert "nothing was refused" in table_world("say", "Why not?", "--as", "xuan", code=1).stderr
    table_world("forbid", "trash", "on", "wallet", "--as", "alexis")
    table_world("check", "trash", "wallet", code=3)
    table_world("check", "pickUp", "mug")  # permitted: the refusal stays the wallet's
    out = table_world.json("say", "Why not?", "--as", "xuan")
    assert out["instructions"] == ["explain"]
    assert "trash is forbidden on wallet: permission 1 'forbid trash on wallet' from alexis" in out["reply"]


def test_why_cant_you_names_its_action_and_object(table_world: Ownctl) -> None:
    table_world("forbid", "pickUp", "if", "isColored", "red")
    out = table_world.json("say", "Why can't you pick up the mug?", "--as", "xuan")
    assert out["instructions"] == ["explain pickUp mug"]
    assert "rule 1 'forbid pickUp if isColored red' holds with p=1" in out["reply"]


def test_an_introduction_adds_the_agent_and_makes_it_the_speaker(table_world: Ownctl) -> None:
    out = table_world.json("say", "Hi, I'm Jake. This is mine.", "--as", "xuan", "--about", "pen")
    assert out["instructions"] == ["agent add jake", "claim pen jake"]
    assert out["speaker"] == "jake"
    assert "jake" in [a["name"] for a in table_world.json("agent", "list")]
    assert table_world.json("say", "That's mine too", "--about", "mug")["instructions"] == ["claim mug jake"]
    again = table_world.json("say", "I'm Jake")  # known: just the speaker
    assert again["results"][0]["data"]["added"] is False


def test_an_exclusive_claim_takes_the_object_from_everyone_else(table_world: Ownctl) -> None:
    out = table_world.json("say", "It's mine now, not Alexis's", "--as", "xuan", "--about", "wallet")
    assert out["instructions"] == ["claim wallet xuan --only", "claim wallet alexis --not"]
    owners = {o["agent"]: o["p"] for o in table_world.json("owners", "wallet")["owners"]}
    assert owners == {"xuan": 1.0, "alexis": 0.0}


def test_skip_is_recorded(table_world: Ownctl) -> None:
    table_world("check", "trash", "mug")
    out = table_world.json("say", "Stop!", "--as", "xuan")
    assert out["instructions"] == ["skip mug", "forbid trash on mug"]
    assert out["results"][0]["message"].startswith("noted: stop")
    assert any(e["payload"].get("op") == "skip" for e in table_world.json("log"))


def test_a_task_runs_after_the_utterance_is_stored(table_world: Ownctl) -> None:
    table_world("area", "add", "trash", "--box", "-0.3,0.6,0.2,1.1")
    table_world("forbid", "trash", "if", "ownedBy", "alexis")
    table_world("claim", "pen", "alexis", "--not")
    out = table_world.json("say", "Clear the table", "--as", "xuan")
    assert out["instructions"] == ["run trashAll"]
    run = out["results"][0]["data"]
    assert set(run["delivered"]) == {"mug", "pen"}  # the wallet is Alexis's
    positions = {o["name"]: o["position"] for o in table_world.json("object", "list")}
    assert positions["wallet"] == [0.1, 0.1, 0.0]
    assert -0.3 <= positions["mug"][0] <= 0.2 and 0.6 <= positions["mug"][1] <= 1.1



def test_what_may_you_do_with_it_checks_each_object_action(table_world: Ownctl) -> None:
    table_world("forbid", "pickUp", "if", "isColored", "red")
    out = table_world.json("say", "What are you not allowed to do with the mug?", "--as", "xuan")
    assert out["instructions"] == ["actions mug"]
    assert out["forbidden"] is False  # a list of answers, not a refusal
    checks = {c["action"]: c["decision"] for c in out["results"][0]["data"]["checks"]}
    assert checks == {"trash": "forbidden", "pickUp": "forbidden", "putDown": "permitted",
                      "collect": "forbidden"}
    assert out["reply"].startswith("With mug, I may: put down. I may not: throw away (")
    after = table_world.json("say", "What can you do with the wallet?", "--as", "xuan")
    assert after["reply"] == "With wallet, I may: throw away, pick up, put down, collect."


def test_what_does_someone_own_lists_their_likely_things(table_world: Ownctl) -> None:
    out = table_world.json("say", "What does Alexis own?", "--as", "xuan")
    assert out["instructions"] == ["owners --agent alexis"]
    assert out["reply"].startswith("alexis probably owns wallet (p=1)")
    assert "nothing xuan owns" in table_world.json("say", "What's mine?", "--as", "xuan")["reply"]


def test_objects_are_picked_by_their_percepts(table_world: Ownctl) -> None:
    out = table_world.json("say", "Everything on the desk is mine.", "--as", "xuan")
    assert out["instructions"] == ["claim wallet xuan"]  # the only object inside the desk's box
    red = table_world.json("say", "The red mug's mine.", "--as", "xuan")
    assert red["instructions"] == ["claim mug xuan"]
    wrong = table_world("say", "The blue mug is mine.", "--as", "xuan", code=1)
    assert "mug is red, not blue" in wrong.stderr


def test_a_typo_is_read_and_said(table_world: Ownctl) -> None:
    out = table_world.json("say", "The wallett is Alexis's.", "--as", "xuan")
    assert out["instructions"] == ["claim wallet alexis"]
    assert "(read 'wallett' as 'wallet')" in out["reply"]


def test_an_overlong_utterance_is_refused_at_once(table_world: Ownctl) -> None:
    refused = table_world("say", "The mug is mine. " * 300, "--as", "xuan", code=1)
    assert "characters long; I understand at most 4000" in refused.stderr
    assert "Traceback" not in refused.stderr


def test_whose_says_someone_owns_it_when_no_one_agent_is_likely_but_their_union_is(
        table_world: Ownctl) -> None:
    for agent in ("alexis", "xuan"):
        table_world("claim", "mug", agent, "--p", "0.4")
        table_world("claim", "pen", agent, "--p", "0.2")
    mug = table_world.json("say", "Whose is the mug?")["reply"]
    assert "probably someone does (p=0.64)" in mug and "nobody" not in mug  # 1 - 0.6 * 0.6
    pen = table_world.json("say", "Whose is the pen?")["reply"]
    assert "I think nobody owns pen (p=0.64)" in pen  # 0.8 * 0.8


def test_a_norm_said_in_the_rule_language_is_that_norm(table_world: Ownctl) -> None:
    out = table_world.json("say", "Allow trash if isColored red and not ownedBy xuan.")
    assert out["intent"] == "norm"
    assert out["instructions"] == ["allow trash if not ownedBy xuan and isColored red"]  # canonical
    said = table_world.json("say", "forbid pickUp if ownedBy any and inArea desk")
    assert said["instructions"] == ["forbid pickUp if ownedBy any and inArea desk"]
    assert "forbid pickUp if ownedBy any and inArea desk" in _rules(table_world)
    before = table_world.digest()
    error = table_world("say", "forbid trash if ownedBy ghost", code=1).stderr
    assert "unknown agent 'ghost'" in error and error.count("\n") == 1
    assert table_world.digest() == before


def test_a_norm_the_permissions_narrow_is_acknowledged_as_narrowed(table_world: Ownctl) -> None:
    """Trash was allowed on the wallet (brown, on the desk) and the pen (no colour, nowhere): "don't
    throw away the red things" is taken as said, "never throw anything away" only as what those
    permissions leave of it, and the reply says so."""
    table_world("allow", "trash", "on", "wallet")
    table_world("allow", "trash", "on", "pen")
    table_world("forbid", "trash", "if", "isColored", "red", "and", "inArea", "desk")  # a narrower one
    kept = table_world.json("say", "Don't throw away the red things")
    assert kept["results"][0]["data"]["taken_as"] == ["forbid trash if isColored red"]
    assert not kept["results"][0]["data"]["specialised"] and "take it as" not in kept["reply"]
    out = table_world.json("say", "Never throw anything away")
    data = out["results"][0]["data"]
    assert data["specialised"] and data["taken_as"] and "forbid trash" not in data["taken_as"]
    assert out["reply"].startswith("Understood: I will not throw away anything.")
    assert "Some of my permissions say otherwise, so I take it as: I will not throw away anything " in (
        out["reply"])
    assert {r["text"] for r in table_world.json("rules", "list")} >= set(data["taken_as"])
