"""Round trips of the norm language: canonical printing parses back to an equal norm
(architecture section 2)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ownctl.logic.rules import Literal, Norm, Rule, parse_norm, parse_rule
from ownctl.logic.vocab import ACTIONS

VOCAB_ORDER = ("ownedBy", "isColored", "inArea", "inCategory")  # architecture section 2, written out here
ARGS = {
    "ownedBy": ("any", "alexis", "xuan", "agent1", "agent2", "Bob-1", "a_b"),
    "isColored": ("any", "red", "blue", "Green", "dark-red"),
    "inArea": ("any", "home", "trash", "desk_xuan", "a1"),
    "inCategory": ("any", "cup", "tool", "paper_x"),
}

atoms = st.sampled_from(VOCAB_ORDER).flatmap(lambda p: st.tuples(st.just(p), st.sampled_from(ARGS[p])))
# A dict atom -> negated has no contradictory pair by construction.
literal_sets = st.dictionaries(atoms, st.booleans(), max_size=5).map(
    lambda d: [Literal(pred, arg, neg) for (pred, arg), neg in d.items()]
)
actions = st.sampled_from(tuple(ACTIONS))
signs = st.sampled_from(("forbid", "allow"))
SPACE = st.sampled_from((" ", "  ", "\t", "\n", " \t ", "\r\n", "   "))
RT = settings(max_examples=300, derandomize=True, deadline=None)


def spec_key(lit: Literal) -> tuple[int, int, str, bool]:
    return (VOCAB_ORDER.index(lit.pred), lit.arg != "any", lit.arg, lit.negated)


def raw_text(sign: str, action: str, lits: list[Literal], sep: list[str] | None = None) -> str:
    """Norm text with the literals in the given (non-canonical) order."""
    words = [sign, action]
    if lits:
        words.append("if")
        for k, lit in enumerate(lits):
            if k:
                words.append("and")
            if lit.negated:
                words.append("not")
            words += [lit.pred, lit.arg]
    if sep is None:
        return " ".join(words)
    out = sep[0]
    for k, w in enumerate(words):
        out += w + sep[(k + 1) % len(sep)]
    return out


@RT
@given(signs, actions, literal_sets)
def test_printed_norm_parses_back_equal(sign: str, action: str, lits: list[Literal]) -> None:
    norm = Norm(sign, Rule(action, tuple(lits)))
    text = norm.text()
    assert parse_norm(text) == norm
    assert parse_norm(text).text() == text
    assert set(norm.rule.literals) == set(lits)
    if sign == "forbid":
        assert parse_rule(text) == norm.rule
        assert str(norm.rule) == text


@pytest.mark.slow
@RT
@given(signs, actions, literal_sets)
def test_printed_form_is_in_documented_order(sign: str, action: str, lits: list[Literal]) -> None:
    text = Norm(sign, Rule(action, tuple(lits))).text()
    head = f"{sign} {action}"
    if not lits:
        assert text == head
        return
    assert text.startswith(head + " if ")
    parts = text[len(head) + 4:].split(" and ")
    assert len(parts) == len(lits)
    printed = []
    for part in parts:
        w = part.split(" ")
        neg = w[0] == "not"
        assert len(w) == (3 if neg else 2), part
        printed.append(Literal(w[-2], w[-1], neg))
    assert set(printed) == set(lits)
    keys = [spec_key(lit) for lit in printed]
    assert keys == sorted(keys) and len(set(keys)) == len(keys)


@pytest.mark.slow
@RT
@given(signs, actions, literal_sets, st.randoms(use_true_random=False), st.integers(0, 3))
def test_text_is_invariant_under_permutation_and_duplication(sign, action, lits, rnd, dups) -> None:
    canonical = Norm(sign, Rule(action, tuple(lits))).text()
    shuffled = list(lits) + [rnd.choice(lits) for _ in range(dups if lits else 0)]
    rnd.shuffle(shuffled)
    assert Norm(sign, Rule(action, tuple(shuffled))).text() == canonical
    assert Rule(action, tuple(shuffled)) == Rule(action, tuple(lits))
    # The same literals written in the shuffled order, with repeats, parse to the canonical norm.
    parsed = parse_norm(raw_text(sign, action, shuffled))
    assert parsed == Norm(sign, Rule(action, tuple(lits)))
    assert parsed.text() == canonical


@pytest.mark.slow
@RT
@given(signs, actions, literal_sets, st.lists(SPACE, min_size=1, max_size=6))
def test_extra_whitespace_parses_to_the_same_norm(sign, action, lits, sep) -> None:
    norm = Norm(sign, Rule(action, tuple(lits)))
    messy = raw_text(sign, action, lits, sep)
    assert parse_norm(messy) == norm
    assert parse_norm(messy).text() == norm.text()


def test_examples_from_the_design() -> None:
    rule = parse_rule("forbid pickUp if ownedBy xuan and not isColored red")
    assert rule == Rule("pickUp", (Literal("ownedBy", "xuan"), Literal("isColored", "red", True)))
    assert rule.text() == "forbid pickUp if ownedBy xuan and not isColored red"
    assert parse_rule("forbid trash").literals == ()
    assert parse_rule("forbid trash").text() == "forbid trash"
    # Canonical order: vocabulary order, then 'any' first, then argument, positive before negation.
    messy = ("forbid trash if inCategory cup and not isColored red and ownedBy xuan and "
             "isColored blue and ownedBy any and not inArea home and ownedBy alexis")
    assert parse_rule(messy).text() == (
        "forbid trash if ownedBy any and ownedBy alexis and ownedBy xuan and isColored blue and "
        "not isColored red and not inArea home and inCategory cup"
    )
    allow = parse_norm("  allow\tcollect   if\n not  ownedBy agent2 ")
    assert allow == Norm("allow", Rule("collect", (Literal("ownedBy", "agent2", True),)))
    assert allow.text() == "allow collect if not ownedBy agent2"


def test_positive_literal_prints_before_its_negation() -> None:
    # Contradictory rules are rejected by the parser, but a Rule built in code still prints canonically.
    rule = Rule("trash", (Literal("isColored", "red", True), Literal("isColored", "red")))
    assert rule.text() == "forbid trash if isColored red and not isColored red"
    assert rule.is_contradictory()
