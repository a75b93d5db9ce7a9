"""Law: what silence weighs moves the same in a store as in a Mind kept in memory.

A claim about one agent loads only that agent's predictor when every agent owns something else
(ownctl/app/mindstore.py, ``refit_focus``), with the store's count of the other agents' claims. What
an agent's silence about a claimed object weighs is chosen on every agent's claims (architecture
section 5): when a claim moves it, or is the first about its object while silence weighs, that
partial load cannot refit the silent agents, so the claim is carried out again on the whole Mind.
Owners say "that's mine", then some say what is not theirs: after every claim the store's priors
equal those of a Mind told the same claims, and the partial loads that met a move wrote nothing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from ownctl.world.generator import paper_blocks_world
from tests.app.test_store_pooled_scale import START, spy_partial_loads, stored_world, tell_both


def test_claims_that_move_what_silence_weighs_give_the_store_the_mind_s_priors(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    world = paper_blocks_world(np.random.default_rng(4), 12)
    db, mind = stored_world(world, tmp_path)
    loads = spy_partial_loads(monkeypatch)
    truth = world.true_ownership() >= 0.5
    said: list[tuple[int, str, float, bool]] = []
    for i in range(len(world.objects)):  # owners say "that's mine"; now and then one says "not mine"
        if i % 3 == 0:
            said += [(i, a, 1.0, True) for j, a in enumerate(world.agents) if not truth[i, j]][:1]
        else:
            said += [(i, a, 1.0, False) for j, a in enumerate(world.agents) if truth[i, j]]
    said += [(i, a, 1.0, True) for i in range(len(world.objects)) if i % 3  # then others deny them
             for j, a in enumerate(world.agents) if not truth[i, j] and truth[i].any()]
    now, weights = START, []
    for i, agent, p, negated in said:
        now += 1.0
        tell_both(db, mind, now, i, agent, p, negated)
        weights.append(mind.silence)
    assert len(set(weights)) >= 3, weights  # silence weighed differently as the claims came
    assert any(loads), "no claim moved silence through a partial load"
    assert not all(loads), "no claim went through a partial load"
