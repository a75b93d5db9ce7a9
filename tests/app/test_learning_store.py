"""Learning wired into the store (``ownctl.app.learning``): what each instruction writes and reads.

* a claim refits that agent's predictor and writes its prior for every object with a constant number
  of bulk statements; claims override predictions; inference never feeds prediction;
* a permission runs the gate and induction on *prior* ownership and stores learned rules with their
  provenance; posteriors follow; ``owners`` shows claim, prior and posterior;
* ``disable inference``, ``disable prediction``, ``freeze rules`` and ``freeze perms`` do what they say;
* every instruction is in the event log;
* the store computes exactly what the in-memory :class:`~ownctl.mind.Mind` computes from
  the same instructions.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from sqlalchemy import event

from ownctl.app import admin, decide, instruct, query, things
from ownctl.app.beliefs import decision_belief, induction_belief
from ownctl.app.context import AppContext
from ownctl.app.mindstore import LENT, load
from ownctl.app.worldfile import store_world
from ownctl.config import PredictConfig
from ownctl.errors import OwnctlError
from ownctl.experiment.truth import true_rules
from ownctl.learn import induce
from ownctl.logic.prob import p_forbidden
from ownctl.mind import Mind
from ownctl.world.generator import paper_blocks_world
from ownctl.world.model import make_frame

NOW = 1000.0


@pytest.fixture
def ctx(tmp_path: Path) -> Iterator[AppContext]:
    ctx = AppContext(str(tmp_path / "s.db"), now=NOW)
    ctx.store(create=True)
    yield ctx
    ctx.close()


def small_world(ctx: AppContext, n: int = 6, agents: tuple[str, ...] = ("alexis", "xuan")) -> list[str]:
    for a in agents:
        things.add_agent(ctx, a)
    names = [f"o{i}" for i in range(n)]
    for i, name in enumerate(names):
        colour = ("red", "blue", "green")[i % 3]
        things.add_object(ctx, name, color=colour, pos=f"{0.1 * i:.2f},{0.05 * i:.2f},0")
    return names


def beliefs(ctx: AppContext) -> dict[tuple[str, str], dict[str, Any]]:
    """(object, agent) -> every belief column."""
    out = {}
    for obj in [o["name"] for o in things.list_objects(ctx)]:
        for o in query.owners(ctx, obj)["owners"]:
            out[(obj, o["agent"])] = o
    with ctx.read() as tx:
        names = {o.id: o.name for o in tx.things.objects()}
        agents = {a.id: a.name for a in tx.world.agents()}
        for b in tx.beliefs.ownership():
            key = (names[b.object_id], agents[b.agent_id])
            out[key].update(prior_source=b.prior_source, prior_time=b.prior_time,
                            posterior_source=b.posterior_source)
    return out


# -- claims and prediction -------------------------------------------------------------------------
def test_a_first_claim_about_an_object_writes_every_agents_priors(ctx: AppContext) -> None:
    names = small_world(ctx, 8)
    ctx.now = NOW + 5
    instruct.add_claim(ctx, "o0", "alexis")
    got = beliefs(ctx)
    for name in names:
        alexis, xuan = got[(name, "alexis")], got[(name, "xuan")]
        assert alexis["prior"] is not None and 0 < alexis["prior"] < 1
        assert alexis["prior_source"] in ("prediction", "base-rate") and alexis["prior_time"] == NOW + 5
        # xuan said nothing of o0, which alexis claimed: what that silence says is learned too
        assert xuan["prior_source"] == "prediction" and xuan["prior_time"] == NOW + 5
    assert got[("o0", "alexis")]["p"] == 1.0 and got[("o0", "alexis")]["source"] == "claim"
    near, far = got[("o1", "alexis")]["prior"], got[("o7", "alexis")]["prior"]
    assert near > far  # o1 is next to the claimed o0
    assert got[("o0", "xuan")]["prior"] < got[("o1", "xuan")]["prior"] < 0.25  # lowest where silent
    instruct.add_claim(ctx, "o0", "xuan", negated=True)  # said outright: xuan's claim
    assert beliefs(ctx)[("o0", "xuan")]["source"] == "claim"


def count_writes(ctx: AppContext) -> list[tuple[str, int]]:
    """Record (table, rows) of each cursor execution that writes ownership or priors."""
    calls: list[tuple[str, int]] = []

    def listen(conn: Any, cursor: Any, statement: str, parameters: Any, context: Any, many: bool) -> None:
        words = statement.split()
        verb = words[0].upper() if words else ""
        table = words[2].lower() if verb in ("INSERT", "DELETE") and len(words) > 2 else (
            words[1].lower() if verb == "UPDATE" and len(words) > 1 else "")
        if table in ("ownership", "priors"):
            calls.append((table, len(parameters) if many else 1))

    event.listen(ctx.store().engine, "before_cursor_execute", listen)
    return calls


@pytest.mark.parametrize("n", [5, 60])
def test_priors_are_written_in_bulk(ctx: AppContext, n: int) -> None:
    small_world(ctx, n)
    instruct.add_claim(ctx, "o0", "alexis")
    calls = count_writes(ctx)
    instruct.add_claim(ctx, "o0", "alexis", p=0.95)  # what silence weighs does not move
    # the claim in one upsert; the agent's priors of every object rewritten as one packed chunk
    assert len(calls) <= 4, calls
    assert sum(k for t, k in calls if t == "ownership") == 1, calls
    assert [k for t, k in calls if t == "priors"] == [1, 1], calls  # the old chunk out, the new one in


def test_an_agent_no_claim_says_owns_anything_borrows_recency_and_then_stops(ctx: AppContext) -> None:
    """docs/architecture.md, section 5: xuan's predictor follows alexis' claims while no claim says
    xuan owns something; once one does, a claim about alexis rewrites alexis' priors alone."""
    small_world(ctx, 8)
    for i, agent in ((0, "alexis"), (1, "xuan"), (4, "alexis"), (5, "xuan")):
        things.touch(ctx, f"o{i}", agent, at=NOW - 1)
    ctx.now = NOW + 5
    instruct.add_claim(ctx, "o0", "alexis")
    instruct.add_claim(ctx, "o1", "alexis", negated=True)
    got = beliefs(ctx)
    assert got[("o5", "xuan")]["prior_source"] == "prediction"  # borrowed: xuan touched o5 recently
    assert got[("o5", "xuan")]["prior"] > got[("o6", "xuan")]["prior"]
    instruct.add_claim(ctx, "o1", "xuan")
    calls = count_writes(ctx)
    instruct.add_claim(ctx, "o0", "alexis", p=0.9)  # an object both were told about: no new silence
    assert [k for t, k in calls if t == "priors"] == [1, 1], calls  # alexis' chunk alone


