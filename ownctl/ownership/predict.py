"""Percept-based ownership prediction: per-agent kernel logistic regression on soft labels.

:class:`KernelOwnershipModel` is a scikit-learn-style estimator: ``__init__`` stores settings,
``fit(X, p)`` learns from feature rows ``X`` and claim probabilities ``p`` (soft targets: each
claim enters once as "owned" with weight p and once as "not owned" with weight 1 - p) and returns
self, ``predict_proba(X)`` gives P(owned). The kernel map is exact (Nystroem with as many
components as training rows) plus the raw features, so the model can extrapolate linearly in
log-recency far from the claimed objects.

With too few claims, or claims that are all on one side, the model is a calibrated prior instead:
the mean of the claims shrunk towards ``base_rate`` by pseudo-counts, never exactly 0.5.
"""

from __future__ import annotations

import numpy as np

from ownctl.config import PredictConfig


class KernelOwnershipModel:
    """Kernel logistic regression of P(ownedBy(object, agent)) on one agent's percept features."""

    def __init__(self, cfg: PredictConfig | None = None) -> None:
        self.cfg = cfg or PredictConfig()

    def prior_(self, p: np.ndarray) -> float:
        """Calibrated prior: claims shrunk towards the base rate (4 pseudo-claims), off the 0.5 line."""
        pseudo = 4.0
        value = (float(np.sum(p)) + pseudo * self.cfg.base_rate) / (len(p) + pseudo)
        return value if abs(value - 0.5) > 1e-3 else 0.5 - 1e-3

    def fit(self, X: np.ndarray, p: np.ndarray) -> KernelOwnershipModel:
        """Fit on feature rows ``X`` (n, d) and soft targets ``p`` (n,) in [0, 1]; returns self."""
        X = np.asarray(X, dtype=float)
        p = np.clip(np.asarray(p, dtype=float).reshape(len(X)), 0.0, 1.0)
        self.base_ = self.prior_(p)
        self.n_claims_ = len(p)
        owned_mass, free_mass = float(p.sum()), float((1 - p).sum())
        self.trained_ = len(p) >= self.cfg.min_claims and owned_mass >= 0.5 and free_mass >= 0.5
        if not self.trained_:
            return self
        from sklearn.kernel_approximation import Nystroem
        from sklearn.linear_model import LogisticRegression

        self.map_ = Nystroem(kernel="rbf", gamma=self.cfg.gamma, n_components=len(X), random_state=0).fit(X)
        features = self._features(X)
        y = np.r_[np.ones(len(X)), np.zeros(len(X))]
        w = np.r_[p, 1.0 - p]
        keep = w > 0
        self.clf_ = LogisticRegression(C=self.cfg.C, max_iter=1000).fit(
            np.vstack([features, features])[keep], y[keep], sample_weight=w[keep]
        )
        return self

    def _features(self, X: np.ndarray) -> np.ndarray:
        return np.hstack([self.map_.transform(X), X])

    def predict_proba(self, X: np.ndarray) -> np.ndarray:
        """P(owned) for each row of ``X`` (n,)."""
        X = np.asarray(X, dtype=float)
        if not self.trained_:
            return np.full(len(X), self.base_)
        return self.clf_.predict_proba(self._features(X))[:, 1]

    @property
    def source_(self) -> str:
        """Where predictions come from: ``prediction`` (trained) or ``base-rate`` (calibrated prior)."""
        return "prediction" if self.trained_ else "base-rate"
