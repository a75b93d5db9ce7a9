"""The schema comes from Alembic revisions only: round trips, a downgrade each, models match."""

from __future__ import annotations

import sqlite3
from pathlib import Path

from alembic import command
from alembic.autogenerate import compare_metadata
from alembic.config import Config
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy import create_engine

from ownctl.store.migrate import alembic_config, head_revision, known_revisions, migrations_dir
from ownctl.store.models import metadata


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
        diff = compare_metadata(MigrationContext.configure(conn, opts={"compare_type": True}), metadata)
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


FIRST_REVISION_DATA = [
    "INSERT INTO agents (id, name, created) VALUES (1, 'alexis', 1.0), (2, 'xuan', 1.0)",
    "INSERT INTO areas (id, name, x0, y0, x1, y1) VALUES (1, 'home', 0, 0, 0.5, 0.5)",
    "INSERT INTO objects (id, name, color, x, y, z, extra, created) VALUES "
    "(1, 'wallet', 'brown', 0.1, 0.1, 0, '{}', 1.0), (2, 'mug', 'red', 0.8, 0.8, 0, '{}', 1.0)",
    "INSERT INTO object_categories (object_id, category) VALUES (2, 'kitchen')",
    "INSERT INTO touches (object_id, agent_id, time) VALUES (1, 1, 50.0)",
    "INSERT INTO ownership (object_id, agent_id, claim_p, claim_speaker, claim_trust, claim_time, prior_p, "
    "prior_source, prior_time) VALUES (1, 1, 1.0, 'alexis', 1.0, 60.0, 0.7, 'prediction', 60.0), "
    "(1, 2, NULL, NULL, NULL, NULL, 0.25, 'base-rate', 60.0), (2, 1, NULL, NULL, NULL, NULL, 0.3, "
    "'prediction', 60.0), (2, 2, NULL, NULL, NULL, NULL, 0.25, 'base-rate', 60.0)",
    "INSERT INTO permissions (id, action, object_id, value, speaker, time) VALUES "
    "(1, 'trash', 1, 1.0, 'alexis', 70.0), (2, 'trash', 2, 0.0, NULL, 71.0)",
    "INSERT INTO rules (id, action, text, origin, provenance, created) VALUES "
    "(1, 'trash', 'forbid trash if ownedBy any', 'given', '{\"speaker\": \"alexis\"}', 72.0)",
    "INSERT INTO settings (key, value) VALUES ('allow.trash', '[\"allow trash if isColored red\"]'), "
    "('threshold', '0.4')",
    "INSERT INTO context (id, speaker, target_id, last_refusal) VALUES "
    "(1, 'alexis', 1, '{\"action\": \"trash\", "
    "\"refusal\": {\"action\": \"trash\", \"object\": \"wallet\"}}')",
    "INSERT INTO events (id, time, actor, interface, command, payload) VALUES "
    "(1, 80.0, 'alexis', 'cli', 'claim wallet alexis', '{}')",
]


def _first_revision_store(path: Path) -> Config:
    """A SQLite store at ``path`` at the first revision, holding :data:`FIRST_REVISION_DATA`."""
    cfg = alembic_config(url=f"sqlite:///{path}")
    command.upgrade(cfg, known_revisions()[0])
    with sqlite3.connect(path) as conn:
        for statement in FIRST_REVISION_DATA:
            conn.execute(statement)
    conn.close()
    return cfg


def test_a_store_with_data_at_the_first_revision_upgrades_to_the_head_losing_nothing(tmp_path: Path) -> None:
    from ownctl.app import query
    from ownctl.app.context import AppContext

    path = tmp_path / "old.db"
    cfg = _first_revision_store(path)
    first = known_revisions()[0]
    command.upgrade(cfg, "head")
    ctx = AppContext(str(path), now=100.0)
    try:
        owners = {o["agent"]: o for o in query.owners(ctx, "wallet")["owners"]}
        assert owners["alexis"]["claim"] == 1.0 and owners["alexis"]["prior"] == 0.7
        assert [(p["action"], p["object"], p["value"]) for p in query.list_permissions(ctx)] == [
            ("trash", "wallet", 1.0), ("trash", "mug", 0.0)]
        rules = [(r["text"], r["origin"]) for r in query.list_rules(ctx)]
        assert rules == [("forbid trash if ownedBy any", "given"), ("allow trash if isColored red", "allow")]
        assert query.events(ctx)[0]["command"] == "claim wallet alexis"
        with ctx.read() as tx:
            talk = tx.meta.conversation()
            assert (talk.speaker, talk.target, talk.action) == ("alexis", "wallet", "trash")
            assert talk.refusal == {"action": "trash", "object": "wallet"}
            assert tx.meta.settings() == {"threshold": 0.4}
            seen = {p.object_id: p.seen for p in tx.knowledge.permission_rows()}
            assert seen[1] == {"color": "brown", "position": [0.1, 0.1, 0.0], "categories": [],
                               "touches": {"alexis": 50.0}}
            assert seen[2]["categories"] == ["kitchen"]
    finally:
        ctx.close()
    # and back: the first revision's forms return
    command.downgrade(cfg, first)
    with sqlite3.connect(path) as conn:
        assert conn.execute("SELECT value FROM settings WHERE key = 'allow.trash'").fetchone() == (
            '["allow trash if isColored red"]',)
        assert conn.execute("SELECT count(*) FROM rules").fetchone() == (1,)
    conn.close()


