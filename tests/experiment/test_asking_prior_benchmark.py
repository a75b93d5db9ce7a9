"""``benchmarks/asking_prior.py`` values questions on the posterior under another prior: checked
against the posterior computed afresh with that prior's model on the same space."""

from __future__ import annotations

import dataclasses
import math
from types import ModuleType

import numpy as np
import pytest

from ownctl.config import LearnConfig, Settings
from ownctl.learn.model import model_for, rule_counts
from ownctl.learn.posterior import MAX_RULES, RuleSpace, posterior
from ownctl.mind import Mind, Switches
from ownctl.world.generator import paper_blocks_world
from tests.benchmark_loader import load_benchmark


def _benchmark() -> ModuleType:
    return load_benchmark("asking_prior")


def _taught() -> Mind:
    world = paper_blocks_world(np.random.default_rng(3))
    mind = Mind(world.agents, list(world.objects), world.areas, Settings(learn=LearnConfig(learner="ours")),
                Switches(inference=False, prediction=False))
    mind.claims[:] = world.true_ownership()
    truth = {0: 1.0, 1: 0.0, 2: 0.0}  # one forbidden example and two allowed ones
    mind.permit_all("trash", list(truth.items()))
    return mind


@pytest.mark.parametrize("prior", ["length", "normalised"])
def test_the_reweighted_posterior_is_the_posterior_of_that_prior(prior: str) -> None:
    bench, mind = _benchmark(), _taught()
    rp = mind.rule_posterior("trash")
    atoms, longest = tuple(mind.vocab.atoms()), mind.settings.learn.max_conditions
    counts = rule_counts(atoms, longest)
    stated = model_for(atoms, longest)
    if prior == "length":
        model = dataclasses.replace(stated, counts=counts, count_weight=1.0)
    else:  # every rule pays log Z - log(1/2) more: the same as a larger rule cost
        log_z = math.log(sum(n * math.exp(-stated.cost(k)) for k, n in enumerate(counts)))
        model = dataclasses.replace(stated, rule_cost=stated.rule_cost + log_z - math.log(0.5))
    ev, _ = mind.evidence("trash")
    fresh = posterior(ev, "trash", RuleSpace(rp.rules, MAX_RULES), model)
    assert fresh.sets == rp.sets
    got = bench.PRIORS[prior](mind, "trash", 1.0).probabilities
    np.testing.assert_allclose(got, fresh.probabilities, atol=1e-12)
    assert np.abs(got - rp.probabilities).max() > 0.01  # a different prior, a different posterior
