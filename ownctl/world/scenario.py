"""Scenario files (docs/architecture.md, section 11): the ``[[steps]]`` of a world file, parsed and checked.

Pure: a parsed TOML dict -> :class:`Scenario` (the world part is :func:`ownctl.world.spec.
world_from_dict`'s). Each step does one thing -- ``say`` an utterance (``as`` a speaker, ``about``
an object), run a ``command`` (an ownctl instruction line), or ``run`` a task with optional
``[[steps.interrupt]]`` utterances -- and carries ``expect`` lines, checked after the step::

    check ACTION OBJ = forbidden|permitted      rule 'CANONICAL TEXT'      no rule 'TEXT'
    owner OBJ AGENT > P   (or <)                moved OBJ                  left OBJ

``moved``/``left`` compare an object's position with where it was when the scenario's world was
loaded (``left``: within 1 cm). Unknown keys and malformed lines are errors naming the file, the
step and the valid keys or forms.
"""

from __future__ import annotations

import math
import re
import shlex
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ownctl.errors import BadValue, OwnctlError
from ownctl.logic.names import composed, is_name
from ownctl.logic.rules import parse_norm
from ownctl.logic.vocab import ACTIONS
from ownctl.world.spec import check_table

STEP_KEYS = ("say", "as", "about", "command", "run", "instructor", "interrupt", "expect")
INTERRUPT_KEYS = ("before", "say", "as")
KINDS = ("say", "command", "run")
INSTRUCTORS = ("none", "oracle")
EXPECTATION_FORMS = (
    "check ACTION OBJ = forbidden|permitted",
    "rule 'TEXT'",
    "no rule 'TEXT'",
    "owner OBJ AGENT > P",
    "owner OBJ AGENT < P",
    "moved OBJ",
    "left OBJ",
)
NOT_COMMANDS = ("init", "batch", "scenario")  # lines a scenario may not run


@dataclass(frozen=True)
class CheckExpectation:
    """``check ACTION OBJ = forbidden|permitted``."""

    text: str
    action: str
    object: str
    forbidden: bool


@dataclass(frozen=True)
class RuleExpectation:
    """``rule 'TEXT'`` (present) or ``no rule 'TEXT'``; ``rule`` is the canonical text."""

    text: str
    rule: str
    present: bool


@dataclass(frozen=True)
class OwnerExpectation:
    """``owner OBJ AGENT > P`` (``above``) or ``< P``, on the decision belief."""

    text: str
    object: str
    agent: str
    above: bool
    p: float


@dataclass(frozen=True)
class PlaceExpectation:
    """``moved OBJ`` or ``left OBJ``: compared with the position when the world was loaded."""

    text: str
    object: str
    moved: bool


Expectation = CheckExpectation | RuleExpectation | OwnerExpectation | PlaceExpectation


@dataclass(frozen=True)
class Interruption:
    """``utterance`` said by ``speaker`` when the robot is about to do ``action`` on ``object``."""

    action: str
    object: str
    utterance: str
    speaker: str


@dataclass(frozen=True)
class Step:
    """One step: ``kind`` is ``say``, ``command`` or ``run``; ``text`` the utterance, line or task."""

    number: int
    kind: str
    text: str
    speaker: str | None = None
    about: str | None = None
    words: tuple[str, ...] = ()  # a command line split into arguments
    instructor: str = "none"
    interrupts: tuple[Interruption, ...] = ()
    expect: tuple[Expectation, ...] = ()

    def describe(self) -> str:
        """One line for people: ``say "No, that's mine!" (as xuan, about mug)``."""
        if self.kind == "say":
            extra = [f"as {self.speaker}"] if self.speaker else []
            extra += [f"about {self.about}"] if self.about else []
            return f'say "{self.text}"' + (f" ({', '.join(extra)})" if extra else "")
        if self.kind == "run":
            said = "".join(f'; before {i.action} {i.object}, {i.speaker}: "{i.utterance}"'
                           for i in self.interrupts)
            who = f" with the {self.instructor} instructor" if self.instructor != "none" else ""
            return f"run {self.text}{who}{said}"
        return f"ownctl {self.text}"


