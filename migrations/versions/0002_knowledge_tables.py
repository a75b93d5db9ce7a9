"""Knowledge in its own tables: permission percept snapshots and arrival order, rule order, allow
norms as rules, the conversation's current action in its own column.

- ``permissions.seq`` (arrival rank; a permission given again moves to the end) and
  ``permissions.seen`` (the object's percepts when the permission was given: colour, position,
  categories and touch times). Existing permissions get their id as rank and their object's
  current percepts (the best that is known of them).
- ``rules.rank`` (the learner's order within an action); existing rules get their id.
- Allow norms, kept until now as the settings ``allow.ACTION`` (lists of norm texts), become rules
  of origin ``allow`` (their text is the allow norm's, ``allow ACTION if ...``).
- ``context.action``: the current action, until now packed into ``last_refusal`` as
  ``{"action": ..., "refusal": ...}``; ``last_refusal`` then holds only the refusal.

Revision ID: 0002
Revises: 0001
Create Date: 2026-12-01 13:30:00
"""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from typing import Any

import sqlalchemy as sa
from alembic import op

revision: str = "0002"
down_revision: str | None = "0001"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

ALLOW_PREFIX = "allow."


def _json(value: Any) -> Any:
    """A JSON column's value as Python (drivers return text or already decoded values)."""
    return json.loads(value) if isinstance(value, str) else value


def _snapshots(conn: sa.Connection) -> dict[int, dict[str, Any]]:
    """object id -> its current percepts in the ``seen`` shape."""
    out: dict[int, dict[str, Any]] = {}
    for oid, color, x, y, z in conn.execute(sa.text("SELECT id, color, x, y, z FROM objects")):
        position = None if x is None or y is None else [x, y, 0.0 if z is None else z]
        out[oid] = {"color": color, "position": position, "categories": [], "touches": {}}
    for oid, cat in conn.execute(sa.text("SELECT object_id, category FROM object_categories ORDER BY category")):
        out[oid]["categories"].append(cat)
    names = dict(conn.execute(sa.text("SELECT id, name FROM agents")).all())
    for oid, aid, t in conn.execute(sa.text("SELECT object_id, agent_id, time FROM touches")):
        out[oid]["touches"][names[aid]] = t
    return out


def upgrade() -> None:
    """Add the columns, then move the data into them."""
    with op.batch_alter_table("permissions") as batch:
        batch.add_column(sa.Column("seq", sa.Integer(), nullable=True))
        batch.add_column(sa.Column("seen", sa.JSON(), nullable=True))
    with op.batch_alter_table("rules") as batch:
        batch.add_column(sa.Column("rank", sa.Integer(), nullable=True))
    with op.batch_alter_table("context") as batch:
        batch.add_column(sa.Column("action", sa.String(length=32), nullable=True))

    conn = op.get_bind()
    seen = _snapshots(conn)
    perms = sa.table("permissions", sa.column("id", sa.Integer), sa.column("seq", sa.Integer),
                     sa.column("seen", sa.JSON))
    for pid, oid in conn.execute(sa.text("SELECT id, object_id FROM permissions")).all():
        conn.execute(perms.update().where(perms.c.id == pid).values(seq=pid, seen=seen.get(oid)))
    conn.execute(sa.text("UPDATE rules SET rank = id"))

    rules = sa.table("rules", sa.column("action", sa.String), sa.column("text", sa.Text),
                     sa.column("origin", sa.String), sa.column("provenance", sa.JSON),
                     sa.column("created", sa.Float), sa.column("rank", sa.Integer))
    settings = conn.execute(sa.text("SELECT key, value FROM settings WHERE key LIKE 'allow.%'")).all()
    top = conn.execute(sa.text("SELECT COALESCE(MAX(id), 0) FROM rules")).scalar() or 0
    for key, value in settings:
        action = key[len(ALLOW_PREFIX):]
        for text in _json(value) or []:
            rule_text = text if text.startswith("allow ") else "allow " + text
            exists = conn.execute(sa.text("SELECT 1 FROM rules WHERE action = :a AND text = :t"),
                                  {"a": action, "t": rule_text}).first()
            if exists is None:
                top += 1
                conn.execute(rules.insert().values(action=action, text=rule_text, origin="allow",
                                                   provenance={"given": text}, created=time.time(),
                                                   rank=top))
        conn.execute(sa.text("DELETE FROM settings WHERE key = :k"), {"k": key})

    context = sa.table("context", sa.column("id", sa.Integer), sa.column("action", sa.String),
                       sa.column("last_refusal", sa.JSON))
    for cid, raw in conn.execute(sa.text("SELECT id, last_refusal FROM context")).all():
        packed = _json(raw) or {}
        if "object" in packed:  # a bare refusal record stands for both
            action, refusal = packed.get("action"), packed
        else:
            action, refusal = packed.get("action"), packed.get("refusal")
        conn.execute(context.update().where(context.c.id == cid).values(action=action, last_refusal=refusal))


def downgrade() -> None:
    """Pack the action back into ``last_refusal``, allow rules back into settings, drop the columns."""
    conn = op.get_bind()
    context = sa.table("context", sa.column("id", sa.Integer), sa.column("last_refusal", sa.JSON))
    for cid, action, raw in conn.execute(sa.text("SELECT id, action, last_refusal FROM context")).all():
        conn.execute(context.update().where(context.c.id == cid)
                     .values(last_refusal={"action": action, "refusal": _json(raw)}))
    allows: dict[str, list[str]] = {}
    for action, text in conn.execute(
        sa.text("SELECT action, text FROM rules WHERE origin = 'allow' ORDER BY rank, id")
    ).all():
        allows.setdefault(action, []).append(text)
    settings = sa.table("settings", sa.column("key", sa.String), sa.column("value", sa.JSON))
    for action, texts in allows.items():
        conn.execute(sa.text("DELETE FROM settings WHERE key = :k"), {"k": ALLOW_PREFIX + action})
        conn.execute(settings.insert().values(key=ALLOW_PREFIX + action, value=texts))
    conn.execute(sa.text("DELETE FROM rules WHERE origin = 'allow'"))
    with op.batch_alter_table("context") as batch:
        batch.drop_column("action")
    with op.batch_alter_table("rules") as batch:
        batch.drop_column("rank")
    with op.batch_alter_table("permissions") as batch:
        batch.drop_column("seen")
        batch.drop_column("seq")
