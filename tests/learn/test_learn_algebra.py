"""Laws of the rule algebra the learner builds on (``ownctl.learn.algebra``), checked semantically.

Rules are compared by what they forbid, not by their text: a rule set is evaluated with the exact
``p_forbidden`` (itself checked against ProbLog) on random frames. On crisp frames (ownership 0 or
1) a rule set's value is its truth, so two sets are equivalent when they agree on every object of
many random crisp frames; on probabilistic frames equivalent sets must also give equal probabilities.
"""

from __future__ import annotations

import numpy as np

from ownctl.learn.algebra import merge_pair, merge_rule, refine, rule_diff
from ownctl.learn.evidence import Vocabulary
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import ANY, Literal, Rule

SEED = 7
AGENTS = ("alexis", "casey", "xuan")
COLOURS = ("red", "blue")
AREAS = ("home",)
# a small atom pool, so that random rules often overlap, complement and subsume each other
ATOMS = (
    Literal("ownedBy", ANY), Literal("ownedBy", "alexis"), Literal("ownedBy", "casey"),
    Literal("isColored", "red"), Literal("isColored", "blue"), Literal("inArea", "home"),
)


def crisp_frame(rng: np.random.Generator, n: int = 96) -> Frame:
    own = (rng.random((n, len(AGENTS))) < 0.35).astype(float)
    colours = tuple(None if rng.random() < 0.1 else str(rng.choice(COLOURS)) for _ in range(n))
    return Frame(AGENTS, own, colours, {"home": rng.random(n) < 0.5})


def soft_frame(rng: np.random.Generator, n: int = 32) -> Frame:
    frame = crisp_frame(rng, n)
    return frame.with_own(rng.choice([0.0, 1.0, 0.5, 0.2, 0.9], size=frame.own.shape))


def random_rule(rng: np.random.Generator, max_literals: int = 3, action: str = "trash") -> Rule:
    """A non-contradictory rule over ATOMS with 0..max_literals literals."""
    k = int(rng.integers(0, max_literals + 1))
    picks = rng.choice(len(ATOMS), size=k, replace=False)
    return Rule(action, tuple(ATOMS[i] if rng.random() < 0.6 else ATOMS[i].negate() for i in picks))


def truth(rules: list[Rule] | tuple[Rule, ...], frame: Frame) -> np.ndarray:
    """Bool vector: does the rule set forbid each object of a crisp frame."""
    return p_forbidden(list(rules), frame) >= 0.5


def test_truth_on_crisp_frames_is_zero_or_one() -> None:
    frame = crisp_frame(np.random.default_rng(SEED))
    rng = np.random.default_rng(SEED + 1)
    for _ in range(20):
        p = p_forbidden([random_rule(rng) for _ in range(3)], frame)
        assert set(np.unique(p)) <= {0.0, 1.0}


def test_merge_pair_of_complements_is_their_common_part() -> None:
    rng = np.random.default_rng(SEED)
    frames = [crisp_frame(rng) for _ in range(4)]
    merged = 0
    for _ in range(300):
        base = random_rule(rng, 3)
        free = [a for a in ATOMS if a.atom not in {lit.atom for lit in base.literals}]
        c = free[int(rng.integers(len(free)))]
        c = c if rng.random() < 0.5 else c.negate()
        r1, r2 = base.with_literal(c), base.with_literal(c.negate())
        assert merge_pair(r1, r2) == base and merge_pair(r2, r1) == base
        for frame in frames:
            assert np.array_equal(truth([base], frame), truth([r1, r2], frame))
        merged += 1
    assert merged == 300


def test_merge_pair_is_sound_and_refuses_non_complementary_pairs() -> None:
    rng = np.random.default_rng(SEED + 2)
    frames = [crisp_frame(rng) for _ in range(3)]
    hits = misses = 0
    for _ in range(1000):
        r1, r2 = random_rule(rng, 2), random_rule(rng, 2)
        m = merge_pair(r1, r2)
        if m is None:
            diff = r1.conditions ^ r2.conditions
            assert not (len(diff) == 2 and len({lit.atom for lit in diff}) == 1 and r1 != r2), (r1, r2)
            misses += 1
            continue
        hits += 1
        for frame in frames:
            assert np.array_equal(truth([m], frame), truth([r1, r2], frame)), (r1, r2, m)
    assert hits > 10 and misses > 100
    same_lits = Rule("trash", (Literal("isColored", "red"),))
    assert merge_pair(same_lits, same_lits) is None
    a = Rule("trash", (Literal("isColored", "red"), Literal("inArea", "home")))
    b = Rule("trash", (Literal("isColored", "blue").negate(), Literal("inArea", "home")))
    assert merge_pair(a, b) is None  # two different atoms differ: not A and c / A and not c