@dataclass(frozen=True)
class Scenario:
    """A scenario's steps (its world is read separately); ``source`` names the file in messages."""

    name: str
    source: str
    steps: tuple[Step, ...]


def _text(source: str, where: str, key: str, value: Any) -> str:
    if not isinstance(value, str) or not value.strip():
        raise BadValue(f"{source}: {where}: {key} must be a non-empty string, got {value!r}")
    return value.strip()


def _name(source: str, where: str, what: str, value: str) -> str:
    if isinstance(value, str):
        value = composed(value)
    if not is_name(value):
        raise BadValue(f"{source}: {where}: {value!r} is not a valid {what} name")
    return value


def _bad_expectation(source: str, where: str, line: Any, why: str = "") -> OwnctlError:
    forms = "; ".join(EXPECTATION_FORMS)
    detail = f" ({why})" if why else ""
    return BadValue(f"{source}: {where}: malformed expectation {line!r}{detail}; expectations are: {forms}",
                    EXPECTATION_FORMS)


_CHECK = re.compile(r"check\s+(\S+)\s+(\S+)\s*=\s*(forbidden|permitted)")
_RULE = re.compile(r"(no\s+)?rule\s+(?:'([^']*)'|\"([^\"]*)\")")
_OWNER = re.compile(r"owner\s+(\S+)\s+(\S+)\s*([<>])\s*(\S+)")
_PLACE = re.compile(r"(moved|left)\s+(\S+)")


def parse_expectation(line: Any, source: str = "<scenario>", where: str = "expect") -> Expectation:
    """One expectation line -> its typed form; BadValue naming ``source``/``where`` and the forms."""
    if not isinstance(line, str):
        raise _bad_expectation(source, where, line, "an expectation is a string")
    text = line.strip()

    def name(what: str, value: str) -> str:
        value = composed(value)
        if not is_name(value):
            raise _bad_expectation(source, where, line, f"{value!r} is not a valid {what} name")
        return value

    if m := _CHECK.fullmatch(text):
        if m[1] not in ACTIONS:
            raise _bad_expectation(source, where, line, f"unknown action {m[1]!r}; known actions: "
                                   f"{', '.join(ACTIONS)}")
        return CheckExpectation(text, m[1], name("object", m[2]), m[3] == "forbidden")
    if m := _RULE.fullmatch(text):
        try:
            norm = parse_norm(m[2] if m[2] is not None else m[3])
        except OwnctlError as exc:
            raise _bad_expectation(source, where, line, exc.message) from None
        if norm.sign != "forbid":
            raise _bad_expectation(source, where, line, "rules are kept as forbid rules")
        return RuleExpectation(text, norm.text(), not m[1])
    if m := _OWNER.fullmatch(text):
        try:
            p = float(m[4])
        except ValueError:
            p = math.nan
        if not 0.0 <= p <= 1.0:
            raise _bad_expectation(source, where, line, f"{m[4]!r} is not a probability in [0, 1]")
        return OwnerExpectation(text, name("object", m[1]), name("agent", m[2]), m[3] == ">", p)
    if m := _PLACE.fullmatch(text):
        return PlaceExpectation(text, name("object", m[2]), m[1] == "moved")
    raise _bad_expectation(source, where, line)


def _interrupt(source: str, where: str, table: Any) -> Interruption:
    table = check_table(source, where, table, INTERRUPT_KEYS)
    missing = [k for k in INTERRUPT_KEYS if k not in table]
    if missing:
        raise BadValue(f"{source}: {where} needs {', '.join(missing)} (keys: {', '.join(INTERRUPT_KEYS)})",
                       INTERRUPT_KEYS)
    before = _text(source, where, "before", table["before"]).split()
    if len(before) != 2 or before[0] not in ACTIONS:
        raise BadValue(f"{source}: {where}: before must be 'ACTION OBJECT' with ACTION one of "
                       f"{', '.join(ACTIONS)}, got {table['before']!r}", ACTIONS)
    return Interruption(before[0], _name(source, where, "object", before[1]),
                        _text(source, where, "say", table["say"]),
                        _name(source, where, "agent", _text(source, where, "as", table["as"])))


