"""Differential oracle: rule-based ownership inference equals brute-force Bayes over every agent's atom.

``ownctl.ownership.infer.posterior`` conditions only on the atoms the rules name and folds every other
agent into one "owned by someone else" atom. The oracle here does none of that: for each object it
enumerates all 2^m joint assignments of all m agents' ownership atoms, evaluates every literal
directly from the object's percepts, multiplies the prior by each permission's likelihood
``f * P(say forbid | world) + (1 - f) * P(say allow | world)`` with ``P(say forbid | world) =
1 - noise`` if some rule of that action holds, else ``noise``, and marginalises. Both must agree to
1e-9 on every generated case (several actions whose rules share atoms, ``any``, negations, agents the
frame does not know, soft permission values, missing permissions, noise including 0).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from ownctl.logic.frame import Frame
from ownctl.logic.rules import ANY, Literal, Rule, parse_rule
from ownctl.ownership.infer import posterior

SEED = 20240917
N_CASES = 400
TOL = 1e-9
AGENT_POOL = ("alexis", "xuan", "agent1", "agent2", "agent3", "casey")
ABSENT = "ghost"  # named by rules, never an agent of the frame
COLOURS = ("red", "blue", "green")
AREAS = ("home", "trash")
CATEGORIES = ("cup", "tool")
ACTIONS = ("trash", "pickUp", "collect")


# -- the oracle ------------------------------------------------------------------------------------
def literal_holds(lit: Literal, frame: Frame, i: int, world: tuple[int, ...]) -> bool:
    """Truth of ``lit`` for object ``i`` when agent j owns it iff ``world[j]``."""
    pred, arg = lit.atom
    if pred == "ownedBy":
        value = any(world) if arg == ANY else (arg in frame.agents and bool(world[frame.agents.index(arg)]))
    elif pred == "isColored":
        value = frame.colors[i] is not None if arg == ANY else frame.colors[i] == arg
    elif pred == "inArea":
        inside = {a for a, member in frame.areas.items() if member[i]}
        value = bool(inside) if arg == ANY else arg in inside
    else:
        value = bool(frame.categories[i]) if arg == ANY else arg in frame.categories[i]
    return value != lit.negated


def brute_posterior(
    frame: Frame, rule_sets: dict[str, list[Rule]], perms: dict[str, np.ndarray], noise: float
) -> np.ndarray:
    """Exact posterior by enumerating all 2^m assignments of all m agents' atoms, object by object."""
    m = len(frame.agents)
    out = frame.own.copy()
    for i in range(frame.n):
        evidence = [(rule_sets[a], float(perms[a][i])) for a in sorted(rule_sets)
                    if rule_sets[a] and a in perms and not math.isnan(perms[a][i])]
        if not evidence:
            continue
        total = 0.0
        marg = np.zeros(m)
        for world in itertools.product((0, 1), repeat=m):
            weight = 1.0
            for j, bit in enumerate(world):
                weight *= frame.own[i, j] if bit else 1.0 - frame.own[i, j]
            for rules, f in evidence:
                holds = any(all(literal_holds(lit, frame, i, world) for lit in r.literals) for r in rules)
                say_forbid = 1.0 - noise if holds else noise
                weight *= f * say_forbid + (1.0 - f) * (1.0 - say_forbid)
            total += weight
            marg += weight * np.array(world, dtype=float)
        if total > 0:  # zero-likelihood evidence (noise 0) leaves the prior in place
            out[i] = marg / total
    return out


# -- generated cases -------------------------------------------------------------------------------
def probability(rng: np.random.Generator) -> float:
    return float(rng.choice([0.0, 1.0, 0.5, rng.random(), rng.random(), rng.random()]))


def random_frame(rng: np.random.Generator) -> Frame:
    n = int(rng.integers(1, 7))
    m = int(rng.integers(1, 6))
    agents = tuple(str(a) for a in rng.choice(AGENT_POOL, size=m, replace=False))
    own = np.array([[probability(rng) for _ in range(m)] for _ in range(n)])
    colours = tuple(None if rng.random() < 0.2 else str(rng.choice(COLOURS)) for _ in range(n))
    areas = {a: rng.random(n) < 0.4 for a in AREAS if rng.random() < 0.8}
    cats = tuple(frozenset(c for c in CATEGORIES if rng.random() < 0.3) for _ in range(n))
    return Frame(agents, own, colours, areas, cats)


