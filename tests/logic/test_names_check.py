"""The naming rule (architecture section 2): a letter of any script, then letters, marks, digits,
'_' or '-', in one script and composed; reserved words refused."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ownctl.errors import BadName, OwnctlError
from ownctl.logic.names import NAME_RULE, RESERVED, check_name, composed, is_name, scripts

VALID = [
    "alexis", "xuan", "agent2", "block1", "desk_xuan", "Bob-1", "a", "A_b-9", "x" * 64, "anyone", "nonever",
    "al\u00e9xis", "Jos\u00e9", "Zo\u00eb", "S\u00f8ren", "\u0414\u0438\u043c\u0430", "\u0930\u093e\u092e",
    "\u5c71\u7530", "\u5c71\u7530\u305f\u308d\u3046", "\u0645\u0631\u064a\u0645", "tasse-\u00e0-caf\u00e9_2",
]
HOSTILE = [
    "", " ", "1agent", "_agent", "-x", "x'; drop table objects; --", "robert');DROP", 'a"b', "a'b", "a b",
    "a\x00", "a\nb", "ab\n", "\tab", "a\x1b[31m", "a\x7f", "\u0430gent", "p\u0430ypal",
    "\u0301a", "\u00bda", "a\u200bb", "a\u00a0b", "a.b", "a/b", "a;b",
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


@pytest.mark.parametrize(
    ("typed", "stored"),
    [
        ("Jose\u0301", "Jos\u00e9"),  # a combining accent composes
        ("\uff4a\uff4f\uff53\u00e9", "jos\u00e9"),  # full-width letters fold
        ("Zo\u00eb", "Zo\u00eb"),
    ],
)
def test_a_name_is_stored_in_its_composed_form(typed: str, stored: str) -> None:
    assert not is_name(typed) or typed == stored
    assert check_name("agent", typed) == stored
    assert is_name(stored)


def test_a_mixed_script_name_is_refused_naming_its_scripts() -> None:
    with pytest.raises(BadName) as info:
        check_name("agent", "\u0430gent")  # a Cyrillic a before Latin letters
    assert "Cyrillic" in info.value.message and "Latin" in info.value.message
    assert scripts("\u5c71\u7530\u305f\u308d\u3046") == {"CJK", "HIRAGANA"}
    assert scripts("A_b-9") == {"LATIN"}


@given(st.text(max_size=12))
def test_check_name_returns_a_name_it_accepts_unchanged(text: str) -> None:
    """Law: whatever is accepted comes back composed, a name, and accepted again unchanged."""
    try:
        name = check_name("object", text)
    except BadName:
        return
    assert name == composed(text) and is_name(name)
    assert check_name("object", name) == name


def test_an_unknown_name_among_many_names_the_closest_not_every_one() -> None:
    from ownctl.errors import MAX_LISTED, UnknownName

    few = UnknownName("object", "cup", ["mug", "pen"])
    assert few.message == "unknown object 'cup'; known objects: mug, pen" and few.valid == ["mug", "pen"]
    many = [f"block{i}" for i in range(5000)]
    error = UnknownName("object", "blok12", many)
    assert error.valid == sorted(many)  # --json still lists every valid name
    assert len(error.message) < 200 and "5,000 known objects" in error.message
    assert "the closest: block12," in error.message and "ownctl object list" in error.message
    assert "the closest" not in UnknownName("agent", "zzz", many).message
    assert len(UnknownName("colour", "x", many[: MAX_LISTED + 1]).message) < 100
