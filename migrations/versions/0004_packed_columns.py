"""Priors and touches packed per agent in chunks of object ids; ownership rows only where needed.

- ``priors``: one row per (agent, chunk of 4,096 object ids) holding the chunk's predicted priors
  (float64, little-endian, NaN where none is held), their sources (one byte each: 0 none,
  1 ``prediction``, 2 ``base-rate``) and the time of the chunk's last write. The priors of
  ``ownership`` move there (a chunk's time becomes the latest ``prior_time`` among its priors).
- ``ownership`` loses ``prior_p``, ``prior_source`` and ``prior_time``, and keeps only the rows that
  hold a claim or a posterior.
- ``touches``: one row per (agent, chunk) holding the chunk's last-touch times (float64, NaN where
  the agent never touched the object) instead of one row per touched (object, agent) pair.

The packing is written out here, not imported, so that this revision keeps meaning what it meant.

Revision ID: 0004
Revises: 0003
Create Date: 2026-12-15 10:00:00
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sqlalchemy as sa
from alembic import op

revision: str = "0004"
down_revision: str | None = "0003"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

CHUNK = 4096
SOURCES = {"prediction": 1, "base-rate": 2}
KEPT = ("object_id", "agent_id", "claim_p", "claim_speaker", "claim_trust", "claim_time", "posterior_p",
        "posterior_source", "posterior_time")


def _prior_columns() -> list[sa.Column]:
    """The prior columns ownership had up to revision 0003 (new Column objects each call)."""
    return [sa.Column("prior_p", sa.Float(), nullable=True),
            sa.Column("prior_source", sa.String(length=32), nullable=True),
            sa.Column("prior_time", sa.Float(), nullable=True)]


def _ownership(name: str, with_priors: bool) -> None:
    """Create the ownership table under ``name``, with or without the prior columns."""
    columns = [
        sa.Column("object_id", sa.Integer(), nullable=False),
        sa.Column("agent_id", sa.Integer(), nullable=False),
        sa.Column("claim_p", sa.Float(), nullable=True),
        sa.Column("claim_speaker", sa.String(length=64), nullable=True),
        sa.Column("claim_trust", sa.Float(), nullable=True),
        sa.Column("claim_time", sa.Float(), nullable=True),
        *(_prior_columns() if with_priors else []),
        sa.Column("posterior_p", sa.Float(), nullable=True),
        sa.Column("posterior_source", sa.String(length=32), nullable=True),
        sa.Column("posterior_time", sa.Float(), nullable=True),
    ]
    op.create_table(
        name, *columns,
        sa.ForeignKeyConstraint(["agent_id"], ["agents.id"], name=op.f("fk_ownership_agent_id_agents"),
                                ondelete="CASCADE"),
        sa.ForeignKeyConstraint(["object_id"], ["objects.id"], name=op.f("fk_ownership_object_id_objects"),
                                ondelete="CASCADE"),
        sa.PrimaryKeyConstraint("agent_id", "object_id", name=op.f("pk_ownership")),
        sqlite_with_rowid=False,
    )


def _rebuild(with_priors: bool, where: str = "") -> None:
    """SQLite: rebuild ownership with or without the prior columns, copying the kept columns of the
    rows matching ``where``."""
    columns = ", ".join(KEPT)
    op.drop_index(op.f("ix_ownership_object_id"), table_name="ownership")
    _ownership("_ownership_new", with_priors)
    op.execute(f"INSERT INTO _ownership_new ({columns}) SELECT {columns} FROM ownership {where} "
               "ORDER BY agent_id, object_id")
    op.drop_table("ownership")
    op.rename_table("_ownership_new", "ownership")
    op.create_index(op.f("ix_ownership_object_id"), "ownership", ["object_id"])


def _touch_rows() -> list[tuple[int, int, float]]:
    """The (object, agent, time) touches of revision 0003's layout."""
    return [(int(o), int(a), float(t)) for o, a, t in
            op.get_bind().execute(sa.text("SELECT object_id, agent_id, time FROM touches")).all()]


