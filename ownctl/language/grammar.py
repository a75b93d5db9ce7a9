"""The grammar engine: rules are (intent, pattern, builder) triples tried in a fixed order.

A rule's pattern is a template over the normalised utterance with named fragments in angle
brackets (``<FORBID><ACT> <OBJ>``), expanded to a regular expression and compiled once. A rule
applies when its pattern matches the *whole* utterance and its builder returns instructions; a
builder returns None (or raises :class:`~ownctl.language.resolve.Decline`) to decline (the words
fit the pattern but not the meaning, e.g. "it is red"
is no introduction of someone called "red"), and the next rule is tried. Builders raise
:class:`~ownctl.errors.OwnctlError` for a recognised form with a bad name ("that's Bob's" with no
agent bob), so the user learns what was wrong rather than that nothing matched.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from ownctl.language.instructions import Instruction
from ownctl.language.lexicon import NOT_NOUNS, actions_regex, alternation
from ownctl.language.resolve import LOCATIVE, Decline, Resolver
from ownctl.logic.names import word_pattern

_NAME = word_pattern()

_WORD = rf"(?!{alternation(NOT_NOUNS)}){_NAME}"
_NOUN = rf"{_WORD}(?: \d+)?"
_DETERMINER = rf"(?:this|that|these|those|the|a|an|my|your|our|his|her|their|{_NAME} 's)"
#: The two forms of an object phrase: pointing at it ("that one", "them") or naming it ("the red mug",
#: "Jake's cup", "block 2").
_POINTING = r"(?:this|that|it)(?: one)?|these|those|they|them"
_NOUN_PHRASE = rf"(?:{_DETERMINER} )?(?:{_WORD} ){{0,2}}{_NOUN}"

#: Named fragments usable in rule templates.
FRAGMENTS: dict[str, str] = {
    # an action phrase ("throw away", "pick up", "collect")
    "ACT": rf"(?P<act>{actions_regex()})",
    # an object phrase: "that", "this one", "this wallet", "the wallet", "jake 's cup", "block 2"
    # (adjectives are checked against the object: "the red mug")
    "OBJ": rf"(?P<obj>{_POINTING}|{_NOUN_PHRASE})",
    # an object phrase that may say where the object is: "the mug on the table", "the book on my
    # desk" (the place must be a known area the object is in: Resolver.obj)
    "LOBJ": rf"(?P<obj>{_POINTING}|{_NOUN_PHRASE}(?: {LOCATIVE})?)",
    # "do that": the action the robot is doing now
    "DO": r"do (?:that|this|it|so)",
    # a prohibition ("don't", "never", "you may not", ...) followed by a space
    "FORBID": r"(?:do not|never|you (?:can|could|may|must|should|shall) not|you (?:must|should) never|"
              r"i would (?:rather|prefer(?: it if)?) you did not|i would prefer you not to|"
              r"you had better not|you better not|please do not|i do not want you ever to|you are never to|"
              r"you (?:are|were) not (?:allowed|permitted|supposed) to|you are forbidden to|"
              r"i do not want you to|"
              r"i forbid you to|do not you dare) ",
    # a permission ("you can", "it's ok to", "feel free to", ...) followed by a space
    "ALLOW": r"(?:you (?:can|may|are allowed to|are permitted to|are free to|have permission to)"
             r"(?: always| go ahead and)?|feel free to|go ahead and|"
             r"it is (?:ok|fine|allowed) (?:for you )?to|"
             r"i allow you to|i permit you to|you have my permission to) ",
    # the opening of a reprimand ("no", "hey", "stop", "don't", ...), each word followed by a space
    "REPRIMAND": r"(?:(?:no|nope|hey|stop|wait|whoa|oi|careful|do not|stop it|stop that|"
                 r"do not do that|not that(?: one)?|hands off) )+",
    # an optional hedge opening a claim ("i think that ...")
    "THINK": r"(?P<think>(?:i think|i believe|i guess|i am sure|i am pretty sure)(?: that)? )?",
    # an agent or object name
    "NAME": rf"{_NAME}",
}
_PLACEHOLDER = re.compile(r"<([A-Z]+)>")

Builder = Callable[[re.Match[str], Resolver], tuple[Instruction, ...] | None]


def expand(template: str) -> str:
    """The regular expression of a template (fragments substituted)."""
    return _PLACEHOLDER.sub(lambda m: FRAGMENTS[m.group(1)], template)


@dataclass(frozen=True)
class GrammarRule:
    """One form: its name (the builder's), intent, template, compiled pattern and builder."""

    name: str
    intent: str
    template: str
    pattern: re.Pattern[str]
    build: Builder


class Grammar:
    """An ordered list of rules; ``@grammar.rule(intent, *templates)`` registers a builder."""

    def __init__(self) -> None:
        self.rules: list[GrammarRule] = []

    def rule(self, intent: str, *templates: str) -> Callable[[Builder], Builder]:
        """Register the decorated builder under each template, in order."""

        def register(build: Builder) -> Builder:
            for template in templates:
                pattern = re.compile(expand(template))
                self.rules.append(GrammarRule(build.__name__, intent, template, pattern, build))
            return build

        return register


def first_match(
    rules: tuple[GrammarRule, ...], text: str, r: Resolver
) -> tuple[GrammarRule, tuple[Instruction, ...]] | None:
    """The first rule whose pattern matches all of ``text`` and whose builder accepts it (a
    builder declines by returning None or raising :class:`Decline`)."""
    for rule in rules:
        m = rule.pattern.fullmatch(text)
        if m is not None:
            try:
                built = rule.build(m, r)
            except Decline:
                continue
            if built is not None:
                return rule, built
    return None


def group(m: re.Match[str], name: str) -> str | None:
    """A named group's text, or None if the pattern has no such group or it did not take part."""
    return m.groupdict().get(name)
