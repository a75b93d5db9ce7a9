"""What an agent's silence says, in the Mind (architecture section 5; ownctl/ownership/silence.py).

Laws: the priors depend on the claims, not on the order they came in (silence refits the agents
whose silent objects changed, and every agent when its weight moves); a Mind told the claims one at
a time ends where one given them at once ends. Behaviour: told only owners' "that's mine", the
robot predicts the other objects better with silence weighed than without, on the paper's world and
on one whose percepts say nothing of who owns what; claims that do not depend on their answer (every
agent's ownership stated) leave nobody silent: the priors are those of a robot that ignores silence.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from ownctl.config import PredictConfig, Settings
from ownctl.mind import Mind
from ownctl.world.generator import paper_blocks_world, scattered_world
from ownctl.world.model import World

SILENT_OFF = Settings(predict=replace(PredictConfig(), silence_step=0.0))


def _mind(world: World, settings: Settings | None = None) -> Mind:
    return Mind(world.agents, list(world.objects), world.areas, settings or Settings())


def _owners_say(world: World, objects: np.ndarray) -> list[tuple[int, str, bool]]:
    """Each owner of ``objects`` says "that's mine"; one non-owner of every third says "not mine"."""
    truth = world.true_ownership() >= 0.5
    out: list[tuple[int, str, bool]] = []
    for k, i in enumerate(objects.tolist()):
        out += [(i, a, False) for j, a in enumerate(world.agents) if truth[i, j]]
        if k % 3 == 0:
            out += [(i, a, True) for j, a in enumerate(world.agents) if not truth[i, j]][:1]
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_priors_do_not_depend_on_the_order_of_the_claims(seed: int) -> None:
    world = paper_blocks_world(np.random.default_rng(seed))
    said = _owners_say(world, np.random.default_rng(seed).permutation(len(world.objects))[:10])
    minds = []
    shuffled = [said[k] for k in np.random.default_rng(seed + 9).permutation(len(said))]
    for order in (said, said[::-1], shuffled):
        mind = _mind(world)
        for i, agent, negated in order:
            mind.claim(i, agent, negated=negated)
            _ = mind.prior  # refit after every claim
        minds.append(mind)
    at_once = _mind(world)
    for i, agent, negated in said:
        at_once.claims[i, at_once.agents.index(agent)] = 0.0 if negated else 1.0
    at_once.refit_all()
    _ = at_once.prior
    assert minds[0].silence > 0
    for mind in (*minds[1:], at_once):
        assert mind.silence == minds[0].silence
        np.testing.assert_allclose(mind.prior, minds[0].prior, rtol=0, atol=1e-9)


def test_claims_of_every_agent_leave_nobody_silent() -> None:
    world = paper_blocks_world(np.random.default_rng(3))
    truth = world.true_ownership()
    mind = _mind(world)
    for i in range(0, len(world.objects), 2):
        for j, agent in enumerate(world.agents):
            mind.claim(i, agent, float(truth[i, j]))
    alone = _mind(world, SILENT_OFF)
    alone.claims[:] = mind.claims
    alone.refit_all()
    np.testing.assert_allclose(mind.prior, alone.prior, rtol=0, atol=1e-12)


def _held_out_error(draw: object, settings: Settings, seeds: range) -> tuple[float, float]:
    """Mean absolute error and accuracy of the priors of the objects nobody spoke of, after the
    owners of a random half said "that's mine"."""
    errors, hits = [], []
    for seed in seeds:
        world = draw(np.random.default_rng(seed))  # type: ignore[operator]
        truth = world.true_ownership() >= 0.5
        order = np.random.default_rng(seed + 100).permutation(len(world.objects))
        half, rest = order[: len(order) // 2], order[len(order) // 2:]
        mind = _mind(world, settings)
        for i in half.tolist():
            for j, agent in enumerate(world.agents):
                if truth[i, j]:
                    mind.claim(i, agent)
        prior = mind.prior[rest]
        errors.append(np.abs(prior - truth[rest]).mean())
        hits.append(((prior >= 0.5) == truth[rest]).mean())
    return float(np.mean(errors)), float(np.mean(hits))


@pytest.mark.parametrize("draw", [paper_blocks_world, scattered_world])
def test_told_only_that_s_mine_the_robot_predicts_better_with_silence(draw: object) -> None:
    error, accuracy = _held_out_error(draw, Settings(), range(12))
    error_off, accuracy_off = _held_out_error(draw, SILENT_OFF, range(12))
    assert error < error_off and accuracy > accuracy_off
