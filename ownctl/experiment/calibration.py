"""Calibration of the ownership predictions on Table 2's protocol (docs/asking.md, section 7).

For every condition and trial of Table 2 (the same seeds, so the same worlds and halves), the
predictions the decisions see on the held-out objects (no permission there: the prior, a function of
the claims and percepts) are pooled over (object, agent) pairs: the expected calibration error
over 10 equal-width bins, ``sum_b (n_b / n) |mean p_b - frequency_b|``, and its reliability
diagram; and for each pair the split-conformal set of :mod:`ownctl.mind.conformal`, whose
empirical coverage (the share of pairs whose true label is in the set) and mean size are reported.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ownctl.experiment.norms import WorldFactory
from ownctl.experiment.ownership import OWNERSHIP_CONDITIONS, protocol
from ownctl.experiment.runner import trial_rng
from ownctl.mind.conformal import NOT, OWNS, label_set, loo_scores, threshold

BINS = 10


def reliability(p: np.ndarray, y: np.ndarray, bins: int = BINS) -> list[dict[str, float]]:
    """Per equal-width bin of ``p`` (the last one closed): its range, count, mean p and frequency."""
    edges = np.linspace(0.0, 1.0, bins + 1)
    which = np.clip(np.digitize(p, edges[1:-1], right=False), 0, bins - 1)
    out = []
    for b in range(bins):
        sel = which == b
        out.append({"lo": float(edges[b]), "hi": float(edges[b + 1]), "count": int(sel.sum()),
                    "mean_p": float(p[sel].mean()) if sel.any() else float("nan"),
                    "frequency": float(y[sel].mean()) if sel.any() else float("nan")})
    return out


def ece(p: np.ndarray, y: np.ndarray, bins: int = BINS) -> float:
    """The expected calibration error of probabilities ``p`` for 0/1 outcomes ``y``."""
    if len(p) == 0:
        return 0.0
    rows = reliability(np.asarray(p, float), np.asarray(y, float), bins)
    return float(sum(r["count"] / len(p) * abs(r["mean_p"] - r["frequency"]) for r in rows if r["count"]))


def calibration(make_world: WorldFactory, trials: int, seed: int, learner: str,
                conditions: Sequence[int] | None = None, coverage: float = 0.9) -> list[dict[str, Any]]:
    """Per condition: ECE, reliability bins, conformal coverage and set size on the held-out pairs."""
    out = []
    paper = [c for c, cond in enumerate(OWNERSHIP_CONDITIONS) if cond.claims == "all"]
    for c in paper if conditions is None else conditions:
        cond = OWNERSHIP_CONDITIONS[c]
        ps, ys, hits, sizes = [], [], [], []
        for t in range(trials):
            mind, world, test = protocol(make_world, cond, learner, trial_rng(seed, c, t))
            truth = world.true_ownership() >= 0.5
            post = mind.posterior()
            for j, agent in enumerate(world.agents):
                q = threshold(loo_scores(mind, agent), coverage)
                for i in test:
                    p = float(post[i, j])
                    ps.append(p)
                    ys.append(float(truth[i, j]))
                    labels = label_set(p, q)
                    hits.append((OWNS if truth[i, j] else NOT) in labels)
                    sizes.append(len(labels))
        p_arr, y_arr = np.array(ps), np.array(ys)
        out.append({"name": cond.name, "pairs": len(ps), "ece": ece(p_arr, y_arr),
                    "reliability": reliability(p_arr, y_arr), "coverage_target": coverage,
                    "coverage": float(np.mean(hits)) if hits else float("nan"),
                    "set_size": float(np.mean(sizes)) if sizes else float("nan")})
    return out
