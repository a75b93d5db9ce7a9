"""Permissions taught together (``Mind.permit_all``) give the rules taught one at a time give.

The default learner's rules depend only on the set of permissions, so Table 1 teaches each action's
permissions at once and learns after the last; the paper's learner learns after each either way."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ownctl.experiment.norms import NORM_CONDITIONS, NormsSetup, norms_setup, norms_trial, taught_mind
from ownctl.mind import Switches
from ownctl.world.families import norm_family
from ownctl.world.generator import paper_blocks_world

LEARNING = [c for c in NORM_CONDITIONS if not c.baseline]


@pytest.mark.parametrize("cond", LEARNING, ids=[c.name for c in LEARNING])
def test_a_trial_scores_the_same_with_permissions_together_or_one_at_a_time(cond) -> None:  # type: ignore[no-untyped-def]
    for make_world, seed in [(paper_blocks_world, 0), (paper_blocks_world, 1), (norm_family(3), 2)]:
        together = norms_trial(make_world, cond, "ours", np.random.default_rng(seed))
        apart = norms_trial(make_world, cond, "ours", np.random.default_rng(seed), together=False)
        assert together == apart


def _setup(seed: int, chosen: list[int]) -> NormsSetup:
    setup = norms_setup(paper_blocks_world, NORM_CONDITIONS[4], np.random.default_rng(seed))
    return replace(setup, chosen=np.asarray(chosen, dtype=int))


@settings(max_examples=12, deadline=None)
@given(seed=st.integers(0, 50), order=st.permutations(range(20)), size=st.integers(1, 20),
       learner=st.sampled_from(["ours", "paper"]))
def test_permit_all_learns_the_rules_of_the_same_permissions_given_one_by_one(
        seed: int, order: list[int], size: int, learner: str) -> None:
    setup = _setup(seed, order[:size])
    together, apart = taught_mind(setup, learner), taught_mind(setup, learner, together=False)
    for action in setup.rules:
        assert together.rules[action] == apart.rules[action]
        assert list(together.perms[action]) == list(apart.perms[action])


def test_permit_all_stores_and_learns_nothing_while_permissions_are_frozen() -> None:
    mind = taught_mind(_setup(0, []))
    mind.switches = Switches(inference=False, prediction=False, frozen_perms=True)
    name = mind.objects[0].name
    assert mind.permit_all("trash", [(name, 1.0)]) is None
    assert not mind.perms["trash"] and mind.rules["trash"] == ()
    assert mind.permit_all("trash", []) is None


def test_permit_all_with_an_unknown_object_stores_nothing() -> None:
    mind = taught_mind(_setup(0, []))
    with pytest.raises(KeyError, match="nothing"):
        mind.permit_all("trash", [(mind.objects[0].name, 1.0), ("nothing", 0.0)])
    assert not mind.perms["trash"]
