"""What other agents' claims teach (ownctl/ownership/predict.py; docs/architecture.md, section 5).

An agent that no claim says owns anything borrows how recency reads from the other agents' claims:
the pooled fit is the stated MAP problem (checked against a general-purpose optimiser), its slope
rounded to a grid, a model fitted with a borrowed recency term corrects it, and in a Mind only such
agents borrow, follow the others' claims when the rounded slope moves (and only then), end where a
Mind told the same claims at once ends, and predict their own objects better for it on the paper's
blocks world.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import minimize

from ownctl.config import PredictConfig, Settings
from ownctl.mind import Mind, Switches
from ownctl.ownership.predict import KernelOwnershipModel, borrows, fit_shared_recency, rounded
from ownctl.world.generator import paper_blocks_world


def _objective(theta: np.ndarray, r: np.ndarray, y: np.ndarray, cfg: PredictConfig) -> float:
    f = theta[1] + theta[0] * r
    nll = np.logaddexp(0.0, -f) * y + np.logaddexp(0.0, f) * (1.0 - y)
    base = np.log(cfg.base_rate / (1 - cfg.base_rate))
    prior = theta[0] ** 2 / cfg.C + (theta[1] - base) ** 2 / cfg.intercept_scale**2
    return float(nll.sum() + 0.5 * prior)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_pooled_fit_is_the_stated_map_estimate(seed: int) -> None:
    rng = np.random.default_rng(seed)
    r = rng.normal(size=15)
    y = np.clip((r < 0).astype(float) * 0.9 + rng.uniform(0, 0.1, 15), 0, 1)
    cfg = replace(PredictConfig(), share_step=0.0)  # unrounded
    shared = fit_shared_recency(r, y, cfg)
    assert shared is not None
    oracle = minimize(_objective, np.zeros(2), args=(r, y, cfg), method="BFGS", options={"gtol": 1e-10})
    assert np.allclose([shared.slope, shared.intercept], oracle.x, atol=1e-5)
    assert shared.slope < 0  # recent (low log-age) objects are the owned ones here
    assert np.allclose(shared.term(r), shared.slope * r)
    step = PredictConfig().share_step
    on_grid = fit_shared_recency(r, y)
    assert on_grid is not None and on_grid.intercept == shared.intercept
    assert on_grid.slope == rounded(shared.slope, step)
    assert abs(on_grid.slope - shared.slope) <= step / 2 + 1e-12
    assert on_grid.slope / step == pytest.approx(round(on_grid.slope / step), abs=1e-9)


def test_rounding_to_a_grid() -> None:
    assert rounded(-1.13, 0.25) == -1.25
    assert rounded(-1.12, 0.25) == -1.0
    assert rounded(0.3, 0.0) == 0.3
    assert rounded(0.1, 0.25) == 0.0


def test_claims_that_own_nothing_teach_nothing_to_borrow() -> None:
    assert fit_shared_recency(np.array([0.1, -1.0]), np.array([0.0, 0.3])) is None
    assert fit_shared_recency(np.zeros(0), np.zeros(0)) is None
    assert borrows(np.array([0.0, 0.49])) and borrows(np.zeros(0)) and not borrows(np.array([0.0, 0.5]))


def test_a_model_fitted_around_an_offset_corrects_it_and_needs_it_to_predict() -> None:
    rng = np.random.default_rng(3)
    X = rng.normal(size=(8, 2))
    offset = 2.0 * X[:, 1]
    untrained = KernelOwnershipModel().fit(X[:0], np.zeros(0), offset[:0])
    base = np.log(PredictConfig().base_rate / (1 - PredictConfig().base_rate))
    assert np.allclose(untrained.predict_proba(X, offset), 1 / (1 + np.exp(-(base + offset))))
    assert untrained.source_ == "prediction"
    p = (X[:, 0] > 0).astype(float)
    model = KernelOwnershipModel().fit(X, p, offset)
    logit = model.decision_function(X, offset)
    assert np.allclose(logit - model.rescale_[0] * offset, model.decision_function(X, np.zeros(8)))
    plain = KernelOwnershipModel().fit(X, p)
    assert not np.allclose(model.predict_proba(X, offset), plain.predict_proba(X))
    with pytest.raises(ValueError):
        model.predict_proba(X)
    with pytest.raises(ValueError):
        plain.predict_proba(X, offset)


def _mind(seed: int, share: bool, step: float = PredictConfig().share_step) -> tuple[Mind, np.ndarray]:
    """A Mind of a paper world; what silence says is off (silence_step 0): these tests are about
    what borrowers learn from the lenders' claims alone (tests/ownership/test_ownership_silence.py
    and tests/mind/test_mind_silence.py are about silence)."""
    world = paper_blocks_world(np.random.default_rng(seed))
    settings = Settings(predict=replace(PredictConfig(), share_recency=share, share_step=step,
                                        silence_step=0.0))
    mind = Mind(world.agents, list(world.objects), world.areas, settings, Switches())
    return mind, world.true_ownership()


def _teach(mind: Mind, truth: np.ndarray, objects: range) -> None:
    """Claims of every agent about ``objects``, as the task's instructor states owners."""
    for i in objects:
        for j, agent in enumerate(mind.agents):
            mind.claim(i, agent, float(truth[i, j]))


