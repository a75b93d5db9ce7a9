"""Decisions on the near-best rule sets (``decide.rules = window``) against a plain computation:
the window keeps exactly the sets within the width of the most probable, and P(forbidden) is the
plain mean, set by set, over those sets and the learner's own set (counted once)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ownctl.config import LearnConfig
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import subtract
from ownctl.learn.posterior import rule_posterior, window_p_forbidden, window_size
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import Rule, parse_rule

AGENTS = ("a1", "a2")
VOCAB = Vocabulary(("a1",), ("blue", "red"), ("desk",))


def case(seed: int) -> tuple[Frame, np.ndarray]:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 7))
    own = rng.choice([0.0, 1.0, 0.3, 0.75], size=(n, 2))
    colours = tuple(str(c) for c in rng.choice(["blue", "red"], size=n))
    return Frame(AGENTS, own, colours, {"desk": rng.random(n) < 0.5}), rng.choice([0.0, 1.0], size=n)


def plain_mean(sets: list[tuple[Rule, ...]], allows: tuple[Rule, ...], own: tuple[Rule, ...],
               frame: Frame) -> np.ndarray:
    """The mean of each set's exact P(forbidden), allow norms subtracted, plus the learner's own set
    when no set of the window is it."""
    table = []
    for rules in sets:
        kept = list(rules)
        for allow in allows:
            kept = subtract(kept, allow)
        table.append(kept)
    if frozenset(own) not in [frozenset(k) for k in table]:
        table.append(list(own))
    return np.mean([p_forbidden(k, frame) for k in table], axis=0)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("within", [0.0, 0.7, 2.0, pytest.param(1e9, marks=pytest.mark.slow)])  # 1e9: all
def test_the_window_is_the_plain_mean_over_the_near_best_sets(seed: int, within: float) -> None:
    frame, values = case(seed)
    allows = (parse_rule("forbid trash if isColored blue"),) if seed % 3 == 2 else ()
    post = rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig(), allows=allows)
    best = float(post.log_weights.max())
    near = [s for s, w in zip(post.sets, post.log_weights.tolist(), strict=True) if w >= best - within]
    window = post.window(within)
    assert list(window.sets) == near and math.isclose(float(window.probabilities.sum()), 1.0)
    assert np.allclose(window.probabilities, 1.0 / len(near))
    probe, _ = case(seed + 50)
    # the learner's own set: the most probable set (in the window), or a set outside the posterior
    for own in (tuple(post.map()), (parse_rule("forbid trash if ownedBy a2 and isColored red"),)):
        kept = list(own)
        for allow in allows:
            kept = subtract(kept, allow)
        got = window_p_forbidden(post, tuple(kept), probe, within)
        assert np.allclose(got, plain_mean(near, allows, tuple(kept), probe), atol=1e-12)
        if not allows:
            assert window_size(post, tuple(kept), within) == len(near) + (frozenset(kept) not in
                                                                          {frozenset(s) for s in near})
    if within >= 1e9:  # every set, equally weighted: between the least and the most cautious set
        each = np.array([p_forbidden(list(s), probe) for s in post.sets])
        assert (got >= each.min(axis=0) - 1e-12).all() and (got <= each.max(axis=0) + 1e-12).all()


def test_a_width_below_zero_or_not_a_number_is_refused() -> None:
    frame, values = case(0)
    post = rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig())
    for bad in (-0.5, float("nan")):
        with pytest.raises(ValueError, match="at least 0"):
            post.window(bad)


def test_one_example_against_its_rivals_forbids_only_as_far_as_they_agree() -> None:
    """One red object of a1's forbidden, nothing allowed: "red", "owned by a1" and their conjunction
    explain it about equally well, so the window forbids a blue object of a1's with P about 1/2 or less
    where the most probable set alone says 0 or 1."""
    own = np.array([[1.0, 0.0]])
    frame = Frame(AGENTS, own, ("red",), {"desk": np.zeros(1, dtype=bool)})
    post = rule_posterior(Evidence(frame, [1.0]), "trash", VOCAB, LearnConfig())
    probe = Frame(AGENTS, np.array([[1.0, 0.0]]), ("blue",), {"desk": np.zeros(1, dtype=bool)})
    alone = float(p_forbidden(list(post.map()), probe)[0])
    mean = float(window_p_forbidden(post, tuple(post.map()), probe, 2.0)[0])
    assert alone in (0.0, 1.0) and 0.0 < mean < 1.0 and window_size(post, tuple(post.map()), 2.0) > 1
