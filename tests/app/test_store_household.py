"""Law: the width of the intercepts' prior moves the same in a store as in a Mind kept in memory.

A claim about one agent loads only that agent's predictor when every agent owns something else
(ownctl/app/mindstore.py, ``refit_focus``), with the store's per-agent totals of the other agents'
claims. How much the agents differ in how often they own things is read from every agent's claims
(ownctl/ownership/household.py): when a claim moves the width, that partial load cannot refit the
others, so the claim is carried out again on the whole Mind. After every claim the store's priors
equal those of a Mind told the same claims, and the partial loads that met a move wrote nothing.
"""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from ownctl.app import instruct, mindstore
from ownctl.app.context import AppContext
from ownctl.mind import WholeMindNeeded
from ownctl.world.generator import scattered_world
from tests.app.test_store_pooled_scale import START, stored_priors, stored_world

SEED = 3  # a scattered world of 24 objects whose claims move the width five times


@pytest.mark.slow
def test_claims_that_move_the_intercepts_width_give_the_store_the_mind_s_priors(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    world = scattered_world(np.random.default_rng(SEED), 24)
    db, mind = stored_world(world, tmp_path)
    loads: list[bool] = []  # per partial load, whether it met a move
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
    truth = world.true_ownership()
    now, widths = START, []
    for i, obj in enumerate(world.objects):
        for j, agent in enumerate(world.agents):
            now += 1.0
            ctx = AppContext(db, now=now)
            try:
                instruct.add_claim(ctx, obj.name, agent, float(truth[i, j]))
            finally:
                ctx.close()
            mind.at(now)
            mind.claim(i, agent, float(truth[i, j]))
            mind.refresh()
            widths.append(mind.household.spread)
            np.testing.assert_allclose(stored_priors(db, now), mind.prior, rtol=0, atol=1e-12)
    moves = sum(a != b for a, b in zip(widths, widths[1:], strict=False))
    assert moves >= 2, widths
    assert any(loads), "no claim moved the width through a partial load"
    assert not all(loads), "no claim went through a partial load"
