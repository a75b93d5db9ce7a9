"""Priors that another version of the predictor wrote are refitted (ownctl/app/mindstore.py).

The store keeps each agent's predictions (its priors) and reads them back instead of refitting.
When what the predictor computes changes (``PREDICTOR_VERSION``), a store written before holds
priors no Mind told the same things would hold: its next load refits every agent, and its next
write stores the new priors and the version.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from ownctl.app import instruct
from ownctl.app.context import AppContext
from ownctl.app.mindstore import VERSION, load
from ownctl.app.worldfile import store_world
from ownctl.mind import Mind
from ownctl.ownership.predict import PREDICTOR_VERSION
from ownctl.world.generator import paper_blocks_world

NOW = 1000.0


@pytest.fixture
def ctx(tmp_path: Path) -> Iterator[AppContext]:
    ctx = AppContext(str(tmp_path / "s.db"), now=NOW)
    ctx.store(create=True)
    yield ctx
    ctx.close()


def _told(ctx: AppContext) -> Mind:
    """Twelve objects' true owners told to the store and to a Mind (enough claims per agent for
    the predictor's recalibration); returns the Mind."""
    world = paper_blocks_world(np.random.default_rng(2))
    truth = world.true_ownership()
    with ctx.write({"op": "test"}) as tx:
        store_world(tx, world, ctx.now)
    mind = Mind(world.agents, list(world.objects), world.areas)
    for i in range(12):
        for j, agent in enumerate(world.agents):
            mind.claim(i, agent, float(truth[i, j]))
            instruct.add_claim(ctx, world.objects[i].name, agent, negated=not truth[i, j])
    return mind


def _as_if_written_before(ctx: AppContext, version: int | None) -> None:
    """Every stored prior set to 0.5 and the version key to ``version``, as an older store's."""
    with ctx.write({"op": "test"}) as tx:
        objects = [r.id for r in tx.things.object_table()]
        agents = [a.id for a in tx.world.agents()]
        pairs = [(o, a) for o in objects for a in agents]
        tx.beliefs.write_priors([o for o, _ in pairs], [a for _, a in pairs], [0.5] * len(pairs),
                                ["prediction"] * len(pairs), NOW)
        tx.meta.set_setting(VERSION, version)


def _stored_priors(ctx: AppContext) -> np.ndarray:
    with ctx.read() as tx:
        objects = [r.id for r in tx.things.object_table()]
        agents = [a.id for a in tx.world.agents()]
        return np.asarray(tx.beliefs.priors(objects, agents).p, dtype=float)


def test_a_write_stores_the_predictor_version(ctx: AppContext) -> None:
    _told(ctx)
    with ctx.read() as tx:
        assert tx.meta.settings()[VERSION] == PREDICTOR_VERSION


@pytest.mark.parametrize("older", [None, PREDICTOR_VERSION - 1])
def test_priors_another_predictor_wrote_are_refitted_and_written_again(ctx: AppContext,
                                                                         older: int | None) -> None:
    mind = _told(ctx)
    _as_if_written_before(ctx, older)
    with ctx.read() as tx:  # a read refits in memory
        assert np.allclose(load(tx, NOW).mind.prior, mind.prior, atol=1e-12)
    assert np.allclose(_stored_priors(ctx), 0.5)
    instruct.add_claim(ctx, mind.objects[15].name, mind.agents[0], negated=True)  # any write
    mind.claim(15, mind.agents[0], 0.0)
    mind.refresh()
    assert np.allclose(_stored_priors(ctx), mind.predicted, atol=1e-12)
    with ctx.read() as tx:
        assert tx.meta.settings()[VERSION] == PREDICTOR_VERSION


def test_priors_this_predictor_wrote_are_read_as_they_are(ctx: AppContext) -> None:
    _told(ctx)
    _as_if_written_before(ctx, PREDICTOR_VERSION)
    with ctx.read() as tx:
        assert np.allclose(load(tx, NOW).mind.predicted, 0.5)
