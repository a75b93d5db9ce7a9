"""The pieces: normalisation, instruction texts, owner and class phrases, multi-sentence context."""

from __future__ import annotations

import pytest
from language_cases import CTX

from ownctl.errors import BadValue, UnknownName
from ownctl.language import (
    RULES,
    AskOwner,
    AskPermitted,
    AskWhy,
    Claim,
    Introduce,
    NormInstruction,
    Permission,
    Request,
    RunTask,
    Skip,
    normalize,
    understand,
)
from ownctl.language.phrases import class_literals
from ownctl.language.resolve import Resolver
from ownctl.logic.rules import parse_norm


@pytest.mark.parametrize(("raw", "norm"), [
    ("No Baxter, that\u2019s mine!", "no that is mine"),
    ("Don't, that's Casey's!", "do not that is casey 's"),
    ("Throw this wallet away", "throw away this wallet"),
    ("Baxter, please pick that up.", "pick up that"),
    ("That belongs to Baxter", "that belongs to baxter"),
    ("No one owns this, Baxter!", "nobody owns this"),
    ("the twins' stuff", "the twins 's stuff"),
    ("I can't, you won't, it isn't", "i can not you will not it is not"),
    ("Okay, you're allowed to", "ok you are allowed to"),
    ("That'd be Bo's; those would be mine", "that is bo 's those are mine"),
])
def test_normalize(raw: str, norm: str) -> None:
    assert normalize(raw) == norm


def test_instruction_texts() -> None:
    assert Claim("wallet", "casey").text() == "claim wallet casey"
    assert Claim("wallet", "xuan", negated=True).text() == "claim wallet xuan --not"
    assert Claim("wallet", "jake", exclusive=True).text() == "claim wallet jake --only"
    assert Claim("wallet", "jake", p=0.8).text() == "claim wallet jake --p 0.8"
    assert Permission("trash", "wallet", forbid=True).text() == "forbid trash on wallet"
    assert Permission("pickUp", "cup", forbid=False).text() == "allow pickUp on cup"
    norm = parse_norm("forbid trash if ownedBy casey")
    assert NormInstruction(norm).text() == "forbid trash if ownedBy casey"
    assert Introduce("jake").text() == "agent add jake"
    assert Skip("wallet").text() == "skip wallet"
    assert AskOwner("wallet").text() == "owners wallet"
    assert AskPermitted("trash", "wallet").text() == "check trash wallet"
    assert AskWhy().text() == "explain"
    assert AskWhy("trash", "wallet").text() == "explain trash wallet"
    assert RunTask("trashAll").text() == "run trashAll"


def test_instructions_validate_their_values() -> None:
    with pytest.raises(BadValue):
        Claim("wallet", "casey", p=1.5)
    with pytest.raises(BadValue):
        Claim("wallet", "casey", negated=True, exclusive=True)
    with pytest.raises(UnknownName, match="known actions"):
        Permission("thrash", "wallet", forbid=True)
    with pytest.raises(BadValue, match="trashAll"):
        RunTask("danceAll")


def test_negated_claim_probability_and_request_is_a_check() -> None:
    assert Claim("w", "a", p=0.8, negated=True).probability == pytest.approx(0.2)
    got = understand("Throw this away", CTX).instructions[0]
    assert isinstance(got, Request) and isinstance(got, AskPermitted)


@pytest.mark.parametrize(("phrase", "literals"), [
    ("my stuff", ["ownedBy casey"]),
    ("other people 's red things", ["ownedBy any", "isColored red"]),
    ("anything nobody owns", ["not ownedBy any"]),
    ("things without an owner", ["not ownedBy any"]),
    ("non-red blocks", ["not isColored red"]),
    ("anything jake owns and that is in the home area", ["ownedBy Jake", "inArea home"]),
    ("it if it is blue", ["isColored blue"]),
    ("anything", []),
])
def test_class_phrases(phrase: str, literals: list[str]) -> None:
    got = class_literals(phrase, Resolver(CTX))
    assert got is not None and [lit.text() for lit in got] == literals


@pytest.mark.parametrize("phrase", ["wallet", "that", "it", "red", "things blah"])
def test_not_class_phrases(phrase: str) -> None:
    assert class_literals(phrase, Resolver(CTX)) is None


def test_an_introduction_makes_the_next_sentence_its_speakers() -> None:
    got = understand("Hi, I'm Bob. That's mine, not Xuan's.", CTX)
    assert got.texts() == ("agent add bob", "claim wallet bob", "claim wallet xuan --not")
    assert got.intent == "claim" and got.form == "introduce+claim"
    assert got.reply.startswith("Hi bob, I'm Baxter. Noted: wallet belongs to bob")


def test_names_come_back_in_their_stored_spelling() -> None:
    assert understand("That's JAKE's", CTX).texts() == ("claim wallet Jake",)
    assert understand("hi i'm JAKE", CTX).texts() == ("agent add Jake",)
    assert understand("Don't trash the CUP", CTX).texts() == ("forbid trash on cup",)


def test_the_action_in_context_is_used() -> None:
    from dataclasses import replace

    got = understand("No, that's mine!", replace(CTX, action="pickUp"))
    assert got.texts()[-1] == "forbid pickUp if ownedBy casey"


def test_rules_are_ordered_statements_first_and_documented() -> None:
    names = [r.name for r in RULES]
    assert names[0] == "reprimand_claim" and names.index("claim") < names.index("introduce")
    assert len(RULES) >= 30
    for rule in RULES:
        assert rule.build.__doc__, rule.name
        assert rule.intent in {"reprimand", "claim", "permission", "norm", "introduction", "question",
                               "request", "task", "greeting", "thanks", "remark"}
