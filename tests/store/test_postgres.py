"""The same store on PostgreSQL (a fleet of robots sharing one knowledge base).

Runs when OWNCTL_TEST_PG names a PostgreSQL server URL whose user may create databases
(`.ci/run` starts a local server and sets it); each test gets a database of its own.
"""

from __future__ import annotations

import os
import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest

from ownctl.store.migrate import head_revision
from tests.cli.conftest import Ownctl

SERVER = os.environ.get("OWNCTL_TEST_PG")
pytestmark = pytest.mark.skipif(not SERVER, reason="OWNCTL_TEST_PG is not set (no PostgreSQL server)")


@pytest.fixture
def pg_store() -> Iterator[Ownctl]:
    from sqlalchemy import create_engine, text

    assert SERVER is not None
    name = f"ownctl_{uuid.uuid4().hex[:12]}"
    admin = create_engine(SERVER, isolation_level="AUTOCOMMIT")
    with admin.connect() as conn:
        conn.execute(text(f'CREATE DATABASE "{name}"'))
    base = SERVER.rsplit("/", 1)[0]
    store = Ownctl(Path(name))  # the helper, pointed at the server instead of a file
    store.url = f"{base}/{name}"
    try:
        yield store
    finally:
        with admin.connect() as conn:
            conn.execute(text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        admin.dispose()


def test_a_robot_learns_on_postgresql(pg_store: Ownctl) -> None:
    pg_store("init")
    assert head_revision() in pg_store("db", "current").stdout
    report = pg_store.json("run", "trashAll", "--kinematic", "--seed", "2")
    assert report["loaded_world"] and report["violations"] == []
    texts = {r["text"] for r in pg_store.json("rules", "list")}
    assert "forbid trash if ownedBy any" in texts
    owner = next(s["object"] for s in report["steps"] if s["outcome"] == "skipped")
    assert pg_store.json("check", "trash", owner, code=3)["decision"] == "forbidden"
    pg_store("claim", owner, "agent9", code=1)  # a bad instruction writes nothing
    assert pg_store.json("claims", "list")


def test_a_missing_database_is_refused_not_created(pg_store: Ownctl) -> None:
    missing = Ownctl(Path("missing"))
    missing.url = pg_store.url + "_missing"
    assert missing("agent", "list", code=1).stderr.startswith("ownctl: ")


def test_a_store_with_data_upgrades_to_the_head_and_back_on_postgresql(pg_store: Ownctl) -> None:
    """The first revision's data through every revision, on PostgreSQL: beliefs, priors and touches
    survive the packed layout and come back from it (columns compared by name: PostgreSQL appends
    re-added columns at the end)."""
    from alembic import command
    from sqlalchemy import create_engine, text

    from ownctl.app import query
    from ownctl.app.context import AppContext
    from ownctl.store.migrate import alembic_config, known_revisions
    from tests.store.test_migrations import FIRST_REVISION_DATA

    cfg = alembic_config(url=pg_store.url)
    command.upgrade(cfg, known_revisions()[0])
    engine = create_engine(pg_store.url)
    columns = ("object_id, agent_id, claim_p, claim_speaker, claim_trust, claim_time, prior_p, prior_source, "
               "prior_time, posterior_p, posterior_source, posterior_time")
    try:
        with engine.begin() as conn:
            for statement in FIRST_REVISION_DATA:
                conn.execute(text(statement.replace(":", "\\:")))
            for table in ("agents", "areas", "objects", "permissions", "rules", "events", "context"):
                # explicit ids above: move each sequence past them, as inserts by ownctl would
                conn.execute(text(f"SELECT setval(pg_get_serial_sequence('{table}', 'id'), "
                                  f"(SELECT max(id) FROM {table}))"))
        command.upgrade(cfg, "0003")
        with engine.connect() as conn:
            beliefs = conn.execute(text(f"SELECT {columns} FROM ownership ORDER BY 1, 2")).all()
            touches = conn.execute(text("SELECT * FROM touches ORDER BY object_id, agent_id")).all()
        command.upgrade(cfg, "head")
        ctx = AppContext(pg_store.url, now=100.0)
        try:
            owners = {o["agent"]: (o["claim"], o["prior"]) for o in query.owners(ctx, "wallet")["owners"]}
        finally:
            ctx.close()
        assert owners == {"alexis": (1.0, 0.7), "xuan": (None, 0.25)}
        command.downgrade(cfg, "0003")
        with engine.connect() as conn:
            assert conn.execute(text(f"SELECT {columns} FROM ownership ORDER BY 1, 2")).all() == beliefs
            assert conn.execute(text("SELECT * FROM touches ORDER BY object_id, agent_id")).all() == touches
    finally:
        engine.dispose()


def test_names_in_any_script_on_postgresql(pg_store: Ownctl, tmp_path: Path) -> None:
    """Names in any script (docs/architecture.md, section 2) are stored, found and listed on
    PostgreSQL as on SQLite: the same answers from both stores."""
    lite = Ownctl(tmp_path / "lite.db")
    answers = []
    for store in (pg_store, lite):
        store("init")
        for agent in ("Jose\u0301", "\u0414\u0438\u043c\u0430", "\u0930\u093e\u092e", "alexis"):
            store("agent", "add", agent)
        store("object", "add", "ta\u0301za", "--color", "gr\u00fcn", "--pos", "0.1,0.1")
        store("object", "add", "\u5c71", "--color", "red", "--pos", "0.3,0.1")
        store("claim", "t\u00e1za", "Jos\u00e9")
        store("say", "Don't throw away \u0930\u093e\u092e's things", "--as", "alexis")
        store("say", "\u5c71 is mine", "--as", "\u0930\u093e\u092e")
        answers.append((store.json("agent", "list"), store.json("owners", "t\u00e1za")["owners"][0],
                        store.json("check", "trash", "\u5c71", code=3)["decision"],
                        [r["text"] for r in store.json("rules", "list")]))
    assert answers[0] == answers[1]
    assert answers[0][1]["agent"] == "Jos\u00e9" and answers[0][2] == "forbidden"
