"""The ground truth of a simulated world, as the simulated instructor and the metrics read it.

:class:`TrueNorms` holds the world's true norms (grouped by action) and true ownership, and answers
what they say about an object in its current state. Learning never reads it.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden, relevant_atoms
from ownctl.logic.rules import Rule, parse_rule
from ownctl.world.model import ObjectSpec, World, make_frame


def true_rules(world: World) -> dict[str, tuple[Rule, ...]]:
    """The world's true norms grouped by action, in the order the norms are listed."""
    out: dict[str, list[Rule]] = {}
    for text in world.norms:
        rule = parse_rule(text)
        out.setdefault(rule.action, []).append(rule)
    return {a: tuple(r) for a, r in out.items()}


class TrueNorms:
    """True norms and owners of ``world``; objects are addressed by their index in ``world.objects``."""

    def __init__(self, world: World) -> None:
        self.world = world
        self.rules = true_rules(world)
        self.ownership = world.true_ownership()

    def frame(self, objects: Sequence[ObjectSpec]) -> Frame:
        """All objects in their state ``objects`` (same order as the world's) with true owners."""
        return make_frame(objects, self.world.areas, self.world.agents, self.ownership)

    def forbidden(self, i: int, state: ObjectSpec, steps: Sequence[str]) -> dict[str, float]:
        """P(the true norms forbid each step) on object ``i`` in state ``state`` (0 or 1 for crisp owners)."""
        frame = make_frame([state], self.world.areas, self.world.agents, self.ownership[i : i + 1])
        return {s: float(p_forbidden(self.rules.get(s, ()), frame)[0]) for s in steps}

    def violated(self, i: int, state: ObjectSpec, steps: Sequence[str]) -> bool:
        """Whether the true norms forbid some step on object ``i`` in state ``state``."""
        return any(p >= 0.5 for p in self.forbidden(i, state, steps).values())

    def referenced_agents(self, steps: Sequence[str]) -> tuple[str, ...]:
        """Agents named by ownedBy literals of the steps' true rules (``any`` = all), in world order."""
        named, uses_any = relevant_atoms(self.rules.get(s, ()) for s in steps)
        return tuple(a for a in self.world.agents if uses_any or a in named)

    def owner_row(self, i: int) -> np.ndarray:
        """True ownership of object ``i`` per agent (world agent order)."""
        row: np.ndarray = self.ownership[i]
        return row
