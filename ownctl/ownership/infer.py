"""Rule-based Bayesian inference of ownership from object-specific permissions (paper, Eq. 1).

Given an object's prior ownership atoms (independent Bernoulli variables), the rules of each action
and the instructor's permissions on that object, the posterior of every atom is obtained by exact
conditioning over the joint assignments of the atoms the rules mention (the other agents fold into
one atom, as in :mod:`ownctl.logic.prob`). The paper's Eq. 1 conditions on one permission; here all
of an object's permissions are conditioned on at once.

A permission with value f (1 forbid, 0 allow; soft values allowed) has likelihood
``f * P(say forbid | world) + (1 - f) * P(say allow | world)`` where the instructor says what the
rules imply with probability ``1 - noise``. The noise term means evidence the rules cannot explain
(a forbid on an object no rule could cover) leaves the prior in place instead of zeroing every
owner (the original code's bug B2).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.logic.prob import OTHER, enumerate_worlds, relevant_atoms, rule_truth
from ownctl.logic.rules import Rule


def _group_keys(
    permissions: Mapping[str, np.ndarray], actions: Sequence[str], n: int
) -> list[tuple[str, ...]]:
    """For each object, the actions (with rules) that have a permission on it."""
    known = {a: ~np.isnan(np.asarray(permissions[a], dtype=float)) for a in actions}
    return [tuple(a for a in actions if known[a][i]) for i in range(n)]


def posterior(
    frame: Frame,
    rule_sets: Mapping[str, Sequence[Rule]],
    permissions: Mapping[str, np.ndarray],
    noise: float = 0.05,
    seen: Mapping[str, Frame] | None = None,
) -> np.ndarray:
    """Posterior ownership (n, m) of the frame's objects given their permissions.

    ``frame.own`` holds the priors. ``permissions[action]`` is a length-n vector of values in [0, 1]
    with NaN where the object has no permission for that action. Objects without any permission on
    an action that has rules keep their prior exactly. Rules that do not mention ownership change
    nothing. ``seen[action]`` (same objects and agents as ``frame``) holds the percepts each object
    had when its permission of that action was given; an action's rules are evaluated on those
    (default: ``frame``'s percepts).
    """
    out = frame.own.copy()
    actions = sorted(a for a, rules in rule_sets.items() if rules and a in permissions)
    if not actions or frame.n == 0:
        return out
    keys = _group_keys(permissions, actions, frame.n)
    for key in sorted(set(keys)):
        if not key:
            continue
        idx = np.array([i for i, k in enumerate(keys) if k == key])
        part = frame.take(idx)
        views = [part if seen is None or a not in seen else seen[a].take(idx).with_own(part.own) for a in key]
        out[idx] = _posterior_group(part, views, [rule_sets[a] for a in key],
                                    [np.asarray(permissions[a], dtype=float)[idx] for a in key], noise)
    return out


def _posterior_group(
    frame: Frame, views: list[Frame], rule_sets: list[Sequence[Rule]], values: list[np.ndarray],
    noise: float,
) -> np.ndarray:
    """Posterior for objects that share the same set of evidenced actions (``views``: each action's
    percepts of them, with ``frame``'s priors)."""
    named, uses_any = relevant_atoms(rule_sets)
    named = tuple(a for a in named if a in frame.agents)
    if not named and not uses_any:
        return frame.own.copy()
    worlds = enumerate_worlds(frame, named, with_other=True)
    joint = worlds.weights.copy()  # (W, n)
    for view, rules, f in zip(views, rule_sets, values, strict=True):
        truth = rule_truth(rules, view, worlds)
        p_say_forbid = np.where(truth, 1.0 - noise, noise)
        joint *= f[None, :] * p_say_forbid + (1.0 - f[None, :]) * (1.0 - p_say_forbid)
    total = joint.sum(axis=0)
    safe = np.where(total > 0, total, 1.0)
    marg = (joint[:, None, :] * worlds.bits[:, :, None]).sum(axis=0) / safe  # (K, n)
    out = frame.own.copy()
    for k, atom in enumerate(worlds.atoms):
        if atom == OTHER:
            prior_other = worlds.probs[k]
            scale = np.divide(marg[k], prior_other, out=np.zeros_like(prior_other), where=prior_other > 0)
            for j, agent in enumerate(frame.agents):
                if agent not in named:
                    out[:, j] = np.clip(frame.own[:, j] * scale, 0.0, 1.0)
        else:
            out[:, frame.agents.index(atom)] = marg[k]
    return np.where((total > 0)[:, None], out, frame.own)
