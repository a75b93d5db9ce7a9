"""The store generation counter, and ownership beliefs kept together per agent.

- ``generation``: one row (``id`` 1) whose ``value`` every write transaction advances, in the same
  transaction, so that a process keeping loaded state between instructions can tell whether anyone
  wrote since it loaded (docs/architecture.md, section 6).
- ``ownership``: the primary key becomes (agent_id, object_id), with an index on object_id for
  lookups by object. On SQLite the table is stored by its key (``WITHOUT ROWID``), so an agent's
  beliefs about every object lie together and rewriting one agent's priors after a claim touches
  few pages.

Revision ID: 0003
Revises: 0002
Create Date: 2026-12-08 10:00:00
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0003"
down_revision: str | None = "0002"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

COLUMNS = ("object_id", "agent_id", "claim_p", "claim_speaker", "claim_trust", "claim_time", "prior_p",
           "prior_source", "prior_time", "posterior_p", "posterior_source", "posterior_time")


def _ownership(name: str, key: tuple[str, str], **kwargs: object) -> None:
    """Create the ownership table under ``name`` with primary key ``key``."""
    op.create_table(
        name,
        sa.Column("object_id", sa.Integer(), nullable=False),
        sa.Column("agent_id", sa.Integer(), nullable=False),
        sa.Column("claim_p", sa.Float(), nullable=True),
        sa.Column("claim_speaker", sa.String(length=64), nullable=True),
        sa.Column("claim_trust", sa.Float(), nullable=True),
        sa.Column("claim_time", sa.Float(), nullable=True),
        sa.Column("prior_p", sa.Float(), nullable=True),
        sa.Column("prior_source", sa.String(length=32), nullable=True),
        sa.Column("prior_time", sa.Float(), nullable=True),
        sa.Column("posterior_p", sa.Float(), nullable=True),
        sa.Column("posterior_source", sa.String(length=32), nullable=True),
        sa.Column("posterior_time", sa.Float(), nullable=True),
        sa.ForeignKeyConstraint(["agent_id"], ["agents.id"], name=op.f("fk_ownership_agent_id_agents"),
                                ondelete="CASCADE"),
        sa.ForeignKeyConstraint(["object_id"], ["objects.id"], name=op.f("fk_ownership_object_id_objects"),
                                ondelete="CASCADE"),
        sa.PrimaryKeyConstraint(*key, name=op.f("pk_ownership")),
        **kwargs,
    )


def _rekey(key: tuple[str, str], without_rowid: bool) -> None:
    """Give ownership the primary key ``key`` (SQLite: rebuild the table and copy the rows)."""
    if op.get_bind().dialect.name == "sqlite":
        columns = ", ".join(COLUMNS)
        _ownership("_ownership_new", key, sqlite_with_rowid=not without_rowid)
        op.execute(f"INSERT INTO _ownership_new ({columns}) SELECT {columns} FROM ownership "
                   f"ORDER BY {', '.join(key)}")
        op.drop_table("ownership")
        op.rename_table("_ownership_new", "ownership")
    else:
        op.drop_constraint(op.f("pk_ownership"), "ownership", type_="primary")
        op.create_primary_key(op.f("pk_ownership"), "ownership", list(key))


def upgrade() -> None:
    """Add the counter (at 0) and re-key ownership by agent."""
    op.create_table(
        "generation",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("value", sa.BigInteger(), nullable=False),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_generation")),
    )
    op.execute("INSERT INTO generation (id, value) VALUES (1, 0)")
    _rekey(("agent_id", "object_id"), without_rowid=True)
    op.create_index(op.f("ix_ownership_object_id"), "ownership", ["object_id"])


def downgrade() -> None:
    """Drop the counter; key ownership by object again."""
    op.drop_index(op.f("ix_ownership_object_id"), table_name="ownership")
    _rekey(("object_id", "agent_id"), without_rowid=False)
    op.drop_table("generation")
