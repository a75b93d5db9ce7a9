"""Two small sub-grammars: who a claim says owns an object, and which objects a norm is about.

*Owner phrases* follow "this is ..." / "this belongs to ...": ``[hedge] [not] [only] OWNER [now]
[alone] [and ALSO] [too] [not OTHER]`` ("probably mine", "mine now, not Xuan's", "Jake's alone",
"mine and Jake's", "Mia and Jake's" or "Jake and mine": joint ownership, two claims).

*Class phrases* describe a set of objects as literals about the target object:
``[determiner] premodifier* HEAD postmodifier*`` where premodifiers are possessors and colours
("my", "Jake's", "other people's", "red", "non-red", "unowned"), the head a word such as
"things", "stuff", "anything", and postmodifiers relative clauses or prepositional phrases
("that belong to Xuan", "of Jake's", "nobody owns", "in the home area", "if it is red"),
joined by an optional "and". Each modifier is one (pattern, builder) pair; a builder returning
None declines (e.g. a word that is not a colour), and the next modifier is tried. A head may also
be a known category, singular or plural ("cups", "any book").

:func:`class_alternatives` adds the connectives: "or" between two owners or colours gives two
alternatives ("things of Jake's or Xuan's": two rules), and "unless ..." adds the negation of its
condition ("Casey's stuff unless it's green": ``ownedBy casey and not isColored green``; an
exception that is itself a conjunction gives one alternative per negated literal).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from itertools import product

from ownctl.language.lexicon import CLASS_HEADS, HEDGES, alternation, hedge_of
from ownctl.language.resolve import NOBODY, POSSESSIVE_PRONOUNS, Resolver
from ownctl.logic.names import letters_pattern, word_pattern
from ownctl.logic.rules import ANY, Literal

_NAME = word_pattern()
_LETTERS = letters_pattern()

# -- owner phrases ---------------------------------------------------------------------------

_OWNER = rf"(?:mine|{_NAME}(?: 's)?)"
_TAIL = re.compile(
    rf"(?P<hedge>{alternation(tuple(HEDGES))} )?(?P<neg>not )?"
    r"(?P<only>(?:only|all|solely|exclusively|just) (?:to )?)?"
    r"(?:both |also )?"
    rf"(?P<owner>{_OWNER})"
    r"(?P<excl>(?: now| alone| only| exclusively| and (?:only )?(?P=owner)(?: alone)?)*)"
    rf"(?: and (?P<also>{_OWNER}))?"
    r"(?: too| as well| also)?"
    rf"(?: (?:and |but )?not (?P<other>{_OWNER})(?: anymore| any more)?)?"
    r"(?: either| anymore| any more| now| then)?"
)


@dataclass(frozen=True)
class Owned:
    """One resolved statement of ownership: ``agent`` (never ANY) owns the object, or not."""

    agent: str
    negated: bool = False
    exclusive: bool = False
    p: float = 1.0


def _possessive(word: str) -> bool:
    """True if an owner word is possessive: "mine", "ours", "hers", "Jake 's"."""
    return word in ("mine", "ours") or word in POSSESSIVE_PRONOUNS or word.endswith(" 's")


def owners(rest: str, possessive: bool, negated: bool, r: Resolver) -> list[Owned] | None:
    """Parse an owner phrase; ``possessive`` after "is" ("mine", "Jake's"), else after "belongs to".

    "nobody" becomes a negative statement for every known agent. Returns None if ``rest`` is not an
    owner phrase of that form (or says something a claim cannot hold: "someone's", "not only mine").
    """
    m = _TAIL.fullmatch(rest)
    if m is None:
        return None
    word = m["owner"]
    said = _possessive(word)
    # "Mia and Jake's", "Jake and mine": one possessive for two owners (joint, as "Mia's and Jake's")
    joint = possessive and not said and m["also"] is not None and _possessive(m["also"])
    if possessive != said and not joint:
        return None
    neg = negated ^ bool(m["neg"])
    exclusive = bool(m["only"]) or bool(m["excl"].strip())
    p = hedge_of(m["hedge"])
    who = r.owner(word)
    if who == ANY:
        who, neg = (NOBODY, not neg) if neg else (ANY, neg)
    if who == ANY or (neg and exclusive) or (who == NOBODY and (neg or exclusive)):
        return None
    if who == NOBODY:
        found = [Owned(a, True, False, p) for a in sorted(r.ctx.agents)]
    else:
        found = [Owned(who, neg, exclusive, p)]
    for phrase, against in ((m["also"], False), (m["other"], True)):
        if phrase:  # "mine and Jake's" (joint), "mine, not Xuan's" (explicitly not Xuan's)
            agent = r.owner(phrase)
            if agent in (ANY, NOBODY) or who == NOBODY or neg or (exclusive and not against):
                return None
            found.append(Owned(agent, against, False, p))
    return found


# -- class phrases ---------------------------------------------------------------------------

Build = Callable[[re.Match[str], Resolver], list[Literal] | None]


@dataclass(frozen=True)
class Modifier:
    """One way of narrowing a class of objects: a pattern and the literals it contributes."""

    pattern: re.Pattern[str]
    build: Build


def own(who: str, negated: bool = False) -> Literal:
    """``ownedBy who`` (NOBODY becomes ``not ownedBy any``)."""
    if who == NOBODY:
        return Literal("ownedBy", ANY, not negated)
    return Literal("ownedBy", who, negated)


def _colour(m: re.Match[str], r: Resolver) -> list[Literal] | None:
    name = r.colour(m["c"])
    return None if name is None else [Literal("isColored", name, bool(m.groupdict().get("neg")))]


def _area(m: re.Match[str], r: Resolver) -> list[Literal] | None:
    name = r.area(m["a"], bool(m["said"]))
    negated = bool(m["neg"]) ^ m["prep"].startswith("outside")
    return None if name is None else [Literal("inArea", name, negated)]


def _category(m: re.Match[str], r: Resolver) -> list[Literal] | None:
    name = r.category(m["k"] or m["k2"])
    return None if name is None else [Literal("inCategory", name, bool(m["neg"]))]


def _owner(m: re.Match[str], r: Resolver) -> list[Literal]:
    return [own(r.owner(m["o"]), bool(m.groupdict().get("neg")))]


def _mod(pattern: str, build: Build) -> Modifier:
    return Modifier(re.compile(pattern + r"(?= |$)"), build)


_REL = r"(?:(?:that|which|if|when|whenever|as long as) (?:it |they )?)?"
_BE = r"(?:(?:is|are) )?"
_NOT = r"(?P<neg>not )?"
_WHO_WORDS = rf"other people|someone else|anyone else|other agents|another person|{_NAME}"
_WHO = rf"(?P<o>{_WHO_WORDS})"
_POSS = rf"(?P<o>mine|(?:{_WHO_WORDS}) 's)"

PREMODIFIERS: tuple[Modifier, ...] = (
    _mod(rf"(?P<o>(?:{_WHO_WORDS}) 's|my)", _owner),
    _mod(rf"(?P<neg>non-?|not )(?P<c>{_LETTERS})", _colour),
    _mod(rf"(?P<c>{_LETTERS})", _colour),
    _mod(r"(?:owned|claimed)", lambda m, r: [own(ANY)]),
    _mod(r"(?:unowned|ownerless|unclaimed)", lambda m, r: [own(ANY, True)]),
)

POSTMODIFIERS: tuple[Modifier, ...] = (
    _mod(rf"{_REL}{_BE}{_NOT}in (?:the )?(?:category (?P<k>{_NAME})|(?P<k2>{_NAME}) category)",
         _category),
    _mod(rf"{_REL}{_BE}{_NOT}(?P<prep>in|on|inside|within|at|from|off|outside(?: of)?) "
         rf"(?:the )?(?P<a>{_NAME})(?P<said> area| zone| region)?", _area),
    _mod(rf"{_REL}(?P<neg>(?:does|do) not )?belongs? to {_WHO}", _owner),
    _mod(rf"{_REL}{_BE}{_NOT}owned by {_WHO}", _owner),
    _mod(rf"{_REL}(?:is|are) {_NOT}{_POSS}", _owner),
    _mod(rf"of {_POSS}", _owner),
    _mod(rf"{_REL}{_WHO} (?P<neg>(?:does|do) not )?owns?", _owner),
    _mod(rf"{_REL}{_BE}{_NOT}owned", lambda m, r: [own(ANY, bool(m["neg"]))]),
    _mod(rf"{_REL}{_BE}unowned", lambda m, r: [own(ANY, True)]),
    _mod(rf"{_REL}(?P<neg>(?:does|do) not )?(?:has|have|with) (?:an? |some )?owners?",
         lambda m, r: [own(ANY, bool(m["neg"]))]),
    _mod(rf"{_REL}(?:has|have) no owners?", lambda m, r: [own(ANY, True)]),
    _mod(r"without (?:an? )?owners?", lambda m, r: [own(ANY, True)]),
    _mod(rf"{_REL}{_BE}{_NOT}(?:colored )?(?P<c>{_LETTERS})", _colour),
)

_DETERMINER = re.compile(r"(?:(?:any|all|every|each)(?: of)?(?: the)? |the )")
_HEAD = re.compile(alternation(CLASS_HEADS) + "(?= |$)")
_AND = re.compile(r"(?:and |but )")


def _modifiers(text: str, pos: int, mods: tuple[Modifier, ...], r: Resolver,
               joiner: bool) -> tuple[int, list[Literal]]:
    """Consume as many modifiers as possible from ``pos``; returns the new position and literals."""
    found: list[Literal] = []
    while pos < len(text):
        start = pos
        if joiner and found and (j := _AND.match(text, pos)):
            start = j.end()
        for mod in mods:
            m = mod.pattern.match(text, start)
            if m is None or m.end() == start:
                continue
            lits = mod.build(m, r)
            if lits is not None:
                found += lits
                pos = m.end() + 1 if m.end() < len(text) else m.end()
                break
        else:
            break
    return pos, found


def class_literals(phrase: str, r: Resolver) -> tuple[Literal, ...] | None:
    """The literals of a class phrase ("other people's red things", "anything nobody owns").

    None if ``phrase`` is not a class phrase (no head word, or words left over). A bare head
    ("anything") gives no literals: the norm then applies to every object. "it"/"them" heads need a
    condition ("it if it is red").
    """
    det = m.group() if (m := _DETERMINER.match(phrase)) else ""
    pos, pre = _modifiers(phrase, len(det), PREMODIFIERS, r, joiner=False)
    kind: list[Literal] = []
    word = phrase[pos:].split(" ", 1)[0]
    category = r.category_noun(word) if r.ctx.categories else None
    if category is not None and word == category and det == "the " and r.is_object(word):
        category = None  # "the cup" is one object; "cups", "any cup", "the kitchenware" are a class
    if category is not None:
        kind, end, head_word = [Literal("inCategory", category)], pos + len(word), word
    elif (head := _HEAD.match(phrase, pos)) is not None:
        end, head_word = head.end(), head.group()
    else:
        return None
    pos = end + 1
    pos, post = _modifiers(phrase, pos, POSTMODIFIERS, r, joiner=True)
    if pos < len(phrase) or (head_word in ("it", "them") and not (pre or post)):
        return None
    return tuple(dict.fromkeys((*pre, *kind, *post)))


# -- connectives: "or" and "unless" ----------------------------------------------------------------

_OR = re.compile(rf"(?:(?<= )|^)(?P<a>{_NAME}(?: 's)?) (?:or|nor) (?P<b>{_NAME}(?: 's)?)(?= |$)")
#: "Jake's and Mia's cups" in a class phrase: the cups of either (one rule each), as "or" gives.
_AND_OWNERS = re.compile(rf"(?:(?<= )|^)(?P<a>{_NAME} 's) and (?P<b>{_NAME} 's)(?= |$)")
_SUBJECT = re.compile(r"(?:it|they|something|anything|an object|a thing|the object|the thing|that|"
                      r"this|these|those|things|stuff|an item|the item) ")
_OBJECT_TAIL = re.compile(r" (?:it|them)$")


def condition_phrase(clause: str) -> str:
    """A clause about "it" as a class phrase: "it is red" -> "anything that is red", "something
    belongs to someone" -> "anything that belongs to someone", "nobody owns it" -> "anything that
    nobody owns"."""
    clause = _OBJECT_TAIL.sub("", clause)
    m = _SUBJECT.match(clause)
    return "anything that " + (clause[m.end():] if m else clause)


