"""Actions, their prerequisites, and the predicate registry (docs/architecture.md, section 2).

The registry order fixes the canonical literal order: ``ownedBy``, ``isColored``, ``inArea``,
``inCategory``. Adding a predicate is adding one :class:`Predicate` entry.
"""

from __future__ import annotations

from dataclasses import dataclass

from ownctl.errors import UnknownName


@dataclass(frozen=True)
class Action:
    """An action the robot can take; ``prerequisites`` are forbidden-together steps."""

    name: str
    target: str | None  # "object", "location" or None
    prerequisites: tuple[str, ...] = ()

    @property
    def steps(self) -> tuple[str, ...]:
        """The prerequisites then the action itself: every step a decision must check."""
        return (*self.prerequisites, self.name)


ACTIONS: dict[str, Action] = {
    a.name: a
    for a in (
        Action("find", "object"),
        Action("pickUp", "object"),
        Action("putDown", None),
        Action("release", None),
        Action("goHome", None),
        Action("moveTo", "location"),
        Action("replace", None, ("putDown",)),
        Action("wait", None),
        Action("trash", "object", ("find", "pickUp", "release")),
        Action("collect", "object", ("find", "pickUp", "goHome", "putDown")),
    )
}

#: The actions the paper's experiments give permissions for (object-targeted, with rules).
OBJECT_ACTIONS = tuple(name for name, a in ACTIONS.items() if a.target == "object")


def action(name: str) -> Action:
    """The action called ``name``; raise UnknownName listing the known actions otherwise."""
    try:
        return ACTIONS[name]
    except KeyError:
        raise UnknownName("action", name, ACTIONS) from None


def object_steps(name: str) -> tuple[str, ...]:
    """The object-targeted steps of an action (what permissions and instructors speak of)."""
    return tuple(s for s in action(name).steps if ACTIONS[s].target == "object")


@dataclass(frozen=True)
class Predicate:
    """A typed predicate whose first argument is the rule's target object.

    ``argument`` names the kind of the second argument (agent, colour, area, category);
    ``crisp`` predicates are 0/1 facts of the object's percepts, the others are probabilities.
    """

    name: str
    argument: str
    crisp: bool
    order: int


PREDICATES: dict[str, Predicate] = {
    p.name: p
    for p in (
        Predicate("ownedBy", "agent", crisp=False, order=0),
        Predicate("isColored", "colour", crisp=True, order=1),
        Predicate("inArea", "area", crisp=True, order=2),
        Predicate("inCategory", "category", crisp=True, order=3),
    )
}


def predicate(name: str) -> Predicate:
    """The predicate called ``name``; raise UnknownName listing the known predicates otherwise."""
    try:
        return PREDICATES[name]
    except KeyError:
        raise UnknownName("predicate", name, PREDICATES) from None
