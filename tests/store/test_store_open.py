"""Opening stores: where they are, creating them, refusing foreign or too-new databases."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

from ownctl.errors import DuplicateName, StoreError, UnknownName
from ownctl.store.engine import Location, locate, open_store
from ownctl.store.migrate import head_revision


def _new(tmp_path: Path) -> Location:
    return locate(str(tmp_path / "s.db"))


def test_locate_forms(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    default = locate(None)
    assert default.path == tmp_path / "data" / "ownctl" / "ownctl.db" and not default.explicit
    bare = locate("rel.db")
    assert bare.explicit and bare.path == Path("rel.db").resolve() and bare.url.startswith("sqlite:///")
    url = locate(f"sqlite:///{tmp_path}/u.db")
    assert url.path == tmp_path / "u.db"
    assert locate("postgresql://u:secret@host/db").display == "postgresql://u:***@host/db"
    with pytest.raises(StoreError, match="cannot use database"):
        open_store(locate("nosuch://"))


def test_explicit_store_is_created_only_on_request(tmp_path: Path) -> None:
    location = _new(tmp_path)
    with pytest.raises(StoreError, match="ownctl --db .* init"):
        open_store(location)
    assert not location.path.exists()  # type: ignore[union-attr]
    store = open_store(location, create=True)
    assert store.created and store.revision() == head_revision()
    store.close()
    again = open_store(location)
    assert not again.created and again.previous == head_revision()
    again.close()


def test_default_store_is_created_on_first_use(tmp_path: Path) -> None:
    path = tmp_path / "deep" / "dir" / "ownctl.db"
    store = open_store(Location(f"sqlite:///{path}", path, explicit=False))
    assert store.created and path.exists()
    store.close()


def test_in_memory_store(tmp_path: Path) -> None:
    store = open_store(locate("sqlite://"))
    with store.transaction() as tx:
        tx.world.add_agent("a", 0.0)
    with store.transaction(write=False) as tx:
        assert [a.name for a in tx.world.agents()] == ["a"]
    store.close()


def _bytes(path: Path) -> bytes:
    return path.read_bytes()


def test_foreign_sqlite_database_is_refused_untouched(tmp_path: Path) -> None:
    path = tmp_path / "other.db"
    with sqlite3.connect(path) as conn:
        conn.execute("CREATE TABLE recipes (id INTEGER PRIMARY KEY, name TEXT)")
        conn.execute("INSERT INTO recipes (name) VALUES ('soup')")
    conn.close()
    before = _bytes(path)
    for create in (False, True):
        with pytest.raises(StoreError, match="not an ownctl store.*recipes"):
            open_store(locate(str(path)), create=create)
    assert _bytes(path) == before
    assert not Path(f"{path}-wal").exists()


def test_junk_file_is_refused_untouched(tmp_path: Path) -> None:
    path = tmp_path / "junk.db"
    path.write_bytes(b"\x00\x01 definitely not sqlite " * 50)
    before = _bytes(path)
    with pytest.raises(StoreError, match="not an SQLite database"):
        open_store(locate(str(path)), create=True)
    assert _bytes(path) == before


def test_directory_is_refused(tmp_path: Path) -> None:
    with pytest.raises(StoreError, match="not a file"):
        open_store(locate(str(tmp_path)))


def test_newer_schema_is_refused_untouched(tmp_path: Path) -> None:
    location = _new(tmp_path)
    open_store(location, create=True).close()
    with sqlite3.connect(location.path) as conn:  # type: ignore[arg-type]
        conn.execute("UPDATE alembic_version SET version_num = 'f00dfeed'")
    conn.close()
    before = _bytes(location.path)  # type: ignore[arg-type]
    with pytest.raises(StoreError, match="newer than this ownctl"):
        open_store(location)
    assert _bytes(location.path) == before  # type: ignore[arg-type]


def test_connection_pragmas(tmp_path: Path) -> None:
    store = open_store(_new(tmp_path), create=True)
    with store.engine.connect() as conn:
        assert conn.exec_driver_sql("PRAGMA foreign_keys").scalar() == 1
        assert conn.exec_driver_sql("PRAGMA busy_timeout").scalar() == 30_000
        assert conn.exec_driver_sql("PRAGMA journal_mode").scalar() == "wal"
    store.close()


def test_a_failing_transaction_writes_nothing(tmp_path: Path) -> None:
    store = open_store(_new(tmp_path), create=True)
    with pytest.raises(DuplicateName):
        with store.transaction() as tx:
            tx.world.add_agent("a", 0.0)
            tx.meta.log(0.0, None, "cli", "agent add a", {})
            tx.world.add_agent("a", 0.0)
    with store.transaction(write=False) as tx:
        assert tx.world.agents() == [] and tx.meta.events() == []
        with pytest.raises(UnknownName, match="known agents: \\(none yet\\)"):
            tx.world.agent("a")
    store.close()


def test_beliefs_are_written_in_bulk_and_cascade(tmp_path: Path) -> None:
    store = open_store(_new(tmp_path), create=True)
    with store.transaction() as tx:
        agents = [tx.world.add_agent(f"agent{i}", 0.0) for i in range(3)]
        ids = tx.things.add_objects([{"name": f"block{i}", "color": "red"} for i in range(200)], 0.0)
        objects = [tx.things.object(name) for name in ids]
        rows = [
            {"object_id": o.id, "agent_id": agents[1].id, "prior_p": 0.3, "prior_source": "prediction"}
            for o in objects
        ]
        tx.beliefs.write_beliefs(rows)
    with store.transaction() as tx:
        beliefs = tx.beliefs.ownership(agent_id=agents[1].id)
        assert len(beliefs) == 200 and {b.prior_p for b in beliefs} == {0.3}
        assert len(tx.beliefs.ownership()) == 600
        tx.things.remove_objects([tx.things.object("block0").id])
        assert len(tx.beliefs.ownership()) == 597
        tx.beliefs.write_beliefs([{"object_id": b.object_id, "agent_id": b.agent_id, "prior_p": None}
                                  for b in tx.beliefs.ownership()])
        assert all(b.prior_p is None for b in tx.beliefs.ownership())
    store.close()


def test_uncreatable_location_is_a_user_error(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(StoreError, match="cannot create store"):
        open_store(locate(str(blocker / "sub" / "s.db")), create=True)


def test_the_repository_is_split_by_concern() -> None:
    """A transaction offers a few cohesive parts, none a grab bag of every query."""
    import inspect

    from ownctl.store import repo

    parts = {"world": repo.World, "things": repo.Things, "touches": repo.Touches, "beliefs": repo.Beliefs,
             "knowledge": repo.Knowledge, "meta": repo.Meta}
    for name, part in parts.items():
        public = [m for m, _ in inspect.getmembers(part, inspect.isfunction) if not m.startswith("_")]
        assert 0 < len(public) <= 16, (name, public)
    assert [m for m, _ in inspect.getmembers(repo.Tx, inspect.isfunction) if not m.startswith("_")] == []
