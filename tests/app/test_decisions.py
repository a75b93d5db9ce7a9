"""Application use cases: which belief decides, how check combines steps, claims and trust."""

from __future__ import annotations

from pathlib import Path

import pytest

from ownctl.app import decide, instruct, query, things
from ownctl.app.beliefs import decision_belief, induction_belief
from ownctl.app.context import AppContext
from ownctl.errors import BadValue, OwnctlError


@pytest.fixture
def ctx(tmp_path: Path) -> AppContext:
    ctx = AppContext(str(tmp_path / "a.db"), now=100.0)
    ctx.store(create=True)
    for name in ("alexis", "xuan"):
        things.add_agent(ctx, name)
    things.add_object(ctx, "wallet", color="brown")
    things.add_object(ctx, "mug", color="red")
    yield ctx
    ctx.close()


def _set(ctx: AppContext, obj: str, agent: str, **columns: object) -> None:
    with ctx.write({"op": "test"}) as tx:
        row = {"object_id": tx.things.object(obj).id, "agent_id": tx.world.agent(agent).id, **columns}
        tx.beliefs.write_beliefs([row])


def test_belief_precedence(ctx: AppContext) -> None:
    _set(ctx, "wallet", "alexis", prior_p=0.3, prior_source="prediction")
    assert query.owners(ctx, "wallet")["owners"][0] == {
        "agent": "alexis",
        "p": 0.3,
        "source": "prediction",
        "claim": None,
        "prior": 0.3,
        "posterior": None,
    }
    instruct.add_claim(ctx, "wallet", "alexis", 0.8)
    _set(ctx, "wallet", "alexis", posterior_p=0.9, posterior_source="inference")
    with ctx.read() as tx:
        (row,) = [b for b in tx.beliefs.ownership() if b.claim_p is not None]
        assert decision_belief(row) == (0.9, "inference")
        assert induction_belief(row) == (0.8, "claim")
    # decisions use the Mind's posterior, computed from the permissions on the object: with none,
    # the claim decides, whatever a stale posterior column says
    atoms = decide.check(ctx, "trash", "wallet").data["atoms"]
    assert atoms[0] == {"agent": "alexis", "p": 0.8, "source": "claim"}


def test_rules_sharing_atoms_are_exact(ctx: AppContext) -> None:
    instruct.add_claim(ctx, "mug", "alexis", 0.5)
    instruct.add_claim(ctx, "mug", "xuan", 0.5)
    instruct.add_norm(ctx, "forbid trash if ownedBy alexis")
    instruct.add_norm(ctx, "forbid trash if ownedBy xuan and isColored red")
    report = decide.check(ctx, "trash", "mug")
    assert report.data["p_forbidden"] == pytest.approx(0.75)
    assert report.forbidden and report.data["decided_by"] == "rules"
    assert [r["p"] for r in report.data["steps"][-1]["rules"]] == pytest.approx([0.5, 0.5])


def test_soft_permission_decides_its_step(ctx: AppContext) -> None:
    instruct.add_norm(ctx, "forbid trash")  # an empty condition forbids always
    assert decide.check(ctx, "trash", "mug").forbidden
    instruct.add_permission(ctx, "trash", "mug", 0.4)
    report = decide.check(ctx, "trash", "mug")
    assert not report.forbidden and report.data["decided_by"] == "permission"
    assert report.data["steps"][-1]["p_rules"] == 1.0 and report.data["p_forbidden"] == 0.4


def test_exclusive_claim_and_trust(ctx: AppContext) -> None:
    instruct.add_claim(ctx, "wallet", "xuan", 1.0)
    with ctx.write({"op": "test"}) as tx:
        tx.meta.set_setting("trust", 0.5)
    done = instruct.add_claim(ctx, "wallet", "alexis", 1.0, exclusive=True)
    assert done.data["p"] == 0.5
    owners = {o["agent"]: o["p"] for o in query.owners(ctx, "wallet")["owners"]}
    assert owners == {"alexis": 0.5, "xuan": 0.0}
    assert instruct.add_claim(ctx, "mug", "xuan", 0.6, negated=True).data["p"] == pytest.approx(0.7)


def test_instructions_are_logged_in_their_transaction(ctx: AppContext) -> None:
    ctx.command, ctx.interface = "claim wallet ghost", "say"
    before = len(query.events(ctx))
    with pytest.raises(OwnctlError):
        instruct.add_claim(ctx, "wallet", "ghost")
    assert len(query.events(ctx)) == before
    instruct.add_claim(ctx, "wallet", "xuan", speaker="xuan")
    last = query.events(ctx)[-1]
    assert (last["actor"], last["interface"], last["payload"]["op"]) == ("xuan", "say", "claim")


@pytest.mark.parametrize("p", [float("nan"), -0.01, 1.01, float("inf")])
def test_probabilities_are_checked(ctx: AppContext, p: float) -> None:
    with pytest.raises(BadValue):
        instruct.add_claim(ctx, "wallet", "xuan", p)
    with pytest.raises(BadValue):
        instruct.add_permission(ctx, "trash", "wallet", p)
