"""The repository: every read and write the application layer makes, on one open transaction.

:class:`Tx` wraps a SQLAlchemy session; the app layer never sees SQL. Lookups by name raise
:class:`UnknownName` listing the known names; adding a taken name raises :class:`DuplicateName`.
Claims and posteriors about many (object, agent) pairs are written with one bulk upsert by primary
key; priors are packed per agent in chunks of object ids (``ownctl/store/packed.py``).
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from itertools import islice
from typing import Any, cast

import numpy as np
from sqlalchemy import Table, delete, func, insert, select, update
from sqlalchemy.orm import Session

from ownctl.errors import DuplicateName, StoreError, UnknownName
from ownctl.store import packed as packing
from ownctl.store.models import (
    Agent,
    Area,
    Base,
    Category,
    Conversation,
    Event,
    Generation,
    Object,
    Ownership,
    Permission,
    RuleRow,
    Setting,
    TruthNorm,
    TruthOwner,
)

CHUNK = 900  # ids per IN (...) clause, below SQLite's default limit on bound parameters
BATCH = 100_000  # rows per executemany of a bulk insert

KEEP: Any = object()


def _table(model: type[Base]) -> Table:
    """The Core table of an ORM model (for bulk statements)."""
    return cast(Table, model.__table__)


#: PostgreSQL array types of the columns that bulk updates pass as arrays.
PG_ARRAY_TYPES = {"object_id": "integer[]", "agent_id": "integer[]", "time": "float8[]"}


def _pg_array_type(column: str) -> str:
    if column in PG_ARRAY_TYPES:
        return PG_ARRAY_TYPES[column]
    return "text[]" if column.endswith(("_speaker", "_source")) else "float8[]"


def bulk_insert(session: Session, table: str, columns: Sequence[str], rows: Iterable[Sequence[Any]]) -> None:
    """Insert many rows of plain values (a JSON column given as its text) with one statement: COPY
    on PostgreSQL, one executemany on SQLite (no per-row ORM or parameter-dict work)."""
    conn = session.connection()
    names = ", ".join(columns)
    if conn.dialect.name == "postgresql":
        raw: Any = conn.connection.dbapi_connection
        with raw.cursor() as cur, cur.copy(f"COPY {table} ({names}) FROM STDIN") as copy:
            for row in rows:
                copy.write_row(row)
        return
    marks = ", ".join("?" for _ in columns)
    statement = f"INSERT INTO {table} ({names}) VALUES ({marks})"
    it = iter(rows)
    while batch := list(map(tuple, islice(it, BATCH))):
        conn.exec_driver_sql(statement, batch)


def bulk_upsert(session: Session, table: str, keys: Sequence[str], columns: Sequence[str],
                values: Mapping[str, Sequence[Any]]) -> None:
    """Insert or update many rows with one statement: ``INSERT ... ON CONFLICT (keys) DO UPDATE``,
    an executemany on SQLite and one ``INSERT ... SELECT FROM unnest(arrays)`` on PostgreSQL.
    ``values`` maps every key and column to a list, one entry per row."""
    if not values[keys[0]]:
        return
    conn = session.connection()
    names = [*keys, *columns]
    sets = ", ".join(f"{c} = excluded.{c}" for c in columns)
    conflict = f"ON CONFLICT ({', '.join(keys)}) " + (f"DO UPDATE SET {sets}" if columns else "DO NOTHING")
    if conn.dialect.name == "postgresql":
        arrays = ", ".join(f"%(a{k})s::{_pg_array_type(c)}" for k, c in enumerate(names))
        sql = (f"INSERT INTO {table} ({', '.join(names)}) SELECT * FROM unnest({arrays}) "
               f"AS v({', '.join(names)}) {conflict}")
        conn.exec_driver_sql(sql, {f"a{k}": list(values[c]) for k, c in enumerate(names)})
        return
    marks = ", ".join("?" for _ in names)
    rows = list(zip(*(values[c] for c in names), strict=True))
    conn.exec_driver_sql(f"INSERT INTO {table} ({', '.join(names)}) VALUES ({marks}) {conflict}", rows)


@dataclass(frozen=True)
class PackedTable:
    """A table of per-agent chunks of object ids (``ownctl/store/packed.py``): its packed array
    columns with their types, and its per-chunk scalar columns."""

    name: str
    arrays: tuple[tuple[str, np.dtype], ...]
    scalars: tuple[str, ...] = ()


PRIORS = PackedTable("priors", (("p", packing.FLOAT), ("source", packing.CODE)), ("time",))
TOUCHES = PackedTable("touches", (("times", packing.FLOAT),))


def read_packed(session: Session, table: PackedTable, object_ids: Sequence[int] | np.ndarray,
                agent_ids: Sequence[int]) -> dict[str, np.ndarray]:
    """Column -> (len(object_ids), len(agent_ids)) values of ``table``: NaN (floats) or 0 (codes)
    where nothing is held; a scalar column gives its chunk's value to every cell the chunk holds."""
    objs = np.asarray(object_ids, dtype=np.int64)
    n, m = len(objs), len(agent_ids)
    out = {c: np.full((n, m), np.nan) if t.kind == "f" else np.zeros((n, m), dtype=t)
           for c, t in table.arrays}
    out.update({c: np.full((n, m), np.nan) for c in table.scalars})
    if not n or not m:
        return out
    chunk, slot = packing.chunk_of(objs)
    column = {int(a): j for j, a in enumerate(agent_ids)}
    wanted = np.unique(chunk).tolist()
    by_chunk = {c: np.flatnonzero(chunk == c) for c in wanted}
    names = [c for c, _ in table.arrays]
    where = [f"agent_id IN ({', '.join(str(a) for a in column)})"]
    if len(wanted) < CHUNK:
        where.append(f"chunk IN ({', '.join(str(c) for c in wanted)})")
    sql = (f"SELECT agent_id, chunk, {', '.join([*names, *table.scalars])} FROM {table.name} "
           f"WHERE {' AND '.join(where)}")
    for agent, c, *values in session.connection().exec_driver_sql(sql):
        rows = by_chunk.get(int(c))
        if rows is None:
            continue
        j, here = column[int(agent)], slot[rows]
        for (name, dtype), data in zip(table.arrays, values, strict=False):
            out[name][rows, j] = packing.decode(data, dtype)[here]
        for name, value in zip(table.scalars, values[len(names):], strict=True):
            out[name][rows, j] = value
    return out