def test_rule_diff_is_exactly_r1_and_not_r2() -> None:
    rng = np.random.default_rng(SEED + 3)
    crisp = [crisp_frame(rng) for _ in range(3)]
    soft = [soft_frame(rng) for _ in range(3)]
    kinds = {"empty": 0, "disjoint": 0, "pieces": 0}
    for _ in range(400):
        r1, r2 = random_rule(rng), random_rule(rng)
        pieces = rule_diff(r1, r2)
        kinds["empty" if not pieces else "disjoint" if pieces == [r1] else "pieces"] += 1
        for piece in pieces:
            assert r1.conditions <= piece.conditions and not piece.is_contradictory()
        for frame in crisp:
            assert np.array_equal(truth(pieces, frame), truth([r1], frame) & ~truth([r2], frame)), (r1, r2)
        both = Rule(r1.action, r1.literals + r2.literals)  # r1 and r2 (contradictory: never holds)
        for frame in soft:
            want = p_forbidden([r1], frame) - p_forbidden([both], frame)
            got = p_forbidden(pieces, frame) if pieces else np.zeros(frame.n)
            assert np.allclose(got, want, atol=1e-12), (r1, r2, pieces)
    assert min(kinds.values()) > 20, kinds


def test_rule_diff_cases_from_the_reference() -> None:
    owned = Rule("trash", (Literal("ownedBy", ANY),))
    red = Rule("trash", (Literal("isColored", "red"),))
    not_red = Literal("isColored", "red", True)
    assert rule_diff(owned, red) == [Rule("trash", (Literal("ownedBy", ANY), not_red))]
    assert rule_diff(red, Rule("trash")) == []  # minus "always" leaves nothing
    assert rule_diff(owned.with_literal(Literal("isColored", "red")), red) == []  # r2 more general
    assert rule_diff(red, Rule("trash", (not_red,))) == [red]  # disjoint


def check_irredundant(rules: list[Rule]) -> None:
    for a in rules:
        for b in rules:
            assert a is b or not a.conditions <= b.conditions, (a, b, rules)


def test_merge_rule_keeps_the_union_and_drops_only_subsumed_rules() -> None:
    rng = np.random.default_rng(SEED + 4)
    frames = [crisp_frame(rng) for _ in range(3)]
    for _ in range(150):
        rules: list[Rule] = []
        added: list[Rule] = []
        for _ in range(int(rng.integers(1, 7))):
            new = random_rule(rng)
            if new.is_contradictory():
                continue
            rules = merge_rule(rules, new)
            added.append(new)
            check_irredundant(rules)
            for frame in frames:
                assert np.array_equal(truth(rules, frame), truth(added, frame)), (added, rules)


def test_merge_rule_merges_complements_repeatedly() -> None:
    red, home = Literal("isColored", "red"), Literal("inArea", "home")
    rules = [Rule("trash", (red, home)), Rule("trash", (red.negate(), home.negate())),
             Rule("trash", (red.negate(), home))]
    out = merge_rule(rules[:2], rules[2])
    # (not red and home) merges with (red and home) -> home; (not red and not home) stays
    assert set(out) == {Rule("trash", (home,)), Rule("trash", (red.negate(), home.negate()))}
    out = merge_rule(out, Rule("trash", (red, home.negate())))
    # (red and not home) ... -> not home, then with home -> always
    assert out == [Rule("trash")]


def test_merge_rule_with_examples_keeps_every_covered_example() -> None:
    """The paper's data-driven subsumption may drop a rule, but only one whose examples ``new`` covers."""
    rng = np.random.default_rng(SEED + 5)
    dropped = 0
    for _ in range(200):
        examples = crisp_frame(rng, n=int(rng.integers(3, 12)))

        def covers(rule: Rule, ex: Frame = examples) -> np.ndarray:
            return p_forbidden([rule], ex) >= 0.5

        rules: list[Rule] = []
        for _ in range(int(rng.integers(1, 5))):
            new = random_rule(rng)
            if new.is_contradictory():
                continue
            before = [*rules, new]
            rules = merge_rule(rules, new, covers)
            covered_before = np.logical_or.reduce([covers(r) for r in before])
            covered_after = np.logical_or.reduce([covers(r) for r in rules] or [np.zeros(examples.n, bool)])
            assert np.array_equal(covered_before, covered_after), (before, rules)
            gone = [r for r in before if r not in rules]
            dropped += len(gone)
    assert dropped > 0


def test_refine_adds_each_unused_atom_positive_then_negated() -> None:
    atoms = Vocabulary(("xuan", "alexis"), ("red",)).atoms()
    assert [a.text() for a in atoms] == ["ownedBy any", "ownedBy alexis", "ownedBy xuan", "isColored any",
                                         "isColored red"]
    base = Rule("trash", (Literal("ownedBy", "alexis", True),))
    out = refine(base, atoms)
    assert len(out) == 2 * (len(atoms) - 1)
    assert out[0] == base.with_literal(atoms[0]) and out[1] == base.with_literal(atoms[0].negate())
    assert all(base.conditions < r.conditions for r in out)


def test_vocabulary_atoms_do_not_depend_on_input_order() -> None:
    a = Vocabulary(("xuan", "alexis", "casey"), ("red", "blue"), ("home", "desk"), ("cup",))
    b = Vocabulary(("casey", "xuan", "alexis", "xuan"), ("blue", "red"), ("desk", "home"), ("cup",))
    assert a.atoms() == b.atoms()