def random_literal(rng: np.random.Generator, frame: Frame) -> Literal:
    pred = str(rng.choice(["ownedBy", "ownedBy", "ownedBy", "isColored", "inArea", "inCategory"]))
    pool = {
        "ownedBy": [ANY, ANY, *frame.agents, ABSENT],
        "isColored": [ANY, *COLOURS],
        "inArea": [ANY, *AREAS],
        "inCategory": [ANY, *CATEGORIES],
    }[pred]
    return Literal(pred, str(rng.choice(pool)), bool(rng.random() < 0.35))


def random_rules(rng: np.random.Generator, frame: Frame, action: str) -> list[Rule]:
    return [
        Rule(action, tuple(random_literal(rng, frame) for _ in range(int(rng.integers(0, 4)))))
        for _ in range(int(rng.integers(0, 4)))
    ]


Case = tuple[Frame, dict[str, list[Rule]], dict[str, np.ndarray], float]


def random_case(rng: np.random.Generator) -> Case:
    frame = random_frame(rng)
    actions = [str(a) for a in rng.choice(ACTIONS, size=int(rng.integers(1, 4)), replace=False)]
    rule_sets = {a: random_rules(rng, frame, a) for a in actions}
    perms: dict[str, np.ndarray] = {}
    for a in actions:
        if rng.random() < 0.9:
            values = np.array([float(rng.choice([np.nan, 0.0, 1.0, rng.random()])) for _ in range(frame.n)])
            perms[a] = values
    noise = float(rng.choice([0.0, 0.05, 0.2, rng.uniform(0.0, 0.5)]))
    return frame, rule_sets, perms, noise


def test_posterior_equals_brute_force_bayes_over_all_agents() -> None:
    rng = np.random.default_rng(SEED)
    shared = 0
    for case in range(N_CASES):
        frame, rule_sets, perms, noise = random_case(rng)
        got = posterior(frame, rule_sets, perms, noise)
        want = brute_posterior(frame, rule_sets, perms, noise)
        assert got.shape == frame.own.shape
        err = float(np.max(np.abs(got - want))) if got.size else 0.0
        assert err <= TOL, (case, frame, rule_sets, perms, noise, got, want)
        shared += sum(1 for a in perms if rule_sets[a]) > 1
    assert shared > N_CASES // 4  # many cases condition on several actions' rules at once


def test_the_generator_covers_the_interesting_cases() -> None:
    """Guard against a silently weak oracle: the cases really use any, negation, absent agents..."""
    rng = np.random.default_rng(SEED)
    seen = {"any": 0, "negated ownedBy": 0, "absent agent": 0, "soft value": 0, "noise 0": 0, "m=5": 0}
    for _ in range(N_CASES):
        frame, rule_sets, perms, noise = random_case(rng)
        lits = [lit for rules in rule_sets.values() for r in rules for lit in r.literals]
        seen["any"] += any(lit.pred == "ownedBy" and lit.arg == ANY for lit in lits)
        seen["negated ownedBy"] += any(lit.pred == "ownedBy" and lit.negated for lit in lits)
        seen["absent agent"] += any(lit.arg == ABSENT for lit in lits)
        seen["soft value"] += any(0 < v < 1 for vals in perms.values() for v in vals if not math.isnan(v))
        seen["noise 0"] += noise == 0.0
        seen["m=5"] += len(frame.agents) == 5
    assert all(count >= 20 for count in seen.values()), seen


# -- laws ------------------------------------------------------------------------------------------
def frame_of(own: list[list[float]], colours: tuple[str | None, ...] | None = None,
             agents: tuple[str, ...] = ("agent1", "agent2", "agent3")) -> Frame:
    arr = np.array(own, dtype=float)
    return Frame(agents, arr, colours or tuple("blue" for _ in range(len(arr))))