def write_packed(session: Session, table: PackedTable, object_ids: Sequence[int] | np.ndarray,
                 agent_ids: Sequence[int] | np.ndarray, values: Mapping[str, np.ndarray],
                 scalars: Mapping[str, Any] | None = None) -> None:
    """Set the cells (object_ids[k], agent_ids[k]) of every array column of ``table`` to
    ``values[column][k]``, rewriting each touched chunk once (its scalar columns become
    ``scalars``). A pair given twice takes its last value."""
    if not len(object_ids):
        return
    objs = np.asarray(object_ids, dtype=np.int64)
    agents = np.asarray(agent_ids, dtype=np.int64)
    chunk, slot = packing.chunk_of(objs)
    key = agents * (int(chunk.max()) + 1) + chunk  # one integer per (agent, chunk)
    order = np.argsort(key, kind="stable")
    parts = np.split(order, np.flatnonzero(np.diff(key[order])) + 1)
    keys = [(int(agents[part[0]]), int(chunk[part[0]])) for part in parts]
    names = [c for c, _ in table.arrays]
    conn = session.connection()
    sql = (f"SELECT agent_id, chunk, {', '.join(names)} FROM {table.name} "
           f"WHERE agent_id IN ({', '.join(str(a) for a in sorted({a for a, _ in keys}))}) "
           f"AND chunk IN ({', '.join(str(c) for c in sorted({c for _, c in keys}))})")
    stored = {(int(a), int(c)): data for a, c, *data in conn.exec_driver_sql(sql)}
    missing = sorted(set(table.scalars) - set(scalars or {}))
    if missing:
        raise ValueError(f"writing {table.name} needs a value for {', '.join(missing)}")
    extra = [scalars[c] for c in table.scalars] if scalars else []
    rows: list[tuple[Any, ...]] = []
    for k, part in zip(keys, parts, strict=True):
        held = stored.get(k)
        packed = []
        for n, (name, dtype) in enumerate(table.arrays):
            array = packing.empty(dtype) if held is None else packing.decode(held[n], dtype)
            array[slot[part]] = values[name][part]
            packed.append(packing.encode(array, dtype))
        rows.append((*k, *packed, *extra))
    old = [{"a": a, "c": c} for a, c in keys if (a, c) in stored]
    if old:
        mark = "%({})s" if conn.dialect.name == "postgresql" else ":{}"
        conn.exec_driver_sql(f"DELETE FROM {table.name} WHERE agent_id = {mark.format('a')} "
                             f"AND chunk = {mark.format('c')}", old)
    bulk_insert(session, table.name, ("agent_id", "chunk", *names, *table.scalars), rows)


def clear_packed(session: Session, table: PackedTable, object_ids: Sequence[int],
                 agent_ids: Sequence[int]) -> None:
    """Empty the cells of ``object_ids`` x ``agent_ids`` in every array column of ``table``
    (objects being removed: their ids may be given to new objects)."""
    objects = np.repeat(np.asarray(object_ids, dtype=np.int64), len(agent_ids))
    if len(objects):
        agents = np.tile(np.asarray(agent_ids, dtype=np.int64), len(object_ids))
        write_packed(session, table, objects, agents,
                     {c: np.full(len(objects), np.nan) if t.kind == "f" else np.zeros(len(objects), dtype=t)
                      for c, t in table.arrays}, {c: 0.0 for c in table.scalars})


