"""How much a household's agents differ in how often they own things (docs/architecture.md,
section 5).

Each agent's predictor has an intercept: how often that agent owns an object, whatever it looks
like, with a Gaussian prior around the configured base rate. With the prior's configured width
(``intercept_scale``, 1 logit) the intercept follows the chance share of one agent's claims: ten
claims of which four say "owns" put an agent at about 0.4 where it owns a quarter of the objects.
Where percepts tell little of who owns what, that chance share is most of what the predictions
say, and they are badly calibrated.

How far an agent's rate strays from the base rate is a property of the household, read from every
agent's claims at once (as the scale is, ``pooled_scale`` in ``ownctl/ownership/predict.py``). An
agent's claims, ``k`` of ``n`` saying "owns" (weights allowed), are Bernoulli draws at its rate
``sigmoid(m + tau z)``, ``m`` the base rate's logit and ``z`` standard normal; the evidence of a
width ``tau`` is the product over the agents of that likelihood integrated over ``z``
(Gauss-Hermite quadrature). The width every intercept's prior uses is the most probable of
``household_spreads`` (times ``intercept_scale``; 1, 0.5 and 0.2), the first of equals winning
(``household_bonus``, 0 by default, is a log prior for the configured width): agents are pooled
towards the base rate when their claims say they are alike, and keep the configured width when
their claims say they differ.

The prior's centre stays the configured base rate: claims are often about objects chosen by what
happened (a robot corrected after acting on an owned object is told its owners), so their share of
"owns" is no estimate of the household's rate; their spread around the base rate is read only as
evidence of how alike the agents are. When silence weighs (``ownctl/ownership/silence.py``) the
claims are chosen by their answer, and the prior is the configured one, as it is with no claim.
The width is one of a few values, so it moves only now and then, and every predictor follows it
when it does.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.config import PredictConfig
from ownctl.ownership.link import logit, sigmoid

#: Gauss-Hermite nodes and weights (for integrals against exp(-x^2)), centred and scaled on each
#: agent's integrand (adaptive quadrature, as for generalised linear mixed models).
_HERMITE = np.polynomial.hermite.hermgauss(20)


@dataclass(frozen=True)
class Household:
    """The prior of every agent's intercept: its mean (a logit) and standard deviation."""

    mean: float
    spread: float

    @classmethod
    def configured(cls, cfg: PredictConfig) -> Household:
        """The prior without the household's claims: the configured base rate and intercept scale."""
        return cls(logit(cfg.base_rate), cfg.intercept_scale)


def household_prior(owned: Sequence[float] | np.ndarray, stated: Sequence[float] | np.ndarray,
                    cfg: PredictConfig | None = None, silence: float = 0.0) -> Household:
    """The prior of every agent's intercept given each agent's claims: ``owned`` their total
    weight for "owns", ``stated`` their number, one entry per agent (module docstring); the
    configured prior when silence weighs, no agent has a claim or ``household_spreads`` offers no
    other width."""
    cfg = cfg or PredictConfig()
    configured = Household.configured(cfg)
    n = np.asarray(stated, dtype=float)
    if silence > 0 or len(cfg.household_spreads) < 2 or not np.any(n > 0):
        return configured
    k = np.asarray(owned, dtype=float)
    return Household(configured.mean, pooled_spread(k[n > 0], n[n > 0], cfg, configured.mean))


def pooled_spread(owned: np.ndarray, stated: np.ndarray, cfg: PredictConfig, mean: float) -> float:
    """The width of the intercepts' prior around ``mean`` most probable given the agents' claims
    (``owned`` of ``stated``, one entry per agent), among ``cfg.household_spreads`` times
    ``cfg.intercept_scale``, the first with a log prior of ``cfg.household_bonus``; the first of
    equals wins."""
    candidates = [f * cfg.intercept_scale for f in cfg.household_spreads]
    evidence = np.array([spread_evidence(owned, stated, mean, tau) for tau in candidates])
    evidence[0] += cfg.household_bonus
    return float(candidates[int(np.flatnonzero(evidence >= evidence.max() - 1e-9)[0])])


def spread_evidence(owned: np.ndarray, stated: np.ndarray, mean: float, spread: float) -> float:
    """log p(claims | mean, spread): each agent's claims (``owned`` of ``stated`` say "owns")
    as Bernoulli draws at its rate ``sigmoid(mean + spread z)``, ``z`` standard normal, integrated
    by Gauss-Hermite quadrature centred on the mode of each agent's integrand and scaled by its
    curvature (exact to about 1e-9 for a few claims or thousands), summed over the agents."""
    k = np.asarray(owned, dtype=float)
    n = np.asarray(stated, dtype=float)

    def log_integrand(z: np.ndarray) -> np.ndarray:
        eta = mean + spread * z
        out: np.ndarray = (-k[:, None] * np.logaddexp(0.0, -eta) - (n - k)[:, None] * np.logaddexp(0.0, eta)
                           - z**2 / 2)
        return out

    mode = np.zeros(len(k))
    for _ in range(50):  # Newton's method on a concave function of z, one per agent
        rate = sigmoid(mean + spread * mode)
        slope = spread * (k - n * rate) - mode
        curve = spread**2 * n * rate * (1.0 - rate) + 1.0
        mode = mode + slope / curve
        if np.max(np.abs(slope / curve)) < 1e-12:
            break
    rate = sigmoid(mean + spread * mode)
    width = math.sqrt(2.0) / np.sqrt(spread**2 * n * rate * (1.0 - rate) + 1.0)
    nodes, weights = _HERMITE
    z = mode[:, None] + width[:, None] * nodes[None, :]
    terms = log_integrand(z) + nodes[None, :] ** 2
    top = terms.max(axis=1)
    mass = (np.exp(terms - top[:, None]) * weights[None, :]).sum(axis=1) * width / math.sqrt(2 * math.pi)
    return float(np.sum(top + np.log(mass)))


def claim_totals(claims: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per agent (column) of a claims table (objects x agents, NaN where none): the claims' total
    weight for "owns" and their number."""
    known = ~np.isnan(claims)
    return np.where(known, claims, 0.0).sum(axis=0), known.sum(axis=0).astype(float)
