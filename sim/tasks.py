"""Whole-table tasks on a :class:`~sim.world.PhysicsWorld`, and a paper-like 20-block test world.

``trash_all`` / ``collect_all`` act on every block not already in the target area, in a given order,
and report what was delivered. ``paper_blocks`` draws a world like the paper's blocks world; the
project's own generator lives in ``ownctl.world`` and this one exists so the simulator can be tested
and benchmarked on its own.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from sim.world import PhysicsWorld, SimBlock, StepOutcome

PAPER_COLORS = ("none", "red", "green", "blue")


def paper_blocks(rng: np.random.Generator, n_agents: int = 3, per_cluster: int = 5) -> list[SimBlock]:
    """Blocks like the paper's world: ``per_cluster`` unowned blocks within 0.3 m of the origin, and as
    many around each agent's centre (radius U(0.4, 0.8) in that agent's 120-degree sector), each within
    0.3 m of its centre (uniform radius, as in the original code), colours uniform over ``PAPER_COLORS``.
    """
    centres = [np.zeros(2)]
    for i in range(n_agents):
        radius = rng.uniform(0.4, 0.8)
        angle = rng.uniform(i, i + 1) * 2 * np.pi / n_agents
        centres.append(radius * np.array([np.cos(angle), np.sin(angle)]))
    blocks = []
    for k in range(per_cluster * len(centres)):
        centre = centres[k % len(centres)]
        r, theta = rng.uniform(0, 0.3), rng.uniform(0, 2 * np.pi)
        x, y = centre + r * np.array([np.cos(theta), np.sin(theta)])
        color = str(rng.choice(PAPER_COLORS))
        blocks.append(SimBlock(f"block{k + 1}", color, (float(x), float(y), 0.0)))
    return blocks


@dataclass
class TaskResult:
    """Outcome of a whole-table task: per-step outcomes, what ended in the area, sim and wall seconds."""

    task: str
    outcomes: list[StepOutcome] = field(default_factory=list)
    delivered: list[str] = field(default_factory=list)
    attempted: list[str] = field(default_factory=list)
    sim_seconds: float = 0.0
    wall_seconds: float = 0.0

    @property
    def fraction(self) -> float:
        """Share of attempted blocks that ended inside the target area (1.0 if none was attempted)."""
        return len(self.delivered) / len(self.attempted) if self.attempted else 1.0


def _run(
    world: PhysicsWorld, task: str, area: str, act: Callable[[str], StepOutcome], order: Sequence[str] | None
) -> TaskResult:
    names = list(order) if order is not None else list(world.names)
    todo = [n for n in names if not world.in_area(n, area)]
    result = TaskResult(task, attempted=todo)
    start_sim, start_wall = world.sim_time, time.perf_counter()
    for name in todo:
        result.outcomes.append(act(name))
    world.go_home()
    result.sim_seconds = world.sim_time - start_sim
    result.wall_seconds = time.perf_counter() - start_wall
    result.delivered = [n for n in todo if world.in_area(n, area)]
    return result


def trash_all(world: PhysicsWorld, order: Sequence[str] | None = None) -> TaskResult:
    """Trash every block not already in the trash area, in ``order`` (default: the world's order)."""
    return _run(world, "trashAll", "trash", world.trash, order)


def collect_all(world: PhysicsWorld, order: Sequence[str] | None = None) -> TaskResult:
    """Collect every block not already in the home area, in ``order`` (default: the world's order)."""
    return _run(world, "collectAll", "home", world.collect, order)
