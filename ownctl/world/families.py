"""Norm families: random true norm sets over the blocks world's vocabulary, one per seed.

A :class:`NormFamily` is what a new user might write for a household robot in the paper's blocks
world (three agents, four colours, the home and trash areas): for each of the actions ``trash``,
``pickUp`` and ``collect``, 0 to 3 forbid rules of 1 to 3 literals (negated literals, ``ownedBy
any``, owner-specific and colour rules, disjunctions of several rules for one action), together
with how its worlds are laid out. Calling a family with a random generator draws one world of it.

Laws (tested in ``tests/experiment/test_families.py``):

* ``norm_family(seed)`` is a pure function of the seed.
* Features are forced on a cycle of five seeds (:data:`SCHEDULE`), so among any ``N`` consecutive
  seeds each feature of :data:`FEATURES` occurs in at least ``N // 5`` families (random draws add
  more): a disjunction, a rare norm, an action with no norm, a negated literal, ``ownedBy any``, an
  owner-specific rule, a colour rule, a conjunction, and a layout whose home area holds one agent's
  objects instead of the unowned ones (so a position cannot stand in for "unowned").
* A *rare* action has one rule, and every world the family draws has one or two objects that rule
  forbids (worlds are redrawn until that holds).
* Every other rule forbids on average between :data:`MIN_COVER` and :data:`MAX_COVER` of the 20
  objects of a sample of the family's worlds, and each rule of a disjunction forbids on average at
  least :data:`MIN_GAIN` objects the action's other rules do not.

Seeds :data:`EVALUATION_SEEDS` are reserved for evaluation: the learner is tuned on other seeds only.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.errors import BadValue
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import ANY, Literal, Rule
from ownctl.world.generator import PAPER_AGENTS, PAPER_COLORS, paper_blocks_world
from ownctl.world.model import World, make_frame

#: Family seeds reserved for evaluation (chosen before any tuning on other seeds).
EVALUATION_SEEDS = range(1000, 1100)
#: The actions every family gives permissions for and scores, whether or not they have a norm.
FAMILY_ACTIONS = ("trash", "pickUp", "collect")
FEATURES = ("disjunction", "rare", "no_norm", "negated", "any", "owner", "colour", "conjunction",
            "owned_home")
#: Features forced by ``seed % 5``.
SCHEDULE = (
    frozenset({"disjunction", "any"}),
    frozenset({"rare", "owner"}),
    frozenset({"no_norm", "colour"}),
    frozenset({"negated", "conjunction"}),
    frozenset({"owned_home"}),
)
N_OBJECTS = 20
SAMPLE_WORLDS = 24  # worlds drawn once per family to measure what its rules forbid
MIN_COVER, MAX_COVER = 2.0, 16.0  # mean objects a (non-rare) rule forbids in a world of 20
MAX_ACTION_COVER = 17.0  # an action's rules together leave some objects allowed
MIN_GAIN = 1.0  # mean objects each rule of a disjunction adds to the others
RARE_SHARE = 0.3  # a rare rule forbids one or two objects in at least this share of sample worlds
RULE_COUNTS = (0.1, 0.45, 0.3, 0.15)  # P(0, 1, 2, 3 rules) for an action
RULE_LENGTHS = (0.4, 0.4, 0.2)  # P(1, 2, 3 literals)
NEGATION = 0.35
MAX_WORLD_DRAWS = 500
MAX_FAMILY_DRAWS = 200
MAX_RULE_DRAWS = 60  # attempts at one action's rules before the whole family is redrawn
_STREAM = 0x6E6F726D  # keeps family seeds apart from trial seeds


def _atoms() -> tuple[Literal, ...]:
    """The atoms true norms are made of: the blocks world's owners, colours and the home and trash
    areas (``workspace`` holds nearly every object and ``block`` every object, so neither says
    anything a norm could use)."""
    owners = [Literal("ownedBy", a) for a in (ANY, *PAPER_AGENTS)]
    colours = [Literal("isColored", c) for c in PAPER_COLORS]
    areas = [Literal("inArea", a) for a in ("home", "trash")]
    return (*owners, *colours, *areas)


ATOMS = _atoms()


@dataclass(frozen=True)
class NormFamily:
    """A true norm set with the layout of its worlds; ``family(rng)`` draws one world.

    ``norms`` are canonical rule texts; ``actions`` are the actions given permissions and scored
    (some may have no norm); ``home_agent`` is the agent whose objects sit in the home area (None:
    the unowned objects do, as in the paper); ``rare`` lists the actions whose one rule forbids
    only one or two objects of every world. Picklable, so trials can run in worker processes.
    """

    seed: int
    norms: tuple[str, ...]
    actions: tuple[str, ...] = FAMILY_ACTIONS
    home_agent: str | None = None
    rare: tuple[str, ...] = ()
    agents: tuple[str, ...] = PAPER_AGENTS
    n_objects: int = N_OBJECTS

    @property
    def name(self) -> str:
        """``family SEED``."""
        return f"family {self.seed}"

    def rules(self) -> dict[str, tuple[Rule, ...]]:
        """The true rules of every scored action (an empty tuple for an action with no norm)."""
        from ownctl.logic.rules import parse_rule

        parsed = [parse_rule(t) for t in self.norms]
        return {a: tuple(r for r in parsed if r.action == a) for a in self.actions}

    def features(self) -> frozenset[str]:
        """The features of :data:`FEATURES` this family has."""
        rules = self.rules()
        lits = [lit for rs in rules.values() for r in rs for lit in r.literals]
        found = {
            "disjunction": any(len(rs) >= 2 for rs in rules.values()),
            "rare": bool(self.rare),
            "no_norm": any(not rs for rs in rules.values()),
            "negated": any(lit.negated for lit in lits),
            "any": any(lit.pred == "ownedBy" and lit.arg == ANY for lit in lits),
            "owner": any(lit.pred == "ownedBy" and lit.arg != ANY and not lit.negated for lit in lits),
            "colour": any(lit.pred == "isColored" for lit in lits),
            "conjunction": any(len(r.literals) >= 2 for rs in rules.values() for r in rs),
            "owned_home": self.home_agent is not None,
        }
        return frozenset(f for f in FEATURES if found[f])

    def _layout(self, rng: np.random.Generator) -> World:
        home = 0 if self.home_agent is None else self.agents.index(self.home_agent) + 1
        world = paper_blocks_world(rng, self.n_objects, self.agents, self.norms, home_cluster=home)
        return World(self.name, world.agents, world.objects, world.areas, world.norms, world.owners)

    def __call__(self, rng: np.random.Generator) -> World:
        """One world of the family, redrawn until each rare action forbids one or two objects."""
        rules = self.rules()
        for _ in range(MAX_WORLD_DRAWS):
            world = self._layout(rng)
            if all(1 <= forbidden_count(rules[a], world) <= 2 for a in self.rare):
                return world
        raise BadValue(f"{self.name}: no world in {MAX_WORLD_DRAWS} draws has one or two objects "
                       f"forbidden by the rare norms of {', '.join(self.rare)}")


def forbidden_count(rules: Sequence[Rule], world: World) -> int:
    """How many objects of ``world`` the rules forbid under its true owners."""
    frame = make_frame(world.objects, world.areas, world.agents, world.true_ownership())
    return int((p_forbidden(rules, frame) >= 0.5).sum())


class _Sampler:
    """Draws rules and measures, on a fixed sample of the family's worlds, what they forbid."""

    def __init__(self, rng: np.random.Generator, family: NormFamily) -> None:
        self.rng = rng
        self.frames = []
        for _ in range(SAMPLE_WORLDS):
            w = family._layout(rng)
            self.frames.append(make_frame(w.objects, w.areas, w.agents, w.true_ownership()))

    def masks(self, rules: Sequence[Rule]) -> np.ndarray:
        """(worlds, objects) bool: which objects the rules forbid in each sample world."""
        return np.array([p_forbidden(rules, f) >= 0.5 for f in self.frames])

    def rule(self, must: str | None = None) -> Rule | None:
        """A random satisfiable rule without implied literals; with ``must``, one having that
        feature (``negated``, ``any``, ``owner``, ``colour`` or ``conjunction``); None if the draw
        did not give one."""
        rng = self.rng
        length = 1 + int(rng.choice(len(RULE_LENGTHS), p=RULE_LENGTHS))
        if must == "conjunction":
            length = max(length, 2)
        pick = [ATOMS[int(i)] for i in rng.choice(len(ATOMS), size=length, replace=False)]
        lits = [lit.negate() if rng.random() < NEGATION else lit for lit in pick]
        if must == "any":
            lits[0] = Literal("ownedBy", ANY, bool(rng.random() < NEGATION))
        elif must == "owner":
            lits[0] = Literal("ownedBy", PAPER_AGENTS[int(rng.integers(len(PAPER_AGENTS)))])
        elif must == "colour":
            lits[0] = Literal("isColored", PAPER_COLORS[int(rng.integers(len(PAPER_COLORS)))],
                              bool(rng.random() < NEGATION))
        elif must == "negated":
            lits[0] = lits[0] if lits[0].negated else lits[0].negate()
        rule = Rule("trash", tuple(lits))
        if len(rule.literals) != length or not rule.is_satisfiable() or rule.simplified() != rule:
            return None
        preds = [lit.pred for lit in rule.literals]
        if preds.count("ownedBy") > 1 or preds.count("inArea") > 1:
            return None  # owners and these areas are exclusive: a second literal would say nothing
        return rule


