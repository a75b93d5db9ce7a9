"""Resolving the words of an utterance to the store's names, with errors that say what to do.

"me"/"mine" is the speaker, "this"/"that"/"it" the context's object, "do that" its action; names
are matched case-insensitively and returned in their stored spelling. An owner phrase resolves to
an agent name, :data:`ANY` ("someone", "other people") or :data:`NOBODY` ("nobody").
"""

from __future__ import annotations

import re
from functools import lru_cache

from ownctl.errors import OwnctlError, UnknownName
from ownctl.language.context import Context, MissingContext
from ownctl.language.lexicon import (
    ADJECTIVES,
    ANYONE_WORDS,
    DEICTIC,
    GENERIC_NOUNS,
    NOBODY_WORDS,
    SPEAKER_WORDS,
    action_of,
)
from ownctl.logic.names import check_name, is_name, word_pattern
from ownctl.logic.rules import ANY, Literal
from ownctl.logic.vocab import ACTIONS

NOBODY = "\0nobody"

#: Determiners of an object phrase ("the", "this", "my", "Jake's" is handled apart).
DETERMINERS = frozenset({"this", "that", "the", "these", "those", "a", "an", "my", "your", "our",
                         "his", "her", "their", "its"})
#: Possessive determiners that refer to the last agent named ("Jake gave me his pen").
PRONOUNS = frozenset({"his", "her", "their", "he", "she", "they", "him", "them", "hers", "theirs"})
#: The pronouns that stand for an owner after "is" ("it's still hers"), as "mine" does.
POSSESSIVE_PRONOUNS = frozenset({"his", "hers", "theirs"})


class Decline(Exception):
    """Raised by a builder's helper when the words are not of its form after all (e.g. "cups" is
    a class of objects, not an object): the grammar tries the next rule."""


class NotAnObject(OwnctlError):
    """An object phrase whose description does not fit the object it names ("the blue mug" when
    the mug is red)."""


@lru_cache(maxsize=64)
def _index(names: frozenset[str]) -> dict[str, str]:
    """Lower-case name -> stored spelling (cached: a context's names are parsed against many times)."""
    return {n.lower(): n for n in names}


@lru_cache(maxsize=64)
def _colour_index(colors: frozenset[str]) -> dict[str, str]:
    """Lower-case colour -> stored spelling; "none" is a colour value, never a colour word."""
    return {c.lower(): c for c in colors if c.lower() != "none"}


