"""Conformal owner sets and the calibration figures (docs/asking.md, section 7).

Oracles: leave-one-out scores against refitting each agent's predictor without each claim; the
conformal quantile against its definition; the expected calibration error against a direct sum
over bins; coverage on Table 2's protocol near its target.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from ownctl.experiment.calibration import calibration, ece, reliability
from ownctl.experiment.ownership import OWNERSHIP_CONDITIONS, protocol
from ownctl.mind.conformal import NOT, OWNS, claims_needed, label_set, loo_scores, threshold
from ownctl.mind.core import Mind
from ownctl.ownership.predict import KernelOwnershipModel
from ownctl.world.generator import paper_blocks_world


def _refit_scores(mind: Mind, agent: str) -> np.ndarray:
    """Brute force: for each claim, the agent's predictor refitted on the others (borrowing as
    those claims would make it borrow), and 1 - its probability of the claimed label."""
    j = mind.agents.index(agent)
    X, known = mind.features(agent)
    idx = np.flatnonzero(known)
    out = []
    for k, i in enumerate(idx):
        others = np.delete(idx, k)
        claims = mind.claims[others, j]
        offset = mind.borrowed_term(agent, claims, X[:, -1])
        model = KernelOwnershipModel(mind.settings.predict).fit(
            X[others], claims, None if offset is None else offset[others])
        p = float(model.predict_proba(X[i : i + 1], None if offset is None else offset[i : i + 1])[0])
        out.append(1.0 - p if mind.claims[i, j] >= 0.5 else p)
    return np.array(out)


@pytest.mark.parametrize("seed", range(3))
def test_leave_one_out_scores_are_refits_without_each_claim(seed: int) -> None:
    mind, _, _ = protocol(paper_blocks_world, OWNERSHIP_CONDITIONS[0], "ours", np.random.default_rng(seed))
    for agent in mind.agents:
        got, want = loo_scores(mind, agent), _refit_scores(mind, agent)
        assert len(got) >= 6 and np.allclose(got, want, rtol=0, atol=1e-12)


def test_beyond_ten_claims_each_score_is_a_refit_without_its_fold() -> None:
    world = paper_blocks_world(np.random.default_rng(5), n_objects=40)
    mind = Mind(world.agents, list(world.objects), world.areas)
    truth = world.true_ownership()
    for i in range(30):
        for j, agent in enumerate(world.agents):
            mind.claim(i, agent, float(truth[i, j]))
    agent = world.agents[0]
    got = loo_scores(mind, agent)
    X, known = mind.features(agent)
    idx = np.flatnonzero(known)
    assert len(idx) == 30 and len(got) == 30
    for fold in range(10):
        held = np.arange(30) % 10 == fold
        rest = idx[~held]
        claims = mind.claims[rest, 0]
        offset = mind.borrowed_term(agent, claims, X[:, -1])
        model = KernelOwnershipModel(mind.settings.predict).fit(
            X[rest], claims, None if offset is None else offset[rest])
        p = model.predict_proba(X[idx[held]], None if offset is None else offset[idx[held]])
        want = np.where(mind.claims[idx[held], 0] >= 0.5, 1.0 - p, p)
        assert np.allclose(got[held], want, rtol=0, atol=1e-12)


def test_an_agent_without_claims_has_no_scores_and_keeps_both_labels() -> None:
    mind, _, _ = protocol(paper_blocks_world, OWNERSHIP_CONDITIONS[0], "ours", np.random.default_rng(0))
    mind.claims[:, 0] = np.nan
    mind._stale_agents([mind.agents[0]])
    assert len(loo_scores(mind, mind.agents[0])) == 0
    assert threshold(np.zeros(0), 0.9) == 1.0 and label_set(0.3, 1.0) == (OWNS, NOT)


@pytest.mark.parametrize("n", [1, 5, 9, 10, 19, 40])
def test_the_threshold_is_the_smallest_score_covering_its_rank(n: int) -> None:
    scores = np.random.default_rng(n).random(n)
    for coverage in (0.5, 0.8, 0.9, 0.95):
        need = math.ceil((n + 1) * coverage)
        q = threshold(scores, coverage)
        if need > n:
            assert q == 1.0
        else:  # the least q with at least `need` scores at or below it
            assert np.sum(scores <= q) >= need and np.sum(scores < q) < need


@pytest.mark.parametrize("coverage", [0.5, 0.8, 0.9, 0.95, 0.975])
def test_claims_needed_is_the_fewest_scores_below_which_every_set_holds_both_labels(coverage: float) -> None:
    need = claims_needed(coverage)
    assert need == {0.5: 1, 0.8: 4, 0.9: 9, 0.95: 19, 0.975: 39}[coverage]
    assert threshold(np.full(need - 1, 0.01), coverage) == 1.0  # one short: q = 1, both labels stay
    assert threshold(np.full(need, 0.01), coverage) == 0.01


def test_a_label_is_in_the_set_when_its_score_is_within_the_threshold() -> None:
    assert label_set(0.95, 0.1) == (OWNS,)
    assert label_set(0.05, 0.1) == (NOT,)
    assert label_set(0.5, 0.6) == (OWNS, NOT)
    assert label_set(0.5, 0.2) == ()


def test_ece_is_the_count_weighted_gap_of_each_bin() -> None:
    rng = np.random.default_rng(4)
    p = rng.random(500)
    y = (rng.random(500) < p ** 1.5).astype(float)
    want = 0.0
    for b in range(10):
        lo, hi = b / 10, (b + 1) / 10
        sel = (p >= lo) & ((p < hi) if b < 9 else (p <= hi))
        if sel.any():
            want += sel.sum() / len(p) * abs(p[sel].mean() - y[sel].mean())
    assert ece(p, y) == pytest.approx(want, abs=1e-12)
    assert sum(r["count"] for r in reliability(p, y)) == len(p)
    assert ece(np.full(8, 0.25), np.array([1, 0, 0, 0, 1, 0, 0, 0.0])) == pytest.approx(0.0)
    assert ece(np.zeros(0), np.zeros(0)) == 0.0


@pytest.mark.slow
def test_coverage_on_table_2s_protocol_is_near_its_target_and_predictions_are_calibrated() -> None:
    rows = calibration(paper_blocks_world, 20, 11, "ours", conditions=[0], coverage=0.9)
    assert abs(rows[0]["coverage"] - 0.9) <= 0.03
    assert rows[0]["ece"] <= 0.05
