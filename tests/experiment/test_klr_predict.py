"""Laws of the per-agent kernel logistic regression (ownctl.ownership.predict / features)."""

from __future__ import annotations

import numpy as np

from ownctl.config import PredictConfig
from ownctl.ownership.features import agent_features
from ownctl.ownership.predict import KernelOwnershipModel


def blobs(rng: np.random.Generator, n: int = 20) -> tuple[np.ndarray, np.ndarray]:
    owned = rng.normal([1.5, 0.0], 0.2, size=(n // 2, 2))
    free = rng.normal([-1.5, 0.0], 0.2, size=(n - n // 2, 2))
    return np.vstack([owned, free]), np.r_[np.ones(n // 2), np.zeros(n - n // 2)]


def test_fit_returns_self_and_sets_trailing_underscore_attributes() -> None:
    X, y = blobs(np.random.default_rng(0))
    model = KernelOwnershipModel()
    assert model.fit(X, y) is model
    assert model.trained_ and model.n_claims_ == len(y) and model.source_ == "prediction"
    assert model.coef_.shape == (len(X) + X.shape[1] + 1,)


def test_separable_claims_are_predicted_on_new_objects() -> None:
    rng = np.random.default_rng(1)
    X, y = blobs(rng)
    Z, truth = blobs(rng, 40)
    p = KernelOwnershipModel().fit(X, y).predict_proba(Z)
    assert ((p >= 0.5) == (truth == 1)).all()


def test_no_claims_gives_the_base_rate_and_never_one_half() -> None:
    cfg = PredictConfig(base_rate=0.5)
    model = KernelOwnershipModel(cfg).fit(np.zeros((0, 3)), np.zeros(0))
    assert not model.trained_ and model.source_ == "base-rate"
    p = model.predict_proba(np.zeros((4, 3)))
    assert np.all(p != 0.5) and np.allclose(p, 0.5, atol=1e-2)
    default = KernelOwnershipModel().fit(np.zeros((0, 3)), np.zeros(0)).predict_proba(np.zeros((2, 3)))
    assert np.allclose(default, PredictConfig().base_rate)


def test_one_sided_claims_lift_only_similar_objects() -> None:
    X = np.array([[2.0, 0.0]])
    model = KernelOwnershipModel().fit(X, np.ones(1))
    near, far, centre = model.predict_proba(np.array([[2.1, 0.0], [-3.0, 0.0], [0.0, 0.0]]))
    assert near > 0.5 > far
    assert abs(centre - PredictConfig().base_rate) < 0.15  # the intercept prior holds at the mean


def test_soft_label_equals_weighted_pair_of_hard_labels() -> None:
    # a claim of 0.7 is one "owned" example of weight 0.7 and one "not owned" of weight 0.3, so
    # duplicating an object with labels 1 and 0 in proportion 7:3 gives (nearly) the same model
    X = np.array([[0.0], [1.0], [3.0]])
    soft = KernelOwnershipModel().fit(X, np.array([0.7, 1.0, 0.0]))
    hard = KernelOwnershipModel()
    hard.fit(np.vstack([X[:1]] * 10 + [X[1:]]), np.r_[np.ones(7), np.zeros(3), 1.0, 0.0])
    # same loss up to the weight of the first object (10 rows vs 1): compare the fitted logits' signs
    Z = np.linspace(-1, 4, 11)[:, None]
    assert np.array_equal(soft.predict_proba(Z) >= 0.5, hard.predict_proba(Z) >= 0.5)
    assert 0.5 < soft.predict_proba(X[:1])[0] < 0.9


def test_predictions_are_deterministic() -> None:
    X, y = blobs(np.random.default_rng(2))
    a = KernelOwnershipModel().fit(X, y).predict_proba(X)
    b = KernelOwnershipModel().fit(X.copy(), y.copy()).predict_proba(X)
    assert np.array_equal(a, b)


def test_features_are_scale_free_in_position_and_time() -> None:
    rng = np.random.default_rng(3)
    pos = rng.uniform(-1, 1, size=(10, 3))
    ages = rng.exponential(100.0, size=10)
    colours = ["red", "blue"] * 5
    cfg = PredictConfig()
    base = agent_features(pos, colours, ages, ("blue", "red"), cfg)
    scaled = agent_features(pos * 7.0 + 3.0, colours, ages, ("blue", "red"), cfg)
    assert np.allclose(base, scaled)
    # colour mismatch costs color_weight**2 in squared distance
    d = base[0] - base[1]
    assert np.isclose((d[3:5] ** 2).sum(), cfg.color_weight**2)


def test_features_accept_unknown_positions_and_never_touched_objects() -> None:
    pos = np.array([[0.0, 0.0, 0.0], [np.nan, np.nan, np.nan], [1.0, 0.0, 0.0]])
    X = agent_features(pos, [None, "red", "red"], np.array([1.0, np.nan, 10.0]), ("red",), PredictConfig())
    assert np.isfinite(X).all()
    assert X[1, -1] == X[:, -1].max()  # never touched = the oldest