@dataclass(frozen=True)
class Talk:
    """The conversation context by name: who speaks, what "this" is, what the robot is doing on it,
    and the last refusal (``{"action", "object", ...}``, for "why not?")."""

    speaker: str | None = None
    target: str | None = None
    action: str | None = None
    refusal: dict[str, Any] | None = None


class _Part:
    """One concern of the store inside a transaction (shares the session and the caches)."""

    def __init__(self, tx: Tx) -> None:
        self.tx = tx
        self.session = tx.session

    def _expire(self, model: type[Base]) -> None:
        """Forget cached rows of ``model`` after a bulk statement changed them behind the session."""
        for row in list(self.session.identity_map.values()):
            if isinstance(row, model):
                self.session.expire(row)


class World(_Part):
    """Agents and areas: who may own things, and where things can be."""

    def agents(self) -> list[Agent]:
        """Every agent, by name (read once per transaction)."""
        if self.tx._agents is None:
            self.tx._agents = list(self.session.scalars(select(Agent).order_by(Agent.name)))
        return list(self.tx._agents)

    def agent(self, name: str) -> Agent:
        """The agent called ``name``."""
        row = self.session.scalar(select(Agent).where(Agent.name == name))
        if row is None:
            raise UnknownName("agent", name, self.session.scalars(select(Agent.name)))
        return row

    def add_agent(self, name: str, now: float) -> Agent:
        """A new agent (it holds no beliefs yet)."""
        self._unique(Agent, name, "agent")
        self.tx._agents = None
        row = Agent(name=name, created=now)
        self.session.add(row)
        self.session.flush()
        return row

    def remove(self, row: Base) -> None:
        """Delete one row (an agent's or object's beliefs, touches and permissions cascade)."""
        self.tx._agents = None
        self.session.delete(row)
        self.session.flush()

    def areas(self) -> list[Area]:
        """Every area, by name."""
        return list(self.session.scalars(select(Area).order_by(Area.name)))

    def area(self, name: str) -> Area:
        """The area called ``name``."""
        row = self.session.scalar(select(Area).where(Area.name == name))
        if row is None:
            raise UnknownName("area", name, self.session.scalars(select(Area.name)))
        return row

    def add_area(self, name: str, box: Sequence[float]) -> Area:
        """A new box area."""
        self._unique(Area, name, "area")
        x0, y0, x1, y1 = box
        row = Area(name=name, x0=x0, y0=y0, x1=x1, y1=y1)
        self.session.add(row)
        self.session.flush()
        return row

    def _unique(self, model: type[Agent] | type[Object] | type[Area], name: str, kind: str) -> None:
        if self.session.scalar(select(model.id).where(model.name == name)) is not None:
            raise DuplicateName(f"{kind} {name!r} already exists; choose another name")


