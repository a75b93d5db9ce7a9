"""Two robots on one store see each other's teaching on their next decision.

Robot A is a separate process that keeps its store open through the Python API and answers
``check`` lines read from stdin (and takes teaching lines too); robot B is this test's own
long-lived :class:`~ownctl.api.Ownctl`. What one is told (an object's permission, a norm, a claim),
the other obeys on its next check, through the API and through ``ownctl check``. A long-running
``ownctl batch -`` fed line by line sees what another writer taught between two of its lines, and
the other writer sees what the batch was told. Runs on SQLite and, when ``OWNCTL_TEST_PG`` names a
server, on PostgreSQL (docs/architecture.md, section 6).
"""

from __future__ import annotations

import json
import os
import select
import subprocess
import sys
import time
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

import pytest

from ownctl.api import Ownctl

ROOT = Path(__file__).resolve().parents[2]
CLI = "from ownctl.cli.main import run; run()"
TIMEOUT = 60.0

ROBOT = '''
import json, sys
from ownctl.api import Ownctl
with Ownctl.open(sys.argv[1], speaker="robotA") as robot:
    for line in iter(sys.stdin.readline, ""):
        verb, *rest = line.split()
        if verb == "check":
            data = robot.check(*rest).data
            out = {"decision": data["decision"], "decided_by": data["decided_by"]}
        elif verb == "forbid-on":
            out = robot.permit(rest[0], rest[1], forbid=True).data
        elif verb == "claim":
            out = robot.claim(rest[0], rest[1]).data
        else:
            out = robot.forbid(rest[0], " ".join(rest[1:])).data
        print(json.dumps(out), flush=True)
'''


