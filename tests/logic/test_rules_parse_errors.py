"""Malformed norms raise RuleSyntaxError naming the bad word and, where there is a choice, the valid ones."""

from __future__ import annotations

import pytest

from ownctl.errors import OwnctlError, RuleSyntaxError
from ownctl.logic.rules import parse_norm, parse_rule
from ownctl.logic.vocab import ACTIONS, PREDICATES

ALL_ACTIONS = tuple(ACTIONS)
ALL_PREDICATES = tuple(PREDICATES)

# (input, fragments the message must contain, values `valid` must list (and the message too))
BAD = [
    ("forbid thrash", ["'thrash'", "unknown action"], ALL_ACTIONS),
    ("allow Trash if ownedBy a", ["'Trash'", "unknown action"], ALL_ACTIONS),
    ("forbid", ["action is missing"], ALL_ACTIONS),
    ("permit trash", ["'permit'"], ("forbid", "allow")),
    ("Forbid trash", ["'Forbid'"], ("forbid", "allow")),
    ("", ["empty"], ("forbid", "allow")),
    ("  \t\n ", ["empty"], ("forbid", "allow")),
    ("forbid trash if ownsBy alexis", ["'ownsBy'", "unknown predicate"], ALL_PREDICATES),
    ("forbid trash if not isRed", ["'isRed'", "unknown predicate"], ALL_PREDICATES),
    ("forbid trash if (ownedBy a)", ["'(ownedBy'"], ALL_PREDICATES),
    ("forbid trash if ownedBy", ["ownedBy", "argument"], ()),
    ("forbid trash if isColored red and inArea", ["inArea", "argument"], ()),
    ("forbid trash if ownedBy and isColored red", ["'and'"], ()),
    ("forbid trash if", ["literal is missing"], ("not", *ALL_PREDICATES)),
    ("forbid trash if ownedBy a and", ["literal is missing"], ("not", *ALL_PREDICATES)),
    ("forbid trash if not", ["literal is missing"], ALL_PREDICATES),
    ("forbid trash if ownedBy a b", ["'b'", "unexpected word"], ("and",)),
    ("forbid trash if ownedBy a and isColored red extra", ["'extra'"], ("and",)),
    ("forbid trash if ownedBy a or isColored red", ["'or'"], ("and",)),
    ("forbid trash if ownedBy a, isColored red", ["'a,'"], ()),
    ("forbid trash when ownedBy a", ["'when'"], ("if",)),
    ("forbid trash ownedBy a", ["'ownedBy'"], ("if",)),
    ("forbid trash if ownedBy none", ["'none'"], ()),
    ("forbid trash if ownedBy not", ["'not'"], ()),
    ("forbid trash if isColored 1red", ["'1red'"], ()),
    ("forbid trash if ownedBy " + "a" * 65, ["'" + "a" * 65 + "'"], ()),
    ("forbid trash if ownedBy \u0430lexis", ["'\u0430lexis'"], ()),
    ("forbid trash if ownedBy x'; drop table", ['"x\';"'], ()),
    ("forbid trash if ownedBy robert');DROP TABLE students;--", ["\"robert');DROP\""], ()),
    ("forbid trash if isColored re\x00d", ["'re\\x00d'"], ()),
    ("forbid trash if isColored red\x07", ["'red\\x07'"], ()),
    ("forbid trash if inArea home\x1b[31m", ["'home\\x1b[31m'"], ()),
    ("forbid trash if isColored red and not isColored red", ["contradictory", "'isColored red'",
                                                               "'not isColored red'"], ()),
    ("forbid pickUp if ownedBy any and inArea home and not ownedBy any",
     ["contradictory", "'ownedBy any'", "'not ownedBy any'"], ()),
]


@pytest.mark.parametrize(("text", "fragments", "valid"), BAD, ids=[repr(b[0])[:40] for b in BAD])
def test_bad_norm_is_rejected_with_a_pointed_message(text: str, fragments: list[str], valid: tuple) -> None:
    with pytest.raises(RuleSyntaxError) as info:
        parse_norm(text)
    err = info.value
    assert isinstance(err, OwnctlError) and err.exit_code == 1
    for fragment in fragments:
        assert fragment in err.message, (fragment, err.message)
    for choice in valid:
        assert choice in err.valid, (choice, err.valid)
        assert choice in err.message, (choice, err.message)
    # The message is one printable line: control characters are escaped, never echoed raw.
    assert err.message.isprintable(), repr(err.message)
    # parse_rule rejects the same input the same way.
    with pytest.raises(RuleSyntaxError):
        parse_rule(text)


def test_unknown_action_lists_the_paper_actions() -> None:
    with pytest.raises(RuleSyntaxError) as info:
        parse_norm("forbid thrash if ownedBy any")
    assert "thrash" in info.value.message
    assert "trash" in info.value.valid and "collect" in info.value.valid
    assert ", trash," in info.value.message and "collect" in info.value.message


def test_parse_rule_refuses_allow() -> None:
    assert parse_norm("allow trash if ownedBy a").sign == "allow"
    with pytest.raises(RuleSyntaxError) as info:
        parse_rule("allow trash if ownedBy a")
    assert "'allow'" in info.value.message and info.value.valid == ["forbid"]


def test_bad_word_position_is_reported() -> None:
    with pytest.raises(RuleSyntaxError) as info:
        parse_norm("forbid  trash\tif ownedBy a and colour red")
    assert "word 7 'colour'" in info.value.message


@pytest.mark.parametrize("arg", ["Any", "ANY", "None", "forbid", "allow", "on"])
def test_reserved_word_is_not_an_argument(arg: str) -> None:
    with pytest.raises(RuleSyntaxError) as info:
        parse_norm(f"forbid trash if ownedBy {arg}")
    assert repr(arg) in info.value.message


@pytest.mark.parametrize("ch", ["\x1c", "\x1d", "\x1e", "\x1f", "\x85"])
def test_control_character_is_not_a_separator(ch: str) -> None:
    with pytest.raises(RuleSyntaxError):
        parse_norm(f"forbid trash if isColored{ch}red")
