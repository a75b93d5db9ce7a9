"""Percept features for ownership prediction (docs/architecture.md, section 5).

Per agent, an object is described by its position, its colour and how recently that agent touched
it, on a log scale: ``log1p(age in seconds)``. The original system used raw seconds, which makes
every rarely-touched object look unlike every other (a flaw of the original system); interaction times are
exponential, so their logarithm is the natural scale.

Position and log-recency are standardised by their spread over the rows given (pass every object
the robot knows, not just the claimed ones), so the kernel sees both in comparable units whatever
the size of the workspace or the time scale of interactions; the weights then set their relative
importance. Colour is a one-hot code whose mismatch costs ``color_weight**2`` in squared distance.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ownctl.config import PredictConfig

NEVER_AGE = 1.0e6  # seconds: the age used for an agent that never touched the object
NEVER_LOG = math.log1p(NEVER_AGE)
RECENCY_SAMPLE = 4096  # at most this many objects give the mean and spread of log-recency
MIN_SCALE = 1e-6


def _spread(values: np.ndarray) -> float:
    """Root-mean-square distance of the rows from their mean (1 when there is no spread)."""
    if len(values) < 2:
        return 1.0
    rms = float(np.sqrt(((values - values.mean(axis=0)) ** 2).sum(axis=1).mean()))
    return rms if rms > MIN_SCALE else 1.0


def percept_features(
    positions: np.ndarray, colors: Sequence[str | None], palette: Sequence[str | None], cfg: PredictConfig,
) -> np.ndarray:
    """(n, 3 + colours) weighted features every agent shares: standardised xyz and colour one-hot.

    ``positions`` (n, 3) may hold NaN (unknown position: placed at the mean position)."""
    pos = np.asarray(positions, dtype=float).reshape(-1, 3)
    n = len(pos)
    known = ~np.isnan(pos).any(axis=1)
    centre = pos[known].mean(axis=0) if known.any() else np.zeros(3)
    pos = np.where(known[:, None], pos, centre[None, :])
    pos = (pos - centre) / _spread(pos[known]) if known.any() else pos
    onehot = np.zeros((n, max(len(palette), 1)))
    index = {c: i for i, c in enumerate(palette)}
    column = np.fromiter((index.get(c, -1) if c is not None else -1 for c in colors), dtype=np.intp, count=n)
    held = column >= 0
    onehot[np.flatnonzero(held), column[held]] = 1.0
    return np.hstack([cfg.position_weight * pos, (cfg.color_weight / np.sqrt(2.0)) * onehot])


def recency_feature(ages: np.ndarray, cfg: PredictConfig, rows: np.ndarray | None = None) -> np.ndarray:
    """(n, 1) weighted standardised log-recency of one agent's touches; ``ages`` (n,) may hold NaN
    (never touched: ``NEVER_AGE``). With ``rows``, only those rows.

    The mean and spread are those of every object when there are at most ``RECENCY_SAMPLE``, else
    of every k-th object (k the smallest that leaves at most that many): a spread estimated from
    4,096 objects is within a few percent of the whole store's, and a claim in a large store, which
    reads the recency of every agent that lends (ownctl/ownership/predict.py), then reads each
    agent's touches at the claimed objects and the sample only."""
    age = np.asarray(ages, dtype=float).reshape(-1)
    n = len(age)
    sample = _log_recency(age[:: -(-n // RECENCY_SAMPLE)] if n > RECENCY_SAMPLE else age)
    mean = float(sample.mean()) if n else 0.0
    spread = _spread(sample[:, None]) if n else 1.0
    values = _log_recency(age if rows is None else age[np.asarray(rows, dtype=np.intp)])
    out: np.ndarray = (cfg.recency_weight * (values - mean) / spread)[:, None]
    return out


def _log_recency(age: np.ndarray) -> np.ndarray:
    """log(1 + age) of each age, ``NEVER_LOG`` (that of ``NEVER_AGE``) where NaN (never touched);
    the logarithm is taken of the touched ones only."""
    touched = np.flatnonzero(~np.isnan(age))
    out = np.full(len(age), NEVER_LOG)
    out[touched] = np.log1p(np.maximum(age[touched], 0.0))
    return out


def agent_features(
    positions: np.ndarray,
    colors: Sequence[str | None],
    ages: np.ndarray,
    palette: Sequence[str | None],
    cfg: PredictConfig,
    shared: np.ndarray | None = None,
) -> np.ndarray:
    """(n, d) weighted features for one agent: standardised xyz, colour one-hot, standardised log-recency.

    ``positions`` (n, 3) may hold NaN (unknown position: placed at the mean position); ``ages`` (n,)
    may hold NaN (never touched: ``NEVER_AGE``). The squared Euclidean distance between rows is the
    kernel's distance. The first two parts are :func:`percept_features` (``shared``, when the
    caller kept them for these percepts), the last :func:`recency_feature`.
    """
    common = percept_features(positions, colors, palette, cfg) if shared is None else shared
    return np.hstack([common, recency_feature(ages, cfg)])
