"""``world load FILE`` and ``world export``: TOML worlds and scenarios (``docs/architecture.md``).

Loading adds the file's agents (existing agents of the same name are reused), areas and objects
(duplicates are errors), turns interaction ages into absolute times (``now - age``), and stores the
ground truth (true owners, true norms) in its own tables. The first file with a ``name`` names the
store's world (setting ``world.name``); a later file adds to that world and does not rename it.
Export writes the same format back, the name included, ages measured at ``now``; ground truth
comes from the truth tables, never from beliefs.
"""

from __future__ import annotations

import tomllib
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ownctl.app.context import AppContext, Done, use_case
from ownctl.app.mindstore import Stored, spec_of
from ownctl.app.mindstore import load as load_mind
from ownctl.errors import BadValue, OwnctlError
from ownctl.humanize import plural
from ownctl.world.model import Area, World
from ownctl.world.spec import to_toml, world_from_dict, world_to_dict

if TYPE_CHECKING:
    from ownctl.store.repo import Tx

#: the setting that keeps the store's world's name (the ``name`` of the first world file loaded)
WORLD_NAME = "world.name"


def read_world(path: str, seed: int = 0) -> World:
    """Parse and validate a world/scenario file; ``seed`` feeds a ``[generator]`` section."""
    import numpy as np

    source = Path(path)
    try:
        text = source.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise OwnctlError(f"cannot read world file {path}: {getattr(exc, 'strerror', None) or exc}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise BadValue(f"{path}: not valid TOML: {exc}") from None
    return world_from_dict(data, str(path), np.random.default_rng(seed))


def store_world(tx: Any, world: World, now: float, skip_existing_areas: bool = False) -> Stored:
    """Add ``world``'s agents (reused when they exist), areas, objects and ground truth to the store.

    The objects join the Mind (every agent's predictions cover them) and are saved in bulk; the
    ground truth goes to its own tables. Returns the saved whole Mind.
    """
    stored = load_mind(tx, now)
    mind = stored.mind
    for name in world.agents:
        if name not in mind.agents:
            mind.add_agent(name)
    known_areas = {a.name for a in mind.areas}
    for area in world.areas:
        if not (skip_existing_areas and area.name in known_areas):
            mind.add_area(area)
    mind.add_objects([replace(s, last_touch={a: now - age for a, age in s.last_touch.items()})
                      for s in world.objects])
    stored.save(tx)
    ids, agents = stored.ids, stored.agent_ids
    truth = [(ids[s.name], agents[a], p)
             for s in world.objects for a, p in world.owners.get(s.name, {}).items()]
    tx.knowledge.set_truth(truth, world.norms)
    return stored


def keep_name(tx: Tx, name: str) -> None:
    """Keep ``name`` as the store's world's name, so that export writes it back; a store whose world
    is already named keeps its name, and an empty ``name`` names nothing."""
    if name and not tx.meta.settings().get(WORLD_NAME):
        tx.meta.set_setting(WORLD_NAME, name)


@use_case
def load(ctx: AppContext, path: str, seed: int = 0) -> Done:
    """Add the world in ``path`` to the store, in one transaction."""
    world = read_world(path, seed)
    payload = {"op": "world.load", "file": str(path), "world": world.name, "seed": seed}
    with ctx.write(payload) as tx:
        ctx.remember(tx, store_world(tx, world, ctx.now))
        keep_name(tx, world.name)
    counts = {"agents": len(world.agents), "areas": len(world.areas), "objects": len(world.objects)}
    listing = ", ".join(plural(n, k.removesuffix("s")) for k, n in counts.items())
    return Done(
        f"loaded {world.name or path}: {listing}, {plural(len(world.norms), 'true norm')}",
        {"world": world.name, **counts, "norms": len(world.norms)},
    )


def current_world(ctx: AppContext, name: str | None = None) -> World:
    """The store's world with its ground truth, interaction ages measured at ``ctx.now``; named
    ``name``, else the name it was loaded with ("" when none)."""
    with ctx.read() as tx:
        if name is None:
            name = str(tx.meta.settings().get(WORLD_NAME) or "")
        agents = {a.id: a.name for a in tx.world.agents()}
        categories = tx.things.categories()
        touched = tx.touches.times()
        rows = tx.things.objects()
        specs = [spec_of(o, categories.get(o.id, set()), touched.get(o.id, {})) for o in rows]
        objects = tuple(replace(s, last_touch={a: max(0.0, ctx.now - t) for a, t in s.last_touch.items()})
                        for s in specs)
        names = {o.id: o.name for o in rows}
        owners: dict[str, dict[str, float]] = {}
        for (oid, aid), p in tx.knowledge.truth_owners().items():
            owners.setdefault(names[oid], {})[agents[aid]] = p
        return World(
            name=name,
            agents=tuple(agents[i] for i in sorted(agents, key=lambda i: agents[i])),
            objects=objects,
            areas=tuple(Area(a.name, (a.x0, a.y0, a.x1, a.y1)) for a in tx.world.areas()),
            norms=tuple(tx.knowledge.truth_norms()),
            owners=owners,
        )


def export(ctx: AppContext, name: str | None = None) -> dict[str, Any]:
    """The store's world as a world-file dict (see :func:`export_toml` for the text), named ``name``,
    else the name it was loaded with."""
    return world_to_dict(current_world(ctx, name))


def export_toml(data: dict[str, Any]) -> str:
    """TOML text of an :func:`export` result."""
    return to_toml(data)


def write_text(path: str | Path, text: str) -> None:
    """Write an exported world to ``path``; an unwritable path is a user error, not a traceback."""
    try:
        Path(path).write_text(text, encoding="utf-8")
    except OSError as exc:
        raise OwnctlError(f"cannot write {path}: {exc.strerror or exc}") from None
