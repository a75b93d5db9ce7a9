"""What an utterance means: typed instructions the application executes in order, in one transaction.

Each instruction prints itself with :meth:`text` as the equivalent CLI instruction, so a user sees
exactly what was understood ("No, that's mine!" -> ``skip wallet``, ``claim wallet casey``,
``forbid trash on wallet``, ``forbid trash if ownedBy casey``). :meth:`say` gives the English the
robot uses in its reply.
"""

from __future__ import annotations

from dataclasses import dataclass

from ownctl.errors import BadValue
from ownctl.logic.rules import Norm
from ownctl.logic.vocab import action as lookup_action

#: The tasks a :class:`RunTask` may name (docs/architecture.md, section 7, ``run``).
TASKS = ("trashAll", "collectAll")

#: How the robot speaks of its object actions in replies.
VERBS = {"trash": "throw away", "pickUp": "pick up", "putDown": "put down", "collect": "collect"}

#: The actions a question about what may be done with an object checks ("what can't you do with
#: the book?"): those people ask the robot for.
OBJECT_ACTIONS = ("trash", "pickUp", "putDown", "collect")


def verb(action: str) -> str:
    """The English verb phrase for an action (``trash`` -> ``throw away``)."""
    return VERBS.get(action, action)


@dataclass(frozen=True)
class Claim:
    """``ownedBy(object, agent)`` as stated by the speaker.

    ``p`` is the speaker's confidence in the stated relation (1.0 unless hedged: "probably mine");
    a ``negated`` claim states that the agent does *not* own the object, so the ownership probability
    it asserts is ``1 - p``. An ``exclusive`` claim also sets every other agent's ownership to 0.
    """

    object: str
    agent: str
    p: float = 1.0
    negated: bool = False
    exclusive: bool = False

    def __post_init__(self) -> None:
        if not 0.0 <= self.p <= 1.0:
            raise BadValue(f"claim confidence {self.p!r} is not a probability in [0, 1]")
        if self.negated and self.exclusive:
            raise BadValue("a claim cannot be both negated and exclusive")

    @property
    def probability(self) -> float:
        """The asserted probability that ``agent`` owns ``object``."""
        return 1.0 - self.p if self.negated else self.p

    def text(self) -> str:
        """``claim wallet casey [--not] [--only] [--p 0.8]`` (the ``ownctl claim`` command line)."""
        flags = (" --not" if self.negated else "") + (" --only" if self.exclusive else "")
        conf = f" --p {self.p:g}" if self.p != 1.0 else ""
        return f"claim {self.object} {self.agent}{flags}{conf}"

    def say(self) -> str:
        """``wallet belongs to casey`` (or ``does not belong``, ``... alone``, ``probably ...``, and
        ``may belong`` for a guess: "I guess", "maybe", below 0.7)."""
        if self.p < GUESS:
            verb = "may not belong" if self.negated else "may belong"
        else:
            hedge = "probably " if self.p < 1.0 else ""
            verb = f"{hedge}does not belong" if self.negated else f"{hedge}belongs"
        alone = " alone" if self.exclusive and not self.negated else ""
        return f"{self.object} {verb} to {self.agent}{alone}"


GUESS = 0.7  # below this confidence a claim is said as a guess ("may belong"), else "probably"


@dataclass(frozen=True)
class Permission:
    """An object-specific permission: ``forbid|allow ACTION on OBJECT`` (an example for induction)."""

    action: str
    object: str
    forbid: bool

    def __post_init__(self) -> None:
        lookup_action(self.action)

    def text(self) -> str:
        """``forbid trash on wallet``."""
        return f"{'forbid' if self.forbid else 'allow'} {self.action} on {self.object}"

    def say(self) -> str:
        """``I won't throw away wallet`` / ``I may pick up wallet``."""
        return f"{'I will not' if self.forbid else 'I may'} {verb(self.action)} {self.object}"


@dataclass(frozen=True)
class NormInstruction:
    """A general norm given in one shot (``forbid trash if ownedBy casey``)."""

    norm: Norm

    def text(self) -> str:
        """The norm's canonical text."""
        return self.norm.text()

    def say(self) -> str:
        """``I will not throw away anything owned by casey``."""
        conds = [describe_literal(lit.pred, lit.arg, lit.negated) for lit in self.norm.rule.literals]
        lead = "I will not" if self.norm.sign == "forbid" else "I may"
        tail = " and ".join(conds)
        return f"{lead} {verb(self.norm.rule.action)} anything{' ' + tail if tail else ''}"


