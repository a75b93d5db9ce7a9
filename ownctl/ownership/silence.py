"""What an agent's silence about a claimed object says (docs/architecture.md, section 5).

People say "that's mine" of what they own and seldom "that's not mine" of what they do not: the
claims a robot hears are chosen by their answer. Fitted as if they were a random sample of the
agent's objects, owner-only claims teach that an agent owns everything that looks like anything
it claimed, and the predictions of a store told only "that's mine" are worse than those of a store
told nothing.

The claims are modelled with how they were chosen. An object *examined* is one some claim is about.
Of the (examined object, agent) pairs, one the agent owns is claimed with probability ``c1``, one
it does not own with probability ``c0``. An agent's silence about an examined object whose
ownership it predicts with probability ``s`` then has the likelihood ``1 - c1 s - c0 (1 - s)``,
proportional to ``1 - kappa s`` with ``kappa = (c1 - c0) / (1 - c0)``: nothing when claims do not
depend on their answer (``c1 = c0``: the paper's protocol, where every agent's ownership of a
claimed object is stated), "probably not mine" when only owners speak (``c0 = 0``).

``c1`` and ``c0`` are estimated over the whole household (how its people speak, not one agent's
habit). Of its ``T`` examined pairs, ``N+`` (the claims' total weight for "owns") were claimed as
owned, each with probability ``pi c1``, ``N-`` as not owned, each with probability ``(1 - pi) c0``,
and ``U = T - N+ - N-`` are silent, each with probability ``1 - pi c1 - (1 - pi) c0``, where ``pi``
is the prior probability that an agent owns an object (``PredictConfig.base_rate``). With a uniform
prior on ``c1`` and ``c0``, their posterior means (on a grid) give ``kappa``; the likelihood of a
silence is linear in them, so the means are what one silence weighs under their uncertainty. When
every pair of every examined object is claimed (``U = 0``: the paper's protocol), the posterior
says nothing of silence and ``kappa`` is 0, whatever share of the claims say "owns"; when only
owners speak, ``c0`` is near 0 and ``kappa`` near ``c1``. ``kappa`` is rounded down to a multiple
of ``silence_step`` (a claim moves it only now and then, and every predictor follows it) and kept
at most ``silence_max``: silence is never taken as a statement.

The row terms are for a Newton fit on logits ``f``: the loss ``-log(1 - kappa sigmoid(f))``, its
gradient ``s - q`` with ``q = s (1 - kappa) / (1 - kappa s)`` (the probability that a silent
agent owns the object: as if ``q`` were a soft claim), and its curvature where it is convex.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ownctl.config import PredictConfig
from ownctl.ownership.household import claim_totals

#: The grid of each selection probability, ``c1`` and ``c0`` (cell midpoints of [0, 1]).
_GRID = (np.arange(200) + 0.5) / 200


@lru_cache(maxsize=4096)  # a pure function of the census, asked again after every claim
def silence_weight(examined: int, agents: int, owned: float, not_owned: float,
                   cfg: PredictConfig | None = None) -> float:
    """``kappa`` for a household whose claims are about ``examined`` objects, with ``agents``
    agents, the claims' total weight ``owned`` for "owns" and ``not_owned`` for "does not own"
    (module docstring); 0 without silent pairs or with ``silence_step`` 0."""
    cfg = cfg or PredictConfig()
    silent = examined * agents - owned - not_owned
    if silent <= 1e-9 or cfg.silence_step <= 0:
        return 0.0
    mean1, mean0 = selection_means(owned, not_owned, silent, cfg.base_rate)
    kappa = max(0.0, (mean1 - mean0) / (1.0 - mean0))
    steps = math.floor(kappa / cfg.silence_step + 1e-9)
    return float(min(cfg.silence_max, round(steps * cfg.silence_step, 9)))


def selection_means(owned: float, not_owned: float, silent: float, prior: float) -> tuple[float, float]:
    """The posterior means of ``c1`` and ``c0`` under a uniform prior, given ``owned`` pairs
    claimed as owned, ``not_owned`` as not owned and ``silent`` pairs unclaimed, an agent owning a
    pair with probability ``prior`` (module docstring; a 200 x 200 grid of cell midpoints)."""
    c1, c0 = _GRID[:, None], _GRID[None, :]
    log_post = owned * np.log(c1) + not_owned * np.log(c0) + silent * np.log1p(-prior * c1 - (1 - prior) * c0)
    weight = np.exp(log_post - log_post.max())
    weight /= weight.sum()
    return float((weight * c1).sum()), float((weight * c0).sum())


def census(claims: np.ndarray) -> tuple[np.ndarray, float, float]:
    """Of a claims table (objects x agents, NaN where none): which objects are examined (some
    claim about them), the claims' total weight for "owns" and for "does not own"."""
    owned, stated = claim_totals(claims)
    return ~np.isnan(claims).all(axis=1), float(owned.sum()), float((stated - owned).sum())


def silent_loss(f: np.ndarray, kappa: float) -> float:
    """``-sum log(1 - kappa sigmoid(f))`` over logits ``f`` (0 when ``kappa`` is 0), computed
    without overflow."""
    if kappa <= 0 or len(f) == 0:
        return 0.0
    return float(np.sum(np.logaddexp(0.0, f) - np.logaddexp(0.0, f + math.log1p(-kappa))))


def silent_target(s: np.ndarray, kappa: float) -> np.ndarray:
    """``q = s (1 - kappa) / (1 - kappa s)``: P(owned) of a silent pair predicted ``s``; the loss's
    gradient in ``f`` is ``s - q``."""
    out: np.ndarray = s * (1.0 - kappa) / (1.0 - kappa * s)
    return out


def silent_curvature(s: np.ndarray, kappa: float) -> np.ndarray:
    """The loss's second derivative in ``f``, ``s (1 - s) (1 - (1 - kappa) / (1 - kappa s)^2)``,
    where it is positive, else 0 (a Newton step needs a convex model of the loss)."""
    out: np.ndarray = s * (1.0 - s) * np.maximum(0.0, 1.0 - (1.0 - kappa) / (1.0 - kappa * s) ** 2)
    return out
