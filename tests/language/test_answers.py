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
                                   "no, don't do that", "Not right now.", "No, not just yet"])
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


# -- replies of several clauses: reply words, asides, statements and remarks ----------------------

ALLOW = (Permission("trash", "mug", forbid=False),)
FORBID = (Permission("trash", "mug", forbid=True),)
RED = {"kind": "rule", "rule": "forbid trash if isColored red"}


@pytest.mark.parametrize(("words", "expected"), [
    ("indeed it does", "yes"), ("nope absolutely not", "no"), ("Actually no.", "no"),
    ("That's not how it works around here", "no"), ("It depends on the colour", "partly"),
    ("Let me check", "unknown"), ("Check with Casey first", "unknown"), ("sure no", None), ("ok ok", None),
])
def test_a_reply_word_may_be_a_run_of_one_kind_with_a_marker_or_a_tail(words: str,
                                                                        expected: str | None) -> None:
    assert reading(words) == expected


@pytest.mark.parametrize("words", ["Sure, it's worn out", "Yes, but be quick", "Yes it's rubbish",
                                   "Go ahead, it has been broken for ages", "Yep. Thanks, why?",
                                   "Of course, nobody uses it anymore"])
def test_a_yes_with_remarks_that_state_nothing_allows(words: str) -> None:
    assert answer_instructions(words, MAY, CTX) == ALLOW


@pytest.mark.parametrize("words", ["No, it's precious", "Nope, I still use it", "No, leave it alone",
                                   "Certainly not, it's brand new", "Nope, put it back"])
def test_a_no_with_remarks_or_a_prohibition_naming_no_action_forbids_the_asked_action(words: str) -> None:
    assert answer_instructions(words, MAY, CTX) == FORBID


def test_a_no_with_whose_it_is_teaches_the_owners_norm_and_a_yes_only_the_claim() -> None:
    ann = answer_instructions("Definitely not, that's Ann's!", MAY, CTX)
    assert ann is not None and set(ann) == {Claim("mug", "ann"), FORBID[0],
                                            NormInstruction(parse_norm("forbid trash if ownedBy ann"))}
    mine = answer_instructions("no it's mine", MAY, CTX)
    assert mine is not None and NormInstruction(parse_norm("forbid trash if ownedBy jake")) in mine
    assert answer_instructions("Sure, it's Casey's and I'm done with it", MAY, CTX) == (
        Claim("mug", "casey"), ALLOW[0])


@pytest.mark.parametrize("words", [
    "Yes, but not today", "Yes, but only if Ann agrees", "Sure, and the book too", "No... actually yes",
    "Yes, but don't throw it away", "No, you can throw it away", "Yes, I still need it",
    "No, nobody needs it anymore",
    "Yes, leave it", "Yes, maybe", "Yes, whose is it?", "Yes, I don't know", "No, Casey wants it",
    "Yes, the red one is broken", "It's broken", "No, don't touch it", "Sure, ask Ann first",
])
def test_a_reply_that_qualifies_contradicts_or_says_something_else_is_no_answer(words: str) -> None:
    assert answer_instructions(words, MAY, CTX) is None


@pytest.mark.parametrize(("words", "norm"), [
    ("Yes, indeed it does", "forbid trash if isColored red"),
    ("Right, leave the red ones alone", "forbid trash if isColored red"),
    ("Never throw away red things", "forbid trash if isColored red"),
    ("Nah, red is alright", "allow trash if isColored red"),
    ("No, red ones are ok", "allow trash if isColored red"),
    ("No, there's no such rule here", "allow trash if isColored red"),
])
def test_a_rule_answer_may_restate_the_norm_it_gives(words: str, norm: str) -> None:
    assert answer_instructions(words, RED, CTX) == (NormInstruction(parse_norm(norm)),)


@pytest.mark.parametrize("words", ["Yes, red is fine", "No, leave the red ones", "Yes, leave the blue ones",
                                   "Yes, it's mine", "Yes, but not always", "Sure, but only on Sundays",
                                   "Throw away the mug"])
def test_a_rule_answer_that_states_another_norm_or_qualifies_is_no_answer(words: str) -> None:
    assert answer_instructions(words, RED, CTX) is None


def test_it_depends_answers_a_rule_question_and_teaches_nothing() -> None:
    assert answer_instructions("Well, it depends on who owns it", RED, CTX) == ()


