"""The naming rule (architecture section 2): a letter, then letters, digits, '_' or '-';
reserved words refused."""

from __future__ import annotations

import pytest

from ownctl.errors import BadName, OwnctlError
from ownctl.logic.names import NAME_RULE, RESERVED, check_name, is_name

VALID = [
    "alexis", "xuan", "agent2", "block1", "desk_xuan", "Bob-1", "a", "A_b-9", "x" * 64, "anyone", "nonever",
]
HOSTILE = [
    "", " ", "1agent", "_agent", "-x", "x'; drop table objects; --", "robert');DROP", 'a"b', "a'b", "a b",
    "a\x00", "a\nb", "ab\n", "\tab", "a\x1b[31m", "a\x7f", "al\u00e9xis", "\u0430gent", "a.b", "a/b", "a;b",
    "x" * 65, "a*", "a:b",
]


@pytest.mark.parametrize("name", VALID)
def test_valid_names_are_returned(name: str) -> None:
    assert is_name(name)
    assert check_name("agent", name) == name


@pytest.mark.parametrize("name", HOSTILE, ids=[repr(n)[:24] for n in HOSTILE])
def test_invalid_names_are_refused_with_the_rule(name: str) -> None:
    assert not is_name(name)
    with pytest.raises(BadName) as info:
        check_name("object", name)
    msg = info.value.message
    assert isinstance(info.value, OwnctlError)
    assert NAME_RULE in msg and "object" in msg
    assert repr(name) in msg
    assert msg.isprintable(), repr(msg)


RESERVED_SAMPLES = ["any", "none", "Any", "NONE", "not", "and", "if", "on", "forbid", "allow", "Forbid"]


@pytest.mark.parametrize("word", RESERVED_SAMPLES)
def test_reserved_words_are_refused(word: str) -> None:
    assert is_name(word)
    with pytest.raises(BadName) as info:
        check_name("agent", word)
    msg = info.value.message
    assert "reserved" in msg and repr(word) in msg
    assert "any" in msg and "none" in msg


def test_design_reserved_words_are_in_the_set() -> None:
    assert {"any", "none"} <= RESERVED


@pytest.mark.parametrize("value", [None, 3, b"alexis", ["alexis"]])
def test_non_strings_are_refused(value) -> None:
    with pytest.raises(BadName):
        check_name("area", value)