def _or_alternatives(phrase: str, r: Resolver) -> list[tuple[Literal, ...]] | None:
    """The alternatives of a class phrase with "A or B" between two words of one kind (or "A's
    and B's" between two owners)."""
    m = _OR.search(phrase) or _AND_OWNERS.search(phrase)
    if m is None:
        lits = class_literals(phrase, r)
        return None if lits is None else [lits]
    out: list[tuple[Literal, ...]] = []
    for word in (m["a"], m["b"]):
        alt = _or_alternatives(phrase[:m.start()] + word + phrase[m.end():], r)
        if alt is None:
            return None
        out += alt
    return list(dict.fromkeys(out))


def class_alternatives(phrase: str, r: Resolver) -> list[tuple[Literal, ...]] | None:
    """The class phrase as alternatives (a disjunction of literal conjunctions), with "or" and
    "unless"; None if it is not a class phrase."""
    main, sep, exception = phrase.partition(" unless ")
    alts = _or_alternatives(main, r)
    if alts is None or not sep:
        return alts
    excepted = _or_alternatives(condition_phrase(exception), r)
    if not excepted or any(not conj for conj in excepted):
        return None
    negations = [tuple(pick) for pick in product(*[[lit.negate() for lit in conj] for conj in excepted])]
    return list(dict.fromkeys(tuple(dict.fromkeys(a + n)) for a in alts for n in negations))
