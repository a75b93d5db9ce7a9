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
from ownctl.logic.prob import p_forbidden
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


def test_the_coverage_prior_charges_each_rule_its_share_of_objects() -> None:
    """Brute force: each set's weight is its stated weight minus the weight times the summed mean
    P(rule holds) of its rules over the Mind's objects, computed object by object."""
    bench, mind = _benchmark(), _taught()
    rp = mind.rule_posterior("trash")
    frame, n = mind.frame(), len(mind.objects)
    share = {r: sum(float(p_forbidden((r,), frame.take([i]))[0]) for i in range(n)) / n for r in rp.rules}
    want = np.array([w - bench.COVERAGE_WEIGHT * sum(share[r] for r in rules)
                     for w, rules in zip(rp.log_weights, rp.sets, strict=True)])
    want = np.exp(want - want.max())
    got = bench.PRIORS["coverage"](mind, "trash", 1.0).probabilities
    np.testing.assert_allclose(got, want / want.sum(), atol=1e-12)
    broad = max(share, key=lambda r: share[r])  # the broadest rule loses weight to the narrower ones
    member = np.array([broad in rules for rules in rp.sets])
    assert got[member].sum() < rp.probabilities[member].sum()
