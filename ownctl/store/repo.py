"""The repository: every read and write the application layer makes, on one open transaction.

:class:`Tx` wraps a SQLAlchemy Core connection inside its transaction; the app layer never sees
SQL. Reads return plain rows (attributes named as the columns of ``ownctl/store/models.py``,
read-only: every change is a statement here). Lookups by name raise
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
from typing import TYPE_CHECKING, Any

import numpy as np
from sqlalchemy import Connection, Row, Table, delete, func, insert, select, update

from ownctl.errors import DuplicateName, StoreError, UnknownName
from ownctl.store import packed as packing
from ownctl.store.models import (
    agents,
    areas,
    categories,
    context,
    events,
    generation,
    objects,
    ownership,
    permissions,
    rules,
    settings,
    truth_norms,
    truth_owners,
)

if TYPE_CHECKING:
    #: A row as the repository returns it: columns by attribute (``row.name``) or by position.
    Record = Row[*tuple[Any, ...]]

CHUNK = 900  # ids per IN (...) clause, below SQLite's default limit on bound parameters
BATCH = 100_000  # rows per executemany of a bulk insert

KEEP: Any = object()


#: PostgreSQL array types of the columns that bulk updates pass as arrays.
PG_ARRAY_TYPES = {"object_id": "integer[]", "agent_id": "integer[]", "time": "float8[]"}


def _pg_array_type(column: str) -> str:
    if column in PG_ARRAY_TYPES:
        return PG_ARRAY_TYPES[column]
    return "text[]" if column.endswith(("_speaker", "_source")) else "float8[]"


def bulk_insert(conn: Connection, table: str, columns: Sequence[str], rows: Iterable[Sequence[Any]]) -> None:
    """Insert many rows of plain values (a JSON column given as its text) with one statement: COPY
    on PostgreSQL, one executemany on SQLite (no per-row parameter-dict work)."""
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


def bulk_upsert(conn: Connection, table: str, keys: Sequence[str], columns: Sequence[str],
                values: Mapping[str, Sequence[Any]]) -> None:
    """Insert or update many rows with one statement: ``INSERT ... ON CONFLICT (keys) DO UPDATE``,
    an executemany on SQLite and one ``INSERT ... SELECT FROM unnest(arrays)`` on PostgreSQL.
    ``values`` maps every key and column to a list, one entry per row."""
    if not values[keys[0]]:
        return
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


def read_packed(conn: Connection, table: PackedTable, object_ids: Sequence[int] | np.ndarray,
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
    wanted = sorted(set(chunk.tolist()))  # (np.unique would import numpy.ma: 15 ms at start-up)
    by_chunk = {c: np.flatnonzero(chunk == c) for c in wanted}
    names = [c for c, _ in table.arrays]
    where = [f"agent_id IN ({', '.join(str(a) for a in column)})"]
    if len(wanted) < CHUNK:
        where.append(f"chunk IN ({', '.join(str(c) for c in wanted)})")
    sql = (f"SELECT agent_id, chunk, {', '.join([*names, *table.scalars])} FROM {table.name} "
           f"WHERE {' AND '.join(where)}")
    for agent, c, *values in conn.exec_driver_sql(sql):
        rows = by_chunk.get(int(c))
        if rows is None:
            continue
        j, here = column[int(agent)], slot[rows]
        for (name, dtype), data in zip(table.arrays, values, strict=False):
            out[name][rows, j] = packing.decode(data, dtype)[here]
        for name, value in zip(table.scalars, values[len(names):], strict=True):
            out[name][rows, j] = value
    return out


def write_packed(conn: Connection, table: PackedTable, object_ids: Sequence[int] | np.ndarray,
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
    bulk_insert(conn, table.name, ("agent_id", "chunk", *names, *table.scalars), rows)


def clear_packed(conn: Connection, table: PackedTable, object_ids: Sequence[int],
                 agent_ids: Sequence[int]) -> None:
    """Empty the cells of ``object_ids`` x ``agent_ids`` in every array column of ``table``
    (objects being removed: their ids may be given to new objects)."""
    objects = np.repeat(np.asarray(object_ids, dtype=np.int64), len(agent_ids))
    if len(objects):
        agents = np.tile(np.asarray(agent_ids, dtype=np.int64), len(object_ids))
        write_packed(conn, table, objects, agents,
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
    """One concern of the store inside a transaction (shares the connection and the caches)."""

    def __init__(self, tx: Tx) -> None:
        self.tx = tx
        self.conn = tx.conn

    def _rows(self, query: Any) -> list[Record]:
        return list(self.conn.execute(query).all())

    def _row(self, query: Any) -> Record | None:
        return self.conn.execute(query).first()

    def _scalars(self, query: Any) -> list[Any]:
        return list(self.conn.execute(query).scalars())

    def _scalar(self, query: Any) -> Any:
        return self.conn.execute(query).scalar()

    def _insert(self, table: Table, **values: Any) -> Record:
        """Insert one row and return it as stored (defaults and the new id filled in)."""
        key = self.conn.execute(insert(table).values(**values)).inserted_primary_key
        assert key is not None
        cols = list(table.primary_key.columns)
        row = self._row(select(table).where(*(c == k for c, k in zip(cols, key, strict=True))))
        assert row is not None
        return row


class World(_Part):
    """Agents and areas: who may own things, and where things can be."""

    def agents(self) -> list[Record]:
        """Every agent, by name (read once per transaction)."""
        if self.tx._agents is None:
            self.tx._agents = self._rows(select(agents).order_by(agents.c.name))
        return list(self.tx._agents)

    def agent(self, name: str) -> Record:
        """The agent called ``name``."""
        row = self._row(select(agents).where(agents.c.name == name))
        if row is None:
            raise UnknownName("agent", name, self._scalars(select(agents.c.name)))
        return row

    def add_agent(self, name: str, now: float) -> Record:
        """A new agent (it holds no beliefs yet)."""
        self._unique(agents, name, "agent")
        self.tx._agents = None
        return self._insert(agents, name=name, created=now)

    def remove_agent(self, agent_id: int) -> None:
        """Delete an agent (its beliefs, touches and ground truth cascade)."""
        self.tx._agents = None
        self.conn.execute(delete(agents).where(agents.c.id == agent_id))

    def remove_area(self, area_id: int) -> None:
        """Delete an area."""
        self.conn.execute(delete(areas).where(areas.c.id == area_id))

    def areas(self) -> list[Record]:
        """Every area, by name."""
        return self._rows(select(areas).order_by(areas.c.name))

    def area(self, name: str) -> Record:
        """The area called ``name``."""
        row = self._row(select(areas).where(areas.c.name == name))
        if row is None:
            raise UnknownName("area", name, self._scalars(select(areas.c.name)))
        return row

    def add_area(self, name: str, box: Sequence[float]) -> Record:
        """A new box area."""
        self._unique(areas, name, "area")
        x0, y0, x1, y1 = box
        return self._insert(areas, name=name, x0=x0, y0=y0, x1=x1, y1=y1)

    def _unique(self, table: Table, name: str, kind: str) -> None:
        if self._scalar(select(table.c.id).where(table.c.name == name)) is not None:
            raise DuplicateName(f"{kind} {name!r} already exists; choose another name")


class Things(_Part):
    """Objects and their percepts: colour, position, categories and touches."""

    def objects(self) -> list[Record]:
        """Every object, in the order they were added (by id), as the paper's tasks visit them."""
        return self._rows(select(objects).order_by(objects.c.id))

    def object(self, name: str) -> Record:
        """The object called ``name``."""
        row = self._row(select(objects).where(objects.c.name == name))
        if row is None:
            raise UnknownName("object", name, self._scalars(select(objects.c.name)))
        return row

    def object_name(self, object_id: int) -> str:
        """The name of the object with primary key ``object_id``."""
        name = self._scalar(select(objects.c.name).where(objects.c.id == object_id))
        if name is None:
            raise UnknownName("object", f"#{object_id}", self._scalars(select(objects.c.name)))
        return str(name)

    def object_by_id(self, object_id: int) -> Record | None:
        """The object with primary key ``object_id``, if any."""
        return self._row(select(objects).where(objects.c.id == object_id))

    def object_ids(self) -> list[int]:
        """Every object's id, in id order."""
        return self._scalars(select(objects.c.id).order_by(objects.c.id))

    def object_table(self, object_ids: Sequence[int] | None = None) -> list[Record]:
        """Objects as plain rows (id, name, color, x, y, z), in id order; optionally only ``object_ids``."""
        c = objects.c
        query = select(c.id, c.name, c.color, c.x, c.y, c.z).order_by(c.id)
        if object_ids is None:
            return self._rows(query)
        out: list[Record] = []
        ids = list(object_ids)
        for start in range(0, len(ids), CHUNK):
            out.extend(self._rows(query.where(c.id.in_(ids[start : start + CHUNK]))))
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
        bulk_insert(self.conn, "objects", (*keys, "extra", "created"),
                    ((*(s.get(k) for k in keys), json.dumps(s.get("extra") or {}), now) for s in specs))
        return self._object_ids(names)

    def _object_ids(self, names: Sequence[str]) -> dict[str, int]:
        """name -> id of the stored objects among ``names`` (many names: one scan of the table)."""
        c = objects.c
        if len(names) > 10 * CHUNK:
            wanted = set(names)
            return {n: i for n, i in self._rows(select(c.name, c.id)) if n in wanted}
        out: dict[str, int] = {}
        for start in range(0, len(names), CHUNK):
            query = select(c.name, c.id).where(c.name.in_(names[start : start + CHUNK]))
            out.update({name: oid for name, oid in self._rows(query)})
        return out

    def remove_objects(self, object_ids: Sequence[int]) -> None:
        """Forget objects (their beliefs, touches, categories and permissions cascade)."""
        ids = list(object_ids)
        held = [a.id for a in self.tx.world.agents()]
        for packed in (PRIORS, TOUCHES):  # packed per agent: no cascade reaches them
            clear_packed(self.conn, packed, ids, held)
        for start in range(0, len(ids), CHUNK):
            chunk = ids[start : start + CHUNK]
            for table in (ownership, categories, permissions, truth_owners):
                self.conn.execute(delete(table).where(table.c.object_id.in_(chunk)))
            self.conn.execute(update(context).where(context.c.target_id.in_(chunk)).values(target_id=None))
            self.conn.execute(delete(objects).where(objects.c.id.in_(chunk)))

    def set_percepts(self, object_id: int, row: dict[str, Any]) -> None:
        """Store an object's colour and position (``row``: color, x, y, z)."""
        self.conn.execute(update(objects).where(objects.c.id == object_id)
                          .values(color=row["color"], x=row["x"], y=row["y"], z=row["z"]))

    def vocabulary(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The distinct colours and categories of every stored object, sorted."""
        colors = self._scalars(select(objects.c.color).where(objects.c.color.is_not(None)).distinct())
        cats = self._scalars(select(categories.c.category).distinct())
        return tuple(sorted(c for c in colors if c)), tuple(sorted(cats))

    def categories(self, object_ids: Sequence[int] | None = None) -> dict[int, set[str]]:
        """object id -> its categories (of every object, or only of ``object_ids``)."""
        c = categories.c
        query = select(c.object_id, c.category)
        queries = [query] if object_ids is None else [
            query.where(c.object_id.in_(list(object_ids)[start : start + CHUNK]))
            for start in range(0, len(object_ids), CHUNK)
        ]
        out: dict[int, set[str]] = {}
        for q in queries:
            for oid, cat in self._rows(q):
                out.setdefault(oid, set()).add(cat)
        return out

    def set_categories(self, object_id: int, names: Iterable[str]) -> None:
        """Replace an object's categories."""
        self.conn.execute(delete(categories).where(categories.c.object_id == object_id))
        self.add_categories([(object_id, c) for c in names])

    def add_categories(self, rows: Sequence[tuple[int, str]]) -> None:
        """Many (object id, category) memberships, at once."""
        if rows:
            self.conn.execute(insert(categories),
                              [{"object_id": o, "category": c} for o, c in sorted(set(rows))])


class Touches(_Part):
    """When each agent last interacted with each object, packed per agent (``ownctl/store/packed.py``)."""

    def table(self, object_ids: Sequence[int] | None = None,
                    agent_ids: Sequence[int] | None = None) -> tuple[list[int], list[int], np.ndarray]:
        """(object ids, agent ids, (objects, agents) absolute times of each agent's last interaction,
        NaN where it never interacted): every object and agent unless given."""
        held = self.tx.things.object_ids() if object_ids is None else list(object_ids)
        who = sorted(a.id for a in self.tx.world.agents()) if agent_ids is None else list(agent_ids)
        return held, who, read_packed(self.conn, TOUCHES, held, who)["times"]

    def pairs(
        self, agent_id: int | None = None, object_ids: Sequence[int] | None = None
    ) -> dict[tuple[int, int], float]:
        """(object id, agent id) -> absolute time of the agent's last interaction.

        Optionally only one agent's and/or only some objects' interactions.
        """
        what, who, times = self.table(object_ids, None if agent_id is None else [agent_id])
        i, j = np.nonzero(~np.isnan(times))
        return {(what[a], who[b]): float(times[a, b])
                for a, b in zip(i.tolist(), j.tolist(), strict=True)}

    def counts(self) -> dict[int, int]:
        """agent id -> how many objects it has interacted with (a removed object's cells are
        emptied, so each chunk counts its own)."""
        out: dict[int, int] = {}
        for agent, data in self.conn.exec_driver_sql(f"SELECT agent_id, {TOUCHES.arrays[0][0]} FROM touches"):
            held = int(np.count_nonzero(~np.isnan(packing.decode(data, TOUCHES.arrays[0][1]))))
            out[int(agent)] = out.get(int(agent), 0) + held
        return out

    def times(
        self, object_ids: Sequence[int] | None = None, agent_ids: Sequence[int] | None = None
    ) -> dict[int, dict[str, float]]:
        """object id -> {agent name: absolute time of its last interaction} (optionally some objects,
        and only some agents' interactions)."""
        names = {a.id: a.name for a in self.tx.world.agents()}
        what, ids, times = self.table(object_ids, agent_ids)
        who = [names[a] for a in ids]
        out: dict[int, dict[str, float]] = {}
        for oid, row in zip(what, times.tolist(), strict=True):
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
            write_packed(self.conn, TOUCHES, object_ids, agent_ids,
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
        query = select(*ownership.columns)
        if agent_ids is not None:
            query = query.where(ownership.c.agent_id.in_(list(agent_ids)))
        if object_ids is None:
            return self._rows(query)
        out: list[Any] = []
        ids = list(object_ids)
        for start in range(0, len(ids), CHUNK):
            out.extend(self._rows(query.where(ownership.c.object_id.in_(ids[start : start + CHUNK]))))
        return out

    def claimed_objects(self, besides_agents: Sequence[int] = ()) -> list[int]:
        """The ids of the objects some claim is about, over the agents other than ``besides_agents``
        (one query over the claims; their totals per agent: :meth:`claim_totals`)."""
        c = ownership.c
        query = select(c.object_id).where(c.claim_p.is_not(None)).distinct()
        if besides_agents:
            query = query.where(c.agent_id.not_in(list(besides_agents)))
        return [int(o) for (o,) in self._rows(query)]

    def claim_totals(self, besides_agents: Sequence[int] = ()) -> list[tuple[float, int]]:
        """Per agent with claims, other than ``besides_agents``: the claims' total probability and
        their count (one grouped query over the claims; the order of the agents is the query's)."""
        c = ownership.c
        query = (select(c.agent_id, func.sum(c.claim_p), func.count(c.claim_p))
                 .where(c.claim_p.is_not(None)).group_by(c.agent_id))
        if besides_agents:
            query = query.where(c.agent_id.not_in(list(besides_agents)))
        return [(float(total), int(n)) for _, total, n in self._rows(query)]

    def agents_owning(self, besides: int | None = None) -> set[int]:
        """The ids of the agents some claim says own an object (``claim_p`` at least 1/2), not
        counting the claims about object ``besides`` (one query over the claims)."""
        query = select(ownership.c.agent_id).where(ownership.c.claim_p >= 0.5).distinct()
        if besides is not None:
            query = query.where(ownership.c.object_id != besides)
        return {int(row[0]) for row in self._rows(query)}

    def priors(self, object_ids: Sequence[int], agent_ids: Sequence[int]) -> PriorTable:
        """The priors of ``object_ids`` x ``agent_ids``, read chunk by chunk (``ownctl/store/packed.py``)."""
        got = read_packed(self.conn, PRIORS, object_ids, agent_ids)
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
        write_packed(self.conn, PRIORS, object_ids, agent_ids, {"p": values, "source": codes},
                     {"time": time})

    def belief_table(
        self, object_ids: Sequence[int] | None = None, agent_id: int | None = None,
        agent_ids: Sequence[int] | None = None,
    ) -> list[BeliefRow]:
        """Every (object, agent) pair's beliefs, by object id then agent id; optionally only
        ``object_ids`` and/or one agent (or only ``agent_ids``)."""
        if agent_id is not None:
            agent_ids = [agent_id]
        who = sorted(a.id for a in self.tx.world.agents()) if agent_ids is None else sorted(set(agent_ids))
        what = self.tx.things.object_ids() if object_ids is None else sorted(set(object_ids))
        got = self.priors(what, who)
        held = {(r.object_id, r.agent_id): r for r in self.held(None if object_ids is None else what,
                                                                   None if agent_ids is None else who)}
        out: list[BeliefRow] = []
        for i, oid in enumerate(what):
            for j, aid in enumerate(who):
                p = got.p[i, j]
                prior: dict[str, Any] = {} if np.isnan(p) else {
                    "prior_p": float(p), "prior_source": got.source[i, j],
                    "prior_time": float(got.time[i, j])}
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
            bulk_upsert(self.conn, "ownership", ("agent_id", "object_id"), columns,
                        {"agent_id": agent_ids, "object_id": object_ids, **{c: values[c] for c in columns}})


class Knowledge(_Part):
    """What instructors said: permissions and rules, and the ground truth of simulated worlds."""

    def permissions(self, object_id: int | None = None) -> list[Record]:
        """Permissions (all, or one object's), oldest first."""
        query = select(permissions).order_by(permissions.c.id)
        if object_id is not None:
            query = query.where(permissions.c.object_id == object_id)
        return self._rows(query)

    def permission_table(self) -> list[Record]:
        """Every permission as a plain row (id, action, object_id, value), oldest first."""
        c = permissions.c
        return self._rows(select(c.id, c.action, c.object_id, c.value).order_by(c.id))

    def permission_rows(self, object_ids: Sequence[int] | None = None) -> list[Record]:
        """Permissions with every column (of every object, or only of ``object_ids``), oldest first."""
        query = select(permissions).order_by(permissions.c.id)
        if object_ids is None:
            return self._rows(query)
        out: list[Record] = []
        ids = list(object_ids)
        for start in range(0, len(ids), CHUNK):
            out.extend(self._rows(query.where(permissions.c.object_id.in_(ids[start : start + CHUNK]))))
        return sorted(out, key=lambda r: r.id)

    def permission_id(self, action: str, object_id: int) -> int | None:
        """The id of the permission for (action, object), if any."""
        c = permissions.c
        found = self._scalar(select(c.id).where(c.action == action, c.object_id == object_id))
        return None if found is None else int(found)

    def permission(self, permission_id: int) -> Record:
        """The permission with id ``permission_id``."""
        row = self._row(select(permissions).where(permissions.c.id == permission_id))
        if row is None:
            ids = [str(i) for i in self._scalars(select(permissions.c.id))]
            raise UnknownName("permission", str(permission_id), ids)
        return row

    def set_permission(
        self, action: str, object_id: int, value: float, speaker: str | None, now: float,
        seq: int | None = None, seen: dict[str, Any] | None = None,
    ) -> Record:
        """Insert or overwrite the permission for (action, object) with its arrival rank and the
        object's percepts when it was given; the last instruction wins."""
        held = self.permission_id(action, object_id)
        values = {"value": value, "speaker": speaker, "time": now, "seq": seq, "seen": seen}
        if held is None:
            return self._insert(permissions, action=action, object_id=object_id, **values)
        self.conn.execute(update(permissions).where(permissions.c.id == held).values(**values))
        return self.permission(held)

    def delete_permission(self, action: str, object_id: int) -> None:
        """Forget the permission for (action, object), if any."""
        c = permissions.c
        self.conn.execute(delete(permissions).where(c.action == action, c.object_id == object_id))

    def max_permission_seq(self) -> int:
        """The highest arrival rank of any permission (0 without any)."""
        c = permissions.c
        return int(self._scalar(select(func.max(func.coalesce(c.seq, c.id)))) or 0)

    def rules(self, action: str | None = None) -> list[Record]:
        """Rules (all, or one action's), by action, rank and id."""
        c = rules.c
        query = select(rules).order_by(c.action, c.rank, c.id)
        if action is not None:
            query = query.where(c.action == action)
        return self._rows(query)

    def rule(self, rule_id: int) -> Record:
        """The rule with id ``rule_id``."""
        row = self._row(select(rules).where(rules.c.id == rule_id))
        if row is None:
            ids = [str(i) for i in self._scalars(select(rules.c.id))]
            raise UnknownName("rule", str(rule_id), ids)
        return row

    def replace_rules(
        self, action: str, given: Sequence[tuple[str, str, dict[str, Any]]], now: float
    ) -> None:
        """Make ``given`` (text, origin, provenance), in this order, the rules of ``action``; kept
        rules keep their ids and creation times."""
        wanted = {t for t, _, _ in given}
        old = {row.text: row.id for row in self.rules(action)}
        gone = [i for t, i in old.items() if t not in wanted]
        if gone:
            self.conn.execute(delete(rules).where(rules.c.id.in_(gone)))
        for rank, (text_, origin, provenance) in enumerate(given):
            kept = old.get(text_)
            if kept is None:
                self.conn.execute(insert(rules).values(action=action, text=text_, origin=origin,
                                                       provenance=provenance, created=now, rank=rank))
            else:
                self.conn.execute(update(rules).where(rules.c.id == kept)
                                  .values(origin=origin, provenance=provenance, rank=rank))

    def set_truth(self, owners: Sequence[tuple[int, int, float]], norms: Iterable[str]) -> None:
        """Add ground truth: (object id, agent id, p) triples and true norm texts."""
        if owners:
            self.conn.execute(insert(truth_owners),
                              [{"object_id": o, "agent_id": a, "p": p} for o, a, p in owners])
        known = set(self.truth_norms())
        fresh = [n for n in dict.fromkeys(norms) if n not in known]
        if fresh:
            self.conn.execute(insert(truth_norms), [{"text": n} for n in fresh])

    def truth_owners(self) -> dict[tuple[int, int], float]:
        """Ground truth: (object id, agent id) -> true ownership probability."""
        c = truth_owners.c
        return {(o, a): p for o, a, p in self._rows(select(c.object_id, c.agent_id, c.p))}

    def truth_norms(self) -> list[str]:
        """Ground truth: the true norms, in load order."""
        return self._scalars(select(truth_norms.c.text).order_by(truth_norms.c.id))


class Meta(_Part):
    """Settings, the conversation, the event log and bulk clearing."""

    def settings(self) -> dict[str, Any]:
        """Every stored setting (key -> JSON value); a copy, read once per transaction."""
        if self.tx._settings is None:
            c = settings.c
            self.tx._settings = {k: v for k, v in self._rows(select(c.key, c.value))}
        return dict(self.tx._settings)

    def advance(self) -> int:
        """Advance the store generation (the first statement of every write transaction); the
        transaction's ``generation`` and ``previous`` follow."""
        c = generation.c
        self.conn.execute(update(generation).where(c.id == 1).values(value=c.value + 1))
        self.tx.generation = self.generation()
        self.tx.previous = self.tx.generation - 1
        return self.tx.generation

    def generation(self) -> int:
        """The store generation: how many write transactions were committed (or this one's number)."""
        value = self._scalar(select(generation.c.value).where(generation.c.id == 1))
        if value is None:
            raise StoreError("the store has no generation row; it is damaged (restore it from a backup)")
        return int(value)

    def set_setting(self, key: str, value: Any) -> None:
        """Store (or with ``value`` None, delete) a setting."""
        self.tx._settings = None
        c = settings.c
        self.conn.execute(delete(settings).where(c.key == key))
        if value is not None:
            self.conn.execute(insert(settings).values(key=key, value=value))

    def conversation(self) -> Talk:
        """The conversation context (empty when nothing was said or checked yet)."""
        row = self._row(select(context).where(context.c.id == 1))
        if row is None:
            return Talk()
        target = self.tx.things.object_by_id(row.target_id) if row.target_id is not None else None
        return Talk(row.speaker, target.name if target else None, row.action, row.last_refusal)

    def converse(
        self, *, speaker: Any = KEEP, target: Any = KEEP, action: Any = KEEP, refusal: Any = KEEP
    ) -> None:
        """Update the parts of the conversation given (None clears one)."""
        values: dict[str, Any] = {}
        if speaker is not KEEP:
            values["speaker"] = speaker
        if target is not KEEP:
            values["target_id"] = None if target is None else self.tx.things.object(target).id
        if action is not KEEP:
            values["action"] = action
        if refusal is not KEEP:
            values["last_refusal"] = refusal
        if self._scalar(select(context.c.id).where(context.c.id == 1)) is None:
            self.conn.execute(insert(context).values(id=1, **values))
        elif values:
            self.conn.execute(update(context).where(context.c.id == 1).values(**values))

    def log(
        self, time: float, actor: str | None, interface: str, command: str, payload: dict[str, Any]
    ) -> Record:
        """Append an instruction to the event log."""
        return self._insert(events, time=time, actor=actor, interface=interface, command=command,
                            payload=payload)

    def events(self, limit: int | None = None) -> list[Record]:
        """The last ``limit`` events (all when None), oldest first."""
        query = select(events).order_by(events.c.id.desc())
        if limit is not None:
            query = query.limit(limit)
        return list(reversed(self._rows(query)))

    def clear(self, what: str) -> int:
        """Delete every permission ("perms"), rule ("rules") or the context ("context"); the count."""
        table = {"perms": permissions, "rules": rules, "context": context}[what]
        count = self._scalar(select(func.count()).select_from(table)) or 0
        self.conn.execute(delete(table))
        return int(count)


class Tx:
    """Typed access to the store inside one transaction, by concern: ``world`` (agents, areas),
    ``things`` (objects and percepts), ``touches`` (interactions), ``beliefs`` (ownership),
    ``knowledge`` (permissions, rules, ground truth) and ``meta`` (settings, conversation, event
    log)."""

    def __init__(self, conn: Connection) -> None:
        self.conn = conn
        self._settings: dict[str, Any] | None = None  # read once per transaction, kept in step
        self._agents: list[Record] | None = None  # likewise
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