def _words(source: str, where: str, line: str) -> tuple[str, ...]:
    try:
        words = shlex.split(line, comments=True)
    except ValueError as exc:
        raise BadValue(f"{source}: {where}: cannot split command {line!r} into words: {exc}") from None
    if words and words[0] == "ownctl":
        words = words[1:]
    if not words:
        raise BadValue(f"{source}: {where}: command is empty")
    if words[0] in NOT_COMMANDS or any(w == "--db" or w.startswith("--db=") for w in words):
        raise BadValue(f"{source}: {where}: a scenario cannot run {line!r} (no {', '.join(NOT_COMMANDS)} "
                       "or --db inside a scenario)", NOT_COMMANDS)
    return tuple(words)


def parse_step(source: str, number: int, table: Any) -> Step:
    """Step ``number`` (1-based) of ``source``."""
    where = f"step {number}"
    table = check_table(source, where, table, STEP_KEYS)
    kinds = [k for k in KINDS if k in table]
    if len(kinds) != 1:
        raise BadValue(f"{source}: {where} must have exactly one of {', '.join(KINDS)}, got "
                       f"{', '.join(kinds) or 'none'}", KINDS)
    kind = kinds[0]
    text = _text(source, where, kind, table[kind])
    allowed = {"say": ("as", "about"), "command": (), "run": ("instructor", "interrupt")}[kind]
    for key in ("as", "about", "instructor", "interrupt"):
        if key in table and key not in allowed:
            raise BadValue(f"{source}: {where}: key {key!r} does not go with {kind}; a {kind} step takes "
                           f"{', '.join((kind, *allowed, 'expect'))}", (kind, *allowed, "expect"))
    speaker = about = None
    if "as" in table:
        speaker = _name(source, where, "agent", _text(source, where, "as", table["as"]))
    if "about" in table:
        about = _name(source, where, "object", _text(source, where, "about", table["about"]))
    instructor = table.get("instructor", "none")
    if instructor not in INSTRUCTORS:
        raise BadValue(f"{source}: {where}: unknown instructor {instructor!r}; valid instructors: "
                       f"{', '.join(INSTRUCTORS)}", INSTRUCTORS)
    raw = table.get("interrupt", [])
    if not isinstance(raw, list):
        raise BadValue(f"{source}: {where}: interrupt must be an array of tables ([[steps.interrupt]])")
    interrupts = tuple(_interrupt(source, f"{where} interrupt {i + 1}", t) for i, t in enumerate(raw))
    expect = table.get("expect", [])
    if not isinstance(expect, list):
        raise BadValue(f"{source}: {where}: expect must be a list of strings, got {expect!r}",
                       EXPECTATION_FORMS)
    return Step(
        number=number,
        kind=kind,
        text=text,
        speaker=speaker,
        about=about,
        words=_words(source, where, text) if kind == "command" else (),
        instructor=instructor,
        interrupts=interrupts,
        expect=tuple(parse_expectation(line, source, f"{where} expect") for line in expect),
    )


def scenario_from_dict(data: Mapping[str, Any], source: str) -> Scenario:
    """The steps of a parsed scenario file (top-level keys are checked by the world parser)."""
    steps = data.get("steps", [])
    if not isinstance(steps, list):
        raise BadValue(f"{source}: steps must be an array of tables ([[steps]]), got {steps!r}")
    name = data.get("name", "")
    return Scenario(
        name=name if isinstance(name, str) else "",
        source=source,
        steps=tuple(parse_step(source, i + 1, t) for i, t in enumerate(steps)),
    )
