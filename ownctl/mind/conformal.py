"""Split-conformal prediction sets over {owns, does not own} for one object and agent.

Pure core (docs/asking.md, section 7). Calibration scores come from the agent's claimed objects by
leave-one-out (by ten folds beyond ten claims): for each claimed object, the agent's predictor is
refitted on the other claims (of the other folds) and the score is ``1 - P(the claimed label)`` (a
claim of at least 0.5 is "owns"). With ``n`` scores and coverage ``1 - a``, ``q`` is the
``ceil((n + 1)(1 - a))``-th smallest score (1 when that exceeds ``n``: too few claims, both labels
stay in the set), and the set of an object is every label ``y`` with ``1 - P(y) <= q``, ``P`` the
prediction from all claims. For exchangeable objects the set holds the true label with
probability about ``1 - a`` (at least ``1 - 2a`` in the worst case of leave-one-out and
cross-conformal sets; measured, docs/asking.md, section 7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ownctl.errors import BadValue
from ownctl.mind.core import Mind
from ownctl.ownership.predict import KernelOwnershipModel

OWNS, NOT = "owns", "does not own"


@dataclass(frozen=True)
class PredictionSet:
    """One agent's conformal set for one object: the labels, the prediction, the threshold."""

    agent: str
    labels: tuple[str, ...]
    p: float
    q: float
    calibration: int  # how many claimed objects gave scores

    def as_dict(self) -> dict[str, object]:
        """``{"agent", "set", "p", "q", "calibration"}``."""
        return {"agent": self.agent, "set": list(self.labels), "p": self.p, "q": self.q,
                "calibration": self.calibration}


def check_coverage(coverage: float) -> float:
    """``coverage`` if strictly between 0 and 1; BadValue otherwise."""
    if not isinstance(coverage, int | float) or math.isnan(coverage) or not 0.0 < coverage < 1.0:
        raise BadValue(f"--coverage must be a number strictly between 0 and 1, got {coverage!r}")
    return float(coverage)


FOLDS = 10


def loo_scores(mind: Mind, agent: str) -> np.ndarray:
    """Held-out scores ``1 - P(claimed label)`` over the agent's claimed objects (object order):
    ``P`` the agent's predictor as the Mind fits it (its rows, scale and silence,
    :meth:`Mind.fit_inputs`) refitted without the claim, leave-one-out up to ``FOLDS`` claims;
    beyond, without the claim's fold, the claims split into ``FOLDS`` interleaved folds (claim
    ``k`` in fold ``k mod FOLDS``; cross-conformal), so that a store with hundreds of claims per
    agent costs ``FOLDS`` refits, not one per claim."""
    j = mind.agents.index(agent)
    idx = np.flatnonzero(~np.isnan(mind.claims[:, j]))
    claims = mind.claims[idx, j]
    folds = np.arange(len(idx)) % max(min(FOLDS, len(idx)), 1)
    out = np.empty(len(idx))
    cfg = mind.settings.predict
    for fold in range(min(FOLDS, len(idx))):
        held = folds == fold
        without = np.zeros(len(mind.objects), dtype=bool)
        without[idx[held]] = True
        # as the Mind's own predictor learns: its rows, borrowed term, scale, silence and household
        X, rows, targets, offset = mind.fit_inputs(agent, without)
        model = KernelOwnershipModel(cfg).fit(X[rows], targets, None if offset is None else offset[rows],
                                             cfg.scales[mind.scale], kappa=mind.silence,
                                             household=mind.household)
        p = model.predict_proba(X[idx[held]], None if offset is None else offset[idx[held]])
        out[held] = np.where(claims[held] >= 0.5, 1.0 - p, p)
    return out


def threshold(scores: np.ndarray, coverage: float) -> float:
    """The conformal quantile: the ceil((n + 1) coverage)-th smallest score, or 1 past n."""
    n = len(scores)
    rank = math.ceil((n + 1) * coverage)
    return 1.0 if rank > n else float(np.sort(scores)[rank - 1])


def claims_needed(coverage: float) -> int:
    """The fewest calibration scores with which a set can leave a label out at ``coverage``: the
    smallest ``n`` with ``ceil((n + 1) coverage) <= n`` (9 at 0.9, 19 at 0.95). With fewer, every
    unclaimed pair's set holds both labels."""
    coverage = check_coverage(coverage)
    n = 1
    while math.ceil((n + 1) * coverage) > n:
        n += 1
    return n


def label_set(p: float, q: float) -> tuple[str, ...]:
    """Every label whose score ``1 - P(label)`` is at most ``q`` (owns first)."""
    return tuple(label for label, score in ((OWNS, 1.0 - p), (NOT, p)) if score <= q + 1e-12)


def prediction_sets(mind: Mind, obj: int | str, coverage: float = 0.9) -> list[PredictionSet]:
    """Per agent, the conformal set of the object (its prior prediction; a claimed pair's set is
    its claimed label)."""
    coverage = check_coverage(coverage)
    i = mind.obj(obj)
    prior = mind.prior
    out = []
    for j, agent in enumerate(mind.agents):
        scores = loo_scores(mind, agent) if mind.switches.prediction else np.zeros(0)
        q = threshold(scores, coverage)
        p = float(prior[i, j])
        if not np.isnan(mind.claims[i, j]):
            out.append(PredictionSet(agent, (OWNS if p >= 0.5 else NOT,), p, q, len(scores)))
        else:
            out.append(PredictionSet(agent, label_set(p, q), p, q, len(scores)))
    return out