def _action_rules(s: _Sampler, action: str, count: int, rare: bool, must: Sequence[str]
                  ) -> tuple[Rule, ...] | None:
    """``count`` rules for ``action`` meeting the coverage laws (rare: one rule, one or two objects
    in many worlds); ``must`` features are given to the first rules; None if a draw failed."""
    rules: list[Rule] = []
    for k in range(count):
        want = must[k] if k < len(must) else None
        drawn = s.rule(want)
        if drawn is None:
            return None
        rule = Rule(action, drawn.literals)
        cover = s.masks([rule]).sum(axis=1)
        if rare:
            if np.mean((cover >= 1) & (cover <= 2)) < RARE_SHARE:
                return None
        elif not MIN_COVER <= cover.mean() <= MAX_COVER:
            return None
        if any(r.conditions <= rule.conditions or rule.conditions <= r.conditions for r in rules):
            return None
        rules.append(rule)
    if len(rules) >= 2:
        for r in rules:
            others = s.masks([x for x in rules if x != r])
            if (s.masks([r]) & ~others).sum(axis=1).mean() < MIN_GAIN:
                return None
        if s.masks(rules).sum(axis=1).mean() > MAX_ACTION_COVER:
            return None
    return tuple(rules)


def norm_family(seed: int) -> NormFamily:
    """The family of ``seed``: its features forced by :data:`SCHEDULE`, the rest drawn at random."""
    if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
        raise BadValue(f"a family seed is a non-negative integer, got {seed!r}")
    rng = np.random.default_rng([_STREAM, seed])
    forced = SCHEDULE[seed % len(SCHEDULE)]
    owned_home = "owned_home" in forced or rng.random() < 0.5
    home_agent = PAPER_AGENTS[int(rng.integers(len(PAPER_AGENTS)))] if owned_home else None
    sampler = _Sampler(rng, NormFamily(seed, (), home_agent=home_agent))
    literal_features = [f for f in ("any", "owner", "colour", "negated", "conjunction") if f in forced]
    for _ in range(MAX_FAMILY_DRAWS):
        counts = [int(rng.choice(len(RULE_COUNTS), p=RULE_COUNTS)) for _ in FAMILY_ACTIONS]
        order = [int(i) for i in rng.permutation(len(FAMILY_ACTIONS))]
        if "no_norm" in forced:
            counts[order[0]] = 0
        if "disjunction" in forced and max(counts) < 2:
            counts[order[1]] = 2 + int(rng.integers(2))
        if "rare" in forced:
            counts[order[2]] = 1
        if not any(counts):
            continue
        rare = {a for a, c in zip(FAMILY_ACTIONS, counts, strict=True)
                if c == 1 and ((a == FAMILY_ACTIONS[order[2]] and "rare" in forced) or rng.random() < 0.2)}
        must = list(literal_features)
        norms: list[str] = []
        for a, c in zip(FAMILY_ACTIONS, counts, strict=True):
            mine = must[:c]
            got = None
            for _ in range(MAX_RULE_DRAWS):
                got = _action_rules(sampler, a, c, a in rare, mine)
                if got is not None:
                    break
            if got is None:
                break
            must = must[len(mine):]
            norms += [r.text() for r in got]
        else:
            family = NormFamily(seed, tuple(norms), home_agent=home_agent, rare=tuple(sorted(rare)))
            if forced <= family.features():
                return family
    raise BadValue(f"no norm family with the features {sorted(forced)} found for seed {seed}")


MAX_FAMILIES = 10_000  # each is drawn (and checked for its features) before the first trial runs


def norm_families(count: int, first: int = EVALUATION_SEEDS.start) -> list[NormFamily]:
    """``count`` families of consecutive seeds from ``first`` (by default the evaluation range)."""
    if not 1 <= count <= MAX_FAMILIES:
        raise BadValue(f"--families must be an integer from 1 to {MAX_FAMILIES:,}, got {count}")
    return [norm_family(first + i) for i in range(count)]
