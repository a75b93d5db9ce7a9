"""What rules are evaluated on: crisp percepts of n objects and their ownership probabilities.

A :class:`Frame` is column-oriented so that evaluation is vectorised over objects.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ownctl.logic.rules import ANY, Literal


@dataclass(frozen=True)
class Frame:
    """n objects: ``own[i, j]`` = P(ownedBy(object i, agents[j])); colours, area membership, categories.

    ``areas`` maps an area name to a boolean vector of length n. Unknown agents, areas, colours or
    categories in a literal are simply false for every object.
    """

    agents: tuple[str, ...]
    own: np.ndarray
    colors: tuple[str | None, ...]
    areas: Mapping[str, np.ndarray] = field(default_factory=dict)
    categories: tuple[frozenset[str], ...] = ()

    def __post_init__(self) -> None:
        n = len(self.colors)
        own = np.asarray(self.own, dtype=float).reshape(n, len(self.agents))
        object.__setattr__(self, "own", own)
        if not self.categories:
            object.__setattr__(self, "categories", tuple(frozenset() for _ in range(n)))

    @property
    def n(self) -> int:
        """Number of objects."""
        return len(self.colors)

    def agent_column(self, agent: str) -> np.ndarray:
        """P(ownedBy(o, agent)) for every object (zeros for an agent the frame does not know)."""
        if agent in self.agents:
            return self.own[:, self.agents.index(agent)]
        return np.zeros(self.n)

    def crisp(self, lit: Literal) -> np.ndarray:
        """Truth (bool, length n) of a crisp literal's atom, ignoring its sign."""
        pred, arg = lit.atom
        if pred == "isColored":
            if arg == ANY:
                return np.array([c is not None for c in self.colors], dtype=bool)
            return np.array([c == arg for c in self.colors], dtype=bool)
        if pred == "inArea":
            if arg == ANY:
                out = np.zeros(self.n, dtype=bool)
                for member in self.areas.values():
                    out |= np.asarray(member, dtype=bool)
                return out
            return np.asarray(self.areas.get(arg, np.zeros(self.n, dtype=bool)), dtype=bool)
        if pred == "inCategory":
            if arg == ANY:
                return np.array([bool(c) for c in self.categories], dtype=bool)
            return np.array([arg in c for c in self.categories], dtype=bool)
        raise ValueError(f"{pred} is not a crisp predicate")

    def content(self) -> tuple[object, ...]:
        """Everything the frame is made of, as a hashable value (equal values, equal frames): the
        agents and ownership probabilities, colours, areas and categories, in the objects' order.
        Results computed from a frame are kept by it (:mod:`ownctl.learn.posterior`,
        :mod:`ownctl.mind.ask`)."""
        areas = tuple((name, np.asarray(self.areas[name], dtype=bool).tobytes())
                      for name in sorted(self.areas))
        return (self.agents, self.own.shape, self.own.tobytes(), self.colors, areas, self.categories)

    def with_own(self, own: np.ndarray) -> Frame:
        """The same objects with other ownership probabilities."""
        return Frame(self.agents, own, self.colors, self.areas, self.categories)

    def take(self, index: Sequence[int] | np.ndarray) -> Frame:
        """The frame restricted to the objects at ``index`` (in that order)."""
        idx = np.asarray(index, dtype=int)
        return Frame(
            self.agents,
            self.own[idx],
            tuple(self.colors[i] for i in idx),
            {k: np.asarray(v, dtype=bool)[idx] for k, v in self.areas.items()},
            tuple(self.categories[i] for i in idx),
        )
