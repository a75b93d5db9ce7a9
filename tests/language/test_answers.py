"""Answers to a pending question (``ownctl.language.answers``): which words answer which question."""

from __future__ import annotations

import pytest

from ownctl.language import Claim, Context, NormInstruction, Permission
from ownctl.language.answers import answer_instructions, reading
from ownctl.logic.rules import parse_norm

CTX = Context(speaker="jake", agents=frozenset({"jake", "casey", "ann"}),
              objects=frozenset({"mug", "book"}))
MAY = {"kind": "may", "object": "mug", "action": "trash"}
RULE = {"kind": "rule", "rule": "forbid trash if isColored red"}
WHOSE = {"kind": "whose", "object": "mug"}


@pytest.mark.parametrize("words", ["yes", "Yes, you may.", "sure", "go ahead", "you can", "Sure, go ahead!",
                                   "Yeah, sure. Thanks!", "Absolutely", "yes thanks", "Of course, go for it",
                                   "Yes, throw it away", "Throw it away", "You may throw it away"])
def test_yes_to_may_allows(words: str) -> None:
    assert answer_instructions(words, MAY, CTX) == (Permission("trash", "mug", forbid=False),)


@pytest.mark.parametrize("words", ["no", "No, you may not!", "don't", "you can't", "No way, don't!",
                                   "Nope - never.", "Of course not.", "no thanks", "Absolutely not!",
                                   "No, don't throw it away", "Don't throw the mug away",
                                   "no, don't do that"])
def test_no_to_may_forbids(words: str) -> None:
    assert answer_instructions(words, MAY, CTX) == (Permission("trash", "mug", forbid=True),)


def test_rule_answers() -> None:
    rule = parse_norm(RULE["rule"]).rule
    assert answer_instructions("yes", RULE, CTX) == (NormInstruction(parse_norm(RULE["rule"])),)
    no = answer_instructions("no", RULE, CTX)
    assert no is not None and isinstance(no[0], NormInstruction)
    assert no[0].norm.sign == "allow" and no[0].norm.rule == rule
    assert answer_instructions("not always", RULE, CTX) == ()
    assert answer_instructions("Definitely not.", RULE, CTX) == no
    assert answer_instructions("Yes, always", RULE, CTX) == answer_instructions("yes", RULE, CTX)


def test_a_permission_answer_may_say_whose_it_is() -> None:
    got = answer_instructions("No, that's Casey's", MAY, CTX)
    assert got is not None and Permission("trash", "mug", forbid=True) in got and Claim("mug", "casey") in got
    assert sum(isinstance(i, Permission) for i in got) == 1


@pytest.mark.parametrize("question", [MAY, RULE, WHOSE])
@pytest.mark.parametrize("words", ["I don't know", "No idea, sorry", "Hmm, not sure", "dunno"])
def test_not_knowing_answers_and_teaches_nothing(words: str, question: dict) -> None:
    assert answer_instructions(words, question, CTX) == ()


@pytest.mark.parametrize(("words", "expected"), [("Sure, go ahead, thanks!", "yes"), ("No. Never!", "no"),
                                                 ("yes... no", None), ("no, yes", None), ("ok ok", None),
                                                 ("sometimes", "partly"), ("no idea", "unknown")])
def test_a_reply_is_read_clause_by_clause_and_must_agree(words: str, expected: str | None) -> None:
    assert reading(words) == expected


def test_whose_answers_name_every_owner() -> None:
    assert answer_instructions("It's Casey's", WHOSE, CTX) == (
        Claim("mug", "casey"), Claim("mug", "ann", negated=True), Claim("mug", "jake", negated=True))
    mine = answer_instructions("mine", WHOSE, CTX)
    assert mine is not None and Claim("mug", "jake") in mine and Claim("mug", "casey", negated=True) in mine
    nobody = answer_instructions("nobody's", WHOSE, CTX)
    assert nobody is not None and all(c.negated for c in nobody)


def test_a_whose_answer_that_only_denies_says_nothing_of_the_others() -> None:
    assert answer_instructions("Not mine", WHOSE, CTX) == (Claim("mug", "jake", negated=True),)
    assert answer_instructions("It's not Casey's", WHOSE, CTX) == (Claim("mug", "casey", negated=True),)


def test_a_hedged_whose_answer_is_as_sure_of_the_others() -> None:
    assert answer_instructions("Casey's, I think", WHOSE, CTX) == (
        Claim("mug", "casey", 0.8), Claim("mug", "ann", 0.8, negated=True),
        Claim("mug", "jake", 0.8, negated=True))


@pytest.mark.parametrize(("words", "expected"), [
    ("Fine by me", "yes"), ("I'd rather you didn't", "no"), ("Help yourself!", "yes"), ("Mostly", "partly"),
    ("Usually, yes", None),
])
def test_more_everyday_replies(words: str, expected: str | None) -> None:
    assert reading(words) == expected


@pytest.mark.parametrize(("words", "question"), [("hello", MAY), ("maybe", RULE), ("yes", WHOSE),
                                                 ("throw away the book", MAY), ("pick it up", MAY),
                                                 ("yes... no", MAY), ("go ahead", WHOSE),
                                                 ("No, don't throw away the book", MAY)])
def test_other_words_are_no_answer(words: str, question: dict) -> None:
    assert answer_instructions(words, question, CTX) is None