@pytest.mark.parametrize(("words", "owner"), [
    ("Belongs to Ann", "ann"), ("That'd be Casey's", "casey"), ("Casey's, why do you ask?", "casey"),
    ("It's Ann's, ask her", "ann"), ("Ann's, it's been on the shelf for ages", "ann"),
])
def test_a_whose_answer_may_carry_asides_remarks_and_a_referral(words: str, owner: str) -> None:
    got = answer_instructions(words, WHOSE, CTX)
    assert got is not None and Claim("mug", owner) in got
    assert {c.agent for c in got if isinstance(c, Claim) and c.negated} == {"ann", "casey", "jake"} - {owner}


def test_owners_named_together_own_it_together() -> None:
    assert answer_instructions("Mine and Casey's, why?", WHOSE, CTX) == (
        Claim("mug", "jake"), Claim("mug", "casey"), Claim("mug", "ann", negated=True))


def test_a_denial_may_come_with_a_dont_know_and_nobody_with_a_remark() -> None:
    not_mine = (Claim("mug", "jake", negated=True),)
    assert answer_instructions("Not mine, check with Ann", WHOSE, CTX) == not_mine
    assert answer_instructions("Not mine, no idea whose", WHOSE, CTX) == not_mine
    nobody = answer_instructions("Nobody's, it has sat there for ages", WHOSE, CTX)
    assert nobody is not None and len(nobody) == 3
    assert all(isinstance(c, Claim) and c.negated for c in nobody)


@pytest.mark.parametrize("words", ["Casey's, no idea", "Casey's, and the book is Ann's", "It's broken",
                                   "Casey's, though Ann uses it", "How come?", "Casey's, maybe, why?",
                                   "Casey's? No, Ann's", "Ann's, I mean Casey's",
                                   "Ann's, but she gave it to Casey"])
def test_a_whose_answer_that_doubts_itself_or_says_something_else_is_no_answer(words: str) -> None:
    assert answer_instructions(words, WHOSE, CTX) is None


# -- don't-knows built from parts, hold markers, restrictions, reasons, "ours", feelings ------------

@pytest.mark.parametrize("question", [MAY, RULE, WHOSE])
@pytest.mark.parametrize("words", ["Haven't the foggiest.", "I don't have a clue", "Not the slightest idea!",
                                   "No clue whatsoever, sorry", "I've got no idea whose it is",
                                   "Hang on, let me ask Casey.", "Wait a sec - check with Ann",
                                   "One moment, I'll ask Ann.", "Hold on a minute, I'm not sure"])
def test_dont_knows_from_parts_and_after_a_hold_marker_answer_and_teach_nothing(words: str,
                                                                                 question: dict) -> None:
    assert answer_instructions(words, question, CTX) == ()


@pytest.mark.parametrize(("words", "question"), [
    ("Hang on.", MAY), ("Hang on, yes.", MAY), ("Hang on, no.", MAY), ("Hold on, it's Casey's", WHOSE),
    ("One second, yes it does", RULE), ("It's Casey's, let me ask her", WHOSE),
])
def test_a_hold_marker_goes_only_with_a_dont_know(words: str, question: dict) -> None:
    assert answer_instructions(words, question, CTX) is None


@pytest.mark.parametrize("words", ["Only when Ann is home.", "Except on weekends", "Unless it's cracked",
                                   "Well, only if it is red", "So, only if it is red"])
def test_a_restriction_to_a_rule_question_is_partly(words: str) -> None:
    assert answer_instructions(words, RED, CTX) == ()
    assert reading(words) == "partly"


@pytest.mark.parametrize(("words", "question"), [
    ("Only if you're quick", MAY), ("Only when Ann is home", WHOSE), ("Yes, only for her books", RED),
    ("No, except on weekends", RED), ("Sure, unless Ann minds", MAY),
    ("Only if you ask first, it's Casey's", RED), ("It depends on who owns it, it's Casey's", RED),
])
def test_a_restriction_answers_no_other_question_and_no_yes_or_no(words: str, question: dict) -> None:
    assert answer_instructions(words, question, CTX) is None


@pytest.mark.parametrize("words", [
    "No! Casey is still drinking from it.", "Nope, my sister needs it for school", "No, he's still using it",
    "No, Ann isn't done with it", "Absolutely not, the kids are playing with it right now"])
def test_a_no_with_someone_using_the_object_forbids_and_teaches_nothing_more(words: str) -> None:
    assert answer_instructions(words, MAY, CTX) == FORBID


