"""Literals, rules and norms, with canonical printing and parsing (docs/architecture.md, section 2).

A :class:`Rule` is a conjunction of literals about its target object; a rule set (a tuple of rules
for one action) is their disjunction. A :class:`Norm` is a rule with a sign: ``forbid`` rules are
kept, ``allow`` rules are subtracted from them by the learner (paper, Algorithm 4).

Canonical text: ``forbid trash if ownedBy any and not isColored red``; literals in vocabulary order,
then by argument (``any`` first), a positive literal before its negation. An empty condition list
prints as ``forbid trash`` (always forbidden).
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from ownctl.errors import RuleSyntaxError
from ownctl.logic.names import RESERVED, composed, is_name
from ownctl.logic.vocab import ACTIONS, PREDICATES

ANY = "any"
_SPACE = re.compile(r"[ \t\r\n]+")
SIGNS = ("forbid", "allow")


@dataclass(frozen=True, order=False, eq=False)
class Literal:
    """``[not] pred arg`` about the rule's target object, e.g. ``not isColored red``."""

    pred: str
    arg: str
    negated: bool = False

    def __post_init__(self) -> None:
        # literals are hashed and sorted millions of times during rule search: compute once
        object.__setattr__(self, "_hash", hash((self.pred, self.arg, self.negated)))
        object.__setattr__(self, "_key", (PREDICATES[self.pred].order if self.pred in PREDICATES else 99,
                                          self.arg != ANY, self.arg, self.negated))

    def __hash__(self) -> int:
        return self._hash  # type: ignore[attr-defined, no-any-return]

    def __eq__(self, other: object) -> bool:
        if self is other:
            return True
        if not isinstance(other, Literal):
            return NotImplemented
        return self._key == other._key and self.pred == other.pred  # type: ignore[attr-defined]

    def __reduce__(self) -> tuple[type, tuple[str, str, bool]]:
        return (Literal, (self.pred, self.arg, self.negated))  # the cached hash is per process

    @property
    def atom(self) -> tuple[str, str]:
        """The literal without its sign."""
        return (self.pred, self.arg)

    def negate(self) -> Literal:
        """The complementary literal (made once per literal: search asks for it very often)."""
        neg = self.__dict__.get("_neg")
        if neg is None:
            neg = Literal(self.pred, self.arg, not self.negated)
            object.__setattr__(self, "_neg", neg)
            object.__setattr__(neg, "_neg", self)
        assert isinstance(neg, Literal)
        return neg

    def sort_key(self) -> tuple[int, bool, str, bool]:
        """Canonical order: vocabulary order, ``any`` first, then argument, positive first."""
        return self._key  # type: ignore[attr-defined, no-any-return]

    def text(self) -> str:
        """Canonical text of the literal."""
        return f"{'not ' if self.negated else ''}{self.pred} {self.arg}"


def implies(a: Literal, b: Literal) -> bool:
    """Whether literal ``a`` holding for an object forces ``b`` to hold (about the same object).

    ``P x`` implies ``P any``; ``not P any`` implies ``not P x``; and colours are exclusive, so
    ``isColored x`` implies ``not isColored y`` for another colour ``y``.
    """
    if a == b:
        return True
    if a.pred != b.pred:
        return False
    if not a.negated and not b.negated:
        return a.arg != ANY and b.arg == ANY
    if a.negated and b.negated:
        return a.arg == ANY and b.arg != ANY
    return (a.pred == "isColored" and not a.negated and b.negated and ANY not in (a.arg, b.arg)
            and a.arg != b.arg)


def canonical(literals: Iterable[Literal]) -> tuple[Literal, ...]:
    """Deduplicated literals in canonical order."""
    return tuple(sorted(set(literals), key=Literal.sort_key))


