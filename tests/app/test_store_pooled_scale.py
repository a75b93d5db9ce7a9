"""Law: the scale every predictor shares moves the same in a store as in a Mind kept in memory.

A claim about one agent loads only that agent's predictor when every agent owns something else
(ownctl/app/mindstore.py, ``refit_focus``). The scale all predictors use is chosen on every
agent's claims (architecture section 5): when a claim moves it, that partial load cannot refit
the others, so the claim is carried out again on the whole Mind. On a scattered world (no
percept says who owns what) whose claims move the scale while every agent owns something, the
store's priors equal the in-memory Mind's after every claim, and the partial loads that met a
move wrote nothing of their own.
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from ownctl.app import instruct, mindstore, worldfile
from ownctl.app.beliefs import induction_belief
from ownctl.app.context import AppContext
from ownctl.mind import Mind, WholeMindNeeded
from ownctl.world.generator import scattered_world
from ownctl.world.model import World
from ownctl.world.spec import to_toml, world_to_dict

START = 10_000.0
SEED = 9  # a world whose later claims move the scale three times while every agent owns something


def stored_priors(db: str, now: float) -> np.ndarray:
    ctx = AppContext(db, now=now)
    try:
        with ctx.read() as tx:
            agents = {a.id: j for j, a in enumerate(tx.world.agents())}
            order = {r.id: i for i, r in enumerate(tx.things.object_table())}
            prior = np.full((len(order), len(agents)), np.nan)
            for b in tx.beliefs.belief_table():
                prior[order[b.object_id], agents[b.agent_id]] = induction_belief(b)[0]
    finally:
        ctx.close()
    return prior


def stored_world(world: World, folder: Path) -> tuple[str, Mind]:
    """A new store in ``folder`` holding ``world`` (loaded at START), and a Mind of the same world."""
    path = folder / "w.toml"
    path.write_text(to_toml(world_to_dict(world)), encoding="utf-8")
    db = str(folder / "s.db")
    ctx = AppContext(db, now=START)
    ctx.store(create=True)
    worldfile.load(ctx, str(path))
    ctx.close()
    return db, Mind(world.agents, list(world.objects), sorted(world.areas, key=lambda a: a.name), now=START)


def spy_partial_loads(monkeypatch: pytest.MonkeyPatch) -> list[bool]:
    """Per instruction that loads only some agents' predictors (a partial load), whether it met a
    move of what every predictor shares and was carried out again on the whole Mind."""
    loads: list[bool] = []
    partial = mindstore.changing

    def spying(*args: Any, **kwargs: Any) -> Any:
        try:
            with partial(*args, **kwargs) as out:
                yield out
            if kwargs.get("agents") is not None:
                loads.append(False)
        except WholeMindNeeded:
            loads.append(True)
            raise

    monkeypatch.setattr(mindstore, "changing", contextlib.contextmanager(spying))
    return loads


def tell_both(db: str, mind: Mind, now: float, i: int, agent: str, p: float, negated: bool = False) -> None:
    """Claim that ``agent`` owns object ``i`` with ``p`` in the store (one instruction at ``now``)
    and in ``mind``, and check that the store's priors are then the Mind's."""
    ctx = AppContext(db, now=now)
    try:
        instruct.add_claim(ctx, mind.objects[i].name, agent, p, negated=negated)
    finally:
        ctx.close()
    mind.at(now)
    mind.claim(i, agent, p, negated=negated)
    mind.refresh()
    np.testing.assert_allclose(stored_priors(db, now), mind.prior, rtol=0, atol=1e-12)


def test_claims_that_move_the_shared_scale_give_the_store_the_mind_s_priors(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    world = scattered_world(np.random.default_rng(SEED), 8)
    db, mind = stored_world(world, tmp_path)
    loads = spy_partial_loads(monkeypatch)
    truth = world.true_ownership()
    now = START
    moves = 0
    for i in range(len(world.objects)):
        for j, agent in enumerate(world.agents):
            now += 1.0
            before = mind.scale
            tell_both(db, mind, now, i, agent, float(truth[i, j]))
            moves += mind.scale != before
    assert moves >= 2
    assert any(loads), "no claim moved the scale through a partial load"
