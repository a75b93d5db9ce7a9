"""The paper's worked examples, typed at the command line against a temporary store (OWNCTL_NOW pinned).

* "Representing ownership": the wallet owned by Alexis with p=0.75 makes ``forbid trash if ownedBy
  any`` evaluate to 0.75;
* "Learning ownership": "Don't, that's Casey's!" is a claim, a permission and a norm;
* "Video demonstration", third scenario: permissions on three owned blocks and one unowned block
  induce ``forbid pickUp if ownedBy any``;
* "Inferring ownership relations": being told trashing is forbidden on an object of uncertain
  ownership raises its ownership.

The learner is ``Settings.learn.learner``, which has no ``config`` key, so the CLI runs the default
learner ("ours"); tests/learn/test_learn_induce.py runs the same stories with both learners.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.cli.conftest import Ownctl, build_template, from_template


@pytest.fixture(scope="module")
def _fresh(tmp_path_factory: pytest.TempPathFactory) -> bytes:
    return build_template(tmp_path_factory, [])


@pytest.fixture
def run(tmp_path: Path, _fresh: bytes) -> Ownctl:
    """An initialised, empty store, driven through the CLI."""
    return from_template(tmp_path / "store.db", _fresh)


def batch(run: Ownctl, text: str) -> None:
    """Several instructions in one process (``ownctl batch -``)."""
    run("batch", "-", "--quiet", input=text)


def rule_texts(run: Ownctl, action: str | None = None) -> list[str]:
    return sorted(r["text"] for r in run.json("rules", "list") if action in (None, r["action"]))


# -- the wallet ------------------------------------------------------------------------------------
def test_wallet_owned_by_alexis_with_p_0_75_is_forbidden_with_0_75(run: Ownctl) -> None:
    batch(run, "agent add alexis\nobject add wallet --color brown --pos 0.3,0.1,0\n")
    run("claim", "wallet", "alexis", "--p", "0.75")
    run("forbid", "trash", "if", "ownedBy", "any")
    report = run.json("check", "trash", "wallet", code=3)  # 0.75 >= threshold 0.5: forbidden, exit 3
    (trash,) = [s for s in report["steps"] if s["action"] == "trash"]
    assert [r["text"] for r in trash["rules"]] == ["forbid trash if ownedBy any"]
    assert trash["rules"][0]["p"] == pytest.approx(0.75, abs=1e-12)
    assert report["p_forbidden"] == pytest.approx(0.75, abs=1e-12) and report["decision"] == "forbidden"
    assert report["atoms"] == [{"agent": "alexis", "p": 0.75, "source": "claim"}]
    # "... will go ahead otherwise": above a stricter obedience threshold the robot may trash it
    run("config", "set", "threshold", "0.8")
    assert run.json("check", "trash", "wallet")["decision"] == "permitted"


def test_wallet_with_a_second_tracked_agent_and_prediction_disabled(run: Ownctl) -> None:
    """The paper's figure assumes Alexis is the only agent tracked. With Xuan tracked too, a claim
    about Xuan elsewhere makes the predictor give Xuan a prior on the wallet, which ``ownedBy any``
    rightly adds (a noisy-or); with prediction disabled an agent without claims keeps the calibrated
    base rate (never an empty prior), so the figure is 1 - 0.25 * 0.75."""
    batch(run, "agent add alexis\nagent add xuan\nobject add wallet --color brown --pos 0.3,0.1,0\n"
               "object add mug --color red --pos 0.31,0.1,0\n")
    run("claim", "mug", "xuan")
    run("claim", "wallet", "alexis", "--p", "0.75")
    run("forbid", "trash", "if", "ownedBy", "any")
    predicted = run.json("check", "trash", "wallet", code=3)
    xuan = {a["agent"]: a for a in predicted["atoms"]}["xuan"]
    assert xuan["source"] == "prediction" and 0 < xuan["p"] < 1
    assert predicted["p_forbidden"] == pytest.approx(1 - 0.25 * (1 - xuan["p"]), abs=1e-12)

    run("disable", "prediction")
    run("reset", "claims", "--yes")  # claims and what was predicted from them go; priors: the base rate
    run("claim", "mug", "xuan")
    run("claim", "wallet", "alexis", "--p", "0.75")
    report = run.json("check", "trash", "wallet", code=3)
    assert report["p_forbidden"] == pytest.approx(1 - 0.25 * 0.75, abs=1e-12)
    assert {a["agent"]: a["source"] for a in report["atoms"]} == {"alexis": "claim", "xuan": "base-rate"}


# -- "Don't, that's Casey's!" ----------------------------------------------------------------------
CASEY_WORLD = """\
agent add casey
agent add alexis
object add mug --color red --pos 0.5,0.5,0
object add cup --color white --pos 0.55,0.5,0
object add spoon --color blue --pos -0.5,-0.5,0
claim cup casey
claim spoon casey --not
claim spoon alexis --not
"""


def dont_thats_caseys(run: Ownctl) -> None:
    """The three pieces of information, as three instructions."""
    run("claim", "mug", "casey")
    run("forbid", "trash", "on", "mug")
    run("forbid", "trash", "if", "ownedBy", "casey")


def test_dont_thats_caseys_stores_claim_permission_and_refuses_caseys_things(run: Ownctl) -> None:
    batch(run, CASEY_WORLD)
    dont_thats_caseys(run)
    assert [(c["object"], c["agent"], c["p"]) for c in run.json("claims", "list")
            if c["object"] == "mug"] == [("mug", "casey", 1.0)]
    perms = [(p["action"], p["object"], p["value"]) for p in run.json("perms", "list")]
    assert perms == [("trash", "mug", 1.0)]
    assert run.json("check", "trash", "mug", code=3)["decided_by"] == "permission"
    other = run.json("check", "trash", "cup", code=3)  # another object claimed by Casey
    assert other["decided_by"] == "rules"
    ops = [e["payload"]["op"] for e in run.json("log")][-3:]
    assert ops == ["claim", "permission", "norm"]


def test_dont_thats_caseys_teaches_the_owner_norm(run: Ownctl) -> None:
    batch(run, CASEY_WORLD)
    dont_thats_caseys(run)
    assert "forbid trash if ownedBy casey" in rule_texts(run, "trash")
    run("check", "trash", "cup", code=3)
    run("check", "trash", "spoon", code=0)


def test_dont_thats_caseys_after_an_allowed_unowned_example(run: Ownctl) -> None:
    """With one earlier 'allow trash on' an unowned object, the same three instructions teach the norm."""
    batch(run, CASEY_WORLD + "object add fork --color green --pos -0.4,-0.5,0\n"
               "claim fork casey --not\nclaim fork alexis --not\nallow trash on fork\n")
    dont_thats_caseys(run)
    assert "forbid trash if ownedBy casey" in rule_texts(run, "trash")
    run("check", "trash", "cup", code=3)
    run("check", "trash", "spoon", code=0)


# -- the third video scenario ----------------------------------------------------------------------
VIDEO_WORLD = """\
agent add agent1
agent add agent2
agent add agent3
object add block1 --color red --pos 0.5,0.1,0
object add block2 --color blue --pos 0.1,0.5,0
object add block3 --color green --pos -0.5,0.1,0
object add block4 --color red --pos 0,0,0
object add block5 --color grey --pos 0.1,-0.5,0
object add block6 --color blue --pos 0.05,0.05,0
claim block1 agent1 --only
claim block2 agent2 --only
claim block3 agent3 --only
claim block5 agent2 --only
claim block4 agent1 --not
claim block4 agent2 --not
claim block4 agent3 --not
claim block6 agent1 --not
claim block6 agent2 --not
claim block6 agent3 --not
"""


@pytest.mark.parametrize("order", [("block1", "block4", "block2", "block3"),
                                   ("block1", "block2", "block3", "block4")])
def test_video_permissions_induce_forbid_pickup_if_owned(run: Ownctl, order: tuple[str, ...]) -> None:
    batch(run, VIDEO_WORLD)
    for name in order:
        run("allow" if name == "block4" else "forbid", "pickUp", "on", name)
    rules = [r for r in run.json("rules", "list") if r["action"] == "pickUp"]
    assert [(r["text"], r["origin"]) for r in rules] == [("forbid pickUp if ownedBy any", "learned")]
    assert rules[0]["accuracy"] == 1.0
    report = run.json("check", "pickUp", "block5", code=3)  # a fourth owned block
    assert report["decided_by"] == "rules" and report["p_forbidden"] == 1.0
    assert run.json("check", "pickUp", "block6")["decision"] == "permitted"  # another unowned block


# -- rule-based inference --------------------------------------------------------------------------
INFERENCE_WORLD = """\
agent add alexis
agent add xuan
object add box --color green --pos 0.3,0.3,0
""" + "".join(f"object add o{i} --color red --pos {0.1 * i:.1f},0,0\n" for i in range(8)) + "".join(
    f"claim o{i} {'alexis' if i % 4 == 0 else 'xuan'} --only\n" if i % 2 == 0
    else f"claim o{i} alexis --not\nclaim o{i} xuan --not\n" for i in range(8))


def owners(run: Ownctl, obj: str) -> dict[str, dict]:
    return {o["agent"]: o for o in run.json("owners", obj)["owners"]}


def test_being_told_trash_is_forbidden_raises_ownership(run: Ownctl) -> None:
    """With accurate rules (the gate holds), the permission is explained by ownership, not by a new rule."""
    batch(run, INFERENCE_WORLD + "forbid trash if ownedBy any\n" + "".join(
        f"{'forbid' if i % 2 == 0 else 'allow'} trash on o{i}\n" for i in range(8)))
    before = owners(run, "box")
    assert all(o["claim"] is None and 0 < o["prior"] < 1 for o in before.values())
    done = run.json("forbid", "trash", "on", "box")
    assert done["induced"] is False and done["accuracy"] >= 0.9
    after = owners(run, "box")
    for agent, o in after.items():
        assert o["posterior"] > o["prior"] == before[agent]["prior"], (agent, o)
        assert o["source"] == "inference" and o["p"] == o["posterior"]
    assert rule_texts(run, "trash") == ["forbid trash if ownedBy any"]


def test_being_told_trash_is_forbidden_raises_ownership_with_rules_frozen(run: Ownctl) -> None:
    batch(run, INFERENCE_WORLD + "forbid trash if ownedBy any\nfreeze rules\n")
    run("forbid", "trash", "on", "box")
    for o in owners(run, "box").values():
        assert o["posterior"] > o["prior"]


def test_being_told_trash_is_forbidden_raises_ownership_on_a_fresh_store(run: Ownctl) -> None:
    batch(run, INFERENCE_WORLD + "forbid trash if ownedBy any\n")
    run("forbid", "trash", "on", "box")
    assert rule_texts(run, "trash") == ["forbid trash if ownedBy any"]
    for o in owners(run, "box").values():
        assert o["posterior"] > o["prior"]
