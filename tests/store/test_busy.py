"""A store another writer holds: bounded retries with backoff, then one line; database errors a user
can cause are one-line errors."""

from __future__ import annotations

import sqlite3
import threading
import time
from pathlib import Path

import pytest

from ownctl.app import things
from ownctl.app.context import ATTEMPTS, AppContext
from ownctl.errors import BadValue, StoreBusy, StoreError
from ownctl.store.engine import database_error, locate


def test_a_busy_instruction_is_tried_again_then_succeeds() -> None:
    ctx = AppContext(None, now=0.0)
    calls: list[int] = []
    waits: list[float] = []

    def flaky() -> str:
        calls.append(1)
        if len(calls) < 3:
            raise StoreBusy("store x is busy")
        return "done"

    assert ctx.retrying(flaky, sleep=waits.append) == "done"
    assert len(calls) == 3 and len(waits) == 2 and waits[1] > waits[0] * 0.5


def test_it_gives_up_after_a_bounded_number_of_tries_in_one_line() -> None:
    ctx = AppContext(None, now=0.0)
    waits: list[float] = []

    def busy() -> None:
        raise StoreBusy("store x is busy: another writer holds it (database is locked)")

    with pytest.raises(StoreBusy) as caught:
        ctx.retrying(busy, sleep=waits.append)
    assert len(waits) == ATTEMPTS - 1 and sum(waits) < 30
    assert "\n" not in str(caught.value) and "gave up after" in str(caught.value)


class _Orig(Exception):
    def __init__(self, message: str, sqlstate: str | None = None) -> None:
        super().__init__(message)
        self.sqlstate = sqlstate


@pytest.mark.parametrize(("message", "state", "kind"), [
    ("database is locked", None, StoreBusy),
    ("deadlock detected", "40P01", StoreBusy),
    ("could not serialize access", "40001", StoreBusy),
    ("attempt to write a readonly database", None, StoreError),
    ("value too long for type character varying(64)", "22001", BadValue),
])
def test_database_errors_become_one_line_user_errors(message: str, state: str | None, kind: type) -> None:
    from sqlalchemy.exc import DBAPIError

    error = database_error(DBAPIError("UPDATE ...", {}, _Orig(message, state)), locate(None))
    assert type(error) is kind and message in str(error) and "\n" not in str(error)


def test_a_writer_waits_for_another_that_holds_the_store_briefly(tmp_path: Path) -> None:
    db = tmp_path / "s.db"
    ctx = AppContext(str(db), now=1.0)
    ctx.store(create=True)
    holder = sqlite3.connect(db, isolation_level=None, check_same_thread=False)
    holder.execute("BEGIN IMMEDIATE")
    release = threading.Timer(0.3, lambda: holder.execute("COMMIT"))
    release.start()
    start = time.perf_counter()
    things.add_agent(ctx, "xuan")
    assert time.perf_counter() - start >= 0.25
    release.join()
    holder.close()
    assert [a["name"] for a in things.list_agents(ctx)] == ["xuan"]
    ctx.close()


def test_a_read_only_store_is_one_line_and_unchanged(tmp_path: Path) -> None:
    db = tmp_path / "ro.db"
    ctx = AppContext(str(db), now=1.0)
    ctx.store(create=True)
    things.add_agent(ctx, "xuan")
    ctx.close()
    before = db.read_bytes()
    ro = AppContext(f"sqlite:///file:{db}?mode=ro&uri=true", now=2.0)
    with pytest.raises(StoreError) as caught:
        things.add_agent(ro, "jake")
    ro.close()
    assert "\n" not in str(caught.value)
    assert db.read_bytes() == before
