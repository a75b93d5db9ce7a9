"""The logistic link between a probability and its logit, shared by the ownership predictor and
the household's prior of its intercepts (docs/architecture.md, section 5)."""

from __future__ import annotations

import numpy as np


def sigmoid(z: np.ndarray) -> np.ndarray:
    """``1 / (1 + exp(-z))`` elementwise, in a form that does not overflow."""
    out: np.ndarray = 0.5 * (1.0 + np.tanh(0.5 * z))
    return out


def logit(p: float) -> float:
    """log(p / (1 - p)) of a probability kept inside (1e-6, 1 - 1e-6)."""
    q = float(np.clip(p, 1e-6, 1 - 1e-6))
    return float(np.log(q / (1.0 - q)))
