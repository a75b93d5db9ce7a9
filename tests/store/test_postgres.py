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
