"""How much a household's agents differ in how often they own things (ownctl/ownership/household.py).

Oracles: the evidence of a width against the integral over an agent's rate done on a fine grid;
the chosen width against the most probable one by brute force over the candidates; the width
recovered from households simulated with a known one (many agents, many claims each); the fit with
the household's prior against the maximum of its stated one-parameter posterior found on a grid;
the order of the agents (a property); and, as behaviour, the calibration of Table 2's protocol on
a world where percepts say nothing of who owns what.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ownctl.config import PredictConfig
from ownctl.ownership.household import (
    Household,
    claim_totals,
    household_prior,
    pooled_spread,
    spread_evidence,
)
from ownctl.ownership.predict import KernelOwnershipModel

CFG = PredictConfig()
MEAN = Household.configured(CFG).mean


def _evidence_on_a_grid(owned: list[float], stated: list[float], mean: float, spread: float) -> float:
    """The sum over agents of log of the integral over z of rate^k (1 - rate)^(n - k) N(z; 0, 1),
    by the trapezoid rule on a fine grid, in logs."""
    z = np.linspace(-12, 12, 400001)
    step = z[1] - z[0]
    total = 0.0
    for k, n in zip(owned, stated, strict=True):
        eta = mean + spread * z
        logs = (-k * np.logaddexp(0, -eta) - (n - k) * np.logaddexp(0, eta)
                - z**2 / 2 - 0.5 * math.log(2 * math.pi))
        top = logs.max()
        weights = np.full(len(z), step)
        weights[[0, -1]] /= 2
        total += top + math.log(float(np.sum(np.exp(logs - top) * weights)))
    return total


def test_without_claims_or_under_silence_the_prior_is_the_configured_one() -> None:
    configured = Household.configured(CFG)
    assert configured == Household(math.log(CFG.base_rate / (1 - CFG.base_rate)), CFG.intercept_scale)
    alike = ([25.0, 24.0, 26.0], [100.0, 100.0, 100.0])
    assert household_prior([0.0, 0.0], [0.0, 0.0], CFG) == configured
    assert household_prior(*alike, CFG, silence=0.4) == configured
    assert household_prior(*alike, replace(CFG, household_spreads=(1.0,))) == configured
    got = household_prior(*alike, CFG)
    assert got.mean == configured.mean and got.spread < CFG.intercept_scale


@pytest.mark.parametrize(("owned", "stated", "spread"), [
    ([4.0, 4.0, 2.0], [10.0, 10.0, 10.0], 1.0),
    ([0.0, 7.5, 1.0], [3.0, 9.0, 1.0], 0.2),
    ([30.0], [40.0], 2.0),
    ([2000.0, 10.0], [3000.0, 12.0], 0.5),
])
def test_the_evidence_of_a_width_is_the_integral_over_each_agent_s_rate(
        owned: list[float], stated: list[float], spread: float) -> None:
    got = spread_evidence(np.array(owned), np.array(stated), MEAN, spread)
    assert got == pytest.approx(_evidence_on_a_grid(owned, stated, MEAN, spread), abs=1e-6)


@pytest.mark.parametrize(("owned", "stated"), [
    ([25.0, 24.0, 26.0], [100.0, 100.0, 100.0]),  # alike: the narrowest
    ([90.0, 5.0, 40.0], [100.0, 100.0, 100.0]),  # far apart: the configured width
    ([1.0, 0.0, 0.0], [1.0, 1.0, 1.0]),  # a few claims: the configured width
    ([3.0, 2.0, 3.0, 2.0], [10.0, 10.0, 10.0, 10.0]),
])
def test_the_width_is_the_most_probable_candidate_by_brute_force(owned: list[float],
                                                                 stated: list[float]) -> None:
    candidates = [f * CFG.intercept_scale for f in CFG.household_spreads]
    scores = [_evidence_on_a_grid(owned, stated, MEAN, tau) + (CFG.household_bonus if i == 0 else 0.0)
              for i, tau in enumerate(candidates)]
    assert pooled_spread(np.array(owned), np.array(stated), CFG, MEAN) == candidates[int(np.argmax(scores))]


def test_alike_agents_are_pooled_and_different_ones_are_not() -> None:
    assert pooled_spread(np.array([25.0, 24.0, 26.0]), np.array([100.0] * 3), CFG, MEAN) == 0.2
    assert pooled_spread(np.array([90.0, 5.0, 40.0]), np.array([100.0] * 3), CFG, MEAN) == 1.0
    assert pooled_spread(np.array([1.0, 0.0, 0.0]), np.array([1.0] * 3), CFG, MEAN) == 1.0


@pytest.mark.parametrize("tau", [0.2, 0.6, 1.2])
def test_the_most_probable_width_recovers_a_simulated_household_s(tau: float) -> None:
    rng = np.random.default_rng(3)
    agents, claims = 300, 100
    owned = rng.binomial(claims, 1 / (1 + np.exp(-(MEAN + tau * rng.standard_normal(agents)))))
    fine = replace(CFG, household_spreads=tuple(np.round(np.arange(0.05, 2.0, 0.05), 2)), household_bonus=0.0)
    got = pooled_spread(owned.astype(float), np.full(agents, float(claims)), fine, MEAN)
    assert got == pytest.approx(tau, abs=0.15)


@given(st.lists(st.tuples(st.integers(0, 12), st.integers(0, 12)), min_size=1, max_size=6), st.randoms())
def test_the_order_of_the_agents_does_not_matter(counts: list[tuple[int, int]], shuffle: object) -> None:
    owned = [float(min(k, n)) for k, n in counts]
    stated = [float(n) for _, n in counts]
    order = list(range(len(counts)))
    shuffle.shuffle(order)  # type: ignore[attr-defined]
    assert household_prior(owned, stated, CFG) == household_prior(
        [owned[i] for i in order], [stated[i] for i in order], CFG)


def test_claim_totals_count_each_agent_s_claims() -> None:
    claims = np.array([[1.0, np.nan], [0.0, 0.8], [np.nan, np.nan], [1.0, 0.0]])
    owned, stated = claim_totals(claims)
    np.testing.assert_allclose(owned, [2.0, 0.8])
    np.testing.assert_allclose(stated, [3.0, 2.0])


def test_identical_objects_fit_the_intercept_s_stated_posterior_mode() -> None:
    """With every claimed object alike, the fit's prediction is sigmoid(b*), b* the maximum of
    k log sigmoid(b) + (n - k) log(1 - sigmoid(b)) - (b - mean)^2 / (2 spread^2), percepts aside
    (the smallest scale leaves them next to nothing)."""
    cfg = replace(CFG, scales=(1e-6,), recalibrate_min=1000)
    household = Household(mean=-1.0, spread=0.3)
    X = np.zeros((10, 4))
    p = np.array([1.0] * 4 + [0.0] * 6)
    model = KernelOwnershipModel(cfg).fit(X, p, scale=1e-6, household=household)
    grid = np.linspace(-4, 4, 400001)
    objective = (4 * -np.logaddexp(0, -grid) + 6 * -np.logaddexp(0, grid)
                 - (grid - household.mean) ** 2 / (2 * household.spread**2))
    best = grid[np.argmax(objective)]
    assert model.predict_proba(X[:1])[0] == pytest.approx(1 / (1 + math.exp(-best)), abs=1e-4)
    wide = KernelOwnershipModel(cfg).fit(X, p, scale=1e-6)  # the configured, looser prior
    assert abs(wide.predict_proba(X[:1])[0] - 0.4) < abs(model.predict_proba(X[:1])[0] - 0.4)


@pytest.mark.slow
def test_where_percepts_say_nothing_the_household_prior_calibrates_table_2(
        monkeypatch: pytest.MonkeyPatch) -> None:
    import ownctl.experiment.ownership as table2
    from ownctl.app.experiment import load_world
    from ownctl.config import Settings
    from ownctl.experiment.calibration import ece
    from ownctl.experiment.runner import trial_rng

    make_world = load_world("scenarios/scattered.toml")
    errors = {}
    for spreads in ((1.0,), CFG.household_spreads):
        predict = replace(CFG, household_spreads=spreads)
        monkeypatch.setattr(table2, "Settings",
                            lambda learn, predict=predict: Settings(learn=learn, predict=predict))
        ps, ys = [], []
        for t in range(30):
            mind, world, test = table2.protocol(make_world, table2.OWNERSHIP_CONDITIONS[0], "ours",
                                                trial_rng(11, 0, t))
            ps.append(mind.posterior()[test].ravel())
            ys.append((world.true_ownership()[test] >= 0.5).ravel())
        errors[spreads] = ece(np.concatenate(ps), np.concatenate(ys).astype(float))
    assert errors[CFG.household_spreads] < errors[(1.0,)] - 0.01