def _ownership_layout(path: Path) -> tuple[str, list[str]]:
    """The ownership table's CREATE statement and its primary key columns, in key order."""
    with sqlite3.connect(path) as conn:
        sql = conn.execute("SELECT sql FROM sqlite_master WHERE name = 'ownership'").fetchone()[0]
        info = conn.execute("PRAGMA table_info(ownership)").fetchall()
        key = [r[1] for r in sorted(info, key=lambda r: r[5]) if r[5] > 0]
    conn.close()
    return sql, key


def test_the_generation_revision_keys_beliefs_by_agent_and_back(tmp_path: Path) -> None:
    path = tmp_path / "g.db"
    cfg = _first_revision_store(path)
    command.upgrade(cfg, "0003")
    sql, key = _ownership_layout(path)
    assert key == ["agent_id", "object_id"] and "WITHOUT ROWID" in sql.upper()
    with sqlite3.connect(path) as conn:
        assert conn.execute("SELECT id, value FROM generation").fetchall() == [(1, 0)]
        rows = conn.execute("SELECT object_id, agent_id, claim_p, prior_p, prior_source FROM ownership "
                            "ORDER BY object_id, agent_id").fetchall()
        indexes = {r[1] for r in conn.execute("PRAGMA index_list(ownership)").fetchall()}
    conn.close()
    assert rows == [(1, 1, 1.0, 0.7, "prediction"), (1, 2, None, 0.25, "base-rate"),
                    (2, 1, None, 0.3, "prediction"), (2, 2, None, 0.25, "base-rate")]
    assert "ix_ownership_object_id" in indexes
    command.downgrade(cfg, "0002")
    sql, key = _ownership_layout(path)
    assert key == ["object_id", "agent_id"] and "WITHOUT ROWID" not in sql.upper()
    assert "generation" not in _tables(path)
    with sqlite3.connect(path) as conn:
        assert conn.execute("SELECT object_id, agent_id, claim_p, prior_p, prior_source FROM ownership "
                            "ORDER BY object_id, agent_id").fetchall() == rows
    conn.close()


def test_the_packed_priors_revision_moves_priors_into_chunks_and_back(tmp_path: Path) -> None:
    import numpy as np

    from ownctl.store import packed as packing

    path = tmp_path / "p.db"
    cfg = _first_revision_store(path)
    command.upgrade(cfg, "0003")
    with sqlite3.connect(path) as conn:
        before = conn.execute("SELECT * FROM ownership ORDER BY object_id, agent_id").fetchall()
    conn.close()
    command.upgrade(cfg, "0004")
    sql, key = _ownership_layout(path)
    assert key == ["agent_id", "object_id"] and "WITHOUT ROWID" in sql.upper() and "prior_p" not in sql
    with sqlite3.connect(path) as conn:
        held = conn.execute("SELECT object_id, agent_id, claim_p FROM ownership").fetchall()
        chunks = conn.execute("SELECT agent_id, chunk, p, source, time FROM priors "
                              "ORDER BY agent_id").fetchall()
    conn.close()
    assert held == [(1, 1, 1.0)]  # the only row holding a claim or a posterior
    assert [(a, c, t) for a, c, _, _, t in chunks] == [(1, 0, 60.0), (2, 0, 60.0)]
    p, source = packing.decode(chunks[0][2], packing.FLOAT), packing.decode(chunks[0][3], packing.CODE)
    assert p[1:3].tolist() == [0.7, 0.3] and packing.source_names(source[1:3]).tolist() == ["prediction"] * 2
    assert np.isnan(p[0]) and np.isnan(p[3:]).all() and not source[3:].any()
    other = packing.decode(chunks[1][3], packing.CODE)
    assert packing.source_names(other[1:3]).tolist() == ["base-rate"] * 2
    command.downgrade(cfg, "0003")
    with sqlite3.connect(path) as conn:
        after = conn.execute("SELECT * FROM ownership ORDER BY object_id, agent_id").fetchall()
    conn.close()
    assert after == before and "priors" not in _tables(path)


def test_every_write_transaction_advances_the_generation_and_a_failed_one_does_not(tmp_path: Path) -> None:
    from ownctl.app import things
    from ownctl.app.context import AppContext
    from ownctl.errors import OwnctlError

    ctx = AppContext(str(tmp_path / "s.db"), now=10.0)
    ctx.store(create=True)

    def generation() -> int:
        with ctx.read() as tx:
            return tx.meta.generation()

    try:
        start = generation()
        things.add_agent(ctx, "xuan")
        things.add_object(ctx, "mug", color="red")
        assert generation() == start + 2
        try:
            things.add_object(ctx, "mug")  # fails inside its write transaction: a duplicate name
        except OwnctlError:
            pass
        else:
            raise AssertionError("a duplicate object was accepted")
        assert generation() == start + 2  # nothing written, the generation included
        with ctx.write(None) as tx:  # even a write that logs nothing (the conversation)
            assert (tx.previous, tx.generation) == (start + 2, start + 3)
            tx.meta.converse(speaker="xuan")
        assert generation() == start + 3
    finally:
        ctx.close()
