"""Use cases about what the robot knows exists: agents, objects (with percepts) and areas.

Each mutating function is one transaction and one event-log entry that loads the Mind, calls it and
saves what changed (predictions and posteriors follow every change); each returns a :class:`Done`
(a human sentence plus JSON-ready data). Lists return JSON-ready dicts.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from ownctl.app.context import AppContext, Done, use_case
from ownctl.app.mindstore import changing, refit_focus, refitting
from ownctl.errors import BadValue
from ownctl.humanize import iso
from ownctl.logic.names import check_name
from ownctl.mind import KEEP
from ownctl.world.model import Area, ObjectSpec

NONE = "none"  # as a percept value: clear it


def parse_numbers(what: str, text: str, sizes: Sequence[int]) -> tuple[float, ...]:
    """``"0.1,0.2,0"`` -> floats; BadValue unless it has one of ``sizes`` finite numbers."""
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) not in sizes or not all(math.isfinite(v) for v in values):
        counts = " or ".join(map(str, sizes))
        raise BadValue(f"{what} must be {counts} comma-separated finite numbers, got {text!r}")
    return values


def finite(what: str, value: float) -> float:
    """``value`` if finite; BadValue otherwise."""
    if not math.isfinite(value):
        raise BadValue(f"{what} must be a finite number, got {value!r}")
    return value


# -- agents -------------------------------------------------------------------------------------
@use_case
def add_agent(ctx: AppContext, name: str) -> Done:
    """Introduce an agent (a possible owner)."""
    name = check_name("agent", name)
    with changing(ctx, {"op": "agent.add", "agent": name}) as (_, mind):
        mind.add_agent(name)  # the new agent's calibrated prior enters every belief
    return Done(f"added agent {name}", {"agent": name})


def list_agents(ctx: AppContext) -> list[dict[str, Any]]:
    """Every agent with how many objects it has touched."""
    with ctx.read() as tx:
        touched = tx.touches.counts()
        return [{"name": a.name, "touched": touched.get(a.id, 0)} for a in tx.world.agents()]


def _remove_named(ctx: AppContext, kind: str, name: str) -> Done:
    """Forget an agent, area or object; an agent or area is refused while a rule names it.

    Beliefs and permissions about it go with it, and predictions and posteriors follow the change.
    """
    with changing(ctx, {"op": f"{kind}.remove", kind: name}) as (tx, mind):
        lookup = {"agent": tx.world.agent, "area": tx.world.area, "object": tx.things.object}[kind]
        lookup(name)  # an unknown name is an error listing the known ones
        {"agent": mind.remove_agent, "area": mind.remove_area, "object": mind.remove_object}[kind](name)
    return Done(f"removed {kind} {name}", {kind: name})


@use_case
def remove_agent(ctx: AppContext, name: str) -> Done:
    """Forget an agent and its beliefs; refused while a rule names it."""
    return _remove_named(ctx, "agent", name)


# -- objects ------------------------------------------------------------------------------------
def _percepts(color: str | None, pos: str | None) -> dict[str, Any]:
    out: dict[str, Any] = {}
    if color is not None:
        out["color"] = None if color == NONE else check_name("colour", color)
    if pos is not None:
        if pos == NONE:
            out.update(x=None, y=None, z=None)
        else:
            xyz = parse_numbers("--pos", pos, (2, 3))
            out.update(x=xyz[0], y=xyz[1], z=xyz[2] if len(xyz) == 3 else 0.0)
    return out


def _categories(categories: Sequence[str]) -> list[str]:
    if list(categories) == [NONE]:
        return []
    return sorted({check_name("category", c) for c in categories})


@use_case
def add_object(
    ctx: AppContext,
    name: str,
    color: str | None = None,
    pos: str | None = None,
    categories: Sequence[str] = (),
) -> Done:
    """Add an object with its percepts (``pos`` as "x,y[,z]")."""
    name = check_name("object", name)
    percepts = _percepts(color, pos)
    cats = _categories(categories)
    position = None if percepts.get("x") is None else (percepts["x"], percepts["y"], percepts["z"])
    with changing(ctx, {"op": "object.add", "object": name, **percepts, "categories": cats}) as (_, mind):
        mind.add_objects([ObjectSpec(name, percepts.get("color"), position, frozenset(cats))])
    return Done(f"added object {name}", {"object": name})


@use_case
def set_object(
    ctx: AppContext,
    name: str,
    color: str | None = None,
    pos: str | None = None,
    categories: Sequence[str] = (),
) -> Done:
    """Change the given percepts of an object ("none" clears one)."""
    percepts = _percepts(color, pos)
    cats = _categories(categories) if categories else None
    if not percepts and cats is None:
        raise BadValue("nothing to set; give --color, --pos or --category")
    with changing(ctx, {"op": "object.set", "object": name, **percepts, "categories": cats}) as (tx, mind):
        tx.things.object(name)
        position: Any = KEEP
        if "x" in percepts:
            position = None if percepts["x"] is None else (percepts["x"], percepts["y"], percepts["z"])
        mind.set_percepts(name, color=percepts.get("color", KEEP), position=position,
                          categories=KEEP if cats is None else cats)
    changed = sorted({"x": "position", "y": "position", "z": "position"}.get(k, k) for k in percepts)
    if cats is not None:
        changed.append("categories")
    return Done(f"updated object {name}", {"object": name, "changed": sorted(set(changed))})


@use_case
def remove_object(ctx: AppContext, name: str) -> Done:
    """Forget an object with its beliefs and permissions."""
    return _remove_named(ctx, "object", name)


def _object_dict(row: Any, categories: set[str], touches: dict[str, float]) -> dict[str, Any]:
    position = None if row.x is None else [row.x, row.y, row.z]
    return {
        "name": row.name,
        "color": row.color,
        "position": position,
        "categories": sorted(categories),
        "last_touch": touches,
    }


def list_objects(ctx: AppContext) -> list[dict[str, Any]]:
    """Every object with its percepts; ``last_touch`` maps agents to absolute store times."""
    with ctx.read() as tx:
        cats = tx.things.categories()
        touched = tx.touches.times()
        return [_object_dict(o, cats.get(o.id, set()), touched.get(o.id, {})) for o in tx.things.objects()]


def show_object(ctx: AppContext, name: str) -> dict[str, Any]:
    """One object: percepts, permissions and resolved ownership beliefs."""
    from ownctl.app.query import owner_rows

    with ctx.read() as tx:
        row = tx.things.object(name)
        touches = tx.touches.times([row.id]).get(row.id, {})
        out = _object_dict(row, tx.things.categories([row.id]).get(row.id, set()), touches)
        out["permissions"] = [
            {"id": p.id, "action": p.action, "value": p.value} for p in tx.knowledge.permissions(row.id)
        ]
        out["owners"] = owner_rows(tx, row.id)
    return out


@use_case
def touch(ctx: AppContext, obj: str, agent: str, at: float | None = None) -> Done:
    """Record that ``agent`` interacted with ``obj`` at absolute store time ``at`` (default now)."""
    time = ctx.now if at is None else finite("--at", at)
    with ctx.read() as tx:
        tx.things.object(obj), tx.world.agent(agent)  # unknown names are errors listing the known ones
        focus = refit_focus(tx, obj, [agent])
    payload = {"op": "object.touch", "object": obj, "agent": agent, "time": time}
    # recency is a percept of prediction
    refitting(ctx, payload, lambda _, mind: mind.touch(obj, agent, time), agents=focus)
    return Done(f"{agent} touched {obj} at {iso(time)}", {"object": obj, "agent": agent, "time": time})


# -- areas --------------------------------------------------------------------------------------
@use_case
def add_area(ctx: AppContext, name: str, box: str) -> Done:
    """Add a box area ``"x0,y0,x1,y1"`` on the table plane."""
    name = check_name("area", name)
    x0, y0, x1, y1 = parse_numbers("--box", box, (4,))
    if x0 > x1 or y0 > y1:
        raise BadValue(f"--box must be x0,y0,x1,y1 with x0 <= x1 and y0 <= y1, got {box!r}")
    with changing(ctx, {"op": "area.add", "area": name, "box": [x0, y0, x1, y1]}) as (_, mind):
        mind.add_area(Area(name, (x0, y0, x1, y1)))
    return Done(f"added area {name}", {"area": name, "box": [x0, y0, x1, y1]})


def list_areas(ctx: AppContext) -> list[dict[str, Any]]:
    """Every area with its box."""
    with ctx.read() as tx:
        return [{"name": a.name, "box": [a.x0, a.y0, a.x1, a.y1]} for a in tx.world.areas()]


@use_case
def remove_area(ctx: AppContext, name: str) -> Done:
    """Forget an area; refused while a rule names it."""
    return _remove_named(ctx, "area", name)