@dataclass(frozen=True)
class Rule:
    """``forbid action if l1 and l2 ...``: the action is forbidden on an object meeting every literal."""

    action: str
    literals: tuple[Literal, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "literals", canonical(self.literals))
        object.__setattr__(self, "_hash", hash((self.action, self.literals)))

    def __hash__(self) -> int:
        return self._hash  # type: ignore[attr-defined, no-any-return]

    def __reduce__(self) -> tuple[type, tuple[str, tuple[Literal, ...]]]:
        return (Rule, (self.action, self.literals))  # the cached hash is per process

    @property
    def conditions(self) -> frozenset[Literal]:
        """The literals as a set (for subsumption tests)."""
        return frozenset(self.literals)

    def with_literal(self, lit: Literal) -> Rule:
        """This rule refined by one more literal (kept canonical without a full sort)."""
        if lit in self.literals:
            return self
        key = lit._key  # type: ignore[attr-defined]
        lits = self.literals
        at = len(lits)
        for i, x in enumerate(lits):
            if x._key > key:  # type: ignore[attr-defined]
                at = i
                break
        out = object.__new__(Rule)
        merged = (*lits[:at], lit, *lits[at:])
        object.__setattr__(out, "action", self.action)
        object.__setattr__(out, "literals", merged)
        object.__setattr__(out, "_hash", hash((self.action, merged)))
        return out

    def is_contradictory(self) -> bool:
        """True if the rule holds a literal and its negation (it can never fire)."""
        lits = self.conditions
        return any(lit.negate() in lits for lit in lits)

    def simplified(self) -> Rule:
        """The same rule without literals another of its literals implies
        (``ownedBy any and ownedBy xuan`` is ``ownedBy xuan``)."""
        keep = [b for b in self.literals if not any(a != b and implies(a, b) for a in self.literals)]
        return self if len(keep) == len(self.literals) else Rule(self.action, tuple(keep))

    def admits(self, lit: Literal) -> bool:
        """Whether ``self and lit`` could hold for some object: not if a literal of the rule implies
        ``not lit`` (``ownedBy xuan`` with ``not ownedBy any``; ``isColored red`` with ``isColored
        blue``, colours being exclusive)."""
        return not any(implies(a, lit.negate()) or implies(lit, a.negate()) for a in self.literals)

    def is_satisfiable(self) -> bool:
        """False if no object could meet the conditions (see :meth:`admits`)."""
        lits = self.literals
        return all(Rule(self.action, lits[:i]).admits(lit) for i, lit in enumerate(lits))

    def agents(self) -> frozenset[str]:
        """The specific agents named by the rule's ownedBy literals (not ``any``)."""
        return frozenset(lit.arg for lit in self.literals if lit.pred == "ownedBy" and lit.arg != ANY)

    def text(self, sign: str = "forbid") -> str:
        """Canonical text, e.g. ``forbid trash if ownedBy any and not isColored red``."""
        head = f"{sign} {self.action}"
        if not self.literals:
            return head
        return head + " if " + " and ".join(lit.text() for lit in self.literals)

    def __str__(self) -> str:
        return self.text()


@dataclass(frozen=True)
class Norm:
    """A signed rule as an instructor states it: ``forbid ...`` or ``allow ...``."""

    sign: str
    rule: Rule

    def text(self) -> str:
        """Canonical text of the norm."""
        return self.rule.text(self.sign)


def _fail(source: str, index: int, word: str, problem: str, valid: Iterable[str] = ()) -> RuleSyntaxError:
    where = f"word {index + 1} {word!r}" if word else "end of input"
    valid = sorted(valid)
    tail = f"; expected one of: {', '.join(valid)}" if valid else ""
    return RuleSyntaxError(f"in rule {source!r}, {where}: {problem}{tail}", valid)


def parse_literals(words: list[str], start: int, source: str) -> tuple[Literal, ...]:
    """Parse ``[not] pred arg (and [not] pred arg)*`` from ``words[start:]``."""
    lits: list[Literal] = []
    i = start
    while True:
        negated = False
        if i < len(words) and words[i] == "not":
            negated = True
            i += 1
        if i >= len(words):
            raise _fail(source, i, "", "a literal is missing", ["not", *PREDICATES])
        pred = words[i]
        if pred not in PREDICATES:
            raise _fail(source, i, pred, "unknown predicate", PREDICATES)
        i += 1
        if i >= len(words):
            raise _fail(source, i, "", f"{pred} needs an argument ({PREDICATES[pred].argument} name or any)")
        arg = words[i]
        if not is_name(arg) or (arg != ANY and arg.lower() in RESERVED):
            raise _fail(source, i, arg, f"not a valid {PREDICATES[pred].argument} name (or any)")
        lits.append(Literal(pred, arg, negated))
        i += 1
        if i == len(words):
            break
        if words[i] != "and":
            raise _fail(source, i, words[i], "unexpected word after a literal", ["and"])
        i += 1
    literals = canonical(lits)
    for lit in literals:
        if lit.negate() in literals:
            raise RuleSyntaxError(f"in rule {source!r}: contradictory literals '{lit.text()}' and "
                                  f"'{lit.negate().text()}' (the rule could never apply)")
    return literals


def parse_norm(text: str) -> Norm:
    """Parse ``forbid|allow ACTION [if LITERALS]``; errors point at the bad word and list valid ones.
    Names are read in their composed form (docs/architecture.md, section 2)."""
    source = " ".join(w for w in _SPACE.split(composed(text)) if w)
    words = source.split(" ") if source else []
    if not words:
        raise _fail(source, 0, "", "empty rule", SIGNS)
    if words[0] not in SIGNS:
        raise _fail(source, 0, words[0], "a rule starts with forbid or allow", SIGNS)
    if len(words) < 2:
        raise _fail(source, 1, "", "the action is missing", ACTIONS)
    act = words[1]
    if act not in ACTIONS:
        raise _fail(source, 1, act, "unknown action", ACTIONS)
    if len(words) == 2:
        return Norm(words[0], Rule(act))
    if words[2] != "if":
        raise _fail(source, 2, words[2], "expected 'if' after the action", ["if"])
    return Norm(words[0], Rule(act, parse_literals(words, 3, source)))


def parse_rule(text: str) -> Rule:
    """Parse a ``forbid`` rule (the form rule sets are kept in)."""
    norm = parse_norm(text)
    if norm.sign != "forbid":
        raise RuleSyntaxError(f"in rule {text!r}: expected a forbid rule, got {norm.sign!r}", ["forbid"])
    return norm.rule
