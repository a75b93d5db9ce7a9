"""Case, punctuation and whitespace do not change what an utterance means."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from language_cases import CTX, TABLE

from ownctl.language import understand

_GAPS = st.sampled_from([" ", "  ", "\t", " , ", ", ", "! ", "? ", ". ", "... ", " - "])


@st.composite
def perturbed(draw: st.DrawFn) -> tuple[str, str]:
    """A table utterance and a variant: random case, gaps with punctuation, curly apostrophes."""
    utterance = draw(st.sampled_from([u for u, _, _ in TABLE]))
    words = utterance.split()
    out = draw(st.sampled_from(["", " ", "  ", "\u00a0"]))
    for i, word in enumerate(words):
        cased = "".join(c.upper() if draw(st.booleans()) else c.lower() for c in word)
        if draw(st.booleans()):
            cased = cased.replace("'", "\u2019")
        out += cased + (draw(_GAPS) if i < len(words) - 1 else "")
    out += draw(st.sampled_from(["", "!", "?", ".", " !!", "  "]))
    return utterance, out


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(perturbed())
def test_perturbations_mean_the_same(case: tuple[str, str]) -> None:
    original, variant = case
    want = understand(original, CTX)
    got = understand(variant, CTX)
    assert (got.intent, got.texts()) == (want.intent, want.texts())
