"""A store at an older revision is upgraded when opened, in batch mode, without cascading deletes."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest

from ownctl.store import migrate
from ownctl.store.engine import locate, open_store

NEXT = '''"""Test revision: objects get a mass (the table is copied, as SQLite batch mode does)."""

import sqlalchemy as sa
from alembic import op

revision: str = "9001"
down_revision: str | None = "{head}"
branch_labels = None
depends_on = None


def upgrade() -> None:
    with op.batch_alter_table("objects", recreate="always") as batch:
        batch.add_column(sa.Column("mass", sa.Float(), nullable=True))


def downgrade() -> None:
    with op.batch_alter_table("objects", recreate="always") as batch:
        batch.drop_column("mass")
'''


@pytest.fixture
def newer_migrations(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """Our migrations plus one more revision, used instead of the real folder."""
    folder = tmp_path / "migrations"
    shutil.copytree(migrate.migrations_dir(), folder, ignore=shutil.ignore_patterns("__pycache__"))
    (folder / "versions" / "9001_mass.py").write_text(NEXT.format(head=migrate.head_revision()))
    yield folder
    migrate._graph.cache_clear()


def test_older_store_is_upgraded_on_open(
    tmp_path: Path, newer_migrations: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    location = locate(str(tmp_path / "old.db"))
    store = open_store(location, create=True)
    with store.transaction() as tx:
        agent = tx.world.add_agent("alexis", 0.0)
        wallet = tx.things.object(next(iter(tx.things.add_objects([{"name": "wallet"}], 0.0))))
        tx.beliefs.write_beliefs([{"object_id": wallet.id, "agent_id": agent.id, "claim_p": 1.0}])
        tx.knowledge.set_permission("trash", wallet.id, 1.0, None, 0.0)
    store.close()
    old_head = migrate.head_revision()

    monkeypatch.setattr(migrate, "migrations_dir", lambda: newer_migrations)
    migrate._graph.cache_clear()
    assert migrate.head_revision() == "9001"
    upgraded = open_store(location)
    assert upgraded.previous == old_head and upgraded.revision() == "9001"
    with upgraded.transaction(write=False) as tx:  # nothing cascaded away while objects was copied
        assert [b.claim_p for b in tx.beliefs.ownership()] == [1.0]
        assert len(tx.knowledge.permissions()) == 1
    with upgraded.engine.connect() as conn:
        assert "mass" in {row[1] for row in conn.exec_driver_sql("PRAGMA table_info(objects)")}
        assert conn.exec_driver_sql("PRAGMA foreign_keys").scalar() == 1
    upgraded.close()
