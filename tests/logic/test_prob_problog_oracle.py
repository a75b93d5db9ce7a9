"""Differential oracle: ``p_forbidden`` equals ProbLog's exact answer on generated rule programs.

Each generated case is a frame (several objects, 2-5 agents, colours, areas, categories) and a rule
set (1-5 rules, 0-5 literals each) written independently as a ProbLog program: one probabilistic fact
per object/agent ownership atom, crisp facts for the percepts, one clause per rule, one query per
object. docs/architecture.md, section 3: the two must agree to 1e-9 for every object.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from problog import get_evaluatable
from problog.program import PrologString

from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import Literal, Rule
from ownctl.logic.vocab import ACTIONS

SEED = 20240611
N_PROGRAMS = 1000
TOL = 1e-9

AGENT_POOL = ("alexis", "xuan", "agent1", "agent2", "agent3", "Bob-1", "c_d")
ABSENT_AGENTS = ("ghost", "nobody")  # named by rules, never in a frame
COLOURS = ("red", "blue", "green")
AREAS = ("home", "trash", "desk_xuan")
CATEGORIES = ("cup", "tool", "paper")
ACTION_NAMES = tuple(ACTIONS)

# Sentinel facts so every predicate is defined even when no object has it (ProbLog raises on an
# undefined predicate). The sentinel object is not an obj/1, so no rule or query ever reaches it.
PRELUDE = """\
owned(nil_obj, nil_agent).
color(nil_obj, nil_colour).
in_area(nil_obj, nil_area).
in_cat(nil_obj, nil_cat).
owned_any(O) :- owned(O, _).
color_any(O) :- color(O, _).
area_any(O) :- in_area(O, _).
cat_any(O) :- in_cat(O, _).
"""


def q(name: str) -> str:
    """A ProbLog quoted atom for one of our names (letters, digits, '_' and '-' only)."""
    assert all(ch.isalnum() or ch in "_-" for ch in name), name
    return f"'{name}'"


def random_probability(rng: np.random.Generator) -> float:
    kind = rng.integers(0, 6)
    if kind == 0:
        return 0.0
    if kind == 1:
        return 1.0
    if kind == 2:
        return 0.5
    return float(rng.random())


def random_frame(rng: np.random.Generator) -> Frame:
    n = int(rng.integers(1, 9))
    k = int(rng.integers(2, 6))
    agents = tuple(str(a) for a in rng.choice(AGENT_POOL, size=k, replace=False))
    own = np.array([[random_probability(rng) for _ in range(k)] for _ in range(n)])
    colours = tuple(None if rng.random() < 0.25 else str(rng.choice(COLOURS)) for _ in range(n))
    # Some frames leave out an area, so a rule can name an area the frame does not know.
    area_names = [a for a in AREAS if rng.random() < 0.8]
    areas = {a: rng.random(n) < 0.4 for a in area_names}
    categories = tuple(
        frozenset(str(c) for c in CATEGORIES if rng.random() < 0.3) for _ in range(n)
    )
    return Frame(agents, own, colours, areas, categories)


def random_literal(rng: np.random.Generator, frame: Frame) -> Literal:
    pred = ("ownedBy", "ownedBy", "isColored", "inArea", "inCategory")[rng.integers(0, 5)]
    negated = bool(rng.random() < 0.35)
    if pred == "ownedBy":
        r = rng.random()
        if r < 0.3:
            arg = "any"
        elif r < 0.4:
            arg = str(rng.choice(ABSENT_AGENTS))
        else:
            arg = str(rng.choice(frame.agents))
    else:
        pool = {"isColored": COLOURS, "inArea": AREAS, "inCategory": CATEGORIES}[pred]
        arg = "any" if rng.random() < 0.25 else str(rng.choice(pool))
    return Literal(pred, arg, negated)


def random_rules(rng: np.random.Generator, frame: Frame) -> list[Rule]:
    action = str(rng.choice(ACTION_NAMES))
    rules: list[Rule] = []
    for _ in range(int(rng.integers(1, 6))):
        n_lits = int(rng.choice([0, 1, 1, 2, 2, 3, 3, 4, 5]))
        lits = [random_literal(rng, frame) for _ in range(n_lits)]
        # Share atoms between rules: often reuse (possibly flip) a literal of an earlier rule.
        if rules and rules[-1].literals and rng.random() < 0.6:
            prev = rules[int(rng.integers(0, len(rules)))].literals
            if prev:
                lit = prev[int(rng.integers(0, len(prev)))]
                lits.append(lit.negate() if rng.random() < 0.4 else lit)
        rules.append(Rule(action, tuple(lits)))
    return rules


def literal_goal(lit: Literal) -> str:
    pred, arg = lit.atom
    if arg == "any":
        goal = {"ownedBy": "owned_any(O)", "isColored": "color_any(O)",
                "inArea": "area_any(O)", "inCategory": "cat_any(O)"}[pred]
    else:
        fact = {"ownedBy": "owned", "isColored": "color", "inArea": "in_area", "inCategory": "in_cat"}[pred]
        goal = f"{fact}(O, {q(arg)})"
    return f"\\+ {goal}" if lit.negated else goal


def problog_program(rules: list[Rule], frame: Frame) -> str:
    lines = [PRELUDE]
    for i in range(frame.n):
        obj = f"o{i}"
        lines.append(f"obj({obj}).")
        for j, agent in enumerate(frame.agents):
            lines.append(f"{float(frame.own[i, j])!r}::owned({obj}, {q(agent)}).")
        if frame.colors[i] is not None:
            lines.append(f"color({obj}, {q(frame.colors[i])}).")
        for area, member in frame.areas.items():
            if bool(member[i]):
                lines.append(f"in_area({obj}, {q(area)}).")
        for cat in sorted(frame.categories[i]):
            lines.append(f"in_cat({obj}, {q(cat)}).")
        lines.append(f"query(forbidden({obj})).")
    for rule in rules:
        body = ", ".join(["obj(O)", *(literal_goal(lit) for lit in rule.literals)])
        lines.append(f"forbidden(O) :- {body}.")
    return "\n".join(lines) + "\n"


def problog_answers(program: str, n: int) -> np.ndarray:
    result = get_evaluatable().create_from(PrologString(program)).evaluate()
    by_name = {str(term): float(p) for term, p in result.items()}
    assert len(by_name) == n, by_name
    return np.array([by_name[f"forbidden(o{i})"] for i in range(n)])


def test_problog_encoding_sanity() -> None:
    """The oracle itself: a hand-checked program gives the hand-computed answers."""
    frame = Frame(("a", "b"), np.array([[0.3, 0.4], [1.0, 0.0]]), ("red", None),
                  {"home": np.array([True, False])}, (frozenset({"cup"}), frozenset()))
    rules = [Rule("trash", (Literal("ownedBy", "a"), Literal("ownedBy", "b", True))),
             Rule("trash", (Literal("ownedBy", "any"), Literal("isColored", "any")))]
    got = problog_answers(problog_program(rules, frame), frame.n)
    # object 0: P(a & !b or (a|b)) = P(a|b) = 1 - 0.7*0.6 = 0.58; object 1: a & !b certain -> 1
    assert abs(got[0] - 0.58) < 1e-12 and abs(got[1] - 1.0) < 1e-12


@pytest.mark.slow
def test_p_forbidden_matches_problog_on_generated_programs() -> None:
    rng = np.random.default_rng(SEED)
    programs = queries = 0
    coverage = dict.fromkeys(
        ("neg_owned", "owned_any", "neg_owned_any", "absent_agent", "shared_atom",
         "crisp_any", "neg_crisp", "empty_rule", "multi_named"), 0)
    mismatches: list[str] = []
    started = time.perf_counter()
    for _ in range(N_PROGRAMS):
        frame = random_frame(rng)
        rules = random_rules(rng, frame)
        program = problog_program(rules, frame)
        expected = problog_answers(program, frame.n)
        got = p_forbidden(rules, frame)
        assert got.shape == (frame.n,)
        programs += 1
        queries += frame.n
        lits = [lit for r in rules for lit in r.literals]
        atoms = [lit.atom for r in rules for lit in set(r.literals)]
        coverage["neg_owned"] += any(lit.pred == "ownedBy" and lit.negated for lit in lits)
        coverage["owned_any"] += any(lit.atom == ("ownedBy", "any") for lit in lits)
        coverage["neg_owned_any"] += any(lit.atom == ("ownedBy", "any") and lit.negated for lit in lits)
        coverage["absent_agent"] += any(lit.pred == "ownedBy" and lit.arg in ABSENT_AGENTS for lit in lits)
        coverage["shared_atom"] += len(atoms) > len(set(atoms))
        coverage["crisp_any"] += any(lit.pred != "ownedBy" and lit.arg == "any" for lit in lits)
        coverage["neg_crisp"] += any(lit.pred != "ownedBy" and lit.negated for lit in lits)
        coverage["empty_rule"] += any(not r.literals for r in rules)
        coverage["multi_named"] += len({a for r in rules for a in r.agents()}) >= 2
        bad = np.flatnonzero(~(np.abs(got - expected) <= TOL))
        if bad.size:
            mismatches.append(
                f"rules={[r.text() for r in rules]} frame={frame!r} objects={bad.tolist()} "
                f"ours={got[bad].tolist()} problog={expected[bad].tolist()}"
            )
    elapsed = time.perf_counter() - started
    assert not mismatches, f"{len(mismatches)} of {programs} programs disagree; first: {mismatches[0]}"
    assert programs >= 1000, programs
    assert queries >= 3 * programs, queries
    # The generator must keep exercising every feature the brief names.
    for feature, count in coverage.items():
        assert count >= 50, (feature, count, coverage)
    print(f"compared {programs} programs, {queries} queries in {elapsed:.1f}s; coverage {coverage}")
