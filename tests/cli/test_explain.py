"""``ownctl explain ACTION OBJ``: the deciding permission or rules, and where each belief comes from."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ownctl.humanize import iso

if TYPE_CHECKING:
    from tests.cli.conftest import Ownctl

T1000, T900 = iso(1000), iso(900)  # the store times the tests pin, as explanations print them


def test_a_rule_decision_names_the_rule_and_the_atom_with_its_claim(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "if", "ownedBy", "alexis", "--as", "xuan")
    text = table_world("explain", "trash", "wallet").stdout
    assert text.startswith("trash is forbidden on wallet: rule 1 'forbid trash if ownedBy alexis' holds with "
                           f"p=1 (>= 0.5); it was given by xuan at {T1000}.")
    assert f"ownedBy(wallet, alexis) = 1 from a claim at {T1000} (p=1)." in text


def test_a_predicted_owner_is_explained_as_a_prediction(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "if", "ownedBy", "alexis")
    table_world("object", "set", "pen", "--pos", "0.12,0.1", "--color", "brown")  # beside the wallet
    data = table_world.json("explain", "trash", "pen")
    alexis = next(a for a in data["atoms"] if a["agent"] == "alexis")
    assert alexis["source"] == "prediction" and alexis["relevant"]
    assert alexis["because"].startswith("a prediction from percepts")
    assert f"ownedBy(pen, alexis) = {alexis['p']:.2g} from a prediction from percepts" in data["text"]


def test_inference_on_a_claim_names_the_claim_and_its_speaker(ownctl: Ownctl) -> None:
    ownctl("agent", "add", "agent1")
    ownctl("object", "add", "wallet")
    ownctl("claim", "wallet", "agent1", "--p", "0.6", "--as", "agent1", now="900")
    ownctl("forbid", "trash", "if", "ownedBy", "agent1")
    ownctl("forbid", "trash", "on", "wallet")
    data = ownctl.json("explain", "trash", "wallet")
    atom = data["atoms"][0]
    assert atom["source"] == "inference" and atom["claim"] == {"p": 0.6, "speaker": "agent1", "time": 900.0,
                                                                "time_iso": T900, "trust": 1.0}
    assert atom["because"] == ("inference (given the permissions on this object) on a claim by agent1 "
                               f"at {T900} (p=0.6)")
    assert data["decided_by"] == "permission"
    assert "permission 1 'forbid trash on wallet'" in data["text"]


def test_a_permitted_action_says_why_the_rules_do_not_apply(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "if", "ownedBy", "alexis", "and", "isColored", "brown")
    table_world("claim", "mug", "alexis", "--not")
    text = table_world("explain", "trash", "mug").stdout
    assert text.startswith("trash is permitted on mug: rule 1 'forbid trash if ownedBy alexis and isColored "
                           "brown' holds with p=0 (< 0.5) [ownedBy alexis p=0, isColored brown false (mug is "
                           "red)]")


def test_nothing_speaking_is_said_so(table_world: Ownctl) -> None:
    assert table_world("explain", "collect", "pen").stdout.strip() == (
        "collect is permitted on pen: no permission or rule speaks about collect or its steps on pen."
    )


def test_a_forbidden_prerequisite_is_named(table_world: Ownctl) -> None:
    table_world("forbid", "pickUp", "on", "mug", "--as", "xuan")
    data = table_world.json("explain", "collect", "mug")
    assert data["decision"] == "forbidden" and data["decided_by"] == "prerequisite"
    assert data["text"].startswith("collect is forbidden on mug: its prerequisite pickUp is forbidden: "
                                   f"permission 1 'forbid pickUp on mug' from xuan at {T1000} forbids pickUp")


def test_learned_rules_name_their_examples(table_world: Ownctl) -> None:
    table_world("forbid", "pickUp", "on", "mug")
    rule = next(s for s in table_world.json("explain", "pickUp", "wallet")["steps"]
                if s["action"] == "pickUp")["rules"][0]
    assert rule["text"] == "forbid pickUp" and rule["origin"] == f"learned from the examples mug at {T1000}"


def test_explain_keeps_the_conversation(table_world: Ownctl) -> None:
    table_world("forbid", "trash", "on", "wallet")
    table_world("check", "trash", "wallet", code=3)
    table_world("explain", "pickUp", "mug")
    assert "on wallet" in table_world.json("say", "Why not?", "--as", "xuan")["reply"]


def test_json_has_the_check_shape_plus_provenance(table_world: Ownctl) -> None:
    data = table_world.json("explain", "trash", "wallet")
    assert {"action", "object", "decision", "p_forbidden", "threshold", "decided_by", "steps", "atoms",
            "text", "reasons"} <= set(data)
    atom_keys = {"agent", "p", "source", "because", "claim", "prior", "posterior", "relevant"}
    assert atom_keys <= set(data["atoms"][0])


def test_unknown_names_are_errors(table_world: Ownctl) -> None:
    assert "known objects: mug, pen, wallet" in table_world("explain", "trash", "ghost", code=1).stderr
    assert "unknown action 'thrash'" in table_world("explain", "thrash", "mug", code=1).stderr


def test_without_arguments_it_explains_the_last_refusal(table_world: Ownctl) -> None:
    assert "nothing was refused yet" in table_world("explain", code=1).stderr
    table_world("forbid", "trash", "if", "ownedBy", "alexis")
    table_world("check", "trash", "wallet", code=3)  # the refusal is remembered
    assert table_world("explain").stdout == table_world("explain", "trash", "wallet").stdout
    table_world("explain", "trash", code=2)  # an action alone is a usage error
