"""Use cases about what the robot knows exists: agents, objects (with percepts) and areas.

Each mutating function is one transaction and one event-log entry; each returns a :class:`Done`
(a human sentence plus JSON-ready data). Lists return JSON-ready dicts.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from ownctl.app.beliefs import after_claims
from ownctl.app.context import AppContext, Done
from ownctl.app.learning import reinfer, repredict
from ownctl.errors import BadValue, OwnctlError
from ownctl.humanize import iso
from ownctl.logic.names import check_name
from ownctl.logic.rules import parse_rule

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
def add_agent(ctx: AppContext, name: str) -> Done:
    """Introduce an agent (a possible owner)."""
    check_name("agent", name)
    with ctx.write({"op": "agent.add", "agent": name}) as tx:
        tx.add_agent(name, ctx.now)
        after_claims(tx, [name], ctx.now)  # the new agent's calibrated prior enters every belief
    return Done(f"added agent {name}", {"agent": name})


def list_agents(ctx: AppContext) -> list[dict[str, Any]]:
    """Every agent with how many objects it has touched."""
    with ctx.read() as tx:
        touched: dict[int, int] = {}
        for _, aid in tx.touches():
            touched[aid] = touched.get(aid, 0) + 1
        return [{"name": a.name, "touched": touched.get(a.id, 0)} for a in tx.agents()]


def _named_by_rules(tx: Any, pred: str, name: str) -> list[int]:
    return [r.id for r in tx.rules() if any(lit.atom == (pred, name) for lit in parse_rule(r.text).literals)]


def _remove_named(ctx: AppContext, kind: str, name: str, pred: str | None) -> Done:
    """Forget an agent, area or object; an agent or area is refused while a rule names it.

    Beliefs and permissions about it go with it (cascades), and posteriors follow the change.
    """
    with ctx.write({"op": f"{kind}.remove", kind: name}) as tx:
        row = {"agent": tx.agent, "area": tx.area, "object": tx.object}[kind](name)
        users = _named_by_rules(tx, pred, name) if pred else []
        if users:
            raise OwnctlError(
                f"{kind} {name!r} is named by rules {users}; remove them first (ownctl rules remove ID)"
            )
        tx.remove(row)
        reinfer(tx, ctx.now)
    return Done(f"removed {kind} {name}", {kind: name})


def remove_agent(ctx: AppContext, name: str) -> Done:
    """Forget an agent and its beliefs; refused while a rule names it."""
    return _remove_named(ctx, "agent", name, "ownedBy")


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


def add_object(
    ctx: AppContext,
    name: str,
    color: str | None = None,
    pos: str | None = None,
    categories: Sequence[str] = (),
) -> Done:
    """Add an object with its percepts (``pos`` as "x,y[,z]")."""
    check_name("object", name)
    percepts = _percepts(color, pos)
    cats = _categories(categories)
    with ctx.write({"op": "object.add", "object": name, **percepts, "categories": cats}) as tx:
        row = tx.add_object(name, ctx.now, **percepts)
        tx.set_categories(row.id, cats)
        repredict(tx, None, ctx.now, [row.id])  # its priors, from every agent's predictor
    return Done(f"added object {name}", {"object": name})


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
    with ctx.write({"op": "object.set", "object": name, **percepts, "categories": cats}) as tx:
        row = tx.object(name)
        for key, value in percepts.items():
            setattr(row, key, value)
        if cats is not None:
            tx.set_categories(row.id, cats)
        tx.flush()
        after_claims(tx, [a.name for a in tx.agents()], ctx.now)  # percepts feed prediction and rules
    changed = sorted({"x": "position", "y": "position", "z": "position"}.get(k, k) for k in percepts)
    if cats is not None:
        changed.append("categories")
    return Done(f"updated object {name}", {"object": name, "changed": sorted(set(changed))})


def remove_object(ctx: AppContext, name: str) -> Done:
    """Forget an object with its beliefs and permissions."""
    return _remove_named(ctx, "object", name, None)


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
        cats = tx.categories()
        touched = tx.touch_times()
        return [_object_dict(o, cats.get(o.id, set()), touched.get(o.id, {})) for o in tx.objects()]


def show_object(ctx: AppContext, name: str) -> dict[str, Any]:
    """One object: percepts, permissions and resolved ownership beliefs."""
    from ownctl.app.query import owner_rows

    with ctx.read() as tx:
        row = tx.object(name)
        touches = tx.touch_times([row.id]).get(row.id, {})
        out = _object_dict(row, tx.categories([row.id]).get(row.id, set()), touches)
        out["permissions"] = [
            {"id": p.id, "action": p.action, "value": p.value} for p in tx.permissions(row.id)
        ]
        out["owners"] = owner_rows(tx, row.id)
    return out


def touch(ctx: AppContext, obj: str, agent: str, at: float | None = None) -> Done:
    """Record that ``agent`` interacted with ``obj`` at absolute store time ``at`` (default now)."""
    time = ctx.now if at is None else finite("--at", at)
    with ctx.write({"op": "object.touch", "object": obj, "agent": agent, "time": time}) as tx:
        row, who = tx.object(obj), tx.agent(agent)
        tx.touch(row.id, who.id, time)
        after_claims(tx, [agent], ctx.now)  # recency is a percept of prediction
    return Done(f"{agent} touched {obj} at {iso(time)}", {"object": obj, "agent": agent, "time": time})


# -- areas --------------------------------------------------------------------------------------
def add_area(ctx: AppContext, name: str, box: str) -> Done:
    """Add a box area ``"x0,y0,x1,y1"`` on the table plane."""
    check_name("area", name)
    x0, y0, x1, y1 = parse_numbers("--box", box, (4,))
    if x0 > x1 or y0 > y1:
        raise BadValue(f"--box must be x0,y0,x1,y1 with x0 <= x1 and y0 <= y1, got {box!r}")
    with ctx.write({"op": "area.add", "area": name, "box": [x0, y0, x1, y1]}) as tx:
        tx.add_area(name, (x0, y0, x1, y1))
    return Done(f"added area {name}", {"area": name, "box": [x0, y0, x1, y1]})


def list_areas(ctx: AppContext) -> list[dict[str, Any]]:
    """Every area with its box."""
    with ctx.read() as tx:
        return [{"name": a.name, "box": [a.x0, a.y0, a.x1, a.y1]} for a in tx.areas()]


def remove_area(ctx: AppContext, name: str) -> Done:
    """Forget an area; refused while a rule names it."""
    return _remove_named(ctx, "area", name, "inArea")
