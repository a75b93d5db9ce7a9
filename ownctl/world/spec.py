"""World and scenario files (architecture section 11): a parsed TOML dict -> :class:`World`, and back.

Pure: the caller reads the file (``source`` only names it in messages). Every key is checked;
an unknown key is an error naming the file, the key and the valid keys. A ``[generator]`` section is
handed to :func:`ownctl.world.generator.generate` (with the file's agents and an explicit random
generator); its world is merged with the explicit entries (explicit ones win on equal names).
``[[steps]]`` belong to scenarios and are ignored here.
"""

from __future__ import annotations

import importlib.util
import json
import math
from collections.abc import Mapping, Sequence
from typing import Any

from ownctl.errors import BadValue, OwnctlError
from ownctl.logic.names import check_name
from ownctl.logic.rules import ANY, parse_norm
from ownctl.world.model import Area, ObjectSpec, World

TOP_KEYS = ("name", "description", "agents", "norms", "areas", "generator", "objects", "steps")
AREA_KEYS = ("name", "box")
OBJECT_KEYS = ("name", "color", "position", "categories", "owners", "last_touch")


def check_table(source: str, where: str, table: Any, valid: Sequence[str]) -> Mapping[str, Any]:
    """``table`` if it is a TOML table whose keys are all in ``valid``; else an error naming the file,
    the place and the valid keys."""
    if not isinstance(table, Mapping):
        raise BadValue(f"{source}: {where} must be a table, got {type(table).__name__}")
    for key in table:
        if key not in valid:
            raise BadValue(f"{source}: unknown key {key!r} in {where}; valid keys: {', '.join(valid)}", valid)
    return table


def _numbers(source: str, where: str, value: Any, sizes: Sequence[int]) -> tuple[float, ...]:
    ok = isinstance(value, list) and len(value) in sizes
    ok = ok and all(
        isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in value
    )
    if not ok:
        raise BadValue(
            f"{source}: {where} must be a list of {' or '.join(map(str, sizes))} finite numbers, "
            f"got {value!r}"
        )
    return tuple(float(v) for v in value)


def _name(source: str, kind: str, value: Any) -> str:
    try:
        return check_name(kind, value)
    except OwnctlError as exc:
        raise type(exc)(f"{source}: {exc.message}", exc.valid) from None


def _per_agent(
    source: str, where: str, table: Any, agents: Sequence[str], low: float, high: float
) -> dict[str, float]:
    out: dict[str, float] = {}
    for agent, value in check_table(source, where, table, agents).items():
        number = value if isinstance(value, int | float) and not isinstance(value, bool) else math.nan
        if not low <= number <= high:  # NaN fails too
            raise BadValue(
                f"{source}: {where}.{agent} must be a number in [{low:g}, {high:g}], got {value!r}"
            )
        out[agent] = float(number)
    return out


def _area(source: str, i: int, table: Any) -> Area:
    where = f"[[areas]] #{i + 1}"
    table = check_table(source, where, table, AREA_KEYS)
    if "name" not in table or "box" not in table:
        raise BadValue(f"{source}: {where} needs name and box")
    x0, y0, x1, y1 = _numbers(source, f"{where} box", table["box"], (4,))
    if x0 > x1 or y0 > y1:
        raise BadValue(f"{source}: {where} box must be [x0, y0, x1, y1] with x0 <= x1 and y0 <= y1")
    return Area(_name(source, "area", table["name"]), (x0, y0, x1, y1))


def _object(source: str, i: int, table: Any, agents: Sequence[str]) -> tuple[ObjectSpec, dict[str, float]]:
    where = f"[[objects]] #{i + 1}"
    table = check_table(source, where, table, OBJECT_KEYS)
    if "name" not in table:
        raise BadValue(f"{source}: {where} needs a name")
    name = _name(source, "object", table["name"])
    where = f"object {name!r}"
    color = _name(source, "colour", table["color"]) if "color" in table else None
    position = None
    if "position" in table:
        xyz = _numbers(source, f"{where} position", table["position"], (2, 3))
        position = (xyz[0], xyz[1], xyz[2] if len(xyz) == 3 else 0.0)
    cats = table.get("categories", [])
    if not isinstance(cats, list):
        raise BadValue(f"{source}: {where} categories must be a list of names, got {cats!r}")
    spec = ObjectSpec(
        name=name,
        color=color,
        position=position,
        categories=frozenset(_name(source, "category", c) for c in cats),
        last_touch=_per_agent(
            source, f"{where} last_touch", table.get("last_touch", {}), agents, 0.0, math.inf
        ),
    )
    return spec, _per_agent(source, f"{where} owners", table.get("owners", {}), agents, 0.0, 1.0)


def check_norm(source: str, text: Any, agents: Sequence[str], areas: Sequence[str]) -> str:
    """The canonical text of a true norm whose agents and areas exist; errors name ``source``."""
    if not isinstance(text, str):
        raise BadValue(f"{source}: a norm must be a string, got {text!r}")
    try:
        norm = parse_norm(text)
    except OwnctlError as exc:
        raise type(exc)(f"{source}: {exc.message}", exc.valid) from None
    if norm.sign != "forbid":
        # the ground truth (the simulated instructor, the metrics) reads forbid rules only
        raise BadValue(f"{source}: true norm {text!r} is an allow norm; a world's true norms are forbid "
                       f"rules (put the exception into the rule it limits, as 'and not ...')", ["forbid"])
    for lit in norm.rule.literals:
        known = {"ownedBy": agents, "inArea": areas}.get(lit.pred)
        if known is not None and lit.arg != ANY and lit.arg not in known:
            kind = "agent" if lit.pred == "ownedBy" else "area"
            raise BadValue(
                f"{source}: norm {text!r} names unknown {kind} {lit.arg!r}; known: {', '.join(known)}"
            )
    return norm.text()


