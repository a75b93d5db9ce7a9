"""How many ownership worlds an Evidence enumerates: every agent that may own an example while the
(world, example) pairs stay within MAX_PAIRS, the most likely owners first, the rest folded into
"owned by someone else" (which ``ownedBy any`` still counts exactly)."""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.learn.evidence import MAX_NAMED_AGENTS, MAX_PAIRS, Evidence, pair_count
from ownctl.logic.frame import Frame
from ownctl.logic.rules import ANY, Literal, Rule


def frame_of(own: np.ndarray) -> Frame:
    agents = tuple(f"a{j}" for j in range(own.shape[1]))
    return Frame(agents, own, tuple("red" for _ in range(len(own))), {})


def test_few_examples_enumerate_every_likely_owner_exactly() -> None:
    own = np.random.default_rng(0).uniform(0.1, 0.9, size=(20, 5))
    ev = Evidence(frame_of(own), np.zeros(20))
    assert not ev.folded and set(ev.worlds.atoms) >= {f"a{j}" for j in range(5)}
    assert len(ev.pairs[0]) == pair_count(ev.frame, ev.worlds.atoms[:-1]) == 20 * 2 ** 5


@pytest.mark.parametrize(("n", "agents"), [(500, 12), (3000, 6), (70_000, 2)])
def test_many_uncertain_examples_stay_within_the_pair_budget(n: int, agents: int) -> None:
    rng = np.random.default_rng(n)
    own = rng.uniform(0.05, 0.95, size=(n, agents))
    own[:, 0] *= 0.2  # a0 is the least likely owner: folded first
    ev = Evidence(frame_of(own), rng.integers(0, 2, size=n).astype(float))
    # within the budget, or (when even "someone" alone exceeds it) one uncertain atom per example
    assert ev.folded and len(ev.pairs[0]) <= max(MAX_PAIRS, 2 * n)
    assert "a0" not in ev.worlds.atoms
    anyone = ev.q([Rule("trash", (Literal("ownedBy", ANY),))])
    assert anyone == pytest.approx(1 - np.prod(1 - own, axis=1), abs=1e-12)  # still exact
    assert not ev.q([Rule("trash", (Literal("ownedBy", "a0"),))]).any()  # a folded agent is named by no rule


def test_exact_ownership_folds_nobody_however_many_examples() -> None:
    n, agents = 5000, MAX_NAMED_AGENTS
    rng = np.random.default_rng(1)
    own = (rng.uniform(size=(n, agents)) < 0.3).astype(float)
    ev = Evidence(frame_of(own), np.zeros(n))
    assert not ev.folded and len(ev.pairs[0]) == n  # one world per example