def _packed_touches() -> None:
    """Replace the touch rows by packed chunks."""
    chunks: dict[tuple[int, int], np.ndarray] = {}
    for obj, agent, time in _touch_rows():
        key = (agent, obj // CHUNK)
        if key not in chunks:
            chunks[key] = np.full(CHUNK, np.nan, dtype="<f8")
        chunks[key][obj % CHUNK] = time
    op.drop_table("touches")
    table = op.create_table(
        "touches",
        sa.Column("agent_id", sa.Integer(), nullable=False),
        sa.Column("chunk", sa.Integer(), nullable=False),
        sa.Column("times", sa.LargeBinary(), nullable=False),
        sa.ForeignKeyConstraint(["agent_id"], ["agents.id"], name=op.f("fk_touches_agent_id_agents"),
                                ondelete="CASCADE"),
        sa.PrimaryKeyConstraint("agent_id", "chunk", name=op.f("pk_touches")),
        sqlite_with_rowid=False,
    )
    if chunks:
        op.bulk_insert(table, [{"agent_id": a, "chunk": c, "times": v.tobytes()}
                               for (a, c), v in sorted(chunks.items())])


def _row_touches() -> None:
    """Replace the packed chunks by one touch row per touched (object, agent) pair."""
    rows = []
    packed = op.get_bind().execute(sa.text("SELECT agent_id, chunk, times FROM touches")).all()
    for agent, chunk, times in packed:
        values = np.frombuffer(times, dtype="<f8")
        rows += [{"object_id": int(chunk) * CHUNK + int(k), "agent_id": int(agent), "time": float(values[k])}
                 for k in np.flatnonzero(~np.isnan(values))]
    ids = {int(r[0]) for r in op.get_bind().execute(sa.text("SELECT id FROM objects")).all()}
    op.drop_table("touches")
    table = op.create_table(
        "touches",
        sa.Column("object_id", sa.Integer(), nullable=False),
        sa.Column("agent_id", sa.Integer(), nullable=False),
        sa.Column("time", sa.Float(), nullable=False),
        sa.ForeignKeyConstraint(["agent_id"], ["agents.id"], name=op.f("fk_touches_agent_id_agents"),
                                ondelete="CASCADE"),
        sa.ForeignKeyConstraint(["object_id"], ["objects.id"], name=op.f("fk_touches_object_id_objects"),
                                ondelete="CASCADE"),
        sa.PrimaryKeyConstraint("object_id", "agent_id", name=op.f("pk_touches")),
    )
    rows = sorted((r for r in rows if r["object_id"] in ids), key=lambda r: (r["object_id"], r["agent_id"]))
    if rows:
        op.bulk_insert(table, rows)


def upgrade() -> None:
    """Pack the priors and touches into chunks, then drop the priors and the empty rows from ownership."""
    _packed_touches()
    bind = op.get_bind()
    priors = op.create_table(
        "priors",
        sa.Column("agent_id", sa.Integer(), nullable=False),
        sa.Column("chunk", sa.Integer(), nullable=False),
        sa.Column("p", sa.LargeBinary(), nullable=False),
        sa.Column("source", sa.LargeBinary(), nullable=False),
        sa.Column("time", sa.Float(), nullable=False),
        sa.ForeignKeyConstraint(["agent_id"], ["agents.id"], name=op.f("fk_priors_agent_id_agents"),
                                ondelete="CASCADE"),
        sa.PrimaryKeyConstraint("agent_id", "chunk", name=op.f("pk_priors")),
        sqlite_with_rowid=False,
    )
    chunks: dict[tuple[int, int], tuple[np.ndarray, np.ndarray, list[float]]] = {}
    rows = bind.execute(sa.text("SELECT agent_id, object_id, prior_p, prior_source, prior_time "
                                "FROM ownership WHERE prior_p IS NOT NULL"))
    for agent, obj, p, source, time in rows:
        key = (int(agent), int(obj) // CHUNK)
        if key not in chunks:
            chunks[key] = (np.full(CHUNK, np.nan, dtype="<f8"), np.zeros(CHUNK, dtype=np.uint8), [])
        values, codes, times = chunks[key]
        values[int(obj) % CHUNK] = float(p)
        codes[int(obj) % CHUNK] = SOURCES.get(source or "prediction", 1)
        times.append(0.0 if time is None else float(time))
    if chunks:
        op.bulk_insert(priors, [{"agent_id": a, "chunk": c, "p": v.tobytes(), "source": s.tobytes(),
                                 "time": max(t)} for (a, c), (v, s, t) in sorted(chunks.items())])
    held = "WHERE claim_p IS NOT NULL OR posterior_p IS NOT NULL"
    if bind.dialect.name == "sqlite":
        _rebuild(with_priors=False, where=held)
    else:
        op.execute("DELETE FROM ownership WHERE claim_p IS NULL AND posterior_p IS NULL")
        for column in _prior_columns():
            op.drop_column("ownership", column.name)


def downgrade() -> None:
    """One ownership row per (object, agent) again, with the priors unpacked into it; one touch row
    per touched pair."""
    _row_touches()
    bind = op.get_bind()
    if bind.dialect.name == "sqlite":
        _rebuild(with_priors=True)
    else:
        for column in _prior_columns():
            op.add_column("ownership", column)
    op.execute("INSERT INTO ownership (object_id, agent_id) SELECT o.id, a.id "
               "FROM objects o CROSS JOIN agents a WHERE NOT EXISTS "
               "(SELECT 1 FROM ownership w WHERE w.object_id = o.id AND w.agent_id = a.id)")
    names = {code: name for name, code in SOURCES.items()}
    ids = np.array([r[0] for r in bind.execute(sa.text("SELECT id FROM objects"))], dtype=np.int64)
    update = sa.text("UPDATE ownership SET prior_p = :p, prior_source = :s, prior_time = :t "
                     "WHERE agent_id = :a AND object_id = :o")
    stored = bind.execute(sa.text("SELECT agent_id, chunk, p, source, time FROM priors"))
    for agent, chunk, p, source, time in stored.all():
        values, codes = np.frombuffer(p, dtype="<f8"), np.frombuffer(source, dtype=np.uint8)
        mine = ids[ids // CHUNK == chunk]
        params = [{"p": float(values[o % CHUNK]), "s": names.get(int(codes[o % CHUNK]), "prediction"),
                   "t": float(time), "a": int(agent), "o": int(o)}
                  for o in mine.tolist() if not np.isnan(values[o % CHUNK])]
        if params:
            bind.execute(update, params)
    op.drop_table("priors")