def _env() -> dict[str, str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("OWNCTL_NOW", None)
    env.pop("OWNCTL_DB", None)
    return env


def _prepare(db: str) -> None:
    with Ownctl.open(db, create=True) as setup:
        for agent in ("xuan", "jake"):
            setup.add_agent(agent)
        # far apart and each of its own colour, so that one claim predicts little about the others
        for name, color, x, y in (("mug", "red", 0.0, 0.0), ("cup", "blue", 0.9, 0.9),
                                  ("pen", "green", 0.0, 0.9), ("book", "white", 0.9, 0.0),
                                  ("wallet", "brown", 0.45, 0.45), ("key", "black", 0.2, 0.6)):
            setup.add_object(name, color, (x, y, 0.0))


class Line:
    """A process spoken to one line at a time: each line sent gets one line back (with a deadline)."""

    def __init__(self, command: list[str]) -> None:
        self.proc = subprocess.Popen(command, cwd=ROOT, env=_env(), stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, bufsize=1)

    def ask(self, line: str) -> dict[str, Any]:
        """Send ``line``, return the JSON document of the one line it answers."""
        stdin, stdout = self.proc.stdin, self.proc.stdout
        assert stdin is not None and stdout is not None
        stdin.write(line + "\n")
        stdin.flush()
        return json.loads(_readline(stdout, self.proc))

    def finish(self) -> str:
        """Close stdin and return what the process printed on stderr; it must exit with 0."""
        _, err = self.proc.communicate(timeout=TIMEOUT)
        assert self.proc.returncode == 0, err
        return err


def _readline(stream: IO[str], proc: subprocess.Popen[str]) -> str:
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        ready, _, _ = select.select([stream], [], [], 0.5)
        if ready:
            line = stream.readline()
            if line:
                return line
        if proc.poll() is not None:
            break
    proc.kill()
    raise AssertionError(f"no answer (exit {proc.poll()}): {proc.stderr.read() if proc.stderr else ''}")


def _cli_check(db: str, action: str, obj: str) -> str:
    result = subprocess.run([sys.executable, "-c", CLI, "--db", db, "check", action, obj, "--json"],
                            cwd=ROOT, env=_env(), capture_output=True, text=True, timeout=TIMEOUT)
    assert result.returncode in (0, 3), result.stderr
    decision = json.loads(result.stdout)["decision"]
    assert result.returncode == (3 if decision == "forbidden" else 0)
    return str(decision)


def _teach_and_obey(db: str) -> None:
    """B teaches, A obeys at once; A teaches, B obeys at once (both keep the store open)."""
    a = Line([sys.executable, "-c", ROBOT, db])
    with Ownctl.open(db, speaker="robotB") as b:
        try:
            # an object's permission
            assert a.ask("check trash mug")["decision"] == "permitted"
            b.permit("trash", "mug", forbid=True)
            assert a.ask("check trash mug") == {"decision": "forbidden", "decided_by": "permission"}
            assert _cli_check(db, "trash", "mug") == "forbidden"
            # a norm, about an object claimed before it was said
            b.claim("pen", "xuan")
            assert a.ask("check pickUp pen")["decision"] == "permitted"
            b.forbid("pickUp", "if ownedBy xuan")
            assert a.ask("check pickUp pen") == {"decision": "forbidden", "decided_by": "rules"}
            # a claim, under the norm now known
            assert a.ask("check pickUp cup")["decision"] == "permitted"
            b.claim("cup", "xuan")
            assert a.ask("check pickUp cup") == {"decision": "forbidden", "decided_by": "rules"}
            assert _cli_check(db, "pickUp", "cup") == "forbidden"
            # the other way round: A is told, B (which has checked before) obeys on its next check
            assert not b.check("collect", "book").forbidden
            a.ask("forbid-on collect book")
            assert b.check("collect", "book").forbidden
            assert not b.check("replace", "wallet").forbidden
            a.ask("forbid replace if ownedBy jake")
            a.ask("claim wallet jake")
            assert b.check("replace", "wallet").data["decided_by"] == "rules"
            assert b.check("replace", "wallet").forbidden
        finally:
            a.finish()


def _batch_sees_other_writer(db: str) -> None:
    """A long-running ``ownctl batch -`` sees rules taught by another writer between its lines."""
    batch = Line([sys.executable, "-c", CLI, "--db", db, "batch", "-"])
    with Ownctl.open(db, speaker="robotB") as b:
        try:
            assert batch.ask("check wait key --json")["decision"] == "permitted"
            b.forbid("wait", "if ownedBy jake")
            b.claim("key", "jake")
            step = batch.ask("check wait key --json")
            assert (step["decision"], step["decided_by"]) == ("forbidden", "rules")
            assert any(r["text"] == "forbid wait if ownedBy jake" for s in step["steps"] for r in s["rules"])
            b.permit("moveTo", "key", forbid=True)
            assert batch.ask("check moveTo key --json")["decided_by"] == "permission"
            # and the other writer sees at once what the batch was told
            assert not b.check("goHome", "key").forbidden
            batch.ask("forbid goHome on key --json --as robotA")
            assert b.check("goHome", "key").forbidden
        finally:
            batch.finish()
    with Ownctl.open(db) as reader:
        events = [e["command"] for e in _events(reader)]
    assert "forbid goHome on key --json --as robotA" in events


def _events(robot: Ownctl) -> list[dict[str, Any]]:
    from ownctl.app import query

    return list(query.events(robot._context()))


@pytest.mark.slow
def test_two_robots_see_each_other_on_sqlite(tmp_path: Path) -> None:
    db = str(tmp_path / "two.db")
    _prepare(db)
    _teach_and_obey(db)


def test_batch_sees_another_writer_on_sqlite(tmp_path: Path) -> None:
    db = str(tmp_path / "batch.db")
    _prepare(db)
    _batch_sees_other_writer(db)


@pytest.fixture
def pg_store() -> Iterator[str]:
    """A fresh PostgreSQL database, dropped afterwards."""
    import sqlalchemy

    base = os.environ["OWNCTL_TEST_PG"]
    name = f"ownctl_two_{uuid.uuid4().hex[:8]}"
    admin = sqlalchemy.create_engine(base, isolation_level="AUTOCOMMIT")
    with admin.connect() as conn:
        conn.exec_driver_sql(f"CREATE DATABASE {name}")
    try:
        yield base.rsplit("/", 1)[0] + "/" + name
    finally:
        with admin.connect() as conn:
            conn.exec_driver_sql(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)")
        admin.dispose()


@pytest.mark.slow
@pytest.mark.skipif(not os.environ.get("OWNCTL_TEST_PG"), reason="OWNCTL_TEST_PG names no PostgreSQL server")
def test_two_robots_and_a_batch_see_each_other_on_postgresql(pg_store: str) -> None:
    _prepare(pg_store)
    _teach_and_obey(pg_store)
    _batch_sees_other_writer(pg_store)
