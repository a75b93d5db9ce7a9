"""Whole-table tasks on a paper-like 20-block world: everything delivered, nothing else disturbed."""

from __future__ import annotations

import numpy as np
import pytest

from sim.tasks import PAPER_COLORS, collect_all, paper_blocks, trash_all
from sim.world import PhysicsWorld


def test_paper_blocks_look_like_the_paper_world() -> None:
    blocks = paper_blocks(np.random.default_rng(0))
    assert len(blocks) == 20 and len({b.name for b in blocks}) == 20
    assert {b.color for b in blocks} <= set(PAPER_COLORS)
    unowned = [b for k, b in enumerate(blocks) if k % 4 == 0]
    assert all(np.hypot(*b.position[:2]) <= 0.3 for b in unowned if b.position)
    assert all(max(abs(c) for c in b.position[:2]) < 1.1 for b in blocks if b.position)
    assert paper_blocks(np.random.default_rng(0)) == blocks


@pytest.mark.slow
def test_trash_all_delivers_every_block() -> None:
    world = PhysicsWorld(paper_blocks(np.random.default_rng(1)), [], seed=1)
    result = trash_all(world)
    assert result.attempted and result.fraction == 1.0, [o for o in result.outcomes if not o.ok]
    assert all(o.ok for o in result.outcomes)


@pytest.mark.slow
def test_collect_all_delivers_every_block_and_skips_those_at_home() -> None:
    world = PhysicsWorld(paper_blocks(np.random.default_rng(2)), [], seed=2)
    at_home = [n for n in world.names if world.in_area(n, "home")]
    result = collect_all(world)
    assert set(result.attempted).isdisjoint(at_home)
    assert result.fraction == 1.0, [o for o in result.outcomes if not o.ok]
    assert all(world.in_area(n, "home") for n in world.names)