def test_the_slope_the_borrowers_use_is_kept_in_the_store(ctx: AppContext) -> None:
    """docs/architecture.md, section 5: the store holds the rounded slope the borrowers' priors use,
    a Mind loaded from it uses that slope, and once nobody borrows it is gone."""
    small_world(ctx, 8)
    for i, agent in ((0, "alexis"), (1, "xuan"), (4, "alexis"), (5, "xuan")):
        things.touch(ctx, f"o{i}", agent, at=NOW - 1)
    ctx.now = NOW + 5
    instruct.add_claim(ctx, "o0", "alexis")
    with ctx.read() as tx:
        lent = tx.meta.settings().get(LENT)
        loaded = load(tx, ctx.now).mind
    step = PredictConfig().share_step
    assert lent is not None and lent < 0 and lent / step == round(lent / step)
    assert loaded.lent == lent
    instruct.add_claim(ctx, "o1", "xuan")  # xuan owns something claimed: nobody borrows
    with ctx.read() as tx:
        assert LENT not in tx.meta.settings()


def test_exclusive_claim_repredicts_every_agent_it_touches(ctx: AppContext) -> None:
    small_world(ctx, 6)
    instruct.add_claim(ctx, "o0", "alexis", exclusive=True)
    got = beliefs(ctx)
    assert got[("o0", "xuan")]["claim"] == 0.0
    assert all(got[(f"o{i}", "xuan")]["prior"] is not None for i in range(6))
    assert got[("o1", "xuan")]["prior"] < 0.5 < got[("o1", "alexis")]["prior"]


