"""An agent's predictors (``ownctl.ownership.predict.fit_scales``) are kept by content: a kept fit must
predict exactly what a fit computed afresh predicts, for inputs that differ in any part of their
content, and nobody may change a kept fit in place."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from ownctl.config import PredictConfig
from ownctl.ownership import predict
from ownctl.ownership.household import Household

Inputs = tuple[np.ndarray, np.ndarray, np.ndarray | None, PredictConfig, float, Household | None]


def base(seed: int) -> Inputs:
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(9, 3))
    p = rng.choice([0.0, 1.0, 0.8], size=9)
    p[2] = np.nan  # a silence
    return X, p, None, PredictConfig(recalibrate_min=4), 0.4, None


def variants(inputs: Inputs) -> list[Inputs]:
    """The inputs changed in one part each: a percept, a claim, a silence, a borrowed offset (given,
    then changed), the configuration, the silence's weight, the intercept's prior."""
    X, p, offset, cfg, kappa, household = inputs
    moved = X.copy()
    moved[0, 1] += 0.5
    claimed = p.copy()
    claimed[0] = 1.0 - claimed[0]
    spoken = p.copy()
    spoken[2] = 0.0
    shift = np.linspace(-1.0, 1.0, len(p))
    return [(moved, p, offset, cfg, kappa, household), (X, claimed, offset, cfg, kappa, household),
            (X, spoken, offset, cfg, kappa, household), (X, p, shift, cfg, kappa, household),
            (X, p, shift * 2, cfg, kappa, household),
            (X, p, offset, replace(cfg, gamma=0.7), kappa, household),
            (X, p, offset, cfg, 0.2, household), (X, p, offset, cfg, kappa, Household(-1.0, 0.5))]


def predictions(models: list[predict.KernelOwnershipModel], X: np.ndarray,
                offset: np.ndarray | None) -> np.ndarray:
    return np.array([m.predict_proba(X, offset) for m in models])


@pytest.mark.parametrize("seed", range(3))
def test_a_kept_fit_predicts_what_a_fresh_fit_predicts(seed: int) -> None:
    inputs = base(seed)
    for other in variants(inputs):
        predict._fits.clear()
        fresh = predict.fit_scales(*other)
        predict._fits.clear()
        predict.fit_scales(*inputs)  # kept first
        got = predict.fit_scales(*other)
        assert np.array_equal(predictions(got, other[0], other[2]), predictions(fresh, other[0], other[2]))
        assert [m.evidence_ for m in got] == [m.evidence_ for m in fresh]


def test_equal_content_gives_the_same_models_and_they_are_read_only() -> None:
    X, p, offset, cfg, kappa, household = base(7)
    first = predict.fit_scales(X, p, offset, cfg, kappa, household)
    again = predict.fit_scales(X.copy(), p.copy(), offset, replace(cfg), kappa, household)
    assert all(a is b for a, b in zip(first, again, strict=True))
    full = first[0]
    assert full.recalibration_ is not None  # the full scale keeps its leave-one-out system
    with pytest.raises(ValueError):
        full.coef_[0] = 1.0
    with pytest.raises(ValueError):
        full.support_[0, 0] = 1.0
    before = X[0, 0]
    X[0, 0] += 1.0  # the caller's array stays its own
    assert full.support_[0, 0] == before
