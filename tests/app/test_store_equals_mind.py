"""Law: a store behaves exactly like one Mind kept in memory.

Hypothesis draws instruction streams (claims, permissions, norms, allow norms, touches, moves,
object and permission removals, resets, switches) over small worlds. Each step is applied through
the app layer on a real store, opening the store afresh for every step (nothing is kept in memory
between steps), and directly to one in-memory :class:`~ownctl.mind.Mind`. After every step both
hold the same rules (text, in order, with origins) and the same priors and posteriors (to 1e-12).
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ownctl.app import admin, instruct, query, things
from ownctl.app.beliefs import decision_belief, induction_belief
from ownctl.app.context import AppContext
from ownctl.logic.rules import parse_norm
from ownctl.mind import Mind
from ownctl.world.model import Area, ObjectSpec

AGENTS = ("alexis", "xuan", "casey")
COLOURS = ("red", "blue", "green")
AREAS = (Area("home", (0.0, 0.0, 0.4, 0.4)), Area("trash", (0.6, 0.6, 1.0, 1.0)))
ACTIONS = ("trash", "pickUp")
NORMS = (
    "forbid trash if ownedBy any",
    "forbid trash if ownedBy xuan",
    "forbid pickUp if ownedBy alexis and not isColored red",
    "forbid trash if isColored blue",
    "allow trash if isColored red",
    "allow pickUp if inArea home",
    "forbid pickUp if inArea trash",
)
START = 5000.0

names = st.integers(0, 5).map(lambda i: f"o{i}")
steps = st.one_of(
    st.tuples(st.just("claim"), names, st.sampled_from(AGENTS), st.sampled_from([1.0, 0.8, 0.3]),
              st.booleans(), st.booleans()),
    st.tuples(st.just("permit"), names, st.sampled_from(ACTIONS), st.sampled_from([1.0, 0.0])),
    st.tuples(st.just("permit"), names, st.sampled_from(ACTIONS), st.sampled_from([1.0, 0.0])),
    st.tuples(st.just("norm"), st.sampled_from(NORMS)),
    st.tuples(st.just("touch"), names, st.sampled_from(AGENTS), st.floats(0.0, 500.0)),
    st.tuples(st.just("move"), names, st.floats(0.0, 1.0), st.floats(0.0, 1.0)),
    st.tuples(st.just("unpermit"), names, st.sampled_from(ACTIONS)),
    st.tuples(st.just("remove"), names),
    st.tuples(st.just("reset"), st.sampled_from(["perms", "rules", "claims", "all"])),
    st.tuples(st.just("switch"), st.sampled_from(["disabled.inference", "disabled.prediction",
                                                  "frozen.rules"]), st.booleans()),
)


def world_objects() -> list[ObjectSpec]:
    return [ObjectSpec(f"o{i}", COLOURS[i % 3], (0.15 * i, 0.12 * i, 0.0)) for i in range(6)]


def fresh_mind() -> Mind:
    areas = sorted(AREAS, key=lambda a: a.name)
    mind = Mind(sorted(AGENTS), world_objects(), areas, now=START, touch_times=True)
    return mind


def apply(db: str, mind: Mind, step: tuple[Any, ...], now: float) -> None:
    """One step through the app (a fresh context: the store is opened anew) and on the Mind."""
    ctx = AppContext(db, now=now)
    mind.at(now)
    kind, *args = step
    try:
        present = set(mind.index)
        if kind == "claim":
            obj, agent, p, negated, exclusive = args
            if obj not in present or (negated and exclusive):
                return
            instruct.add_claim(ctx, obj, agent, p, negated, exclusive)
            mind.claim(obj, agent, p, negated=negated, exclusive=exclusive)
        elif kind == "permit":
            obj, action, value = args
            if obj not in present or mind.switches.frozen_perms:
                return
            instruct.add_permission(ctx, action, obj, value)
            mind.permit(action, obj, value)
        elif kind == "norm":
            if mind.switches.frozen_rules:
                return
            instruct.add_norm(ctx, args[0])
            mind.instruct(parse_norm(args[0]))
        elif kind == "touch":
            obj, agent, age = args
            if obj not in present:
                return
            things.touch(ctx, obj, agent, at=now - age)
            mind.touch(obj, agent, now - age)
        elif kind == "move":
            obj, x, y = args
            if obj not in present:
                return
            things.set_object(ctx, obj, pos=f"{x!r},{y!r},0")
            mind.move(obj, (x, y, 0.0))
        elif kind == "unpermit":
            obj, action = args
            if obj not in present or mind.permission(action, obj) is None:
                return
            (pid,) = [p["id"] for p in query.list_permissions(ctx)
                      if p["object"] == obj and p["action"] == action]
            query.remove_permission(ctx, pid)
            mind.remove_permission(action, obj)
        elif kind == "remove":
            if args[0] not in present:
                return
            things.remove_object(ctx, args[0])
            mind.remove_object(args[0])
        elif kind == "reset":
            admin.reset(ctx, args[0], yes=True)
            mind.reset(args[0])
        elif kind == "switch":
            key, on = args
            admin.set_flag(ctx, key, on)
            mind.set_switch(key, on)
    finally:
        ctx.close()


def compare(db: str, mind: Mind, now: float) -> None:
    ctx = AppContext(db, now=now)
    try:
        stored = [(r["action"], r["text"], r["origin"]) for r in query.list_rules(ctx)]
        with ctx.read() as tx:
            agents = {a.id: j for j, a in enumerate(tx.world.agents())}
            rows = {r.id: r.name for r in tx.things.object_table()}
            prior = np.full((len(rows), len(agents)), np.nan)
            post = prior.copy()
            order = {oid: i for i, oid in enumerate(rows)}
            for b in tx.beliefs.belief_table():
                i, j = order[b.object_id], agents[b.agent_id]
                prior[i, j] = induction_belief(b)[0]
                post[i, j] = decision_belief(b)[0]
    finally:
        ctx.close()
    expected = [(a, (r.text("allow") if info.origin == "allow" else r.text()), info.origin)
                for a in sorted({a for a, *_ in stored} | {a for a in mind.rules if mind.all_rules(a)})
                for r, info in mind.all_rules(a)]
    assert stored == expected
    assert list(rows.values()) == [o.name for o in mind.objects]
    np.testing.assert_allclose(prior, mind.prior, rtol=0, atol=1e-12)
    np.testing.assert_allclose(post, mind.posterior(), rtol=0, atol=1e-12)


@pytest.mark.slow
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(stream=st.lists(steps, min_size=1, max_size=10))
def test_the_store_behaves_like_one_mind_in_memory(template: Path, tmp_path: Path, stream: list[Any]) -> None:
    db = tmp_path / "s.db"
    shutil.copyfile(template, db)
    mind = fresh_mind()
    now = START
    for step in stream:
        now += 1.0
        apply(str(db), mind, step, now)
        compare(str(db), mind, now)
