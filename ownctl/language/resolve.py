"""Resolving the words of an utterance to the store's names, with errors that say what to do.

"me"/"mine" is the speaker, "this"/"that"/"it" the context's object, "do that" its action; names
are matched case-insensitively and returned in their stored spelling. An owner phrase resolves to
an agent name, :data:`ANY` ("someone", "other people") or :data:`NOBODY` ("nobody").
"""

from __future__ import annotations

from collections.abc import Iterable

from ownctl.errors import UnknownName
from ownctl.language.context import Context, MissingContext
from ownctl.language.lexicon import (
    ANYONE_WORDS,
    DEICTIC,
    GENERIC_NOUNS,
    NOBODY_WORDS,
    SPEAKER_WORDS,
    action_of,
)
from ownctl.logic.names import check_name, is_name
from ownctl.logic.rules import ANY
from ownctl.logic.vocab import ACTIONS

NOBODY = "\0nobody"


def _index(names: Iterable[str]) -> dict[str, str]:
    """Lower-case name -> stored spelling."""
    return {n.lower(): n for n in names}


class Resolver:
    """Resolves words against one :class:`Context` (built once per utterance)."""

    def __init__(self, ctx: Context) -> None:
        self.ctx = ctx
        self._agents = _index(ctx.agents)
        self._objects = _index(ctx.objects)
        self._colors = _index(c for c in ctx.colors if c.lower() != "none")
        self._areas = _index(ctx.areas)
        self._categories = _index(ctx.categories)

    # -- the speaker, agents and owners -------------------------------------------------------

    def speaker(self) -> str:
        """The current speaker; "me" without one is an error."""
        if self.ctx.speaker is None:
            raise MissingContext("who is speaking? 'me'/'mine' needs a speaker: say it with --as AGENT, "
                                 "or introduce yourself first (\"I'm NAME\")")
        return self.ctx.speaker

    def agent(self, word: str) -> str:
        """A known agent by name (any case); UnknownName listing the known agents otherwise."""
        try:
            return self._agents[word.lower()]
        except KeyError:
            raise UnknownName("agent", word, self.ctx.agents) from None

    def is_agent(self, word: str) -> bool:
        """True if ``word`` names a known agent."""
        return word.lower() in self._agents

    def owner(self, phrase: str) -> str:
        """``mine``/``me`` -> speaker, ``jake 's``/``jake`` -> jake, ``someone`` -> ANY, ``nobody``."""
        words = phrase.removesuffix(" 's").strip()
        if words in SPEAKER_WORDS:
            return self.speaker()
        if words in ANYONE_WORDS:
            return ANY
        if words in NOBODY_WORDS:
            return NOBODY
        return self.agent(words)

    def new_agent(self, word: str) -> str:
        """An introduced name: the stored spelling if known, else a valid new name."""
        return self._agents.get(word.lower()) or check_name("agent", word)

    # -- objects and actions ------------------------------------------------------------------

    def about(self, said: str = "that") -> str:
        """The object "this"/"that" refers to; an error telling how to give it otherwise."""
        if self.ctx.about is None:
            raise MissingContext(f"which object is {said!r}? there is no current object: say it with "
                                 "--about OBJ, or name the object (\"don't throw the wallet away\")")
        return self.ctx.about

    def is_object(self, word: str) -> bool:
        """True if ``word`` names a known object."""
        return word.lower() in self._objects

    def obj(self, phrase: str) -> str:
        """An object phrase: "that", "this wallet", "my cup", "the wallet", "wallet", "block 2"."""
        if phrase in DEICTIC:
            return self.about(phrase)
        words = phrase.split()
        det = ""
        if len(words) > 1 and words[1] == "'s":
            det, words = " ".join(words[:2]), words[2:]
        elif len(words) > 1 and not words[-1].isdigit() or len(words) > 2:
            det, words = words[0], words[1:]
        noun = "".join(words)
        if noun.lower() in self._objects:
            return self._objects[noun.lower()]
        if det in ("this", "that") or (words[0] in GENERIC_NOUNS and self.ctx.about is not None):
            return self.about(phrase)
        raise UnknownName("object", noun, self.ctx.objects)

    def current_action(self, said: str = "that") -> str:
        """The action the robot is doing on the current object; an error if there is none."""
        if self.ctx.action is None:
            raise MissingContext(f"which action does {said!r} mean? the robot is not doing anything now: "
                                 "name the action (\"don't throw that away\") or give it in the context")
        if self.ctx.action not in ACTIONS:
            raise UnknownName("action", self.ctx.action, ACTIONS)
        return self.ctx.action

    @staticmethod
    def action(phrase: str) -> str:
        """The action an action phrase names."""
        return action_of(phrase)

    # -- percepts ---------------------------------------------------------------------------

    def colour(self, word: str) -> str | None:
        """The stored spelling of a colour word, or None if it is not one."""
        return self._colors.get(word.lower())

    def area(self, word: str, said_area: bool) -> str | None:
        """An area name; unknown words are areas only when areas are unknown and "area" was said."""
        if word.lower() in self._areas:
            return self._areas[word.lower()]
        return word if said_area and not self._areas and is_name(word) else None

    def category(self, word: str) -> str | None:
        """A category name (any valid name when categories are unknown)."""
        if word.lower() in self._categories:
            return self._categories[word.lower()]
        return word if not self._categories and is_name(word) else None
