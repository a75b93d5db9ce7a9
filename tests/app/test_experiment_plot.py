"""The experiment figure's error bars."""

from __future__ import annotations

from ownctl.app.experiment_plot import error_bars


def test_a_share_s_interval_is_drawn_inside_zero_and_one() -> None:
    below, above = error_bars([0.98, 0.5, 0.03], [0.1, 0.1, 0.1], bounded=True)
    assert below == [0.1, 0.1, 0.03] and [round(a, 9) for a in above] == [0.02, 0.1, 0.1]


def test_a_count_s_interval_is_drawn_whole() -> None:
    assert error_bars([0.2, 3.0], [0.5, 0.4], bounded=False) == [[0.5, 0.4], [0.5, 0.4]]