def test_only_agents_no_claim_says_own_anything_borrow() -> None:
    mind, truth = _mind(0, share=True)
    alone, _ = _mind(0, share=False)
    _teach(mind, truth, range(1, 2))  # block2: agent1's; agents 2 and 3 own nothing claimed
    _teach(alone, truth, range(1, 2))
    assert np.array_equal(mind.prior[:, 0], alone.prior[:, 0])  # agent1 learns from its own claims
    assert not np.allclose(mind.prior[:, 1], alone.prior[:, 1])
    assert mind.borrowed_term("agent2", mind.claims[1:2, 1]) is not None
    assert mind.borrowed_term("agent1", mind.claims[1:2, 0]) is None
    mind.claim(2, "agent2", 1.0)  # agent2 now owns something claimed: it stops borrowing
    alone.claim(2, "agent2", 1.0)
    assert np.array_equal(mind.prior[:, 1], alone.prior[:, 1])


def test_a_borrower_follows_the_other_agents_claims() -> None:
    mind, truth = _mind(1, share=True, step=0.0)
    _teach(mind, truth, range(1, 2))
    before = mind.prior[:, 2].copy()
    mind.claim(5, "agent1", 1.0)  # a claim about agent1 changes what agent3 borrows
    assert not np.allclose(mind.prior[:, 2], before)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_borrowers_are_refitted_when_the_rounded_slope_moves_and_only_then(seed: int) -> None:
    """Claims about the lender one at a time: a borrower's priors change exactly when the lent
    slope does, the lent slope is the rounded fit of the lenders' claims, and the priors end where a
    Mind told every claim at once ends (the order of refits leaves no trace)."""
    mind, truth = _mind(seed, share=True)
    owner = int(np.flatnonzero(truth[:, 0])[0])
    mind.claim(owner, "agent1", 1.0)
    moved = kept = 0
    for i in range(len(mind.objects)):
        if i == owner:
            continue
        before, lent = mind.prior[:, 1:].copy(), mind.lent
        mind.claim(i, "agent1", float(truth[i, 0]))
        _ = mind.prior
        shared = mind._lent(None)
        assert shared is not None and mind.lent == shared.slope
        if mind.lent == lent:
            kept += 1
            assert np.array_equal(mind.prior[:, 1:], before)
        else:
            moved += 1
            assert not np.allclose(mind.prior[:, 1:], before)
    assert moved > 0 and kept > 0  # both happen over a world's claims
    fresh, _ = _mind(seed, share=True)
    for i in range(len(mind.objects)):
        fresh.claims[i, 0] = mind.claims[i, 0]
    fresh._stale_agents(fresh.agents)
    assert np.allclose(fresh.prior, mind.prior, atol=1e-12)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_borrowing_predicts_a_borrowers_own_objects_better(seed: int) -> None:
    """After the owners of one object are stated (one agent's), the other agents' objects are
    found by how recently they touched them: a lower log loss on their true ownership."""
    losses = {}
    for share in (True, False):
        mind, truth = _mind(seed, share)
        _teach(mind, truth, range(1, 2))
        p = np.clip(mind.prior[:, 1:], 1e-9, 1 - 1e-9)
        y = truth[:, 1:]
        losses[share] = float(-(y * np.log(p) + (1 - y) * np.log(1 - p)).mean())
    assert losses[True] < losses[False]
