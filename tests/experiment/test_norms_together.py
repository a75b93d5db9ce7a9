"""Permissions taught together (``Mind.permit_all``) give the rules taught one at a time give.

The default learner's rules depend only on the set of permissions, so Table 1 teaches each action's
permissions at once and learns after the last; the paper's learner learns after each either way."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ownctl.config import LearnConfig, Settings
from ownctl.experiment.norms import NORM_CONDITIONS, norms_setup, norms_trial
from ownctl.mind import Mind, Switches
from ownctl.world.families import norm_family
from ownctl.world.generator import paper_blocks_world

LEARNING = [c for c in NORM_CONDITIONS if not c.baseline]


@pytest.mark.parametrize("cond", LEARNING, ids=[c.name for c in LEARNING])
def test_a_trial_scores_the_same_with_permissions_together_or_one_at_a_time(cond) -> None:  # type: ignore[no-untyped-def]
    for make_world, seed in [(paper_blocks_world, 0), (paper_blocks_world, 1), (norm_family(3), 2)]:
        together = norms_trial(make_world, cond, "ours", np.random.default_rng(seed))
        apart = norms_trial(make_world, cond, "ours", np.random.default_rng(seed), together=False)
        assert together == apart


def _mind(learner: str, seed: int) -> tuple[Mind, dict[str, np.ndarray], list[str]]:
    setup = norms_setup(paper_blocks_world, NORM_CONDITIONS[4], np.random.default_rng(seed))
    world = setup.world
    mind = Mind(world.agents, list(world.objects), world.areas,
                Settings(learn=LearnConfig(learner=learner)), Switches(inference=False, prediction=False))
    mind.claims[:] = setup.claims
    return mind, setup.answers, [o.name for o in world.objects]


@settings(max_examples=12, deadline=None)
@given(seed=st.integers(0, 50), order=st.permutations(range(20)), size=st.integers(1, 20),
       learner=st.sampled_from(["ours", "paper"]))
def test_permit_all_learns_the_rules_of_the_same_permissions_given_one_by_one(
        seed: int, order: list[int], size: int, learner: str) -> None:
    chosen = order[:size]
    one, answers, names = _mind(learner, seed)
    every = _mind(learner, seed)[0]
    for action, truth in answers.items():
        for i in chosen:
            one.permit(action, names[i], float(truth[i]))
        every.permit_all(action, [(names[i], float(truth[i])) for i in chosen])
        assert every.rules[action] == one.rules[action]
        assert list(every.perms[action]) == list(one.perms[action])


def test_permit_all_stores_and_learns_nothing_while_permissions_are_frozen() -> None:
    mind, answers, names = _mind("ours", 0)
    mind.switches = Switches(inference=False, prediction=False, frozen_perms=True)
    assert mind.permit_all("trash", [(names[0], 1.0)]) is None
    assert not mind.perms["trash"] and mind.rules["trash"] == ()
    assert mind.permit_all("trash", []) is None