def test_disable_prediction_leaves_priors_alone(ctx: AppContext) -> None:
    small_world(ctx, 4)
    before = beliefs(ctx)
    admin.set_flag(ctx, "disabled.prediction", True)
    instruct.add_claim(ctx, "o0", "alexis")
    got = beliefs(ctx)
    assert all(got[(f"o{i}", "alexis")]["prior"] == before[(f"o{i}", "alexis")]["prior"] for i in range(4))
    assert got[("o0", "alexis")]["p"] == 1.0


def test_inference_never_feeds_prediction(tmp_path: Path) -> None:
    """Two stores with the same claims, one also with rules and permissions: identical priors."""
    priors = []
    for k, with_rules in enumerate((False, True)):
        ctx = AppContext(str(tmp_path / f"s{k}.db"), now=NOW)
        ctx.store(create=True)
        small_world(ctx, 6)
        if with_rules:
            instruct.add_norm(ctx, "forbid trash if ownedBy any")
            admin.set_flag(ctx, "frozen.rules", True)
            for i in (1, 2, 3):
                instruct.add_permission(ctx, "trash", f"o{i}", 1.0)
        instruct.add_claim(ctx, "o0", "alexis")
        instruct.add_claim(ctx, "o5", "alexis", negated=True)
        got = beliefs(ctx)
        priors.append({key: v["prior"] for key, v in got.items()})
        if with_rules:
            assert got[("o1", "alexis")]["posterior"] > got[("o1", "alexis")]["prior"]
        ctx.close()
    assert priors[0] == priors[1]


# -- permissions, induction, inference -------------------------------------------------------------
def test_a_permission_runs_induction_and_stores_learned_rules_with_provenance(ctx: AppContext) -> None:
    small_world(ctx, 6)
    for i in range(6):
        instruct.add_claim(ctx, f"o{i}", "alexis", negated=i % 2 == 1)
    ctx.now = NOW + 10
    done = instruct.add_permission(ctx, "trash", "o0", 1.0)
    assert done.data["induced"] is True and done.data["rules"]
    ctx.now = NOW + 20
    instruct.add_permission(ctx, "trash", "o1", 0.0)
    instruct.add_permission(ctx, "trash", "o2", 1.0)
    rules = [r for r in query.list_rules(ctx) if r["action"] == "trash"]
    # xuan, never claimed, keeps the base rate: 'ownedBy alexis' explains the examples better than 'any'
    assert [(r["text"], r["origin"]) for r in rules] == [("forbid trash if ownedBy alexis", "learned")]
    prov = rules[0]["provenance"]
    assert set(prov["examples"]) <= {"o0", "o2"} and "o0" in prov["examples"]
    assert prov["learned_at"] >= NOW + 10
    assert rules[0]["accuracy"] == 1.0


def test_induction_sees_priors_and_decisions_see_posteriors(
    ctx: AppContext, monkeypatch: pytest.MonkeyPatch
) -> None:
    small_world(ctx, 6)
    instruct.add_claim(ctx, "o0", "alexis")
    instruct.add_claim(ctx, "o1", "alexis", p=0.4)
    instruct.add_norm(ctx, "forbid trash if ownedBy any")
    admin.set_flag(ctx, "frozen.rules", True)
    instruct.add_permission(ctx, "trash", "o2", 1.0)  # o2: predicted prior only; the posterior rises
    admin.set_flag(ctx, "frozen.rules", False)
    with ctx.read() as tx:
        prior = stored_beliefs(tx, induction_belief, ["o2", "o1"])[0]
        post = stored_beliefs(tx, decision_belief, ["o2", "o1"])[0]
    assert post[0, 0] > prior[0, 0] and prior[1, 0] == 0.4
    owners = {o["agent"]: o for o in query.owners(ctx, "o2")["owners"]}
    assert owners["alexis"]["claim"] is None and owners["alexis"]["prior"] == prior[0, 0]
    assert owners["alexis"]["posterior"] == owners["alexis"]["p"] == post[0, 0]
    atoms = {a["agent"]: a for a in decide.check(ctx, "trash", "o2").data["atoms"]}
    assert atoms["alexis"] == {"agent": "alexis", "p": post[0, 0], "source": "inference"}

    seen: list[np.ndarray] = []
    real = induce.learn_permission  # the Mind imports the learner when it first learns

    def spy(action: str, rules: Any, allows: Any, ev: Any, *rest: Any) -> Any:
        seen.append(ev.frame.own.copy())
        return real(action, rules, allows, ev, *rest)

    monkeypatch.setattr(induce, "learn_permission", spy)
    instruct.add_permission(ctx, "trash", "o1", 1.0)
    assert len(seen) == 1 and np.array_equal(seen[0], prior)  # examples in permission order: o2, o1


