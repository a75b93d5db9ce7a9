"""Seeded worlds: the paper's blocks world (docs/architecture.md, section 8) and scattered worlds.

``k`` agents, each with an angular sector around the home area at the origin; one cluster of
objects per agent plus an unowned cluster at the origin; object ``i`` goes to cluster ``i mod (k+1)``.
Positions are uniform in radius within 0.3 m of the cluster centre; interaction ages are exponential
(mean 10 s for the owner, 1000 s for everyone else); colours are uniform over four names.
The paper's colourless blocks (its colour "none") are called ``grey`` here, because ``none`` is a
reserved word of the norm language.

A *scattered* world (``kind = "scattered"``) is the counter-case: objects uniform over the
workspace, owners uniform over the agents and nobody, colours uniform, so that no position or
colour says who owns what; every agent touched every object about as long ago
(``owner_age`` seconds on average for the owner, 1,000 for everyone else; by default the same), so
that by default no percept predicts ownership either. It tests whether prediction knows when the
percepts carry nothing (docs/architecture.md, section 5).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ownctl.errors import BadValue
from ownctl.world.model import Area, ObjectSpec, World

PAPER_AGENTS = ("agent1", "agent2", "agent3")
PAPER_COLORS = ("grey", "red", "green", "blue")
PAPER_NORMS = (
    "forbid trash if ownedBy any",
    "forbid pickUp if ownedBy agent2",
    "forbid collect if isColored red",
)
PAPER_AREAS = (
    Area("home", (-0.1, -0.1, 0.1, 0.1)),
    Area("trash", (-0.3, 0.6, 0.2, 1.1)),
    Area("workspace", (-1.0, -1.0, 1.0, 1.0)),
)
CLUSTER_RADIUS = 0.3
AVATAR_RANGE = (0.4, 0.8)
MEAN_AGE_OWNER = 10.0
SCATTER_X = (-0.9, 0.9)  # a scattered world's objects: anywhere on the table but the trash area
SCATTER_Y = (-0.9, 0.5)
MEAN_AGE_OTHER = 1000.0
GENERATOR_KEYS = ("kind", "objects", "prefix", "owner_age")
GENERATOR_KINDS = ("paper-blocks", "scattered")


def paper_blocks_world(
    rng: np.random.Generator,
    n_objects: int = 20,
    agents: tuple[str, ...] = PAPER_AGENTS,
    norms: tuple[str, ...] = PAPER_NORMS,
    prefix: str = "block",
    places: np.random.Generator | None = None,
    home_cluster: int = 0,
) -> World:
    """A fresh random blocks world with its ground truth (true owners and true norms).

    ``places`` draws where the agents sit (their sectors' cluster centres); by default ``rng`` does.
    A new layout of the same world draws new objects around the same places. ``home_cluster``
    names the cluster that sits in the home area: 0, the unowned objects (the paper's layout), or
    ``j`` in 1..k, agent ``j``'s objects, the unowned ones taking that agent's place (same draws).
    """
    k = len(agents)
    if k < 1 or n_objects < 0:
        raise BadValue(f"a blocks world needs at least one agent and a non-negative object count, got "
                       f"{k} agents and {n_objects} objects")
    centres = [np.zeros(2)]
    where = rng if places is None else places
    for i in range(k):
        radius = where.uniform(*AVATAR_RANGE)
        angle = where.uniform(i, i + 1) * 2 * np.pi / k
        centres.append(radius * np.array([np.cos(angle), np.sin(angle)]))
    if not 0 <= home_cluster <= k:
        raise BadValue(f"home_cluster must be in [0, {k}] (0: the unowned objects), got {home_cluster}")
    centres[0], centres[home_cluster] = centres[home_cluster], centres[0]
    blocks = []
    for i in range(n_objects):
        cluster = i % (k + 1)
        r = rng.uniform(0.0, CLUSTER_RADIUS)
        theta = rng.uniform(0.0, 2 * np.pi)
        x, y = centres[cluster] + r * np.array([np.cos(theta), np.sin(theta)])
        color = PAPER_COLORS[int(rng.integers(len(PAPER_COLORS)))]
        owner = agents[cluster - 1] if cluster > 0 else None
        xy = (float(x), float(y))
        blocks.append(_block(rng, f"{prefix}{i + 1}", xy, color, owner, agents, MEAN_AGE_OWNER))
    return _world("paper blocks world", agents, norms, blocks)


def _block(rng: np.random.Generator, name: str, xy: tuple[float, float], color: str, owner: str | None,
           agents: tuple[str, ...], owner_age: float) -> tuple[ObjectSpec, dict[str, float]]:
    """One block and its true owners: every agent last touched it an exponential time ago, of mean
    ``owner_age`` seconds for its owner and ``MEAN_AGE_OTHER`` for everyone else (one draw per
    agent, in agent order: exponential(scale) is scale * standard_exponential())."""
    scales = np.where(np.array(agents, dtype=object) == owner, owner_age, MEAN_AGE_OTHER)
    ages = dict(zip(agents, (scales * rng.standard_exponential(len(agents))).tolist(), strict=True))
    return ObjectSpec(name, color, (*xy, 0.0), frozenset({"block"}), ages), ({owner: 1.0} if owner else {})


def _world(name: str, agents: tuple[str, ...], norms: tuple[str, ...],
           blocks: list[tuple[ObjectSpec, dict[str, float]]]) -> World:
    """The world of ``blocks`` (each with its true owners) on the paper's areas."""
    owners = {spec.name: own for spec, own in blocks}
    return World(name, tuple(agents), tuple(spec for spec, _ in blocks), PAPER_AREAS, tuple(norms), owners)


def scattered_world(
    rng: np.random.Generator,
    n_objects: int = 20,
    agents: tuple[str, ...] = PAPER_AGENTS,
    norms: tuple[str, ...] = PAPER_NORMS,
    prefix: str = "block",
    owner_age: float = MEAN_AGE_OTHER,
) -> World:
    """A world whose ownership no position or colour predicts, with its ground truth.

    Each object lies uniformly in the workspace away from the trash area, has a uniform colour and
    a uniform owner among the agents and nobody; each agent last touched it an exponential time
    ago, of mean ``owner_age`` seconds for its owner and ``MEAN_AGE_OTHER`` for everyone else."""
    if not agents or n_objects < 0:
        raise BadValue(f"a scattered world needs at least one agent and a non-negative object count, "
                       f"got {len(agents)} agents and {n_objects} objects")
    blocks = []
    for i in range(n_objects):
        x, y = rng.uniform(*SCATTER_X), rng.uniform(*SCATTER_Y)
        color = PAPER_COLORS[int(rng.integers(len(PAPER_COLORS)))]
        pick = int(rng.integers(len(agents) + 1))
        owner = agents[pick] if pick < len(agents) else None
        blocks.append(_block(rng, f"{prefix}{i + 1}", (float(x), float(y)), color, owner, agents, owner_age))
    return _world("scattered world", agents, norms, blocks)


def generate(spec: Mapping[str, Any], rng: np.random.Generator, agents: tuple[str, ...] = ()) -> World:
    """A world from a TOML ``[generator]`` table: ``kind`` (``paper-blocks`` or ``scattered``),
    ``objects = N``, ``prefix``, and for a scattered world ``owner_age`` (seconds)."""
    unknown = sorted(set(spec) - set(GENERATOR_KEYS))
    if unknown:
        raise BadValue(f"unknown generator key {unknown[0]!r}; valid keys: {', '.join(GENERATOR_KEYS)}")
    kind = spec.get("kind", "paper-blocks")
    if kind not in GENERATOR_KINDS:
        raise BadValue(f"unknown generator kind {kind!r}; valid kinds: {', '.join(GENERATOR_KINDS)}")
    n = spec.get("objects", 20)
    if not isinstance(n, int) or isinstance(n, bool) or not 0 <= n <= 100_000:
        raise BadValue(f"generator objects must be an integer in [0, 100000], got {n!r}")
    who = tuple(agents) or PAPER_AGENTS
    prefix = str(spec.get("prefix", "block"))
    if kind == "paper-blocks":
        if "owner_age" in spec:
            raise BadValue("generator key 'owner_age' is for kind 'scattered'; paper-blocks owners "
                           f"touched their blocks {MEAN_AGE_OWNER:g} s ago on average")
        return paper_blocks_world(rng, n, who, prefix=prefix)
    age = spec.get("owner_age", MEAN_AGE_OTHER)
    if isinstance(age, bool) or not isinstance(age, int | float) or not 0 < age <= 1e6:
        raise BadValue(f"generator owner_age must be a number of seconds in (0, 1000000], got {age!r}")
    return scattered_world(rng, n, who, prefix=prefix, owner_age=float(age))
