"""Every utterance of the table means exactly its instructions, in order."""

from __future__ import annotations

import pytest
from language_cases import CTX, TABLE

from ownctl.language import Understanding, understand


def test_table_is_large_and_has_no_duplicates() -> None:
    assert len(TABLE) >= 70
    assert len({u for u, _, _ in TABLE}) == len(TABLE)


@pytest.mark.parametrize(("utterance", "intent", "texts"), TABLE, ids=[u for u, _, _ in TABLE])
def test_utterance_means(utterance: str, intent: str, texts: tuple[str, ...]) -> None:
    got = understand(utterance, CTX)
    assert isinstance(got, Understanding)
    assert got.texts() == texts
    assert got.intent == intent
    assert got.reply


def test_reprimand_reply_names_the_claim() -> None:
    reply = understand("Don't, that's Casey's!", CTX).reply
    assert reply == "Sorry about that. Noted: wallet belongs to casey."


def test_norm_instruction_round_trips_through_the_rule_parser() -> None:
    from ownctl.language import NormInstruction
    from ownctl.logic.rules import parse_norm

    for utterance, _, _ in TABLE:
        for instruction in understand(utterance, CTX).instructions:
            if isinstance(instruction, NormInstruction):
                assert parse_norm(instruction.text()) == instruction.norm
