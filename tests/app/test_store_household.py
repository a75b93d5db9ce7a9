"""Law: the width of the intercepts' prior moves the same in a store as in a Mind kept in memory.

A claim about one agent loads only that agent's predictor when every agent owns something else
(ownctl/app/mindstore.py, ``refit_focus``), with the store's per-agent totals of the other agents'
claims. How much the agents differ in how often they own things is read from every agent's claims
(ownctl/ownership/household.py): when a claim moves the width, that partial load cannot refit the
others, so the claim is carried out again on the whole Mind. After every claim the store's priors
equal those of a Mind told the same claims, and the partial loads that met a move wrote nothing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from ownctl.world.generator import scattered_world
from tests.app.test_store_pooled_scale import START, spy_partial_loads, stored_world, tell_both

SEED = 3  # a scattered world of 24 objects whose claims move the width five times


@pytest.mark.slow
def test_claims_that_move_the_intercepts_width_give_the_store_the_mind_s_priors(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    world = scattered_world(np.random.default_rng(SEED), 24)
    db, mind = stored_world(world, tmp_path)
    loads = spy_partial_loads(monkeypatch)
    truth = world.true_ownership()
    now, widths = START, []
    for i in range(len(world.objects)):
        for j, agent in enumerate(world.agents):
            now += 1.0
            tell_both(db, mind, now, i, agent, float(truth[i, j]))
            widths.append(mind.household.spread)
    moves = sum(a != b for a, b in zip(widths, widths[1:], strict=False))
    assert moves >= 2, widths
    assert any(loads), "no claim moved the width through a partial load"
    assert not all(loads), "no claim went through a partial load"
