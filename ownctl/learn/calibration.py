"""How the learner reads uncertain ownership claims: a calibration of the claims chosen by evidence.

A claim arrives as a probability, but its source may be over- or under-confident, and may not
know how many objects are owned at all: a noisy "0.6 if it is theirs, else 0.4" label for each of
three agents says, read as three independent probabilities, that almost every object is owned by
someone. The stated model (:mod:`ownctl.learn.model`) therefore reads each ownership atom's given
probability ``p`` through a calibration ``c(p) = sigmoid(confidence * logit(p) + shift)`` (``0``
and ``1`` stay as they are: a certain claim stays certain), one of :data:`CALIBRATIONS`, and the
learner takes the calibration under which the permissions are most probable: the most probable
rule set's posterior (prior times likelihood) under each calibration is compared, a flat prior over
the calibrations, the identity first on ties (type-II maximum likelihood, with the most probable
rule set standing in for the sum over rule sets). With exact ownership every calibration gives the
same examples, and only the identity is tried.

The calibration is a property of how one action's permissions are explained: the rules are
learned, and the posterior over rule sets (:mod:`ownctl.learn.posterior`) is taken, on the examples
so calibrated; decisions on objects still use the ownership they are given.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ownctl.learn.evidence import Evidence

#: (confidence, shift) of each calibration tried, the identity first. A confidence above 1 reads
#: claims as surer than they say; a negative shift, as evidence that fewer objects are owned.
#: Chosen on tuning norm families with noisy claims (``docs/learning.md``).
CALIBRATIONS: tuple[tuple[float, float], ...] = ((1.0, 0.0), (4.0, -1.0))
IDENTITY = CALIBRATIONS[0]


def calibrate(p: np.ndarray, confidence: float, shift: float) -> np.ndarray:
    """``sigmoid(confidence * logit(p) + shift)`` elementwise; probabilities 0 and 1 are kept."""
    p = np.asarray(p, dtype=float)
    if (confidence, shift) == IDENTITY:
        return p
    inner = (p > 0.0) & (p < 1.0)
    safe = np.where(inner, p, 0.5)
    logit = np.log(safe) - np.log1p(-safe)
    return np.where(inner, 1.0 / (1.0 + np.exp(-(confidence * logit + shift))), p)


def uncertain(ev: Evidence) -> bool:
    """Whether some example's ownership is neither certain nor impossible (else calibrating it
    changes nothing)."""
    own = np.asarray(ev.frame.own)
    return bool(np.any((own > 0.0) & (own < 1.0)))


def calibrated(ev: Evidence, calibration: tuple[float, float]) -> Evidence:
    """The same examples with every ownership probability read through ``calibration``."""
    if calibration == IDENTITY:
        return ev
    frame = replace(ev.frame, own=calibrate(ev.frame.own, *calibration))
    return Evidence(frame, ev.t)


def candidates(ev: Evidence) -> tuple[tuple[float, float], ...]:
    """The calibrations worth trying on ``ev``: all of them with uncertain ownership, else the identity."""
    return CALIBRATIONS if uncertain(ev) else (IDENTITY,)
