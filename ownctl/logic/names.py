"""The naming rule for agents, objects, areas, colours and categories (docs/architecture.md, section 2).

Names are Unicode: people are called José, Zoë, Дима or राम, and a household names its things in
its own language. A name is a letter of any script, then letters, combining marks, decimal
digits, '_' or '-'. It is compared in its compatibility-composed form (NFKC, as Python compares
identifiers), so "José" typed with a combining accent, or "ｊｏｓé" in full-width letters, is the
José of the store. A name keeps to one script (or to one of the mixes a language writes with:
Latin, Han, Hiragana, Katakana; Latin, Han, Hangul; Latin, Han, Bopomofo), so that a Cyrillic "а"
in "аgent" cannot pass for the agent "agent".
"""

from __future__ import annotations

import unicodedata
from functools import lru_cache

from ownctl.errors import BadName

NAME_RULE = (
    "a letter, then letters, marks, digits, '_' or '-' (at most 64 characters, in one script)"
)
MAX_NAME = 64
LETTER = r"[^\W\d_]"
"""A regular-expression class for one letter of any script (a word character, not a digit or '_')."""
RESERVED = frozenset({"any", "none", "not", "and", "if", "on", "forbid", "allow"})
_COMMON = "common"
_MIXES = (  # scripts written together by one language (Unicode's "highly restrictive" mixes)
    frozenset({"LATIN", "CJK", "HIRAGANA", "KATAKANA"}),
    frozenset({"LATIN", "CJK", "HANGUL"}),
    frozenset({"LATIN", "CJK", "BOPOMOFO"}),
)


def composed(text: str) -> str:
    """``text`` in its compatibility-composed normal form (NFKC): one spelling per name."""
    return unicodedata.normalize("NFKC", text)


@lru_cache(maxsize=1)
def marks() -> str:
    """The combining marks of the Basic Multilingual Plane as ranges for a regex character class
    (``\\w`` leaves them out, yet Devanagari, Thai or Hebrew words carry them)."""
    ranges: list[str] = []
    start = prev = -2
    for code in range(0x10000):
        if unicodedata.category(chr(code)) in ("Mn", "Mc"):
            if code != prev + 1:
                if start >= 0:
                    ranges.append(_range(start, prev))
                start = code
            prev = code
    ranges.append(_range(start, prev))
    return "".join(ranges)


def _range(first: int, last: int) -> str:
    return f"\\u{first:04x}" if first == last else f"\\u{first:04x}-\\u{last:04x}"


@lru_cache(maxsize=1)
def word_pattern() -> str:
    """A regex for one name-shaped word: a letter, then letters, marks, digits, '_' or '-'."""
    return rf"{LETTER}[\w{marks()}-]*"


@lru_cache(maxsize=1)
def letters_pattern() -> str:
    """A regex for one word of letters and marks only (a colour: "red", "grün")."""
    return rf"{LETTER}(?:{LETTER}|[{marks()}])*"


def _char_ok(char: str) -> bool:
    category = unicodedata.category(char)
    return char in "_-" or category[0] == "L" or category in ("Mn", "Mc", "Nd")


def _script(char: str) -> str:
    """The script a letter or mark is written in, from its Unicode name ("LATIN SMALL LETTER E")."""
    if unicodedata.category(char)[0] not in "LM":
        return _COMMON
    word = unicodedata.name(char, "").split(" ")[0]
    if word in ("COMBINING", "MODIFIER", ""):
        return _COMMON
    if word == "KATAKANA-HIRAGANA":
        return "KATAKANA"
    return word


def scripts(text: str) -> frozenset[str]:
    """The scripts of ``text``'s letters and marks (digits, '_' and '-' belong to none)."""
    return frozenset(s for s in map(_script, text) if s != _COMMON)


def _one_script(text: str) -> bool:
    found = scripts(text)
    return len(found) <= 1 or any(found <= mix for mix in _MIXES)


def is_name(text: str) -> bool:
    """True if ``text`` obeys the naming rule (reserved words included) and is in composed form."""
    return (
        isinstance(text, str)
        and 0 < len(text) <= MAX_NAME
        and unicodedata.category(text[0])[0] == "L"
        and all(map(_char_ok, text))
        and composed(text) == text
        and _one_script(text)
    )


def check_name(kind: str, name: str) -> str:
    """Return ``name``, composed, if it is a valid, unreserved name for a new ``kind``; raise BadName
    otherwise."""
    if not isinstance(name, str):
        raise BadName(f"invalid {kind} name {name!r}: a name is {NAME_RULE}")
    typed, name = name, composed(name)
    if not is_name(name):
        mixed = ", ".join(sorted(s.title() for s in scripts(name)))
        why = "" if _one_script(name) else f" (it mixes {mixed})"
        raise BadName(f"invalid {kind} name {typed!r}: a name is {NAME_RULE}{why}")
    if name.lower() in RESERVED:
        raise BadName(f"{kind} name {typed!r} is reserved; reserved words: {', '.join(sorted(RESERVED))}")
    return name

