"""Law: a process that keeps its loaded Mind between instructions (the Python API's cache) behaves
exactly like one that reads the store afresh for every instruction, and sees other writers at once.

The cache is valid only while the store generation is the one it was kept at: every write
transaction advances the generation, so a write by another process (or another ``Ownctl``) makes
the next call load afresh. Hypothesis draws instruction streams (the store = Mind law's steps, plus
checks and writes by a second process); both stores must then hold bit-identical beliefs and the
same rules and permissions, and every check must report the same document.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ownctl.api import Ownctl
from ownctl.app import admin, decide, instruct, mindstore, query, things
from ownctl.app.context import AppContext
from ownctl.errors import OwnctlError
from tests.app.test_store_equals_mind import ACTIONS, START, names, steps

checks = st.tuples(st.just("check"), names, st.sampled_from(ACTIONS))
foreign = st.tuples(st.just("foreign"), steps)
stream_steps = st.one_of(steps, checks, foreign)


def run(ctx: AppContext, step: tuple[Any, ...]) -> Any:
    """One step through the app on ``ctx``; the outcome, or the error's type and message."""
    kind, *args = step
    try:
        if kind == "claim":
            obj, agent, p, negated, exclusive = args
            return instruct.add_claim(ctx, obj, agent, p, negated, exclusive).data
        if kind == "permit":
            obj, action, value = args
            return instruct.add_permission(ctx, action, obj, value).data
        if kind == "norm":
            return instruct.add_norm(ctx, args[0]).data
        if kind == "touch":
            obj, agent, age = args
            return things.touch(ctx, obj, agent, at=ctx.now - age).data
        if kind == "move":
            obj, x, y = args
            return things.set_object(ctx, obj, pos=f"{x!r},{y!r},0").data
        if kind == "unpermit":
            obj, action = args
            ids = [p["id"] for p in query.list_permissions(ctx)
                   if p["object"] == obj and p["action"] == action]
            return query.remove_permission(ctx, ids[0]).data if ids else None
        if kind == "remove":
            return things.remove_object(ctx, args[0]).data
        if kind == "reset":
            return admin.reset(ctx, args[0], yes=True).data
        if kind == "switch":
            return admin.set_flag(ctx, *args).data
        if kind == "check":
            obj, action = args
            return decide.check(ctx, action, obj).data
    except OwnctlError as exc:
        return (type(exc).__name__, str(exc))
    raise AssertionError(f"unknown step {kind}")


def beliefs(db: str) -> list[tuple[Any, ...]]:
    """Every ownership row of the store, with object and agent names, as stored."""
    ctx = AppContext(db, now=START)
    try:
        with ctx.read() as tx:
            agents = {a.id: a.name for a in tx.world.agents()}
            objects = {r.id: r.name for r in tx.things.object_table()}
            rows = [(objects[b.object_id], agents[b.agent_id], b.claim_p, b.claim_speaker, b.claim_trust,
                     b.claim_time, b.prior_p, b.prior_source, b.prior_time, b.posterior_p,
                     b.posterior_source, b.posterior_time) for b in tx.beliefs.belief_table()]
        rules = [(r["action"], r["text"], r["origin"]) for r in query.list_rules(ctx)]
        perms = [(p["action"], p["object"], p["value"]) for p in query.list_permissions(ctx)]
    finally:
        ctx.close()
    return [*sorted(rows, key=repr), ("rules", *rules), ("permissions", *perms)]


def replay(kept_db: str, fresh_db: str, stream: list[Any]) -> None:
    """Drive the stream through a caching context on one store and fresh contexts on the other."""
    kept = AppContext(kept_db, now=START, cache=True)
    other = AppContext(kept_db, now=START)  # a second process writing to the kept store
    try:
        now = START
        for step in stream:
            now += 1.0
            kept.now = other.now = now
            fresh = AppContext(fresh_db, now=now)
            try:
                if step[0] == "foreign":
                    assert run(other, step[1]) == run(fresh, step[1])
                else:
                    assert run(kept, step) == run(fresh, step), step
            finally:
                fresh.close()
            assert beliefs(kept_db) == beliefs(fresh_db)
    finally:
        kept.close()
        other.close()


@pytest.mark.slow
@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(stream=st.lists(stream_steps, min_size=1, max_size=12))
def test_a_kept_mind_gives_what_fresh_loads_give(template: Path, tmp_path: Path, stream: list[Any]) -> None:
    shutil.copyfile(template, tmp_path / "kept.db")
    shutil.copyfile(template, tmp_path / "fresh.db")
    replay(str(tmp_path / "kept.db"), str(tmp_path / "fresh.db"), stream)


@pytest.mark.slow
def test_a_fixed_stream_with_a_second_writer(template: Path, tmp_path: Path) -> None:
    shutil.copyfile(template, tmp_path / "kept.db")
    shutil.copyfile(template, tmp_path / "fresh.db")
    replay(str(tmp_path / "kept.db"), str(tmp_path / "fresh.db"), [
        ("claim", "o1", "xuan", 1.0, False, False), ("check", "o1", "trash"),
        ("norm", "forbid trash if ownedBy any"), ("check", "o1", "trash"),
        ("foreign", ("claim", "o2", "alexis", 1.0, False, True)), ("check", "o2", "trash"),
        ("permit", "o3", "pickUp", 1.0), ("foreign", ("move", "o3", 0.9, 0.9)),
        ("permit", "o4", "pickUp", 0.0), ("touch", "o2", "casey", 3.0), ("check", "o4", "pickUp"),
        ("foreign", ("permit", "o4", "pickUp", 1.0)), ("check", "o4", "pickUp"), ("remove", "o1"),
        ("claim", "o1", "xuan", 1.0, False, False), ("reset", "claims"), ("check", "o2", "trash"),
    ])


def test_another_writer_invalidates_the_kept_mind(template: Path, tmp_path: Path,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    db = str(tmp_path / "s.db")
    shutil.copyfile(template, db)
    loads: list[int] = []
    real = mindstore.load
    monkeypatch.setattr(mindstore, "load", lambda *a, **k: loads.append(1) or real(*a, **k))
    clock = [START]
    with Ownctl.open(db, clock=lambda: clock[0]) as a, Ownctl.open(db, clock=lambda: clock[0]) as b:
        a.claim("o1", "xuan")
        a.forbid("trash", "if ownedBy any")
        assert a.check("trash", "o1").forbidden
        assert a.check("trash", "o2").data["decided_by"] == "rules"
        assert len(loads) == 1  # loaded once, then kept: its own writes bring it up to date
        b.permit("trash", "o2", forbid=True)  # another writer: the store generation moves on
        clock[0] += 1
        report = a.check("trash", "o2")
        assert report.data["decided_by"] == "permission" and report.forbidden
        assert len(loads) == 3  # b loaded for its write (it keeps its own); a loaded afresh
        b.permit("trash", "o1", forbid=False)
        a.claim("o3", "alexis")  # a write after another writer's: loaded afresh, then saved
        assert a.check("trash", "o1").data["decided_by"] == "permission"
        assert not a.check("trash", "o1").forbidden
        assert len(loads) == 5
    with Ownctl.open(db, cache=False) as c:
        assert c.check("trash", "o3").forbidden  # a's claim reached the store
        assert not c.check("trash", "o1").forbidden
