"""Utterances that cannot be understood fail with one clear line that says what to do."""

from __future__ import annotations

from dataclasses import replace

import pytest
from language_cases import CTX

from ownctl.errors import BadName, OwnctlError, RuleSyntaxError, UnknownName
from ownctl.language import MissingContext, NotUnderstood, understand
from ownctl.language.lexicon import EXAMPLES


@pytest.mark.parametrize("utterance", ["blorp the zorp", "gibberish", "I'm the one", "It's red",
                                       "That's somebody's", "Throw"])
def test_gibberish_is_not_understood_and_lists_examples(utterance: str) -> None:
    with pytest.raises(NotUnderstood) as err:
        understand(utterance, CTX)
    message = str(err.value)
    assert repr(utterance) in message and "\n" not in message
    assert sum(example in message for example in EXAMPLES) >= 3
    assert isinstance(err.value, OwnctlError) and err.value.valid


@pytest.mark.parametrize("utterance", ["ok, ok", "sure, go on", "Okay. Okay.", "hmm, well"])
def test_pieces_that_each_say_nothing_are_not_understood(utterance: str) -> None:
    with pytest.raises(NotUnderstood) as err:
        understand(utterance, CTX)
    assert repr(utterance) in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("utterance", ["", "   ", "!!!", "Baxter!"])
def test_empty_utterances_are_not_understood(utterance: str) -> None:
    with pytest.raises(NotUnderstood, match="nothing to understand"):
        understand(utterance, CTX)


def test_asking_for_yourself_explains_why() -> None:
    with pytest.raises(NotUnderstood, match="Can you throw this away"):
        understand("May I throw this away?", CTX)


def test_a_bad_sentence_among_good_ones_is_named() -> None:
    with pytest.raises(NotUnderstood, match="in particular 'Blorp the wallet'"):
        understand("Hi, I'm Jake. Blorp the wallet.", CTX)


@pytest.mark.parametrize("utterance", ["That's mine", "Don't throw that away", "Whose is this?", "No!"])
def test_that_without_a_current_object(utterance: str) -> None:
    with pytest.raises(MissingContext, match="which object.*--about OBJ"):
        understand(utterance, replace(CTX, about=None))


@pytest.mark.parametrize("utterance", ["That's mine", "I own this", "Don't touch my stuff"])
def test_mine_without_a_speaker(utterance: str) -> None:
    with pytest.raises(MissingContext, match="--as AGENT"):
        understand(utterance, replace(CTX, speaker=None))


@pytest.mark.parametrize("utterance", ["Don't do that", "Stop", "Go ahead", "Don't do that if it's red",
                                       "No, not the cup!"])
def test_a_reprimand_needs_an_action(utterance: str) -> None:
    with pytest.raises(MissingContext, match="which action"):
        understand(utterance, replace(CTX, action=None))


def test_an_action_named_in_the_reprimand_needs_no_context() -> None:
    got = understand("Don't throw that away, it's Jake's", replace(CTX, action=None))
    assert "forbid trash if ownedBy Jake" in got.texts()


@pytest.mark.parametrize("utterance", ["That belongs to Bob", "No Baxter, that's Bob's!",
                                       "Don't pick up anything of Bob's", "Bob owns this"])
def test_unknown_agent_is_named_with_the_known_ones(utterance: str) -> None:
    with pytest.raises(UnknownName) as err:
        understand(utterance, CTX)
    assert "'bob'" in str(err.value) and "Jake, casey, xuan" in str(err.value)


def test_an_introduction_may_name_a_new_agent_but_a_valid_one() -> None:
    assert understand("I'm Bob", CTX).texts() == ("agent add bob",)
    with pytest.raises(BadName, match="reserved"):
        understand("I'm any", CTX)


@pytest.mark.parametrize("utterance", ["I am cold", "It's empty now", "This is worthless", "it is damaged",
                                       "I'm late", "It's quite wobbly", "this is a mess"])
def test_a_state_said_with_i_am_or_it_is_adds_no_agent(utterance: str) -> None:
    try:
        said = understand(utterance, CTX).texts()
    except OwnctlError:
        return  # not understood: nothing is stored
    assert not any(text.startswith("agent add") for text in said), said


def test_it_is_introduces_a_known_agent_or_a_name_that_says_it_speaks() -> None:
    assert understand("It's Xuan", CTX).texts() == ("agent add xuan",)
    assert understand("This is Dana speaking", CTX).texts() == ("agent add dana",)
    assert understand("it is Dana here", CTX).texts() == ("agent add dana",)
    with pytest.raises(OwnctlError):
        understand("This is Dana", CTX)


def test_unknown_object_is_named() -> None:
    with pytest.raises(UnknownName, match="unknown object 'spoon'; known objects: block2, cup, wallet"):
        understand("Don't throw the spoon away", CTX)


def test_contradictory_norm_is_refused() -> None:
    with pytest.raises(RuleSyntaxError, match="could never apply"):
        understand("Never trash things that are red and not red", CTX)