def test_someone_using_the_object_is_a_reason_for_any_action() -> None:
    pick = {"kind": "may", "object": "book", "action": "pickUp"}
    got = answer_instructions("No, Ann is reading it.", pick, CTX)
    assert got == (Permission("pickUp", "book", forbid=True),)


@pytest.mark.parametrize(("words", "question"), [
    ("Yes, Casey is still using it", MAY), ("Sure, Ann needs it", MAY), ("I don't know, Casey uses it", MAY),
    ("No, nobody is using it", MAY), ("No, Casey is not using it", MAY), ("Yes, Casey is using it", RED),
    ("Casey's, Ann is using it", WHOSE), ("No, Casey wants it", MAY),
])
def test_a_reason_to_keep_the_object_goes_with_a_no_to_may_only(words: str, question: dict) -> None:
    assert answer_instructions(words, question, CTX) is None


def test_ours_is_the_speaker_with_the_owners_named_beside_it() -> None:
    both = (Claim("mug", "ann"), Claim("mug", "jake"), Claim("mug", "casey", negated=True))
    assert set(answer_instructions("Both of ours - Ann's and mine.", WHOSE, CTX) or ()) == set(both)
    assert set(answer_instructions("Mine and Ann's, it's both ours", WHOSE, CTX) or ()) == set(both)
    assert set(answer_instructions("We share it: it's mine and Ann's", WHOSE, CTX) or ()) == set(both)
    assert set(answer_instructions("It's ours, mine and Ann's, why?", WHOSE, CTX) or ()) == set(both)


@pytest.mark.parametrize("words", ["Both of ours.", "It's ours", "Ours, I think", "We share it.",
                                   "Both of ours, mine, Ann's and Casey's", "Both of ours, Ann's and Casey's",
                                   "Ours, I mean Casey's"])
def test_ours_that_names_no_other_owner_or_miscounts_them_is_no_answer(words: str) -> None:
    assert answer_instructions(words, WHOSE, CTX) is None


def test_ours_from_an_unknown_speaker_is_no_answer() -> None:
    nobody = Context(agents=CTX.agents, objects=CTX.objects)
    assert answer_instructions("Both of ours", WHOSE, nobody) is None
    assert answer_instructions("Both of ours, Ann's and mine", WHOSE, nobody) is None


def test_ours_says_nothing_to_a_may_question() -> None:
    assert answer_instructions("No, it's both of ours", MAY, CTX) is None


ANNS = {"kind": "rule", "rule": "forbid pickUp if ownedBy ann"}


@pytest.mark.parametrize(("words", "norm"), [
    ("Yes, Ann hates it when people touch her things.", "forbid pickUp if ownedBy ann"),
    ("Right, she can't stand anyone touching her stuff", "forbid pickUp if ownedBy ann"),
    ("Ann doesn't like people touching her things", "forbid pickUp if ownedBy ann"),
    ("No, Ann doesn't mind people picking up her stuff.", "allow pickUp if ownedBy ann"),
])
def test_how_someone_feels_about_others_handling_their_things_restates_the_rule(words: str,
                                                                                 norm: str) -> None:
    assert answer_instructions(words, ANNS, CTX) == (NormInstruction(parse_norm(norm)),)


def test_the_speaker_may_say_how_they_feel_about_their_own_things() -> None:
    mine = {"kind": "rule", "rule": "forbid trash if ownedBy jake"}
    assert answer_instructions("Yes, I hate people throwing my stuff away", mine, CTX) == (
        NormInstruction(parse_norm("forbid trash if ownedBy jake")),)


@pytest.mark.parametrize(("words", "question"), [
    ("Yes, Ann doesn't mind people touching her stuff", ANNS),
    ("No, Ann hates people touching her things", ANNS),
    ("Yes, Ann doesn't like people touching her red things", ANNS),
    ("Yes, Casey hates people touching her stuff", ANNS),
    ("Yes, Ann doesn't like people touching Casey's stuff", ANNS),
    ("Yes, Ann hates people throwing away her things", ANNS),
    ("Yes, Ann likes people touching her stuff", ANNS),
    ("No, Ann hates people throwing away her things", MAY),
    ("Ann's, she hates people touching her stuff", WHOSE),
])
def test_a_feeling_that_states_another_norm_is_no_answer(words: str, question: dict) -> None:
    assert answer_instructions(words, question, CTX) is None