def describe_literal(pred: str, arg: str, negated: bool) -> str:
    """English for one literal about "anything": ``owned by casey``, ``red``, ``in area home``."""
    if pred == "ownedBy":
        if arg == "any":
            return "owned by no one" if negated else "owned by someone"
        return f"{'not ' if negated else ''}owned by {arg}"
    if pred == "isColored":
        return f"{'not ' if negated else ''}colored {arg}"
    if pred == "inArea":
        return f"{'outside' if negated else 'in'} area {arg}"
    return f"{'not ' if negated else ''}in category {arg}"


@dataclass(frozen=True)
class Introduce:
    """The speaker introduces themself: add the agent if new and make it the current speaker."""

    agent: str

    def text(self) -> str:
        """``agent add jake``."""
        return f"agent add {self.agent}"


@dataclass(frozen=True)
class Skip:
    """Stop the current action on ``object`` (a reprimand); the task goes on with the next object."""

    object: str

    def text(self) -> str:
        """``skip wallet``."""
        return f"skip {self.object}"


@dataclass(frozen=True)
class AskOwner:
    """"Whose is this?": report the object's owners."""

    object: str

    def text(self) -> str:
        """``owners wallet``."""
        return f"owners {self.object}"


@dataclass(frozen=True)
class AskOwned:
    """"What do I own?": report the objects an agent probably owns."""

    agent: str

    def text(self) -> str:
        """``owners --agent jake``."""
        return f"owners --agent {self.agent}"


@dataclass(frozen=True)
class AskActions:
    """"What are you not allowed to do with the book?": check each of :data:`OBJECT_ACTIONS` on
    the object and report which are permitted and which forbidden."""

    object: str

    def text(self) -> str:
        """``actions book`` (answered by one ``check`` per action)."""
        return f"actions {self.object}"


@dataclass(frozen=True)
class AskPermitted:
    """"Can you throw this away?": check whether the action is permitted on the object."""

    action: str
    object: str

    def __post_init__(self) -> None:
        lookup_action(self.action)

    def text(self) -> str:
        """``check trash wallet``."""
        return f"check {self.action} {self.object}"


@dataclass(frozen=True)
class Request(AskPermitted):
    """"Throw this away": the robot should do it if permitted; in the store alone that is a check.

    A subclass of :class:`AskPermitted`, so an application that cannot act treats it as a check and
    one that drives the robot may act when the answer is "permitted".
    """


@dataclass(frozen=True)
class AskWhy:
    """"Why not?": explain a decision; with no action and object, the last refusal."""

    action: str | None = None
    object: str | None = None

    def text(self) -> str:
        """``explain trash wallet`` (or ``explain`` for the last refusal)."""
        return " ".join(["explain", *(w for w in (self.action, self.object) if w)])


@dataclass(frozen=True)
class RunTask:
    """Run a whole task (``trashAll`` or ``collectAll``)."""

    task: str

    def __post_init__(self) -> None:
        if self.task not in TASKS:
            raise BadValue(f"unknown task {self.task!r}; known tasks: {', '.join(TASKS)}", TASKS)

    def text(self) -> str:
        """``run trashAll``."""
        return f"run {self.task}"


Instruction = (
    Claim | Permission | NormInstruction | Introduce | Skip | AskOwner | AskOwned | AskActions | AskPermitted
    | AskWhy | RunTask
)


def teaching_order(instructions: tuple[Instruction, ...]) -> list[tuple[int, Instruction]]:
    """The order instructions are applied in: as understood, except that in a run of permissions and
    norms the norms go first, so a norm given in the same breath explains its example ("No, that's
    mine!": the norm ``forbid trash if ownedBy me`` is stored before ``forbid trash on that``, and the
    example then agrees with it instead of inducing an "always forbid" rule from one example)."""
    out: list[tuple[int, Instruction]] = []
    run: list[tuple[int, Instruction]] = []
    for item in [*enumerate(instructions), (len(instructions), None)]:
        if isinstance(item[1], Permission | NormInstruction):
            run.append(item)  # type: ignore[arg-type]
            continue
        out += [x for x in run if isinstance(x[1], NormInstruction)]
        out += [x for x in run if isinstance(x[1], Permission)]
        run = []
        if item[1] is not None:
            out.append(item)  # type: ignore[arg-type]
    return out