def test_paper_equation_1_worked_example() -> None:
    """Reference 4.3: priors 0.5, ``forbid trash if ownedBy any``: forbidden -> 0.5 / 0.875; allowed -> 0."""
    frame = frame_of([[0.5, 0.5, 0.5], [0.5, 0.5, 0.5]])
    rules = {"trash": [parse_rule("forbid trash if ownedBy any")]}
    post = posterior(frame, rules, {"trash": np.array([1.0, 0.0])}, noise=0.0)
    assert np.allclose(post[0], 0.5 / 0.875, atol=1e-12)
    assert np.allclose(post[1], 0.0, atol=1e-12)


def test_no_permission_leaves_the_prior_exactly() -> None:
    frame = frame_of([[0.3, 0.9, 0.0], [0.5, 0.5, 0.5]])
    rules = {"trash": [parse_rule("forbid trash if ownedBy any")], "pickUp": [parse_rule("forbid pickUp")]}
    assert np.array_equal(posterior(frame, rules, {"trash": np.full(2, np.nan)}), frame.own)
    assert np.array_equal(posterior(frame, rules, {}), frame.own)
    # a permission on an action without rules tells nothing about ownership
    assert np.array_equal(posterior(frame, {"collect": []}, {"collect": np.ones(2)}), frame.own)


@pytest.mark.parametrize("noise", [0.0, 0.05, 0.3])
def test_rules_without_ownership_leave_the_prior_exactly(noise: float) -> None:
    """Including the original's bug B2: forbid collect on a non-red object under ``... if isColored red``."""
    frame = frame_of([[0.3, 0.9, 0.2], [0.6, 0.1, 0.4]], colours=("blue", "red"))
    rules = {"collect": [parse_rule("forbid collect if isColored red")]}
    for values in ([1.0, 1.0], [0.0, 0.0], [0.7, 0.2]):
        post = posterior(frame, rules, {"collect": np.array(values)}, noise)
        assert np.array_equal(post, frame.own), (values, post)


def test_impossible_evidence_with_noise_keeps_the_prior_and_never_zeroes_every_owner() -> None:
    frame = frame_of([[0.3, 0.8, 0.6]], colours=("blue",))
    cases = {
        "an owner-specific rule that cannot fire (blue)": "forbid trash if ownedBy agent1 and isColored red",
        "a rule about an agent the object cannot belong to": "forbid trash if ownedBy ghost",
    }
    for why, text in cases.items():
        for noise in (0.0, 0.05):
            post = posterior(frame, {"trash": [parse_rule(text)]}, {"trash": np.ones(1)}, noise)
            assert np.allclose(post, frame.own, atol=1e-12), (why, noise, post)
    # an allow under "forbid always": every world contradicts it
    post = posterior(frame, {"trash": [parse_rule("forbid trash")]}, {"trash": np.zeros(1)}, 0.05)
    assert np.allclose(post, frame.own, atol=1e-12)
    # a forbid under "forbid if owned by agent1" when agent1's claim says 0: others keep their prior
    frame0 = frame_of([[0.0, 0.8, 0.6]])
    rules = {"trash": [parse_rule("forbid trash if ownedBy agent1")]}
    post = posterior(frame0, rules, {"trash": np.ones(1)}, 0.05)
    assert post.max() > 0 and np.allclose(post, frame0.own, atol=1e-12)


def test_an_uninformative_permission_value_changes_nothing() -> None:
    frame = frame_of([[0.2, 0.7, 0.4]])
    rules = {"trash": [parse_rule("forbid trash if ownedBy any")]}
    post = posterior(frame, rules, {"trash": np.array([0.5])}, 0.05)
    assert np.allclose(post, frame.own, atol=1e-12)


def test_forbid_raises_and_allow_lowers_ownership_under_forbid_if_owned() -> None:
    frame = frame_of([[0.2, 0.7, 0.4], [0.2, 0.7, 0.4]])
    rules = {"trash": [parse_rule("forbid trash if ownedBy any")]}
    post = posterior(frame, rules, {"trash": np.array([1.0, 0.0])}, 0.05)
    assert np.all(post[0] > frame.own[0]) and np.all(post[1] < frame.own[1])
    assert np.all((post >= 0) & (post <= 1))
