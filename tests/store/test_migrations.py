"""The schema comes from Alembic revisions only: round trips, a downgrade each, models match."""

from __future__ import annotations

import sqlite3
from pathlib import Path

from alembic import command
from alembic.autogenerate import compare_metadata
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy import create_engine

from ownctl.store.migrate import alembic_config, head_revision, known_revisions, migrations_dir
from ownctl.store.models import Base


def _tables(path: Path) -> set[str]:
    with sqlite3.connect(path) as conn:
        rows = conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'").fetchall()
    conn.close()
    return {r[0] for r in rows}


def test_upgrade_downgrade_upgrade(tmp_path: Path) -> None:
    path = tmp_path / "m.db"
    cfg = alembic_config(url=f"sqlite:///{path}")
    command.upgrade(cfg, "head")
    assert {"ownctl_store", "agents", "objects", "ownership", "permissions", "rules", "events"} <= _tables(
        path
    )
    command.downgrade(cfg, "base")
    assert _tables(path) == {"alembic_version"}
    command.upgrade(cfg, "head")
    assert "ownership" in _tables(path)


def test_models_match_the_head_revision(tmp_path: Path) -> None:
    path = tmp_path / "m.db"
    command.upgrade(alembic_config(url=f"sqlite:///{path}"), "head")
    engine = create_engine(f"sqlite:///{path}")
    with engine.connect() as conn:
        diff = compare_metadata(MigrationContext.configure(conn, opts={"compare_type": True}), Base.metadata)
    engine.dispose()
    assert diff == []


def test_every_revision_has_a_downgrade_and_named_constraints() -> None:
    script = ScriptDirectory(str(migrations_dir()))
    revisions = list(script.walk_revisions())
    assert revisions and revisions[0].revision == head_revision()
    for rev in revisions:
        source = Path(rev.path).read_text()
        assert "def downgrade()" in source
        if any(word in source for word in ("Constraint(", "ForeignKey(", "create_index(")):
            assert "op.f(" in source  # constraints carry the naming convention's names
    assert (migrations_dir() / "versions").is_dir()


def test_revision_reading_agrees_with_alembic() -> None:
    script = ScriptDirectory(str(migrations_dir()))
    assert known_revisions() == [r.revision for r in reversed(list(script.walk_revisions()))]
    assert head_revision() == script.get_current_head()
