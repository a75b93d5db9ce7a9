"""The paper's metrics, exactly as its evaluation code defined them (docs/architecture.md, section 8).

Positive class = "forbidden" (rules) or "owned" (ownership). Per-trial values are averaged over
trials and then over actions or agents (a macro-average), like the paper.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Scores:
    """Accuracy, precision, recall and F1 of one evaluation."""

    accuracy: float
    precision: float
    recall: float
    f1: float

    def as_array(self) -> np.ndarray:
        """The four numbers as an array, in field order."""
        return np.array([self.accuracy, self.precision, self.recall, self.f1])


def _prf(correct: np.ndarray, actual_pos: np.ndarray, predicted_pos: np.ndarray) -> Scores:
    n = len(correct)
    accuracy = float(correct.mean()) if n else 1.0
    recall = float(correct[actual_pos].mean()) if actual_pos.any() else 1.0
    precision = float(correct[predicted_pos].mean()) if predicted_pos.any() else 1.0
    f1 = 2 * precision * recall / (precision + recall) if precision + recall > 0 else 0.0
    return Scores(accuracy, precision, recall, f1)


def rule_scores(actual: np.ndarray, learned: np.ndarray) -> Scores:
    """Rules: correct when (actual - 0.5)(learned - 0.5) >= 0, so exactly 0.5 counts as correct."""
    actual, learned = np.asarray(actual, float), np.asarray(learned, float)
    correct = (actual - 0.5) * (learned - 0.5) >= 0
    return _prf(correct, actual >= 0.5, learned >= 0.5)


def decision_scores(actual: np.ndarray, p_forbidden: np.ndarray, threshold: float = 0.5) -> Scores:
    """Rules scored on the decisions they make: an object is refused iff ``p_forbidden`` is at least
    the obedience ``threshold``. A probability of exactly 0.5 thus counts as the refusal it causes;
    :func:`rule_scores`, the paper's measure, counts it correct whatever the truth, which would reward
    a decision rule for landing on 0.5 (docs/norm-families.md)."""
    decided = (np.asarray(p_forbidden, float) >= threshold).astype(float)
    return rule_scores(actual, decided)


def ownership_scores(truth: np.ndarray, predicted: np.ndarray) -> Scores:
    """Ownership: correct only when (t - 0.5)(p - 0.5) > 0 (strict: 0.5 is always wrong)."""
    truth, predicted = np.asarray(truth, float), np.asarray(predicted, float)
    correct = (truth - 0.5) * (predicted - 0.5) > 0
    return _prf(correct, truth >= 0.5, predicted >= 0.5)


def ci95(values: np.ndarray) -> float:
    """Half-width of the 95% t-interval of the mean of ``values``."""
    values = np.asarray(values, dtype=float)
    n = len(values)
    if n < 2:
        return 0.0
    from ownctl.experiment.student import t_quantile

    return float(t_quantile(0.975, n - 1) * values.std(ddof=1) / np.sqrt(n))