def _generated(data: Mapping[str, Any], source: str, agents: Sequence[str], rng: Any) -> World | None:
    """The world drawn by ``ownctl.world.generator`` from the ``[generator]`` table, if there is one."""
    if "generator" not in data:
        return None
    if importlib.util.find_spec("ownctl.world.generator") is None:
        raise OwnctlError(f"{source}: generator worlds need ownctl.world.generator, which is not installed")
    from ownctl.world import generator

    table = data["generator"]
    if not isinstance(table, Mapping):
        raise BadValue(f"{source}: [generator] must be a table, got {table!r}")
    try:
        return generator.generate(dict(table), rng, tuple(agents))
    except OwnctlError as exc:
        raise type(exc)(f"{source}: [generator]: {exc.message}", exc.valid) from None


def world_from_dict(data: Mapping[str, Any], source: str, rng: Any = None) -> World:
    """Validate a parsed world/scenario file and build its :class:`World` (ground truth included).

    With a ``[generator]`` table, the generated world comes first: its agents, areas and norms are
    used unless the file gives ``agents`` / ``norms`` itself; explicit areas and objects are added
    to the generated ones and replace those of the same name.
    """
    data = check_table(source, "the file", data, TOP_KEYS)
    raw_agents = data.get("agents", [])
    if not isinstance(raw_agents, list):
        raise BadValue(f"{source}: agents must be a list of names, got {raw_agents!r}")
    explicit_agents = list(dict.fromkeys(_name(source, "agent", a) for a in raw_agents))
    generated = _generated(data, source, explicit_agents, rng)
    agents = explicit_agents or list(generated.agents if generated else ())
    areas = {a.name: a for a in (generated.areas if generated else ())}
    for i, table in enumerate(_list(source, data, "areas")):
        area = _area(source, i, table)
        areas[area.name] = area
    objects = {o.name: o for o in (generated.objects if generated else ())}
    owners = {k: dict(v) for k, v in (generated.owners if generated else {}).items()}
    seen: set[str] = set()
    for i, table in enumerate(_list(source, data, "objects")):
        spec, own = _object(source, i, table, agents)
        if spec.name in seen:
            raise BadValue(f"{source}: object {spec.name!r} is listed twice")
        seen.add(spec.name)
        objects[spec.name] = spec
        owners[spec.name] = own
    raw_norms = data.get("norms", [])
    if not isinstance(raw_norms, list):
        raise BadValue(f"{source}: norms must be a list of rule texts, got {raw_norms!r}")
    norms = [check_norm(source, n, agents, list(areas)) for n in raw_norms]
    if "norms" not in data and generated is not None:
        norms = [check_norm(source, n, agents, list(areas)) for n in generated.norms]
    name = data.get("name", generated.name if generated else "")
    if not isinstance(name, str):
        raise BadValue(f"{source}: name must be a string, got {name!r}")
    return World(
        name=name,
        agents=tuple(agents),
        objects=tuple(objects.values()),
        areas=tuple(areas.values()),
        norms=tuple(dict.fromkeys(norms)),
        owners={k: v for k, v in owners.items() if v},
    )


def _list(source: str, data: Mapping[str, Any], key: str) -> list[Any]:
    value = data.get(key, [])
    if not isinstance(value, list):
        raise BadValue(f"{source}: {key} must be an array of tables ([[{key}]]), got {value!r}")
    return value


def world_to_dict(world: World) -> dict[str, Any]:
    """The file form of ``world``: loading it back gives an equal world."""
    objects = []
    for o in world.objects:
        entry: dict[str, Any] = {"name": o.name}
        if o.color is not None:
            entry["color"] = o.color
        if o.position is not None:
            entry["position"] = list(o.position)
        if o.categories:
            entry["categories"] = sorted(o.categories)
        owners = {a: p for a, p in world.owners.get(o.name, {}).items() if p}
        if owners:
            entry["owners"] = owners
        if o.last_touch:
            entry["last_touch"] = dict(o.last_touch)
        objects.append(entry)
    return {
        "name": world.name,
        "agents": list(world.agents),
        "norms": list(world.norms),
        "areas": [{"name": a.name, "box": list(a.box)} for a in world.areas],
        "objects": objects,
    }


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(float(value))
    if isinstance(value, str):  # a JSON string is a TOML basic string, once DEL is escaped as TOML asks
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + " }" if value else "{}"
    return "[" + ", ".join(_toml_value(v) for v in value) + "]"


def to_toml(data: Mapping[str, Any]) -> str:
    """TOML text of a :func:`world_to_dict` result (scalars and arrays first, then arrays of tables)."""
    lines = []
    tables = {
        k: v for k, v in data.items() if isinstance(v, list) and v and all(isinstance(x, Mapping) for x in v)
    }
    for key, value in data.items():
        if key not in tables:
            if isinstance(value, list) and len(value) > 1 and all(isinstance(v, str) for v in value):
                lines.append(f"{key} = [\n" + "".join(f"  {_toml_value(v)},\n" for v in value) + "]")
            else:
                lines.append(f"{key} = {_toml_value(value)}")
    for key, entries in tables.items():
        for entry in entries:
            lines.append(f"\n[[{key}]]")
            lines.extend(f"{k} = {_toml_value(v)}" for k, v in entry.items())
    return "\n".join(lines) + "\n"
