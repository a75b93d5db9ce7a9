"""Recalibration of the ownership predictor on its leave-one-out logits (ownctl/ownership/predict.py).

The closed-form leave-one-out logits are checked against refitting without each claim; the
rescaling against the optimality conditions of its stated objective; the model keeps its logits
below ``recalibrate_min`` claims, and above it predicts with ``a f + b``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from ownctl.config import PredictConfig
from ownctl.ownership.link import sigmoid
from ownctl.ownership.predict import KernelOwnershipModel, _system, loo_logits, rescaling

RAW = replace(PredictConfig(), recalibrate_min=10**9)  # never recalibrates


def _problem(seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(6, 16))
    X = rng.normal(size=(n, 3))
    p = (X[:, 0] + 0.5 * rng.normal(size=n) > 0).astype(float)
    return X, (np.clip(0.8 * p + 0.1, 0.0, 1.0) if seed % 3 == 0 else p)


@pytest.mark.parametrize("seed", range(12))
def test_leave_one_out_logits_are_much_closer_to_refits_than_the_fitted_logits(seed: int) -> None:
    X, p = _problem(seed)
    n = len(p)
    model = KernelOwnershipModel(RAW).fit(X, p)
    design, penalty, _ = _system(X, RAW)
    approx = loo_logits(design, p, penalty, model.coef_, np.zeros(n))
    exact = np.array([KernelOwnershipModel(RAW).fit(X[np.arange(n) != i], p[np.arange(n) != i])
                      .decision_function(X[i : i + 1])[0] for i in range(n)])
    fitted = model.decision_function(X)
    assert np.mean(np.abs(approx - exact)) < min(0.1, 0.15 * np.mean(np.abs(fitted - exact)))
    moved = np.abs(exact - fitted) > 0.05  # and each logit that a refit moves, it moves the same way
    assert np.array_equal(np.sign(approx - fitted)[moved], np.sign(exact - fitted)[moved])


@pytest.mark.parametrize("seed", range(6))
def test_the_rescaling_is_the_optimum_of_its_penalised_objective(seed: int) -> None:
    rng = np.random.default_rng(seed)
    f = rng.normal(scale=2.0, size=20)
    y = sigmoid(3.0 * f - 0.5)  # soft targets sharper than the logits
    scale = 1.0
    a, b = rescaling(f, y, scale)
    s = sigmoid(a * f + b)
    grad = np.array([np.sum((s - y) * f) + (a - 1.0) / scale**2, np.sum(s - y) + b / scale**2])
    assert np.abs(grad).max() < 1e-6
    assert a > 1.0  # the targets are sharper than the logits say


def test_constant_targets_or_a_reversed_order_leave_the_logits_as_they_are() -> None:
    assert rescaling(np.array([-2.0, 0.5, 1.0]), np.zeros(3), 1.0) == (1.0, 0.0)
    f = np.linspace(-3.0, 3.0, 30)
    assert rescaling(f, (f < 0).astype(float), 1.0) == (1.0, 0.0)  # the fit's slope is negative


def test_below_the_minimum_the_model_keeps_its_logits_and_from_it_rescales_them() -> None:
    X, p = _problem(1)
    n = len(p)
    Z = np.random.default_rng(9).normal(size=(8, 3))
    raw = KernelOwnershipModel(RAW).fit(X, p)
    below = KernelOwnershipModel(replace(PredictConfig(), recalibrate_min=n + 1)).fit(X, p)
    assert below.rescale_ == (1.0, 0.0)
    assert np.array_equal(below.predict_proba(Z), raw.predict_proba(Z))
    at = KernelOwnershipModel(replace(PredictConfig(), recalibrate_min=n)).fit(X, p)
    a, b = at.rescale_
    assert (a, b) != (1.0, 0.0)
    assert np.allclose(at.decision_function(Z), a * raw.decision_function(Z) + b)