def test_objects_without_permissions_have_no_posterior(ctx: AppContext) -> None:
    small_world(ctx, 4)
    instruct.add_claim(ctx, "o0", "alexis", p=0.6)
    instruct.add_norm(ctx, "forbid trash if ownedBy any")
    admin.set_flag(ctx, "frozen.rules", True)
    instruct.add_permission(ctx, "trash", "o0", 1.0)
    got = beliefs(ctx)
    assert got[("o0", "alexis")]["posterior"] is not None
    assert all(got[(f"o{i}", a)]["posterior"] is None for i in (1, 2, 3) for a in ("alexis", "xuan"))
    query.remove_permission(ctx, query.list_permissions(ctx)[0]["id"])
    instruct.add_claim(ctx, "o3", "xuan")  # the next instruction re-infers
    assert beliefs(ctx)[("o0", "alexis")]["posterior"] is None


# -- switches --------------------------------------------------------------------------------------
def setup_inferred(ctx: AppContext) -> None:
    small_world(ctx, 4, ("alexis",))
    instruct.add_claim(ctx, "o0", "alexis")
    instruct.add_claim(ctx, "o1", "alexis", negated=True)
    instruct.add_norm(ctx, "forbid trash if ownedBy any")
    admin.set_flag(ctx, "frozen.rules", True)
    instruct.add_permission(ctx, "trash", "o2", 1.0)
    instruct.add_permission(ctx, "trash", "o3", 0.0)


def test_disabled_inference_clears_posteriors_at_the_next_instruction(ctx: AppContext) -> None:
    setup_inferred(ctx)
    before = beliefs(ctx)
    assert before[("o2", "alexis")]["posterior"] > before[("o2", "alexis")]["prior"]
    admin.set_flag(ctx, "disabled.inference", True)
    instruct.add_claim(ctx, "o0", "alexis")
    after = beliefs(ctx)
    assert all(v["posterior"] is None for v in after.values())
    atoms = decide.check(ctx, "trash", "o2").data["atoms"]
    assert atoms == [{"agent": "alexis", "p": after[("o2", "alexis")]["prior"], "source": "prediction"}]
    admin.set_flag(ctx, "disabled.inference", False)
    instruct.add_claim(ctx, "o0", "alexis")
    assert beliefs(ctx)[("o2", "alexis")]["posterior"] == before[("o2", "alexis")]["posterior"]


def test_disable_inference_clears_posteriors_at_once(ctx: AppContext) -> None:
    setup_inferred(ctx)
    admin.set_flag(ctx, "disabled.inference", True)
    assert all(v["posterior"] is None for v in beliefs(ctx).values())
    atoms = decide.check(ctx, "trash", "o2").data["atoms"]
    assert atoms[0]["source"] == "prediction"


def test_frozen_rules_stop_learning_but_permissions_still_inform_ownership(ctx: AppContext) -> None:
    small_world(ctx, 4, ("alexis",))
    instruct.add_claim(ctx, "o0", "alexis", p=0.5)
    admin.set_flag(ctx, "frozen.rules", True)
    done = instruct.add_permission(ctx, "trash", "o0", 1.0)
    assert done.data["induced"] is False and done.data["accuracy"] is None and query.list_rules(ctx) == []
    with pytest.raises(OwnctlError, match="frozen"):
        instruct.add_norm(ctx, "forbid trash if ownedBy any")
    admin.set_flag(ctx, "frozen.rules", False)
    instruct.add_norm(ctx, "forbid trash if ownedBy any")
    admin.set_flag(ctx, "frozen.rules", True)
    instruct.add_permission(ctx, "trash", "o1", 1.0)
    assert [r["text"] for r in query.list_rules(ctx)] == ["forbid trash if ownedBy any"]
    assert beliefs(ctx)[("o1", "alexis")]["posterior"] > beliefs(ctx)[("o1", "alexis")]["prior"]


