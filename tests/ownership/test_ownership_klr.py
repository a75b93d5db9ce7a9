"""Percept-based ownership prediction (architecture section 5): the estimator contract and its behaviour.

``KernelOwnershipModel`` follows scikit-learn's conventions (settings in ``__init__``, ``fit`` returns
self and sets only trailing-underscore attributes), learns from soft targets, falls back to a
calibrated prior that never sits exactly on the 0.5 decision threshold, and on the paper's blocks
world separates each agent's objects from the rest mostly by how recently that agent touched them.
"""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.config import PredictConfig
from ownctl.ownership.features import NEVER_AGE, RECENCY_SAMPLE, agent_features, recency_feature
from ownctl.ownership.predict import KernelOwnershipModel
from ownctl.world.generator import paper_blocks_world
from ownctl.world.model import World, positions


def toy(rng: np.random.Generator, n: int = 12) -> tuple[np.ndarray, np.ndarray]:
    X = rng.normal(size=(n, 3))
    return X, (X[:, 0] > 0).astype(float)


def test_init_stores_settings_and_fit_sets_only_trailing_underscore_attributes() -> None:
    cfg = PredictConfig(gamma=0.7)
    model = KernelOwnershipModel(cfg)
    assert vars(model) == {"cfg": cfg}
    before = set(vars(model))
    X, p = toy(np.random.default_rng(0))
    assert model.fit(X, p) is model
    added = set(vars(model)) - before
    assert added and all(name.endswith("_") and not name.startswith("_") for name in added), added
    assert KernelOwnershipModel().cfg == PredictConfig()


def test_predicting_before_fit_raises_or_gives_the_base_rate() -> None:
    model = KernelOwnershipModel()
    try:
        p = model.predict_proba(np.zeros((3, 3)))
    except (AttributeError, ValueError):
        return  # like scikit-learn's NotFittedError (an AttributeError and ValueError)
    assert np.allclose(p, PredictConfig().base_rate)


def test_refitting_forgets_the_previous_fit() -> None:
    rng = np.random.default_rng(1)
    X, p = toy(rng)
    Z = rng.normal(size=(20, 3))
    once = KernelOwnershipModel().fit(X, p).predict_proba(Z)
    model = KernelOwnershipModel().fit(X, 1.0 - p)
    assert np.array_equal(model.fit(X, p).predict_proba(Z), once)


def test_soft_targets_matter() -> None:
    """A claim of 0.7 is not a claim of 1.0: the claimed object and its neighbours get a lower value."""
    X = np.array([[0.0, 0.0], [0.1, 0.0], [3.0, 0.0], [3.1, 0.0]])
    hard = KernelOwnershipModel().fit(X, np.array([1.0, 1.0, 0.0, 0.0]))
    soft = KernelOwnershipModel().fit(X, np.array([0.7, 0.7, 0.0, 0.0]))
    Z = np.array([[0.0, 0.0], [0.05, 0.0], [0.5, 0.0]])
    ph, ps = hard.predict_proba(Z), soft.predict_proba(Z)
    assert np.all(ps < ph - 0.05), (ps, ph)
    assert np.all(ps[:2] > 0.5)  # at the claimed objects: still more likely owned than not
    # and a 0.3 "probably not" claim differs from a hard "not mine"
    no = KernelOwnershipModel().fit(X, np.array([0.0, 0.0, 1.0, 1.0])).predict_proba(Z)
    maybe = KernelOwnershipModel().fit(X, np.array([0.3, 0.3, 1.0, 1.0])).predict_proba(Z)
    assert np.all(maybe > no + 0.05)


def test_out_of_range_targets_are_clipped_to_probabilities() -> None:
    X = np.array([[0.0], [1.0], [2.0]])
    a = KernelOwnershipModel().fit(X, np.array([1.5, -0.2, 1.0])).predict_proba(X)
    b = KernelOwnershipModel().fit(X, np.array([1.0, 0.0, 1.0])).predict_proba(X)
    assert np.allclose(a, b)


