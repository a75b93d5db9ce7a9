"""Percept features for ownership prediction (DESIGN section 5).

Per agent, an object is described by its position, its colour and how recently that agent touched
it, on a log scale: ``log1p(age in seconds)``. The original system used raw seconds, which makes
every rarely-touched object look unlike every other (reference section 9.3); interaction times are
exponential, so their logarithm is the natural scale.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ownctl.config import PredictConfig

NEVER_AGE = 1.0e6  # seconds: the age used for an agent that never touched the object


def agent_features(
    positions: np.ndarray,
    colors: Sequence[str | None],
    ages: np.ndarray,
    palette: Sequence[str | None],
    cfg: PredictConfig,
) -> np.ndarray:
    """(n, d) weighted features for one agent: scaled xyz, scaled colour one-hot, scaled log-recency.

    ``positions`` (n, 3) may hold NaN (unknown position: centred at 0); ``ages`` (n,) may hold NaN
    (never touched). Squared Euclidean distance between rows is the kernel's distance: position
    weight times metres, colour mismatch adds ``color_weight**2``, recency weight times log-seconds.
    """
    pos = np.nan_to_num(np.asarray(positions, dtype=float).reshape(-1, 3), nan=0.0)
    n = len(pos)
    onehot = np.zeros((n, max(len(palette), 1)))
    index = {c: i for i, c in enumerate(palette)}
    for i, c in enumerate(colors):
        if c in index:
            onehot[i, index[c]] = 1.0
    age = np.asarray(ages, dtype=float).reshape(n)
    age = np.where(np.isnan(age), NEVER_AGE, np.maximum(age, 0.0))
    recency = np.log1p(age)[:, None]
    return np.hstack(
        [
            cfg.position_weight * pos,
            (cfg.color_weight / np.sqrt(2.0)) * onehot,
            cfg.recency_weight * recency,
        ]
    )