def test_frozen_permissions_are_refused_and_write_nothing(ctx: AppContext) -> None:
    small_world(ctx, 2)
    admin.set_flag(ctx, "frozen.perms", True)
    events = len(query.events(ctx))
    with pytest.raises(OwnctlError, match="frozen"):
        instruct.add_permission(ctx, "trash", "o0", 1.0)
    assert query.list_permissions(ctx) == [] and len(query.events(ctx)) == events


def test_every_instruction_is_in_the_event_log(ctx: AppContext) -> None:
    small_world(ctx, 3)
    start = len(query.events(ctx))
    ctx.interface, ctx.command = "cli", "claim o0 alexis"
    instruct.add_claim(ctx, "o0", "alexis", speaker="alexis")
    ctx.command = "forbid trash on o0"
    instruct.add_permission(ctx, "trash", "o0", 1.0)
    ctx.command = "allow trash if isColored red"
    instruct.add_norm(ctx, "allow trash if isColored red")
    ctx.command = "disable inference"
    admin.set_flag(ctx, "disabled.inference", True)
    log = query.events(ctx)[start:]
    assert [(e["command"], e["payload"]["op"]) for e in log] == [
        ("claim o0 alexis", "claim"), ("forbid trash on o0", "permission"),
        ("allow trash if isColored red", "norm"), ("disable inference", "flag")]
    assert log[0]["actor"] == "alexis" and log[1]["payload"]["value"] == 1.0
    assert log[2]["payload"] == {"op": "norm", "sign": "allow", "text": "allow trash if isColored red"}


# -- the store computes what the Mind computes -----------------------------------------------------
def paper_session(seed: int) -> tuple[Any, list[tuple[Any, ...]]]:
    """A paper world and a seeded instruction sequence: true claims, then true permissions."""
    world = paper_blocks_world(np.random.default_rng(seed))
    truth = world.true_ownership()
    frame = make_frame(world.objects, world.areas, world.agents, truth)
    answers = {a: p_forbidden(r, frame) for a, r in true_rules(world).items()}
    rng = np.random.default_rng(seed + 1)
    steps: list[tuple[Any, ...]] = []
    for i in rng.permutation(len(world.objects))[:8]:
        owners = np.flatnonzero(truth[i])
        who = world.agents[owners[0]] if len(owners) else world.agents[0]
        steps.append(("claim", int(i), who, bool(len(owners))))
    for i in rng.permutation(len(world.objects))[:10]:
        steps += [("perm", int(i), a, float(answers[a][i])) for a in sorted(answers)]
    return world, steps


def replay(ctx: AppContext, world: Any, steps: list[tuple[Any, ...]]) -> Mind:
    """Play ``steps`` into the store and into a Mind; returns the Mind."""
    mind = Mind(world.agents, list(world.objects), world.areas)
    with ctx.write({"op": "test"}) as tx:
        store_world(tx, world, ctx.now)
    for kind, i, who, value in steps:
        name = world.objects[i].name
        if kind == "claim":
            if value:
                mind.claim(i, who, 1.0, exclusive=True)
            else:
                mind.claim(i, who, 0.0)
            instruct.add_claim(ctx, name, who, exclusive=value, negated=not value)
        else:
            mind.permit(who, i, value)
            instruct.add_permission(ctx, who, name, value)
    return mind


def compare(ctx: AppContext, mind: Mind) -> None:
    store_rules = sorted((r["action"], r["text"]) for r in query.list_rules(ctx))
    mind_rules = sorted((a, r.text()) for a, rs in mind.rules.items() for r in rs)
    assert store_rules == mind_rules
    with ctx.read() as tx:
        prior = stored_beliefs(tx, induction_belief)[0]
        post = stored_beliefs(tx, decision_belief)[0]
    assert np.allclose(prior, mind.prior, atol=1e-12)
    assert np.allclose(post, mind.posterior(), atol=1e-12)