class Things(_Part):
    """Objects and their percepts: colour, position, categories and touches."""

    def objects(self) -> list[Object]:
        """Every object, in the order they were added (by id), as the paper's tasks visit them."""
        return list(self.session.scalars(select(Object).order_by(Object.id)))

    def object(self, name: str) -> Object:
        """The object called ``name``."""
        row = self.session.scalar(select(Object).where(Object.name == name))
        if row is None:
            raise UnknownName("object", name, self.session.scalars(select(Object.name)))
        return row

    def object_name(self, object_id: int) -> str:
        """The name of the object with primary key ``object_id``."""
        name = self.session.scalar(select(Object.name).where(Object.id == object_id))
        if name is None:
            raise UnknownName("object", f"#{object_id}", self.session.scalars(select(Object.name)))
        return name

    def object_by_id(self, object_id: int) -> Object | None:
        """The object with primary key ``object_id``, if any."""
        return self.session.get(Object, object_id)

    def object_table(self, object_ids: Sequence[int] | None = None) -> list[Any]:
        """Objects as plain rows (id, name, color, x, y, z), in id order; optionally only ``object_ids``."""
        cols = (Object.id, Object.name, Object.color, Object.x, Object.y, Object.z)
        query = select(*cols).order_by(Object.id)
        if object_ids is None:
            return list(self.session.execute(query).all())
        out: list[Any] = []
        ids = list(object_ids)
        for start in range(0, len(ids), CHUNK):
            out.extend(self.session.execute(query.where(Object.id.in_(ids[start : start + CHUNK]))).all())
        rank = {oid: k for k, oid in enumerate(ids)}
        return sorted(out, key=lambda r: rank[r.id])

    def add_objects(self, specs: Sequence[dict[str, Any]], now: float) -> dict[str, int]:
        """Many new objects at once (dicts of name, color, x, y, z), holding no beliefs yet; returns
        name -> id. Duplicate names (among them or with stored objects) are refused."""
        names = [s["name"] for s in specs]
        taken = sorted(self._object_ids(names)) or sorted(n for n, k in Counter(names).items() if k > 1)
        if taken:
            raise DuplicateName(f"object {taken[0]!r} already exists; choose another name")
        if not specs:
            return {}
        keys = ("name", "color", "x", "y", "z")
        bulk_insert(self.session, "objects", (*keys, "extra", "created"),
                    ((*(s.get(k) for k in keys), json.dumps(s.get("extra") or {}), now) for s in specs))
        return self._object_ids(names)

    def _object_ids(self, names: Sequence[str]) -> dict[str, int]:
        """name -> id of the stored objects among ``names`` (many names: one scan of the table)."""
        if len(names) > 10 * CHUNK:
            wanted = set(names)
            rows = self.session.execute(select(Object.name, Object.id)).all()
            return {n: i for n, i in rows if n in wanted}
        out: dict[str, int] = {}
        for start in range(0, len(names), CHUNK):
            query = select(Object.name, Object.id).where(Object.name.in_(names[start : start + CHUNK]))
            out.update({name: oid for name, oid in self.session.execute(query).all()})
        return out

    def remove_objects(self, object_ids: Sequence[int]) -> None:
        """Forget objects (their beliefs, touches, categories and permissions cascade)."""
        ids = list(object_ids)
        agents = [a.id for a in self.tx.world.agents()]
        for packed in (PRIORS, TOUCHES):  # packed per agent: no cascade reaches them
            clear_packed(self.session, packed, ids, agents)
        for start in range(0, len(ids), CHUNK):
            chunk = ids[start : start + CHUNK]
            for table in (Ownership, Category, Permission, TruthOwner):
                self.session.execute(delete(table).where(table.object_id.in_(chunk)))
            self.session.execute(update(Conversation).where(Conversation.target_id.in_(chunk))
                                 .values(target_id=None))
            self.session.execute(delete(Object).where(Object.id.in_(chunk)))
        for model in (Object, Ownership, Permission, Conversation):
            self._expire(model)

    def set_percepts(self, object_id: int, row: dict[str, Any]) -> None:
        """Store an object's colour and position (``row``: color, x, y, z)."""
        self.session.execute(update(Object).where(Object.id == object_id)
                             .values(color=row["color"], x=row["x"], y=row["y"], z=row["z"]))
        self._expire(Object)

    def vocabulary(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The distinct colours and categories of every stored object, sorted."""
        colors = self.session.scalars(select(Object.color).where(Object.color.is_not(None)).distinct())
        cats = self.session.scalars(select(Category.category).distinct())
        return tuple(sorted(c for c in colors if c)), tuple(sorted(cats))

    def categories(self, object_ids: Sequence[int] | None = None) -> dict[int, set[str]]:
        """object id -> its categories (of every object, or only of ``object_ids``)."""
        query = select(Category.object_id, Category.category)
        queries = [query] if object_ids is None else [
            query.where(Category.object_id.in_(list(object_ids)[start : start + CHUNK]))
            for start in range(0, len(object_ids), CHUNK)
        ]
        out: dict[int, set[str]] = {}
        for q in queries:
            for oid, cat in self.session.execute(q).all():
                out.setdefault(oid, set()).add(cat)
        return out

    def set_categories(self, object_id: int, categories: Iterable[str]) -> None:
        """Replace an object's categories."""
        self.session.execute(delete(Category).where(Category.object_id == object_id))
        cats = sorted(set(categories))
        if cats:
            self.session.execute(insert(Category), [{"object_id": object_id, "category": c} for c in cats])

    def add_categories(self, rows: Sequence[tuple[int, str]]) -> None:
        """Many (object id, category) memberships of new objects, at once."""
        if rows:
            self.session.connection().execute(
                insert(_table(Category)),
                [{"object_id": o, "category": c} for o, c in sorted(set(rows))],
            )


class Touches(_Part):
    """When each agent last interacted with each object, packed per agent (``ownctl/store/packed.py``)."""

    def table(self, object_ids: Sequence[int] | None = None,
                    agent_ids: Sequence[int] | None = None) -> tuple[list[int], list[int], np.ndarray]:
        """(object ids, agent ids, (objects, agents) absolute times of each agent's last interaction,
        NaN where it never interacted): every object and agent unless given."""
        objects = (list(self.session.scalars(select(Object.id).order_by(Object.id))) if object_ids is None
                   else list(object_ids))
        agents = sorted(a.id for a in self.tx.world.agents()) if agent_ids is None else list(agent_ids)
        return objects, agents, read_packed(self.session, TOUCHES, objects, agents)["times"]

    def pairs(
        self, agent_id: int | None = None, object_ids: Sequence[int] | None = None
    ) -> dict[tuple[int, int], float]:
        """(object id, agent id) -> absolute time of the agent's last interaction.

        Optionally only one agent's and/or only some objects' interactions.
        """
        objects, agents, times = self.table(object_ids, None if agent_id is None else [agent_id])
        i, j = np.nonzero(~np.isnan(times))
        return {(objects[a], agents[b]): float(times[a, b])
                for a, b in zip(i.tolist(), j.tolist(), strict=True)}

    def counts(self) -> dict[int, int]:
        """agent id -> how many objects it has interacted with."""
        _, agents, times = self.table()
        return dict(zip(agents, (~np.isnan(times)).sum(axis=0).tolist(), strict=True))

    def times(
        self, object_ids: Sequence[int] | None = None, agent_ids: Sequence[int] | None = None
    ) -> dict[int, dict[str, float]]:
        """object id -> {agent name: absolute time of its last interaction} (optionally some objects,
        and only some agents' interactions)."""
        names = {a.id: a.name for a in self.tx.world.agents()}
        objects, agents, times = self.table(object_ids, agent_ids)
        who = [names[a] for a in agents]
        out: dict[int, dict[str, float]] = {}
        for oid, row in zip(objects, times.tolist(), strict=True):
            held = {a: t for a, t in zip(who, row, strict=True) if t == t}  # t != t: NaN, never touched
            if held:
                out[oid] = held
        return out

    def touch(self, object_id: int, agent_id: int, time: float) -> None:
        """Record that an agent interacted with an object at ``time`` (absolute store time)."""
        self.add([object_id], [agent_id], [time])

    def add(self, object_ids: Sequence[int], agent_ids: Sequence[int], times: Sequence[float]) -> None:
        """Many interactions at once: agent_ids[k] with object_ids[k] at times[k] (absolute store
        time; a pair given twice: the last)."""
        if len(object_ids):
            write_packed(self.session, TOUCHES, object_ids, agent_ids,
                         {"times": np.asarray(times, dtype=float)})

#: The ownership columns of each kind of belief a row holds, and the prior's (packed in ``priors``).
CLAIM_COLUMNS = ("claim_p", "claim_speaker", "claim_trust", "claim_time")
POSTERIOR_COLUMNS = ("posterior_p", "posterior_source", "posterior_time")
PRIOR_COLUMNS = ("prior_p", "prior_source", "prior_time")
HELD_COLUMNS = (*CLAIM_COLUMNS, *POSTERIOR_COLUMNS)


@dataclass(frozen=True)
class BeliefRow:
    """One (object, agent) pair's beliefs as the store holds them: None where nothing is held."""

    object_id: int
    agent_id: int
    claim_p: float | None = None
    claim_speaker: str | None = None
    claim_trust: float | None = None
    claim_time: float | None = None
    prior_p: float | None = None
    prior_source: str | None = None
    prior_time: float | None = None
    posterior_p: float | None = None
    posterior_source: str | None = None
    posterior_time: float | None = None


@dataclass(frozen=True)
class PriorTable:
    """Priors of objects (rows) x agents (columns): probability (NaN: none), source (None: none)
    and the time its chunk was last written (NaN: none)."""

    p: np.ndarray
    source: np.ndarray
    time: np.ndarray


class Beliefs(_Part):
    """Ownership beliefs: claims and posteriors (rows where held) and priors (packed per agent)."""

    def held(self, object_ids: Sequence[int] | None = None,
             agent_ids: Sequence[int] | None = None) -> list[Any]:
        """The stored claim and posterior rows as plain rows (object_id, agent_id, claim_*,
        posterior_*), optionally only of some objects and/or agents."""
        query = select(*_table(Ownership).columns)
        if agent_ids is not None:
            query = query.where(Ownership.agent_id.in_(list(agent_ids)))
        if object_ids is None:
            return list(self.session.execute(query).all())
        out: list[Any] = []
        ids = list(object_ids)
        for start in range(0, len(ids), CHUNK):
            part = query.where(Ownership.object_id.in_(ids[start : start + CHUNK]))
            out.extend(self.session.execute(part).all())
        return out

    def claim_counts(self) -> dict[int, int]:
        """agent id -> how many objects carry a claim about it."""
        query = (select(Ownership.agent_id, func.count()).where(Ownership.claim_p.is_not(None))
                 .group_by(Ownership.agent_id))
        return {int(a): int(n) for a, n in self.session.execute(query).all()}

    def priors(self, object_ids: Sequence[int], agent_ids: Sequence[int]) -> PriorTable:
        """The priors of ``object_ids`` x ``agent_ids``, read chunk by chunk (``ownctl/store/packed.py``)."""
        got = read_packed(self.session, PRIORS, object_ids, agent_ids)
        return PriorTable(got["p"], packing.source_names(got["source"]), got["time"])

    def write_priors(self, object_ids: Sequence[int] | np.ndarray, agent_ids: Sequence[int] | np.ndarray,
                     p: Sequence[float | None] | np.ndarray, source: Sequence[str | None] | np.ndarray,
                     time: float) -> None:
        """Set the priors of the pairs (object_ids[k], agent_ids[k]) (None or NaN: none held),
        rewriting each touched chunk once; the chunks' write time becomes ``time``."""
        values = np.asarray([np.nan if v is None else v for v in p] if not isinstance(p, np.ndarray) else p,
                            dtype=float)
        codes = packing.source_codes(source)
        none = np.isnan(values)
        codes[none] = 0
        codes[(codes == 0) & ~none] = packing.SOURCES.index("prediction")  # a prior of unnamed source
        write_packed(self.session, PRIORS, object_ids, agent_ids, {"p": values, "source": codes},
                     {"time": time})

    def belief_table(
        self, object_ids: Sequence[int] | None = None, agent_id: int | None = None,
        agent_ids: Sequence[int] | None = None,
    ) -> list[BeliefRow]:
        """Every (object, agent) pair's beliefs, by object id then agent id; optionally only
        ``object_ids`` and/or one agent (or only ``agent_ids``)."""
        if agent_id is not None:
            agent_ids = [agent_id]
        agents = sorted(a.id for a in self.tx.world.agents()) if agent_ids is None else sorted(set(agent_ids))
        objects = (list(self.session.scalars(select(Object.id).order_by(Object.id))) if object_ids is None
                   else sorted(set(object_ids)))
        priors = self.priors(objects, agents)
        held = {(r.object_id, r.agent_id): r for r in self.held(None if object_ids is None else objects,
                                                                   None if agent_ids is None else agents)}
        out: list[BeliefRow] = []
        for i, oid in enumerate(objects):
            for j, aid in enumerate(agents):
                p = priors.p[i, j]
                prior: dict[str, Any] = {} if np.isnan(p) else {
                    "prior_p": float(p), "prior_source": priors.source[i, j],
                    "prior_time": float(priors.time[i, j])}
                row = held.get((oid, aid))
                kept = {} if row is None else {c: getattr(row, c) for c in HELD_COLUMNS}
                out.append(BeliefRow(oid, aid, **kept, **prior))
        return out

    def ownership(self, object_id: int | None = None, agent_id: int | None = None) -> list[BeliefRow]:
        """Every (object, agent) pair's beliefs, optionally for one object and/or one agent."""
        return self.belief_table(None if object_id is None else [object_id], agent_id)

    def write_beliefs(self, rows: Sequence[dict[str, Any]]) -> None:
        """Set beliefs of (object, agent) pairs; each dict has object_id, agent_id and the columns
        to set. One statement per set of columns (:meth:`update_beliefs`)."""
        groups: dict[tuple[str, ...], list[dict[str, Any]]] = {}
        for row in rows:
            columns = tuple(sorted(k for k in row if k not in ("object_id", "agent_id")))
            groups.setdefault(columns, []).append(row)
        for columns, group in groups.items():
            self.update_beliefs([r["object_id"] for r in group], [r["agent_id"] for r in group],
                                {c: [r[c] for r in group] for c in columns})

    def update_beliefs(self, object_ids: Sequence[int], agent_ids: Sequence[int],
                       values: Mapping[str, Sequence[Any]]) -> None:
        """Set the columns in ``values`` (column -> one value per pair) of the pairs
        (object_ids[k], agent_ids[k]): claim and posterior columns with one bulk upsert
        (:func:`bulk_upsert`), prior columns by rewriting their chunks (:meth:`write_priors`)."""
        if not len(object_ids):
            return
        unknown = sorted(set(values) - {*CLAIM_COLUMNS, *POSTERIOR_COLUMNS, *PRIOR_COLUMNS})
        if unknown:
            raise ValueError(f"unknown belief column {unknown[0]!r}; valid: "
                             f"{', '.join((*CLAIM_COLUMNS, *PRIOR_COLUMNS, *POSTERIOR_COLUMNS))}")
        if "prior_p" in values:
            times = [t for t in values.get("prior_time", ()) if t is not None]
            self.write_priors(object_ids, agent_ids, values["prior_p"],
                              values.get("prior_source", [None] * len(object_ids)), max(times, default=0.0))
        columns = tuple(c for c in values if c not in PRIOR_COLUMNS)
        if columns:
            bulk_upsert(self.session, "ownership", ("agent_id", "object_id"), columns,
                        {"agent_id": agent_ids, "object_id": object_ids, **{c: values[c] for c in columns}})
            self._expire(Ownership)


class Knowledge(_Part):
    """What instructors said: permissions and rules, and the ground truth of simulated worlds."""

    def permissions(self, object_id: int | None = None) -> list[Permission]:
        """Permissions (all, or one object's), oldest first."""
        query = select(Permission).order_by(Permission.id)
        if object_id is not None:
            query = query.where(Permission.object_id == object_id)
        return list(self.session.scalars(query))

    def permission_table(self) -> list[Any]:
        """Every permission as a plain row (id, action, object_id, value), oldest first."""
        cols = (Permission.id, Permission.action, Permission.object_id, Permission.value)
        return list(self.session.execute(select(*cols).order_by(Permission.id)).all())

    def permission_rows(self, object_ids: Sequence[int] | None = None) -> list[Any]:
        """Permissions as plain rows with every column (of every object, or only of ``object_ids``)."""
        query = select(*_table(Permission).columns).order_by(Permission.id)
        if object_ids is None:
            return list(self.session.execute(query).all())
        out: list[Any] = []
        ids = list(object_ids)
        for start in range(0, len(ids), CHUNK):
            chunk = query.where(Permission.object_id.in_(ids[start : start + CHUNK]))
            out.extend(self.session.execute(chunk).all())
        return sorted(out, key=lambda r: r.id)

    def permission_id(self, action: str, object_id: int) -> int | None:
        """The id of the permission for (action, object), if any."""
        return self.session.scalar(select(Permission.id).where(Permission.action == action,
                                                               Permission.object_id == object_id))

    def permission(self, permission_id: int) -> Permission:
        """The permission with id ``permission_id``."""
        row = self.session.get(Permission, permission_id)
        if row is None:
            ids = [str(i) for i in self.session.scalars(select(Permission.id))]
            raise UnknownName("permission", str(permission_id), ids)
        return row

    def set_permission(
        self, action: str, object_id: int, value: float, speaker: str | None, now: float,
        seq: int | None = None, seen: dict[str, Any] | None = None,
    ) -> Permission:
        """Insert or overwrite the permission for (action, object) with its arrival rank and the
        object's percepts when it was given; the last instruction wins."""
        row = self.session.scalar(
            select(Permission).where(Permission.action == action, Permission.object_id == object_id)
        )
        if row is None:
            row = Permission(action=action, object_id=object_id, value=value, speaker=speaker, time=now,
                             seq=seq, seen=seen)
            self.session.add(row)
        else:
            row.value, row.speaker, row.time, row.seq, row.seen = value, speaker, now, seq, seen
        self.session.flush()
        return row

    def delete_permission(self, action: str, object_id: int) -> None:
        """Forget the permission for (action, object), if any."""
        self.session.execute(delete(Permission).where(Permission.action == action,
                                                      Permission.object_id == object_id))
        self._expire(Permission)

    def max_permission_seq(self) -> int:
        """The highest arrival rank of any permission (0 without any)."""
        return int(self.session.scalar(select(func.max(func.coalesce(Permission.seq, Permission.id)))) or 0)

    def rules(self, action: str | None = None) -> list[RuleRow]:
        """Rules (all, or one action's), by id."""
        query = select(RuleRow).order_by(RuleRow.action, RuleRow.rank, RuleRow.id)
        if action is not None:
            query = query.where(RuleRow.action == action)
        return list(self.session.scalars(query))

    def rule(self, rule_id: int) -> RuleRow:
        """The rule with id ``rule_id``."""
        row = self.session.get(RuleRow, rule_id)
        if row is None:
            ids = [str(i) for i in self.session.scalars(select(RuleRow.id))]
            raise UnknownName("rule", str(rule_id), ids)
        return row

    def replace_rules(
        self, action: str, rules: Sequence[tuple[str, str, dict[str, Any]]], now: float
    ) -> None:
        """Make ``rules`` (text, origin, provenance), in this order, the rules of ``action``; kept
        rules keep their ids and creation times."""
        wanted = {t for t, _, _ in rules}
        old: dict[str, RuleRow] = {}
        for row in self.rules(action):
            if row.text not in wanted:
                self.session.delete(row)
            else:
                old[row.text] = row
        self.session.flush()
        for rank, (text_, origin, provenance) in enumerate(rules):
            kept = old.get(text_)
            if kept is None:
                row = RuleRow(action=action, text=text_, origin=origin, provenance=provenance, created=now)
                self.session.add(row)
            else:
                row = kept
                row.origin, row.provenance = origin, provenance
            row.rank = rank
        self.session.flush()

    def set_truth(self, owners: Sequence[tuple[int, int, float]], norms: Iterable[str]) -> None:
        """Add ground truth: (object id, agent id, p) triples and true norm texts."""
        if owners:
            self.session.execute(
                insert(TruthOwner), [{"object_id": o, "agent_id": a, "p": p} for o, a, p in owners]
            )
        known = set(self.truth_norms())
        fresh = [n for n in dict.fromkeys(norms) if n not in known]
        if fresh:
            self.session.execute(insert(TruthNorm), [{"text": n} for n in fresh])

    def truth_owners(self) -> dict[tuple[int, int], float]:
        """Ground truth: (object id, agent id) -> true ownership probability."""
        rows = self.session.execute(select(TruthOwner.object_id, TruthOwner.agent_id, TruthOwner.p))
        return {(o, a): p for o, a, p in rows}

    def truth_norms(self) -> list[str]:
        """Ground truth: the true norms, in load order."""
        return list(self.session.scalars(select(TruthNorm.text).order_by(TruthNorm.id)))


class Meta(_Part):
    """Settings, the conversation, the event log and bulk clearing."""

    def settings(self) -> dict[str, Any]:
        """Every stored setting (key -> JSON value); a copy, read once per transaction."""
        if self.tx._settings is None:
            self.tx._settings = {k: v for k, v in self.session.execute(select(Setting.key, Setting.value))}
        return dict(self.tx._settings)

    def advance(self) -> int:
        """Advance the store generation (the first statement of every write transaction); the
        transaction's ``generation`` and ``previous`` follow."""
        table = _table(Generation)
        self.session.execute(update(table).where(table.c.id == 1).values(value=table.c.value + 1))
        self.tx.generation = self.generation()
        self.tx.previous = self.tx.generation - 1
        return self.tx.generation

    def generation(self) -> int:
        """The store generation: how many write transactions were committed (or this one's number)."""
        value = self.session.scalar(select(Generation.value).where(Generation.id == 1))
        if value is None:
            raise StoreError("the store has no generation row; it is damaged (restore it from a backup)")
        return int(value)

    def set_setting(self, key: str, value: Any) -> None:
        """Store (or with ``value`` None, delete) a setting."""
        self.tx._settings = None
        row = self.session.get(Setting, key)
        if value is None:
            if row is not None:
                self.session.delete(row)
        elif row is None:
            self.session.add(Setting(key=key, value=value))
        else:
            row.value = value
        self.session.flush()

    def context(self) -> Conversation:
        """The conversation context row (created on first use)."""
        row = self.session.get(Conversation, 1)
        if row is None:
            row = Conversation(id=1)
            self.session.add(row)
            self.session.flush()
        return row

    def conversation(self) -> Talk:
        """The conversation context (empty when nothing was said or checked yet)."""
        row = self.session.get(Conversation, 1)
        if row is None:
            return Talk()
        target = self.tx.things.object_by_id(row.target_id) if row.target_id is not None else None
        return Talk(row.speaker, target.name if target else None, row.action, row.last_refusal)

    def converse(
        self, *, speaker: Any = KEEP, target: Any = KEEP, action: Any = KEEP, refusal: Any = KEEP
    ) -> Talk:
        """Update the parts of the conversation given (None clears one); returns the new context."""
        row = self.context()
        if speaker is not KEEP:
            row.speaker = speaker
        if target is not KEEP:
            row.target_id = None if target is None else self.tx.things.object(target).id
        if action is not KEEP:
            row.action = action
        if refusal is not KEEP:
            row.last_refusal = refusal
        self.session.flush()
        return self.conversation()

    def log(
        self, time: float, actor: str | None, interface: str, command: str, payload: dict[str, Any]
    ) -> Event:
        """Append an instruction to the event log."""
        row = Event(time=time, actor=actor, interface=interface, command=command, payload=payload)
        self.session.add(row)
        self.session.flush()
        return row

    def events(self, limit: int | None = None) -> list[Event]:
        """The last ``limit`` events (all when None), oldest first."""
        query = select(Event).order_by(Event.id.desc())
        if limit is not None:
            query = query.limit(limit)
        return list(reversed(list(self.session.scalars(query))))

    def clear(self, what: str) -> int:
        """Delete every permission ("perms"), rule ("rules") or the context ("context"); the count."""
        table = {"perms": Permission, "rules": RuleRow, "context": Conversation}[what]
        count = self.session.scalar(select(func.count()).select_from(table)) or 0
        self.session.execute(delete(table))
        self._expire(table)
        return int(count)


class Tx:
    """Typed access to the store inside one transaction, by concern: ``world`` (agents, areas),
    ``things`` (objects and percepts), ``touches`` (interactions), ``beliefs`` (ownership),
    ``knowledge`` (permissions, rules, ground truth) and ``meta`` (settings, conversation, event
    log)."""

    def __init__(self, session: Session) -> None:
        self.session = session
        self._settings: dict[str, Any] | None = None  # read once per transaction, kept in step
        self._agents: list[Agent] | None = None  # likewise
        #: the store generation this transaction sees (a write transaction: the one it advanced
        #: to) and, in a write transaction, the generation before it (None in a read transaction)
        self.generation: int | None = None
        self.previous: int | None = None
        self.world = World(self)
        self.things = Things(self)
        self.touches = Touches(self)
        self.beliefs = Beliefs(self)
        self.knowledge = Knowledge(self)
        self.meta = Meta(self)
