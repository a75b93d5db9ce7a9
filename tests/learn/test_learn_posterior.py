"""The posterior over rule sets (``ownctl.learn.posterior``) against a brute-force computation of
the stated model: prior x likelihood over every rule set, each object's ownership summed out by
listing its owner sets one by one, in plain Python."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest

from ownctl.config import LearnConfig
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import subtract
from ownctl.learn.model import model_for
from ownctl.learn.posterior import (
    RuleSpace,
    every_rule,
    implication_matrix,
    posterior,
    rule_implies,
    rule_posterior,
)
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import ANY, Rule, parse_rule

AGENTS = ("a1", "a2")
VOCAB = Vocabulary(("a1",), ("blue", "red"), ("desk",))


def holds(rule: Rule, owners: frozenset[str], colour: str | None, desk: bool) -> bool:
    """Plain truth of a rule for one object with a known owner set."""
    for lit in rule.literals:
        if lit.pred == "ownedBy":
            value = bool(owners) if lit.arg == ANY else lit.arg in owners
        elif lit.pred == "isColored":
            value = colour is not None if lit.arg == ANY else colour == lit.arg
        else:
            value = desk  # inArea any and inArea desk: the only area
        if value == lit.negated:
            return False
    return True


def brute_p(rules, p_own: list[float], colour: str, desk: bool) -> float:
    """P(some rule holds) for one object, listing every owner set with its probability."""
    total = 0.0
    for bits in itertools.product((0, 1), repeat=len(AGENTS)):
        weight = math.prod(p if b else 1 - p for p, b in zip(p_own, bits, strict=True))
        owners = frozenset(a for a, b in zip(AGENTS, bits, strict=True) if b)
        if any(holds(r, owners, colour, desk) for r in rules):
            total += weight
    return total


def case(seed: int):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 6))
    own = rng.choice([0.0, 1.0, 0.3, 0.75], size=(n, 2))
    colours = tuple(str(c) for c in rng.choice(["blue", "red"], size=n))
    desk = rng.random(n) < 0.5
    values = rng.choice([0.0, 1.0], size=n)
    return Frame(AGENTS, own, colours, {"desk": desk}), values


@pytest.mark.parametrize("seed", range(8))
def test_the_posterior_equals_brute_force(seed: int) -> None:
    frame, values = case(seed)
    ev = Evidence(frame, values)
    atoms = VOCAB.atoms()
    model = model_for(atoms, 2)
    given = (parse_rule("forbid trash if ownedBy a1 and isColored red"),) if seed % 3 == 0 else ()
    pool = tuple(r for r in every_rule("trash", atoms, 2) if r not in given)
    space = RuleSpace(pool, 2, given)
    post = posterior(ev, "trash", space, model)
    # brute force: every set of at most two pool rules, none implying the other
    pairs = [(a, b) for a, b in itertools.combinations(pool, 2)
             if not rule_implies(a, b) and not rule_implies(b, a)]
    sets = [(), *((r,) for r in pool), *pairs]
    logw = []
    for s in sets:
        rules = (*given, *s)
        loglik = 0.0
        for i in range(frame.n):
            q = brute_p(rules, list(frame.own[i]), frame.colors[i], bool(frame.areas["desk"][i]))
            p = model.noise + (1 - 2 * model.noise) * q
            loglik += math.log(p if values[i] >= 0.5 else 1 - p)
        logw.append(loglik - sum(model.cost_of(r) for r in s))
    top = max(logw)
    z = sum(math.exp(v - top) for v in logw)
    brute = {(*given, *s): math.exp(v - top) / z for s, v in zip(sets, logw, strict=True)}
    assert len(post.sets) == len(brute)
    for rules, p in zip(post.sets, post.probabilities, strict=True):
        assert p == pytest.approx(brute[rules], abs=1e-9)
    assert post.log_evidence == pytest.approx(top + math.log(z), abs=1e-9)
    # marginals: each rule, and P(forbidden) of new objects under uncertain ownership
    marg: dict[Rule, float] = {}
    for rules, p in brute.items():
        for r in rules:
            marg[r] = marg.get(r, 0.0) + p
    got = post.rule_probabilities()
    assert set(got) == set(marg) and all(got[r] == pytest.approx(marg[r], abs=1e-9) for r in marg)
    probe, _ = case(seed + 100)
    expected = [sum(p * brute_p(rules, list(probe.own[i]), probe.colors[i], bool(probe.areas["desk"][i]))
                    for rules, p in brute.items()) for i in range(probe.n)]
    assert np.allclose(post.p_forbidden(probe), expected, atol=1e-9)
    best = max(brute.values())
    assert brute[post.map()] == pytest.approx(best, abs=1e-12)


def test_rule_probabilities_and_support_follow_the_evidence() -> None:
    """Three red objects forbidden, two blue allowed, exact owners: the red rule is near certain."""
    own = np.array([[1, 0], [0, 1], [0, 0], [1, 0], [0, 0]], dtype=float)
    frame = Frame(AGENTS, own, ("red", "red", "red", "blue", "blue"), {"desk": np.zeros(5, dtype=bool)})
    ev = Evidence(frame, [1, 1, 1, 0, 0])
    red = parse_rule("forbid trash if isColored red")
    post = rule_posterior(ev, "trash", Vocabulary(AGENTS, ("blue", "red"), ("desk",)), LearnConfig(), (red,))
    assert post.map() == (red,)
    assert post.support(red, frame) > 0.9
    assert post.support(parse_rule("forbid trash if isColored blue"), frame) < 0.01
    p = post.p_forbidden(frame)
    assert (p[:3] > 0.9).all() and (p[3:] < 0.1).all()


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(2))
def test_p_forbidden_is_the_weighted_sum_over_rule_sets(seed: int) -> None:
    """The vectorised marginal equals summing each set's exact P(forbidden) one by one, on a frame
    larger than one block of the computation, and with an allow norm (subtracted from every set)."""
    frame, values = case(seed)
    post = rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig())
    rng = np.random.default_rng(seed)
    n = 40
    probe = Frame(AGENTS, rng.choice([0.0, 1.0, 0.2, 0.6], size=(n, 2)),
                  tuple(str(c) for c in rng.choice(["blue", "red"], size=n)), {"desk": rng.random(n) < 0.5})
    expected = sum(p * p_forbidden(list(rules), probe) for rules, p in zip(post.sets, post.probabilities,
                                                                            strict=True))
    assert np.allclose(post._p_forbidden_tables(probe, 4, cells=len(post.sets) * 4 * 7), expected, atol=1e-9)
    assert np.allclose(post.p_forbidden(probe), expected, atol=1e-9)
    allow = parse_rule("forbid trash if isColored blue")
    with_allow = replace(post, allows=(allow,))
    kept = sum(p * p_forbidden(subtract(list(rules), allow), probe)
               for rules, p in zip(post.sets, post.probabilities, strict=True))
    assert np.allclose(with_allow.p_forbidden(probe), np.clip(kept, 0, 1), atol=1e-9)


def test_the_pool_names_only_agents_the_examples_name() -> None:
    """A store that knows many agents: the candidates, and so the posterior, are those of the
    vocabulary cut to the agents the examples' ownership names (any other agent's rules cover
    nothing there, or what a shorter rule covers), and building them stays small."""
    frame, values = case(5)
    many = Vocabulary((*AGENTS, *(f"x{k}" for k in range(60))), ("blue", "red"), ("desk",))
    few = Vocabulary(AGENTS, ("blue", "red"), ("desk",))
    ev = Evidence(frame, values)
    wide = rule_posterior(ev, "trash", many, LearnConfig())
    narrow = rule_posterior(ev, "trash", few, LearnConfig())
    assert wide.sets == narrow.sets
    assert not any(lit.arg.startswith("x") for r in wide.rules for lit in r.literals if lit.pred == "ownedBy")


@pytest.mark.parametrize("seed", range(4))
def test_support_is_the_mass_of_the_sets_that_forbid_all_the_rule_forbids(seed: int) -> None:
    frame, values = case(seed)
    post = rule_posterior(Evidence(frame, values), "trash", VOCAB, LearnConfig())
    probe, _ = case(seed + 50)
    ev = Evidence(probe, np.zeros(probe.n))
    for rule in post.rules[:12]:
        mine = ev.truth(rule) & (ev.worlds.weights > 0)
        expected = sum(p for rules, p in zip(post.sets, post.probabilities, strict=True)
                       if not (mine & ~ev.union(rules)).any())
        assert post.support(rule, probe) == pytest.approx(min(expected, 1.0), abs=1e-12)


@pytest.mark.parametrize("length", [1, 2, 3])
def test_the_implication_matrix_is_rule_implies_pair_by_pair(length: int) -> None:
    pool = every_rule("trash", Vocabulary(AGENTS, ("blue", "red", "green"), ("desk", "home")).atoms(), length)
    pool = pool[:: max(1, len(pool) // 60)]  # every rule of length 1; a spread of the longer ones
    got = implication_matrix(pool)
    expected = [[rule_implies(a, b) for b in pool] for a in pool]
    assert got.tolist() == expected
    assert implication_matrix([Rule("trash")]).tolist() == [[True]]