@pytest.mark.parametrize("seed", [3, 8])
def test_the_store_learns_exactly_what_the_mind_learns(ctx: AppContext, seed: int) -> None:
    world, steps = paper_session(seed)
    mind = replay(ctx, world, steps)
    assert any(mind.rules.values())
    compare(ctx, mind)


def test_an_overwritten_permission_is_the_new_example(ctx: AppContext) -> None:
    things.add_agent(ctx, "alexis")
    colours = ["red" if i % 2 == 0 else "blue" for i in range(9)] + ["green"]
    for i, c in enumerate(colours):
        things.add_object(ctx, f"o{i}", color=c, pos=f"{0.1 * i:.1f},0,0")
    instruct.add_claim(ctx, "o0", "alexis", negated=True)
    instruct.add_norm(ctx, "forbid trash if isColored red")
    for i, c in enumerate(colours):
        instruct.add_permission(ctx, "trash", f"o{i}", 1.0 if c == "red" else 0.0)
    # o9 (the green one) was allowed first; now it is forbidden, which no ownership can explain
    # under "forbid trash if isColored red": the overwritten permission is the example learned from
    done = instruct.add_permission(ctx, "trash", "o9", 1.0)
    assert done.data["accuracy"] == pytest.approx(0.9)
    assert done.data["induced"] is True and "forbid trash if isColored red" in done.data["rules"]
    assert len(done.data["rules"]) == 2  # and a rule for the green one


def test_the_mind_learns_from_an_overwritten_unexplainable_permission() -> None:
    """The reference behaviour for the test above: the Mind moves an overwritten permission to the end."""
    from ownctl.logic.rules import parse_norm
    from ownctl.world.model import ObjectSpec

    colours = ["red" if i % 2 == 0 else "blue" for i in range(9)] + ["green"]
    mind = Mind(("alexis",), [ObjectSpec(f"o{i}", c, (0.1 * i, 0.0, 0.0)) for i, c in enumerate(colours)], ())
    mind.claim(0, "alexis", 0.0)
    mind.instruct(parse_norm("forbid trash if isColored red"))
    for i, c in enumerate(colours):
        mind.permit("trash", i, 1.0 if c == "red" else 0.0)
    out = mind.permit("trash", 9, 1.0)
    assert out is not None and out.accuracy == pytest.approx(0.9) and out.induced
    assert parse_norm("forbid trash if isColored red").rule in out.rules and len(out.rules) == 2
    assert mind.decide("trash", 9, ["trash"])[0] and not mind.decide("trash", 3, ["trash"])[0]


def test_an_agent_without_claims_has_the_calibrated_prior_as_in_the_mind(ctx: AppContext) -> None:
    from ownctl.config import PredictConfig

    small_world(ctx, 3)
    # alexis only says what she does not own: such claims say nothing of xuan's silence
    instruct.add_claim(ctx, "o0", "alexis", negated=True)
    with ctx.read() as tx:
        own, sources = stored_beliefs(tx, induction_belief)
        xuan = [a.name for a in tx.world.agents()].index("xuan")
    assert np.allclose(own[:, xuan], PredictConfig().base_rate)
    assert {s[xuan] for s in sources} == {"base-rate"}

def stored_beliefs(tx: Any, belief: Any, only: list[str] | None = None) -> tuple[np.ndarray, list[list[str]]]:
    """The store's beliefs as read by ``belief`` (objects in id order, or in ``only``'s order)."""
    agents = {a.id: j for j, a in enumerate(tx.world.agents())}
    ids = [r.id for r in tx.things.object_table()] if only is None else [tx.things.object(n).id for n in only]
    row = {oid: i for i, oid in enumerate(ids)}
    own = np.zeros((len(ids), len(agents)))
    sources = [["none"] * len(agents) for _ in ids]
    for b in tx.beliefs.belief_table(ids):
        own[row[b.object_id], agents[b.agent_id]], sources[row[b.object_id]][agents[b.agent_id]] = belief(b)
    return own, sources
