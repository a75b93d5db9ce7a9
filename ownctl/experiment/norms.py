"""Table 1: learning norms from object-specific permissions (docs/architecture.md, section 8).

Each trial draws a new world, gives ownership claims for every object (exact, or noisy: each
agent's label is 0.6 if it owns the object else 0.4, plus uniform noise of +-0.2), then permissions
for a fraction of the objects, for every action with a true norm. Inference and prediction are off,
as in the paper. Each action's permissions are taught together (:meth:`ownctl.mind.Mind.permit_all`):
the default learner's rules depend only on the set of permissions, so learning once after the last
gives the rules of learning after each, which the paper's learner still does. The learned rules
are scored against the true norms on all objects with their true ownership.

On a norm family (:class:`ownctl.world.families.NormFamily`) the same protocol gives permissions
for, and scores, every action the family names, including those with no norm (where every
permission allows).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ownctl.config import LearnConfig, Settings
from ownctl.experiment.metrics import Scores, decision_scores
from ownctl.experiment.result import TrialResult
from ownctl.experiment.truth import true_rules
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import Rule
from ownctl.mind import Mind, Switches
from ownctl.world.families import NormFamily
from ownctl.world.model import World, make_frame

WorldFactory = Callable[[np.random.Generator], World]


@dataclass(frozen=True)
class NormCondition:
    """One column of Table 1: fraction of objects with permissions, ownership noise."""

    name: str
    fraction: float
    noisy: bool
    baseline: bool = False


NORM_CONDITIONS = (
    NormCondition("noiseless 1.00", 1.0, False),
    NormCondition("noiseless 0.50", 0.5, False),
    NormCondition("noiseless 0.25", 0.25, False),
    NormCondition("noisy 1.00", 1.0, True),
    NormCondition("noisy 0.50", 0.5, True),
    NormCondition("noisy 0.25", 0.25, True),
    NormCondition("allow everything", 0.0, False, baseline=True),
)


def noisy_labels(truth: np.ndarray, rng: np.random.Generator, mean: float = 0.6,
                 dev: float = 0.2) -> np.ndarray:
    """The paper's noisy ownership labels: ``mean`` if owned else ``1 - mean``, +- U(dev), clipped."""
    base = np.where(truth >= 0.5, mean, 1.0 - mean)
    return np.clip(base + rng.uniform(-dev, dev, size=truth.shape), 0.0, 1.0)


@dataclass(frozen=True)
class NormsSetup:
    """What one trial gives a learner, and what it is scored against: the world, the ownership
    claims (exact or noisy), the objects given permissions (in the order they are given), and per
    scored action its true rules and true answer on every object (true owners)."""

    world: World
    claims: np.ndarray
    chosen: np.ndarray
    rules: dict[str, tuple[Rule, ...]]
    answers: dict[str, np.ndarray]
    true_frame: Frame


def norms_setup(make_world: WorldFactory, cond: NormCondition, rng: np.random.Generator) -> NormsSetup:
    """Draw one trial (world, claims, permitted objects) exactly as :func:`norms_trial` does, so
    other learners can be run on the very same trials."""
    world = make_world(rng)
    truth = world.true_ownership()
    rules = true_rules(world)
    if isinstance(make_world, NormFamily):  # its actions without a norm are given permissions too
        rules = {a: rules.get(a, ()) for a in make_world.actions}
    true_frame = make_frame(world.objects, world.areas, world.agents, truth)
    claims = noisy_labels(truth, rng) if cond.noisy else truth
    n = len(world.objects)
    chosen = rng.permutation(n)[: int(round(cond.fraction * n))]
    answers = {a: p_forbidden(r, true_frame) for a, r in rules.items()}
    return NormsSetup(world, claims, chosen, rules, answers, true_frame)


def taught_mind(setup: NormsSetup, learner: str = "ours", decide: str = "map", together: bool = True) -> Mind:
    """A Mind of the trial's world given its claims and then its permissions, inference and
    prediction off (``decide``: how its rules decide, ``decide.rules``).

    ``together``: each action's permissions are taught in one :meth:`Mind.permit_all`, which learns
    after each only where the learner depends on their order (the paper's); otherwise every
    permission is taught on its own, object by object. Both give the same rules."""
    world = setup.world
    settings = Settings(learn=LearnConfig(learner=learner), decide_rules=decide)
    mind = Mind(world.agents, list(world.objects), world.areas, settings,
                Switches(inference=False, prediction=False))
    mind.claims[:] = setup.claims
    if together:
        for action in setup.rules:  # each action's rules are learned from its own permissions only
            mind.permit_all(action, [(int(obj), float(setup.answers[action][obj])) for obj in setup.chosen])
        return mind
    for obj in setup.chosen:
        for action in setup.rules:
            mind.permit(action, int(obj), float(setup.answers[action][obj]))
    return mind


def norms_trial(make_world: WorldFactory, cond: NormCondition, learner: str,
                rng: np.random.Generator, decide: str = "map", together: bool = True) -> dict[str, Scores]:
    """One trial of one condition; per-action scores of the decisions the learned rules make on
    every object (refused iff P(forbidden) reaches the threshold, :func:`decision_scores`;
    ``decide``: ``decide.rules``; ``together``: as :func:`taught_mind`). The baseline condition
    teaches nothing (allowing everything)."""
    setup = norms_setup(make_world, cond, rng)
    empty = replace(setup, chosen=setup.chosen[:0]) if cond.baseline else setup
    mind = taught_mind(empty, learner, decide, together)
    frame = setup.true_frame
    return {a: decision_scores(setup.answers[a], mind.p_rules_on(a, frame), mind.settings.threshold_for(a))
            for a in setup.rules}


def norms_result(make_world: WorldFactory, cond: NormCondition, learner: str,
                 rng: np.random.Generator, decide: str = "map", together: bool = True) -> TrialResult:
    """:func:`norms_trial` as a trial result: group ``rules``, one row per action with a true norm."""
    return TrialResult({"rules": norms_trial(make_world, cond, learner, rng, decide, together)})
