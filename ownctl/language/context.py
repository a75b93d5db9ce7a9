"""The conversation state an utterance is understood in, the result, and the parser's errors."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ownctl.errors import OwnctlError
from ownctl.language.instructions import Instruction
from ownctl.language.lexicon import COLORS, EXAMPLES


@dataclass(frozen=True)
class Facts:
    """What the robot perceives of one object, for phrases that pick objects by their percepts
    ("the red mug", "everything on the shelf", "the blocks"): its colour, the areas it lies in and
    its categories."""

    color: str | None = None
    areas: frozenset[str] = frozenset()
    categories: frozenset[str] = frozenset()


@dataclass(frozen=True)
class Context:
    """What "me", "this" and "do that" refer to, and the names the parser may resolve.

    ``speaker`` is the agent speaking (``--as AGENT``); ``about`` the object "this"/"that"/"it"
    refers to (``--about OBJ``, else the store's current target); ``action`` what the robot is doing
    or about to do on ``about`` (for "No, that's mine!" and "don't do that"). Names in an utterance
    are matched case-insensitively against ``agents``, ``objects``, ``colors``, ``areas`` and
    ``categories`` and returned in their stored spelling. Empty ``areas``/``categories`` mean
    "not known": any valid name is then accepted after "in the ... area" / "in category ...".
    ``facts`` gives each object's percepts (objects without facts cannot be picked by a class
    phrase); ``mentioned`` is the agent a "he"/"she" refers to (the last one named before).
    """

    speaker: str | None = None
    about: str | None = None
    action: str | None = None
    agents: frozenset[str] = frozenset()
    objects: frozenset[str] = frozenset()
    colors: frozenset[str] = COLORS
    areas: frozenset[str] = frozenset()
    categories: frozenset[str] = frozenset()
    facts: Mapping[str, Facts] = field(default_factory=dict, compare=False)
    mentioned: str | None = None

    def names(self, besides: str | None = None) -> frozenset[str]:
        """Every name the parser may resolve (agents, objects, colours, areas, categories), in lower
        case, leaving out the object ``besides``."""
        return frozenset(n.lower() for n in (*self.agents, *(o for o in self.objects if o != besides),
                                             *self.colors, *self.areas, *self.categories))


@dataclass(frozen=True)
class Understanding:
    """What an utterance means.

    ``intent`` is one of ``reprimand``, ``claim``, ``permission``, ``norm``, ``introduction``,
    ``question``, ``request``, ``task``, ``greeting``, ``thanks``, ``remark`` (how the speaker is:
    "I'm tired"); ``instructions`` are executed in order in one transaction; ``reply`` is what the
    robot answers; ``form`` names the grammar rule that matched (or several, joined by ``+``, for
    a multi-sentence utterance).
    """

    intent: str
    instructions: tuple[Instruction, ...]
    reply: str
    form: str = ""
    topic: str | None = None  # an object named alone ("The scarf?"): what the next sentence is about

    def texts(self) -> tuple[str, ...]:
        """The instructions as CLI instruction texts (what the user is shown)."""
        return tuple(i.text() for i in self.instructions)


class NotUnderstood(OwnctlError):
    """An utterance no grammar rule matches; the message shows what the parser does understand."""

    def __init__(self, utterance: str, detail: str = "") -> None:
        examples = "; ".join(f'"{e}"' for e in EXAMPLES)
        why = f" ({detail})" if detail else ""
        super().__init__(f"I did not understand {utterance!r}{why}; try for example: {examples}", EXAMPLES)
        self.utterance = utterance
        self.detail = detail


class MissingContext(OwnctlError):
    """An utterance refers to something the context does not give ("that" with no current object)."""
