"""Posteriors over rule sets (``ownctl.learn.posterior.rule_posterior``) and the claim calibrations'
objectives (``ownctl.learn.induce.calibration_objectives``) are kept by content: a kept result must
be exactly the one computed afresh, for inputs that differ in any part of their content, and nobody
may change it in place."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from ownctl.config import LearnConfig
from ownctl.learn import induce
from ownctl.learn import posterior as post
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.logic.frame import Frame

AGENTS = ("a1", "a2")
VOCAB = Vocabulary(AGENTS, ("blue", "red"), ("desk", "shelf"))


def base_frame(seed: int) -> tuple[Frame, np.ndarray]:
    rng = np.random.default_rng(seed)
    n = 5
    own = rng.choice([0.0, 1.0, 0.3, 0.75], size=(n, 2))
    colours = tuple(str(c) for c in rng.choice(["blue", "red"], size=n))
    desk = rng.random(n) < 0.5
    return Frame(AGENTS, own, colours, {"desk": desk, "shelf": ~desk}), rng.choice([0.0, 1.0], size=n)


def variants(frame: Frame, values: np.ndarray) -> list[tuple[Frame, np.ndarray]]:
    """The frame and values changed in one part each: a value, an owner's name, a probability, a
    colour, an area's name, an area's membership, a category."""
    flipped = values.copy()
    flipped[0] = 1.0 - flipped[0]
    own = frame.own.copy()
    own[1, 0] = 0.5 if own[1, 0] != 0.5 else 0.25
    recoloured = ("red" if frame.colors[0] == "blue" else "blue", *frame.colors[1:])
    swapped = {"desk": frame.areas["shelf"], "shelf": frame.areas["desk"]}
    moved = dict(frame.areas, desk=~np.asarray(frame.areas["desk"]))
    cats = (frozenset({"cup"}), *frame.categories[1:])
    return [
        (frame, flipped),
        (replace(frame, agents=AGENTS[::-1]), values),
        (frame.with_own(own), values),
        (replace(frame, colors=recoloured), values),
        (replace(frame, areas=swapped), values),
        (replace(frame, areas=moved), values),
        (replace(frame, categories=cats), values),
    ]


def fresh(frame: Frame, values: np.ndarray) -> post.RulePosterior:
    post._posteriors.clear()
    return post.rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig())


@pytest.mark.parametrize("seed", range(3))
def test_a_kept_posterior_is_the_one_computed_afresh(seed: int) -> None:
    frame, values = base_frame(seed)
    for other, vals in variants(frame, values):
        assert Evidence(other, vals).content() != Evidence(frame, values).content()
        expected = fresh(other, vals)
        post.rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig())  # kept first
        got = post.rule_posterior(Evidence(other, vals), "trash", VOCAB, LearnConfig())
        assert got.rules == expected.rules
        assert np.array_equal(got.probabilities, expected.probabilities)
        assert np.array_equal(got.index, expected.index)


def test_equal_content_gives_the_same_posterior_and_it_is_read_only() -> None:
    frame, values = base_frame(7)
    first = post.rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig())
    copy = Frame(frame.agents, frame.own.copy(), tuple(frame.colors),
                 {k: np.array(v) for k, v in frame.areas.items()}, tuple(frame.categories))
    assert post.rule_posterior(Evidence(copy, values.copy()), "trash", VOCAB, LearnConfig()) is first
    narrower = replace(LearnConfig(), max_conditions=2)
    other = post.rule_posterior(Evidence(frame, values), "trash", VOCAB, narrower)
    assert other is not first
    for array in (first.probabilities, first.log_weights, first.index):
        with pytest.raises(ValueError):
            array[0] = 0


def fresh_objectives(frame: Frame, values: np.ndarray) -> dict[tuple[float, float], float]:
    return {cal: option[2] for cal, option in
            induce.calibration_choices("trash", Evidence(frame, values), VOCAB, LearnConfig(), ()).items()}


@pytest.mark.parametrize("seed", range(3))
def test_kept_calibration_objectives_are_the_ones_computed_afresh(seed: int) -> None:
    frame, values = base_frame(seed)
    for other, vals in variants(frame, values):
        induce._objectives.clear()
        induce.calibration_objectives("trash", Evidence(frame, values), VOCAB, LearnConfig(), ())  # kept
        got = induce.calibration_objectives("trash", Evidence(other, vals), VOCAB, LearnConfig(), ())
        assert got == fresh_objectives(other, vals)


def test_calibration_objectives_cannot_be_changed_through_a_result() -> None:
    frame, values = base_frame(4)
    first = induce.calibration_objectives("trash", Evidence(frame, values), VOCAB, LearnConfig(), ())
    assert len(first) == 2  # uncertain ownership: the identity and the other calibration
    first[next(iter(first))] = -1.0
    again = induce.calibration_objectives("trash", Evidence(frame, values), VOCAB, LearnConfig(), ())
    assert again == fresh_objectives(frame, values)
