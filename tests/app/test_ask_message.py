"""How ``ask --put`` shows a gain it refuses: never rounded up to the threshold it is below."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from ownctl.app.ask import shown_below


def test_a_gain_just_below_the_threshold_shows_the_digits_that_keep_it_below() -> None:
    assert shown_below(0.04996, 0.05) == "0.04996"
    assert shown_below(0.0499999, 0.05) == "0.0499999"
    assert shown_below(0.031, 0.05) == "0.031"
    assert shown_below(0.2, 0.05) == "0.200"  # at or above: three decimals, as before


@given(st.floats(-1.0, 1.0), st.floats(0.0, 1.0))
def test_a_gain_below_the_threshold_never_reads_as_reaching_it(gain: float, min_gain: float) -> None:
    if gain < min_gain:
        assert float(shown_below(gain, min_gain)) < min_gain