class Resolver:
    """Resolves words against one :class:`Context` (built once per utterance)."""

    def __init__(self, ctx: Context) -> None:
        self.ctx = ctx
        self.topic: str | None = None  # an object named alone ("The scarf?"), for the next sentence
        self._agents = _index(ctx.agents)
        self._objects = _index(ctx.objects)
        self._colors = _colour_index(ctx.colors)
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

    def pronoun(self, word: str) -> str:
        """The agent "he"/"she"/"his" refers to: the last agent named; an error if none was."""
        if self.ctx.mentioned is None:
            raise MissingContext(f"who is {word!r}? name the person instead")
        return self.ctx.mentioned

    def owner(self, phrase: str) -> str:
        """``mine``/``me`` -> speaker, ``jake 's``/``jake`` -> jake, ``someone`` -> ANY, ``nobody``."""
        words = phrase.removesuffix(" 's").strip()
        if words in SPEAKER_WORDS:
            return self.speaker()
        if words in ANYONE_WORDS:
            return ANY
        if words in NOBODY_WORDS:
            return NOBODY
        if words in PRONOUNS:
            return self.pronoun(words)
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
        """An object phrase: "that", "this wallet", "my cup", "the red mug", "wallet", "block 2".

        Adjectives before the name must fit it: a colour that the object is known not to have, or
        a word that is neither a colour nor a describing adjective, is an error (the phrase then
        names some other thing). A plural that names a class of objects ("cups", "the blocks")
        declines (:class:`Decline`), so a norm's rule can read it.
        """
        if phrase in DEICTIC:
            return self.about(phrase)
        if (located := _LOCATED.fullmatch(phrase)) is not None:
            return self._located(located["head"], located["place"], phrase)
        det, words = split_determiner(phrase)
        if not words:
            raise Decline(phrase)
        number = words[-1] if len(words) > 1 and words[-1].isdigit() else ""
        if number:
            words = [*words[:-2], words[-2] + number]
        noun, adjectives = words[-1], words[:-1]
        if noun.lower() in self._objects:
            name = self._objects[noun.lower()]
            self._check_adjectives(name, adjectives)
            return name
        if (noun in GENERIC_NOUNS or self.is_class_noun(noun)) and adjectives and det not in ("this", "that"):
            return self._described(noun, adjectives, phrase)  # "the yellow block", "the red one"
        if noun in GENERIC_NOUNS and (det in ("this", "that") or self.ctx.about is not None):
            if det not in ("this", "that", "") and not adjectives:
                raise Decline(phrase)  # "the stuff", "my things": a class
            name = self.about(phrase)
            self._check_adjectives(name, adjectives)
            return name
        if det in ("this", "that") and not adjectives:
            return self.about(phrase)
        if self.is_class_noun(noun):
            raise Decline(phrase)
        raise UnknownName("object", noun, self.ctx.objects)

    def possessor(self, phrase: str) -> str | None:
        """The owner an object phrase names ("my cup" -> the speaker, "Jake's mug" -> jake)."""
        det, _ = split_determiner(phrase)
        if det == "my":
            return self.speaker()
        if det.endswith(" 's"):
            who = self.owner(det)
            return who if who not in (ANY, NOBODY) else None
        if det in PRONOUNS:
            return self.pronoun(det)
        return None

    def _described(self, noun: str, adjectives: list[str], phrase: str) -> str:
        """The one object a description picks out by its percepts ("the yellow block": the only
        yellow object in category block, or the only yellow one if "block" is no category)."""
        colours = [c for w in adjectives if (c := self.colour(w)) is not None]
        if len(colours) != len(adjectives) or len(set(colours)) != 1:
            raise Decline(phrase)
        category = self.category_noun(noun)
        lits = [Literal("isColored", colours[0]), *([Literal("inCategory", category)] if category else [])]
        found = self.select(tuple(lits), phrase)
        if len(found) != 1:
            raise MissingContext(f"which one is {phrase!r}? it could be {', '.join(found)}")
        return found[0]

    def _located(self, head: str, place: str, phrase: str) -> str:
        """The object ``head`` names, said to be in the area ``place`` ("the mug on the table"):
        an area the robot knows (else the words name no place: Decline), and one the object is
        known to be in (else the phrase names some other thing)."""
        area = self.area(place, False)
        if area is None:
            raise Decline(phrase)
        name = self.obj(head)
        facts = self.ctx.facts.get(name)
        if facts is not None and area not in facts.areas:
            where = ", ".join(sorted(facts.areas)) or "in no known area"
            raise NotAnObject(f"{name} is not in the {area} area ({where}): which object is {phrase!r}?")
        return name

    def _check_adjectives(self, name: str, adjectives: list[str]) -> None:
        facts = self.ctx.facts.get(name)
        for word in adjectives:
            colour = self.colour(word)
            if colour is not None:
                if facts is not None and facts.color is not None and facts.color != colour:
                    raise NotAnObject(f"{name} is {facts.color}, not {colour}: which object is "
                                      f"'{word} {name}'?")
            elif word not in ADJECTIVES:
                raise Decline(word)

    def is_class_noun(self, word: str) -> bool:
        """True if ``word`` is a category or the plural of one ("cups")."""
        return self.category_noun(word) is not None

    def category_noun(self, word: str) -> str | None:
        """The known category a noun names, in the singular or plural ("cups" -> cup)."""
        for form in plural_stems(word):
            if form in self._categories:
                return self._categories[form]
        return None

    def select(self, literals: tuple[Literal, ...], said: str) -> list[str]:
        """The objects a class phrase picks out by their percepts (in name order); an error if
        the phrase depends on ownership, or no object is known to fit it."""
        if any(lit.pred == "ownedBy" for lit in literals):
            raise MissingContext(f"I cannot tell which objects {said!r} are from what I see: name them")
        found = [name for name in sorted(self.ctx.objects)
                 if (facts := self.ctx.facts.get(name)) is not None
                 and all(holds(lit, facts.color, facts.areas, facts.categories) for lit in literals)]
        if not found:
            raise MissingContext(f"I know of no objects that are {said!r}")
        return found

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


#: Where an object is, after its noun: "on the table", "in my desk area" (the grammar's LOBJ).
LOCATIVE = (r"(?:on|in|at|by|near|under|inside|next to) (?:the|my|your|our|his|her|their) "
            rf"(?P<place>{word_pattern()})(?: area)?")
_LOCATED = re.compile(rf"(?P<head>.+?) {LOCATIVE}")


def split_determiner(phrase: str) -> tuple[str, list[str]]:
    """An object phrase's determiner ("the", "my", "jake 's", or "") and the words after it."""
    words = phrase.split()
    if len(words) > 1 and words[1] == "'s":
        return " ".join(words[:2]), words[2:]
    if words and words[0] in DETERMINERS:
        return words[0], words[1:]
    return "", words


def plural_stems(word: str) -> list[str]:
    """The word and its possible singulars ("cups" -> cups, cup; "boxes" -> box)."""
    forms = [word]
    if word.endswith("ies"):
        forms.append(word[:-3] + "y")
    if word.endswith("es"):
        forms.append(word[:-2])
    if word.endswith("s"):
        forms.append(word[:-1])
    return forms


def holds(lit: Literal, color: str | None, areas: frozenset[str], categories: frozenset[str]) -> bool:
    """The truth of a crisp literal for an object with these percepts."""
    if lit.pred == "isColored":
        value = color is not None if lit.arg == ANY else color == lit.arg
    elif lit.pred == "inArea":
        value = bool(areas) if lit.arg == ANY else lit.arg in areas
    else:
        value = bool(categories) if lit.arg == ANY else lit.arg in categories
    return value != lit.negated