def test_too_few_claims_give_a_calibrated_prior_never_exactly_one_half() -> None:
    cfg = PredictConfig(min_claims=3, base_rate=0.25)
    X = np.zeros((2, 3))
    # two "mine" claims and four pseudo-claims at the base rate average exactly 0.5: nudged off it
    model = KernelOwnershipModel(cfg).fit(X, np.array([1.0, 1.0]))
    p = model.predict_proba(np.zeros((5, 3)))
    assert not model.trained_ and model.source_ == "base-rate"
    assert np.all(p != 0.5) and np.allclose(p, 0.5, atol=1e-2) and len(set(p)) == 1
    # calibrated: shrunk towards the claims seen so far, from the base rate
    one = KernelOwnershipModel(cfg).fit(X[:1], np.array([1.0])).predict_proba(X)
    none = KernelOwnershipModel(cfg).fit(X[:1], np.array([0.0])).predict_proba(X)
    assert none[0] < cfg.base_rate < one[0] < 0.5
    assert one[0] == pytest.approx((1.0 + 4 * 0.25) / 5)


@pytest.mark.parametrize("base_rate", [0.5, 0.25, 0.9])
def test_trained_predictions_never_sit_exactly_on_one_half(base_rate: float) -> None:
    cfg = PredictConfig(base_rate=base_rate)
    X = np.array([[0.0], [1.0]])
    model = KernelOwnershipModel(cfg).fit(X, np.array([0.5, 0.5]))
    p = model.predict_proba(np.linspace(-5, 5, 41)[:, None])
    assert np.all(p != 0.5)


def holdout_accuracy(world: World, rng: np.random.Generator, recency_only: bool) -> float:
    """Claims (true ownership) for half of the objects, per agent; accuracy at 0.5 on the other half."""
    truth = world.true_ownership()
    n = len(world.objects)
    order = rng.permutation(n)
    train, test = order[: n // 2], order[n // 2 :]
    palette = tuple(sorted({o.color for o in world.objects if o.color}))
    pos = np.full((n, 3), np.nan) if recency_only else positions(world.objects)
    colours = [None] * n if recency_only else [o.color for o in world.objects]
    right = 0
    for j, agent in enumerate(world.agents):
        ages = np.array([o.last_touch.get(agent, np.nan) for o in world.objects])
        X = agent_features(pos, colours, ages, palette, PredictConfig())
        p = KernelOwnershipModel().fit(X[train], truth[train, j]).predict_proba(X[test])
        right += int(((p >= 0.5) == (truth[test, j] >= 0.5)).sum())
    return right / (len(test) * len(world.agents))


@pytest.mark.parametrize("seed", range(5))
def test_paper_world_half_claimed_predicts_the_other_half(seed: int) -> None:
    rng = np.random.default_rng(seed)
    world = paper_blocks_world(rng)
    assert holdout_accuracy(world, rng, recency_only=False) >= 0.9


def test_recency_alone_separates_owners_on_the_paper_world() -> None:
    """Owners touched their objects ~10 s ago, others ~1000 s ago: log-recency alone must do it."""
    scores = []
    for seed in range(8):
        rng = np.random.default_rng(100 + seed)
        scores.append(holdout_accuracy(paper_blocks_world(rng), rng, recency_only=True))
    assert np.mean(scores) >= 0.9, scores
    assert min(scores) >= 0.8, scores


def test_without_recency_position_still_carries_ownership() -> None:
    rng = np.random.default_rng(11)
    world = paper_blocks_world(rng)
    blind = World(world.name, world.agents,
                  tuple(type(o)(o.name, o.color, o.position, o.categories, {}) for o in world.objects),
                  world.areas, world.norms, world.owners)
    assert holdout_accuracy(blind, rng, recency_only=False) >= 0.8


@pytest.mark.parametrize("n", [1, 2, 7, RECENCY_SAMPLE, RECENCY_SAMPLE + 1, 3 * RECENCY_SAMPLE + 5])
def test_recency_is_standardised_over_every_object_or_a_regular_sample(n: int) -> None:
    """Up to RECENCY_SAMPLE objects the mean and spread are every object's; beyond, every k-th
    object's, k = ceil(n / RECENCY_SAMPLE); the rows asked for are those of the whole."""
    rng = np.random.default_rng(n)
    ages = np.where(rng.random(n) < 0.4, rng.exponential(50.0, n), np.nan)
    cfg = PredictConfig()
    logs = np.log1p(np.where(np.isnan(ages), NEVER_AGE, ages))
    sample = logs[:: -(-n // RECENCY_SAMPLE)]
    spread = np.sqrt(((sample - sample.mean()) ** 2).mean()) if n > 1 else 1.0
    spread = spread if spread > 1e-6 else 1.0
    want = cfg.recency_weight * (logs - sample.mean()) / spread
    got = recency_feature(ages, cfg)[:, 0]
    assert np.allclose(got, want, atol=1e-12)
    rows = np.arange(0, n, 3)
    assert np.array_equal(recency_feature(ages, cfg, rows)[:, 0], got[rows])
