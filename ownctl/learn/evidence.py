"""Examples of one action, evaluated exactly and vectorised for rule search.

An :class:`Evidence` holds the objects that carry a permission for one action (a frame whose
ownership is the *prior*: induction never sees inferred ownership) and the permission values
(1 forbid, 0 allow). The truth of any literal or conjunction is kept as a (W, n) boolean table over
the joint assignments of the ownership atoms, so the exact probability of a rule set is one
weighted sum, and many candidate rules are scored at once.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.logic.prob import atom_truth, enumerate_worlds, other_probability
from ownctl.logic.rules import ANY, Literal, Rule

MAX_NAMED_AGENTS = 10
#: (world, example) pairs of positive weight an Evidence enumerates at most: beyond, the agents least
#: likely to own the examples are folded into the atom "owned by someone else" (docs/learning.md)
MAX_PAIRS = 1 << 16
#: truth values weighted at once by :meth:`Evidence.pair_prob` (a block of rows bounds its memory)
PAIR_CELLS = 1 << 20


@dataclass(frozen=True)
class Vocabulary:
    """The atoms a learned rule may use: agents, colours, areas and categories the store knows."""

    agents: tuple[str, ...] = ()
    colors: tuple[str, ...] = ()
    areas: tuple[str, ...] = ()
    categories: tuple[str, ...] = ()

    def atoms(self) -> list[Literal]:
        """Positive literals in canonical order, ``any`` first for each predicate."""
        return list(_atoms(self))


@functools.lru_cache(maxsize=256)
def _atoms(vocab: Vocabulary) -> tuple[Literal, ...]:
    """:meth:`Vocabulary.atoms`, made once per vocabulary."""
    out: list[Literal] = []
    for pred, args in (
        ("ownedBy", vocab.agents),
        ("isColored", vocab.colors),
        ("inArea", vocab.areas),
        ("inCategory", vocab.categories),
    ):
        if args:
            out.append(Literal(pred, ANY))
            out.extend(Literal(pred, a) for a in sorted(set(args)))
    return tuple(out)


def pair_count(frame: Frame, named: Sequence[str]) -> int:
    """How many (world, example) pairs of positive weight the worlds of the ``named`` agents (and the
    atom "owned by someone else") have over ``frame``'s objects: 2 to the number of those atoms whose
    probability is strictly between 0 and 1, summed over the objects (exact ownership: one each)."""
    if not frame.n:
        return 0
    probs = np.array([*(frame.agent_column(a) for a in named), other_probability(frame, named)])
    uncertain = ((probs > 0) & (probs < 1)).sum(axis=0)
    return int(np.sum(np.exp2(uncertain)))


class Evidence:
    """The stored permissions of one action as a vectorised truth table.

    Ownership atoms are enumerated for the agents that may own an example, at most
    :data:`MAX_NAMED_AGENTS` of them and only as many as keep the pairs of positive weight within
    :data:`MAX_PAIRS`, the most likely owners first; the others are folded into "owned by someone
    else", which ``ownedBy any`` still counts and no learned rule can name (:attr:`folded`). Below
    those limits every probability is exact.
    """

    def __init__(self, frame: Frame, values: Sequence[float] | np.ndarray) -> None:
        self.frame = frame
        self.t = np.asarray(values, dtype=float).reshape(frame.n)
        mass = frame.own.sum(axis=0) if frame.n else np.zeros(len(frame.agents))
        named = [a for a, m in zip(frame.agents, mass, strict=True) if m > 0]
        ranked = [frame.agents[j] for j in np.argsort(-mass, kind="stable")[: len(named)]]  # likeliest first
        k = min(len(ranked), MAX_NAMED_AGENTS)
        while k > 0 and frame.n << (k + 1) > MAX_PAIRS and pair_count(frame, ranked[:k]) > MAX_PAIRS:
            k -= 1  # (n 2^(k+1) bounds the pairs: only a store with many examples counts them)
        #: whether some agent that may own an example was folded into "someone else"
        self.folded = k < len(named)
        if self.folded:
            named = sorted(ranked[:k])
        self.worlds = enumerate_worlds(frame, tuple(named), with_other=True)
        self._cache: dict[Literal, np.ndarray] = {}
        self._rules: dict[Rule, np.ndarray] = {}
        self._stacks: dict[tuple[Literal, ...], np.ndarray] = {}

    def content(self) -> tuple[object, ...]:
        """Everything the examples are made of, as a hashable value (equal values, equal evidence):
        the permission values and the frame's content (:meth:`Frame.content`), in the examples'
        order. Results computed from evidence are kept by it (:mod:`ownctl.learn.posterior`,
        :func:`ownctl.learn.induce.calibration_objectives`)."""
        return (self.t.tobytes(), *self.frame.content())

    def reordered(self, order: Sequence[int] | np.ndarray) -> Evidence:
        """The examples at the indices ``order`` (a permutation, or a subset), in that order, sharing
        the enumerated worlds."""
        idx = np.asarray(order, dtype=int)
        if len(idx) == self.n and np.array_equal(idx, np.arange(self.n)):
            return self  # the same examples in the same order (and its caches)
        out = object.__new__(Evidence)
        out.frame = self.frame.take(idx)
        out.t = self.t[idx]
        w = self.worlds
        out.worlds = type(w)(w.atoms, w.bits, w.weights[:, idx], w.probs[:, idx])
        out.folded = self.folded
        out._cache, out._rules, out._stacks = {}, {}, {}
        return out

    @property
    def n(self) -> int:
        """Number of examples."""
        return self.frame.n

    @property
    def positives(self) -> np.ndarray:
        """Bool mask of forbid examples (value >= 0.5)."""
        return self.t >= 0.5

    def literal(self, lit: Literal) -> np.ndarray:
        """(W, n) or broadcastable truth of a literal."""
        if lit not in self._cache:
            base = atom_truth(lit, self.frame, self.worlds)
            value = ~base if lit.negated else base
            self._cache[lit] = np.broadcast_to(value, (len(self.worlds.bits), self.n))
        return self._cache[lit]

    def literal_stack(self, lits: Sequence[Literal]) -> np.ndarray:
        """(L, W, n) truth of several literals (cached per literal list)."""
        key = tuple(lits)
        out = self._stacks.get(key)
        if out is None:
            shape = (len(key), len(self.worlds.bits), self.n)
            out = np.stack([self.literal(x) for x in key]) if key else np.zeros(shape, dtype=bool)
            self._stacks[key] = out
        return out

    def truth(self, rule: Rule) -> np.ndarray:
        """(W, n) truth of one conjunction (cached)."""
        out = self._rules.get(rule)
        if out is None:
            out = np.ones((len(self.worlds.bits), self.n), dtype=bool)
            for lit in rule.literals:
                out = out & self.literal(lit)
            self._rules[rule] = out
        return out

    def union(self, rules: Sequence[Rule]) -> np.ndarray:
        """(W, n) truth of a rule set (disjunction)."""
        out = np.zeros((len(self.worlds.bits), self.n), dtype=bool)
        for rule in rules:
            out |= self.truth(rule)
        return out

    @functools.cached_property
    def pairs(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The (world, example) pairs of positive weight, grouped by example: their world index,
        example index and weight, and where each example's pairs start. Truth kept over these pairs
        alone gives every probability exactly (the other pairs weigh nothing), and with exact
        ownership there is one pair per example however many agents there are."""
        ni, wi = np.nonzero(self.worlds.weights.T > 0)
        starts = np.flatnonzero(np.r_[True, ni[1:] != ni[:-1]]) if len(ni) else np.zeros(0, dtype=int)
        return wi, ni, self.worlds.weights[wi, ni], starts

    def pair_literals(self, lits: tuple[Literal, ...]) -> np.ndarray:
        """(literals, pairs) truth of each literal at each pair of :attr:`pairs`, the literals given
        as atom, negation, atom, negation... (made once per literal list)."""
        cache = self.__dict__.setdefault("_pair_rows", {})
        got = cache.get(lits)
        if got is None:
            got = cache[lits] = self._pair_table([atom_truth(lits[k], self.frame, self.worlds)
                                                  for k in range(0, len(lits), 2)])
        out: np.ndarray = got
        return out

    def _pair_table(self, atoms: Sequence[np.ndarray]) -> np.ndarray:
        """(2 len(atoms), pairs): each atom's truth at each pair of :attr:`pairs`, then its negation.
        Atoms of the objects alone ((1, n): percepts) are gathered together by example, atoms of the
        worlds alone ((W, 1): ownership) together by world, any other one by its own pairs."""
        wi, ni, _, _ = self.pairs
        width = len(self.worlds.bits)
        table = np.empty((2 * len(atoms), len(wi)), dtype=bool)
        crisp: list[int] = []
        owned: list[int] = []
        for k, atom in enumerate(atoms):
            if atom.shape == (1, self.n):
                crisp.append(k)
            elif atom.shape == (width, 1):
                owned.append(k)
            else:
                table[2 * k] = np.broadcast_to(atom, (width, self.n))[wi, ni]
        if crisp:
            table[2 * np.asarray(crisp)] = np.concatenate([atoms[k] for k in crisp])[:, ni]
        if owned:
            table[2 * np.asarray(owned)] = np.concatenate([atoms[k] for k in owned], axis=1)[wi].T
        table[1::2] = ~table[0::2]
        return table

    def pair_prob(self, truth: np.ndarray) -> np.ndarray:
        """Exact probability per example of a truth table over :attr:`pairs`, (..., P) -> (..., n)."""
        _, ni, weight, starts = self.pairs
        if not len(ni):
            return np.zeros((*truth.shape[:-1], self.n))
        # sums of weights are never negative: capping them at 1 is the clip to [0, 1]. Rows are taken
        # a block at a time, so the weighted copy stays small (many agents make many pairs)
        lead = truth.shape[:-1]
        flat = truth.reshape(-1, truth.shape[-1])
        out: np.ndarray = np.empty((len(flat), self.n))
        block = max(1, PAIR_CELLS // max(1, flat.shape[1]))
        for lo in range(0, len(flat), block):
            np.minimum(np.add.reduceat(flat[lo : lo + block] * weight, starts, axis=-1), 1.0,
                       out=out[lo : lo + block])
        return out.reshape(*lead, self.n)

    def prob(self, truth: np.ndarray) -> np.ndarray:
        """Exact probability per example of a truth table (..., W, n) -> (..., n)."""
        out: np.ndarray = np.minimum((truth * self.worlds.weights).sum(axis=-2), 1.0)  # sums are >= 0
        return out

    def q(self, rules: Sequence[Rule]) -> np.ndarray:
        """P(forbidden) per example under a rule set."""
        return self.prob(self.union(rules)) if rules else np.zeros(self.n)

    def beyond(self, allows: Sequence[Rule]) -> tuple[Evidence, np.ndarray]:
        """The examples on which no allow norm of ``allows`` surely holds, and their indices here.

        Where an allow norm surely holds, every rule set minus the allow norms says "allowed", so the
        example's likelihood is the same under every rule set: learning without it compares rule sets
        exactly as with it, and a permission that contradicts a stated allow norm (an exception,
        decided by the permission itself) is not generalised to other objects."""
        kept = np.flatnonzero(self.q(allows) < 1.0 - 1e-12) if allows and self.n else np.arange(self.n)
        return self.reordered(kept), kept

    def soft_accuracy(self, rules: Sequence[Rule]) -> float:
        """Mean agreement between each permission and the rules' probability (1 with no examples)."""
        if self.n == 0:
            return 1.0
        q = self.q(rules)
        return float(np.mean(np.minimum(self.t, q) + np.minimum(1 - self.t, 1 - q)))
