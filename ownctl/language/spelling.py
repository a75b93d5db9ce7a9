"""Typos: a misspelt word is read as the one word it is one edit away from, never guessed.

A word of at least :data:`MIN_WORD` letters that the parser does not know, within Levenshtein
distance 1 of exactly one word of the grammar's vocabulary or of exactly one agent or object name
longer than :data:`MAX_SHORT_NAME` letters, is read as that word ("colect" -> "collect", "casy" ->
"casey"); a word near two or more is left alone, and the refusal says which it could be. Shorter
words must be spelt exactly (too many short words are one edit apart: "mug" and "mud"). The
vocabulary is every word the grammar's patterns and the lexicon spell out.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cache

from rapidfuzz import process
from rapidfuzz.distance import Levenshtein

from ownctl.language import lexicon
from ownctl.language.context import Context

#: The fewest letters a word needs to be corrected against the vocabulary.
MIN_WORD = 5
#: Names this short (or shorter) are never matched approximately.
MAX_SHORT_NAME = 3

_GROUP_NAME = re.compile(r"\(\?P[<=]\w+>?|\\[a-zA-Z]")
_WORDS = re.compile(r"[a-z]+")


@dataclass(frozen=True)
class Reading:
    """One corrected word: ``word`` was read as ``as_word``."""

    word: str
    as_word: str

    def note(self) -> str:
        """``(read 'colect' as 'collect')``."""
        return f"(read {self.word!r} as {self.as_word!r})"


def words_of(patterns: Iterable[str]) -> set[str]:
    """The literal words of regular expressions (group names and escapes left out)."""
    out: set[str] = set()
    for pattern in patterns:
        out.update(_WORDS.findall(_GROUP_NAME.sub(" ", pattern)))
    return out


#: The grammar's patterns, told by the grammar when it is defined (:func:`know_patterns`), so that
#: this module need not import the parser that imports it.
_GRAMMAR: list[str] = []


def know_patterns(patterns: Iterable[str]) -> None:
    """Add the grammar's regular expressions to the vocabulary typos are corrected towards."""
    _GRAMMAR.extend(patterns)
    vocabulary.cache_clear()


@cache
def vocabulary() -> frozenset[str]:
    """Every word the parser knows (grammar patterns, phrase modifiers, normalisation, lexicon)."""
    from ownctl.language import phrases
    from ownctl.language.normalize import REWRITES

    patterns = list(_GRAMMAR)
    patterns += [mod.pattern.pattern for mod in (*phrases.PREMODIFIERS, *phrases.POSTMODIFIERS)]
    patterns += [p.pattern for p, _ in REWRITES] + [r for _, r in REWRITES]
    tables: list[Iterable[str]] = [
        lexicon.ACTION_PHRASES, lexicon.GERUNDS, lexicon.PASSIVES, lexicon.HEDGES, lexicon.DISCOURSE,
        lexicon.FILLERS, lexicon.ADJECTIVES, lexicon.COLORS, lexicon.CLASS_HEADS, lexicon.NOT_NOUNS,
        lexicon.GENERIC_NOUNS, lexicon.SPEAKER_WORDS, lexicon.ANYONE_WORDS, lexicon.NOBODY_WORDS,
        lexicon.ROBOT_NAMES, lexicon.BIN_WORDS, lexicon.BIN_VERBS, lexicon.PARTICLES, lexicon.NOT_NAMES,
    ]
    return frozenset(words_of(patterns) | {w for table in tables for phrase in table for w in phrase.split()})


def _near(word: str, choices: Iterable[str]) -> list[str]:
    """The choices within edit distance 1 of ``word`` (itself excluded)."""
    found = process.extract(word, list(choices), scorer=Levenshtein.distance, score_cutoff=1, limit=None)
    return sorted({choice for choice, _, _ in found if choice != word})


def known_words(ctx: Context) -> set[str]:
    """The vocabulary and every name of the context (lower case)."""
    return set(vocabulary()) | ctx.names()


def candidates(word: str, ctx: Context) -> list[str]:
    """What an unknown word may be a typo of: vocabulary words (if it has MIN_WORD letters) and
    agent and object names longer than MAX_SHORT_NAME letters (if it is longer too)."""
    found: set[str] = set()
    if len(word) >= MIN_WORD:
        found.update(_near(word, vocabulary()))
    if len(word) > MAX_SHORT_NAME:
        names = [n.lower() for n in (*ctx.agents, *ctx.objects) if len(n) > MAX_SHORT_NAME]
        found.update(_near(word, names))
    return sorted(found)


def corrections(words: Iterable[str], ctx: Context) -> tuple[list[Reading], dict[str, list[str]]]:
    """For the unknown words among ``words``: the unique corrections, and the words near several."""
    known = known_words(ctx)
    names = {n.lower() for n in (*ctx.objects, *ctx.categories)}
    readings: list[Reading] = []
    unclear: dict[str, list[str]] = {}
    for word in dict.fromkeys(words):
        if word in known or not word.isalpha() or any(s in names for s in _singulars(word)):
            continue
        near = candidates(word, ctx)
        if len(near) == 1:
            readings.append(Reading(word, near[0]))
        elif near:
            unclear[word] = near
    return readings, unclear


def _singulars(word: str) -> list[str]:
    """A plural's possible singulars, so "cups" is not taken for a typo of the object or category
    "cup"."""
    from ownctl.language.resolve import plural_stems

    return plural_stems(word)[1:]


def apply(utterance: str, readings: list[Reading]) -> str:
    """The utterance with each misspelt word replaced (whole words, any case)."""
    for reading in readings:
        utterance = re.sub(rf"(?i)(?<![\w'-]){re.escape(reading.word)}(?![\w-])", reading.as_word, utterance)
    return utterance
