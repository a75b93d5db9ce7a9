"""Table 2: ownership prediction and inference (docs/architecture.md, section 8).

Each trial draws a new world and picks half of the objects at random. Those objects get, one at a
time, exact ownership claims for every agent and then the true permissions of every action that has
a true norm. Ownership (the Mind's posterior) is scored against the truth on the held-out half and
on all objects, per agent. Prediction is on in every condition; the conditions switch inference and
rule learning: (i) inference off, rules frozen; (ii) rules learned, inference on; (iii) the true
norms given first, inference on. In conditions (i')-(iii') (``--claims owners``) each claimed
object is claimed only by its owners, as people say "that's mine": nothing is said of who does not
own it, nor of an object nobody owns.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ownctl.config import LearnConfig, Settings
from ownctl.experiment.metrics import ownership_scores
from ownctl.experiment.norms import WorldFactory
from ownctl.experiment.result import TrialResult
from ownctl.experiment.truth import true_rules
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import parse_norm
from ownctl.mind import Mind, Switches
from ownctl.world.model import World, make_frame

#: Which claims the instructor gives on the claimed half: every agent's, 0 or 1 (the paper's
#: protocol), or only its owners' "that's mine".
CLAIM_MODES = ("all", "owners")


@dataclass(frozen=True)
class OwnershipCondition:
    """One row of Table 2: whether inference runs, rules are learned, the true norms are given,
    and which claims are given (:data:`CLAIM_MODES`)."""

    name: str
    inference: bool
    learn_rules: bool
    rules_given: bool
    claims: str = "all"


_ROWS = (("(i{}) no inference", False, False, False), ("(ii{}) rules learned", True, True, False),
         ("(iii{}) rules given", True, True, True))
OWNERSHIP_CONDITIONS = (
    *(OwnershipCondition(name.format(""), inference=i, learn_rules=lr, rules_given=g)
      for name, i, lr, g in _ROWS),
    *(OwnershipCondition(name.format("'") + ", owners' claims", inference=i, learn_rules=lr,
                         rules_given=g, claims="owners") for name, i, lr, g in _ROWS),
)


def condition_names(claims: str) -> list[str]:
    """The names of the conditions whose instructor gives ``claims`` (of :data:`CLAIM_MODES`)."""
    return [c.name for c in OWNERSHIP_CONDITIONS if c.claims == claims]


def ownership_trial(make_world: WorldFactory, cond: OwnershipCondition, learner: str,
                    rng: np.random.Generator, decide: str = "map") -> TrialResult:
    """One trial; groups ``test`` (held-out half) and ``all`` (every object), rows = agents.
    ``decide`` is accepted for a uniform trial signature: no decision is taken here."""
    mind, world, test = protocol(make_world, cond, learner, rng)
    truth = world.true_ownership()
    post = mind.posterior()
    groups = {
        "test": {a: ownership_scores(truth[test, j], post[test, j]) for j, a in enumerate(world.agents)},
        "all": {a: ownership_scores(truth[:, j], post[:, j]) for j, a in enumerate(world.agents)},
    }
    return TrialResult(groups)


def protocol(make_world: WorldFactory, cond: OwnershipCondition, learner: str,
             rng: np.random.Generator) -> tuple[Mind, World, np.ndarray]:
    """The protocol of one trial: the Mind after the claims and permissions on a random half, the
    world, and the held-out objects (sorted indices)."""
    world = make_world(rng)
    truth = world.true_ownership()
    rules = true_rules(world)
    true_frame = make_frame(world.objects, world.areas, world.agents, truth)
    answers = {a: p_forbidden(r, true_frame) for a, r in rules.items()}
    settings = Settings(learn=LearnConfig(learner=learner))
    switches = Switches(inference=cond.inference, frozen_rules=not cond.learn_rules)
    mind = Mind(world.agents, list(world.objects), world.areas, settings, switches)
    if cond.rules_given:
        for text in world.norms:
            mind.instruct(parse_norm(text))
    n = len(world.objects)
    order = rng.permutation(n)
    train, test = order[: n // 2], np.sort(order[n // 2 :])
    for obj in train:
        i = int(obj)
        for j, agent in enumerate(world.agents):
            if cond.claims == "all":
                mind.claim(i, agent, float(truth[i, j]))
            elif truth[i, j] >= 0.5:  # "that's mine", said by an owner
                mind.claim(i, agent, 1.0)
        for action in rules:
            mind.permit(action, i, float(answers[action][i]))
    return mind, world, test
