"""The claim calibration the default learner reads uncertain ownership through, chosen by evidence."""

from __future__ import annotations

import numpy as np
import pytest

from ownctl.config import LearnConfig
from ownctl.learn import calibration, exact
from ownctl.learn.calibration import CALIBRATIONS, IDENTITY, calibrate, calibrated, candidates
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import MAX_RULES, calibrated_inducer, learn_permission
from ownctl.learn.model import model_for
from ownctl.learn.posterior import rule_posterior
from ownctl.logic.frame import Frame
from ownctl.logic.rules import Literal, Rule

AGENTS = ("a1", "a2", "a3")
VOCAB = Vocabulary(AGENTS, ("blue", "red"), ())


def test_calibrate_keeps_certain_claims_and_the_order_of_the_others() -> None:
    p = np.array([0.0, 0.2, 0.4, 0.5, 0.6, 0.9, 1.0])
    for confidence, shift in CALIBRATIONS:
        c = calibrate(p, confidence, shift)
        assert c[0] == 0.0 and c[-1] == 1.0
        assert np.all(np.diff(c) > 0)
    assert np.array_equal(calibrate(p, *IDENTITY), p)
    sure = calibrate(p, 4.0, -1.0)
    assert sure[5] > p[5] and sure[1] < p[1] and sure[3] < 0.5  # surer, and fewer owned


def noisy_evidence(seed: int = 3, n: int = 16) -> tuple[Evidence, np.ndarray]:
    """Objects owned by one of three agents or by nobody, claims 0.6 for the owner and 0.4 for the
    others (plus a little noise), forbidden exactly when owned; colours say nothing."""
    rng = np.random.default_rng(seed)
    owner = np.arange(n) % 4  # 3: nobody
    truth = np.zeros((n, 3))
    truth[owner < 3, owner[owner < 3]] = 1.0
    claims = np.clip(np.where(truth > 0, 0.6, 0.4) + rng.uniform(-0.05, 0.05, truth.shape), 0.0, 1.0)
    colours = tuple(("blue", "red")[int(k)] for k in rng.integers(0, 2, n))
    frame = Frame(AGENTS, claims, colours, {})
    return Evidence(frame, (owner < 3).astype(float)), truth


def test_with_exact_ownership_only_the_identity_is_tried() -> None:
    ev, truth = noisy_evidence()
    exact_ev = Evidence(Frame(AGENTS, truth, ev.frame.colors, {}), ev.t)
    assert candidates(exact_ev) == (IDENTITY,)
    assert candidates(ev) == CALIBRATIONS
    assert np.array_equal(calibrated(exact_ev, CALIBRATIONS[-1]).frame.own, truth)


def test_the_learner_takes_the_calibration_under_which_the_permissions_are_most_probable() -> None:
    ev, _ = noisy_evidence()
    cfg = LearnConfig()
    model = model_for(VOCAB.atoms(), cfg.max_conditions)
    objectives = []
    for cal in CALIBRATIONS:
        canon, _, _ = exact.canonical_order(calibrated(ev, cal))
        choice = exact.reinduce(canon, "trash", (), VOCAB.atoms(), model, cfg.max_conditions, MAX_RULES)
        objectives.append((choice.runs[choice.chosen].objective, choice.result))
    best = min(range(len(objectives)), key=lambda k: objectives[k][0])
    ind, choice = calibrated_inducer("trash", ev, VOCAB, cfg, ())
    assert choice.result == objectives[best][1]
    out = learn_permission("trash", (), (), ev, ev.n - 1, VOCAB, cfg)
    assert out.rules == objectives[best][1]


def agent_norm_evidence(seed: int, n: int = 10) -> Evidence:
    """Objects owned by one of three agents or by nobody (most of those in the home area), claims
    of 0.6 for the owner and 0.4 for the others, each +- U(0.2); forbidden exactly when a1's."""
    rng = np.random.default_rng(seed)
    owner = rng.integers(0, 4, n)  # 3: nobody
    truth = np.zeros((n, 3))
    truth[owner < 3, owner[owner < 3]] = 1.0
    claims = np.clip(np.where(truth > 0, 0.6, 0.4) + rng.uniform(-0.2, 0.2, truth.shape), 0.0, 1.0)
    colours = tuple(("blue", "red")[int(k)] for k in rng.integers(0, 2, n))
    home = (owner == 3) | (rng.random(n) < 0.15)
    return Evidence(Frame(AGENTS, claims, colours, {"home": home}), truth[:, 0])


def test_noisy_claims_read_through_the_chosen_calibration_teach_an_owner_s_norm_more_often(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Read as three independent probabilities, '0.6 for the owner, 0.4 for the others' makes
    almost every object someone's, and a1's norm is found less often than when the claims are
    read through the calibration the permissions favour."""
    vocab = Vocabulary(AGENTS, ("blue", "red"), ("home",))
    norm = (Rule("trash", (Literal("ownedBy", "a1"),)),)

    def found() -> int:
        evs = [agent_norm_evidence(seed) for seed in range(20)]
        return sum(learn_permission("trash", (), (), ev, ev.n - 1, vocab, LearnConfig()).rules == norm
                   for ev in evs)

    calibrated_hits = found()
    monkeypatch.setattr(calibration, "CALIBRATIONS", (IDENTITY,))
    assert calibrated_hits >= found() + 4


def test_the_posterior_rests_on_the_learner_s_calibration() -> None:
    ev, _ = noisy_evidence()
    out = learn_permission("trash", (), (), ev, ev.n - 1, VOCAB, LearnConfig())
    post = rule_posterior(ev, "trash", VOCAB, LearnConfig(), out.rules)
    assert post.map() == out.rules
