"""Several robots on one store: concurrent writer processes lose nothing and never fail.

8 processes, each giving 25 instructions through the Python API (claims and permissions, every
instruction on its own object so that a lost write would show), against SQLite and, when
``OWNCTL_TEST_PG`` names a server, PostgreSQL. Afterwards every instruction is in the store and in
the event log.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import uuid
from pathlib import Path

import pytest

from ownctl.api import Ownctl

WRITERS = 8
EACH = 25
ROOT = Path(__file__).resolve().parents[2]

WRITER = '''
import sys
from ownctl.api import Ownctl
db, k, each = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
with Ownctl.open(db, speaker="robot%d" % k) as robot:
    for i in range(each):
        name = "o%d_%d" % (k, i)
        if i % 2:
            robot.claim(name, ("xuan", "jake")[i % 4 // 2])
        else:
            robot.permit("trash", name, forbid=bool(i % 4))
'''


def _prepare(db: str) -> None:
    with Ownctl.open(db, create=True, clock=lambda: 1000.0) as robot:
        for agent in ("xuan", "jake"):
            robot.add_agent(agent)
        robot.add_area("home", (0, 0, 0.5, 0.5))
        for k in range(WRITERS):
            for i in range(EACH):
                robot.add_object(f"o{k}_{i}", ("red", "blue")[i % 2], (0.01 * i, 0.1 * k, 0.0))


def _batch_file(folder: Path, k: int) -> str:
    """Writer ``k``'s 25 instructions as a batch file (the same instructions WRITER gives)."""
    lines = []
    for i in range(EACH):
        name = f"o{k}_{i}"
        if i % 2:
            lines.append(f"claim {name} {('xuan', 'jake')[i % 4 // 2]} --as robot{k}")
        else:
            lines.append(f"{'forbid' if i % 4 else 'allow'} trash on {name} --as robot{k}")
    path = folder / f"robot{k}.txt"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return str(path)


def _play(db: str, batch: Path | None = None) -> None:
    """Eight concurrent writers: API processes, or (``batch``: a folder for the files) ownctl batch runs."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("OWNCTL_NOW", None)
    with Ownctl.open(db) as robot:
        from ownctl.app import query

        before = len([e for e in query.events(robot._context()) if (e["actor"] or "").startswith("robot")])
    if batch is None:
        commands = [[sys.executable, "-c", WRITER, db, str(k), str(EACH)] for k in range(WRITERS)]
    else:
        cli = "from ownctl.cli.main import run; run()"
        commands = [[sys.executable, "-c", cli, "--db", db, "batch", _batch_file(batch, k)]
                    for k in range(WRITERS)]
    procs = [subprocess.Popen(c, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for c in commands]
    results = [p.communicate(timeout=120) for p in procs]
    failures = [(p.returncode, err) for p, (_, err) in zip(procs, results, strict=True) if p.returncode]
    assert not failures, failures
    with Ownctl.open(db) as robot:
        ctx = robot._context()
        from ownctl.app import query

        claims = {(c["object"], c["agent"]) for c in query.list_claims(ctx)}
        perms = {p["object"] for p in query.list_permissions(ctx)}
        events = [e for e in query.events(ctx) if (e["actor"] or "").startswith("robot")]
    expected_perms = {f"o{k}_{i}" for k in range(WRITERS) for i in range(0, EACH, 2)}
    expected_claims = {(f"o{k}_{i}", ("xuan", "jake")[i % 4 // 2]) for k in range(WRITERS)
                       for i in range(1, EACH, 2)}
    assert perms == expected_perms
    assert expected_claims <= claims
    assert len(events) - before == WRITERS * EACH


@pytest.mark.slow
def test_eight_writers_on_sqlite_lose_nothing(tmp_path: Path) -> None:
    db = str(tmp_path / "fleet.db")
    _prepare(db)
    _play(db)


@pytest.mark.slow
def test_eight_batch_runs_on_sqlite_lose_nothing(tmp_path: Path) -> None:
    db = str(tmp_path / "batch.db")
    _prepare(db)
    _play(db, tmp_path)


@pytest.mark.slow
@pytest.mark.skipif(not os.environ.get("OWNCTL_TEST_PG"), reason="OWNCTL_TEST_PG names no PostgreSQL server")
def test_eight_writers_on_postgresql_lose_nothing() -> None:
    import sqlalchemy

    base = os.environ["OWNCTL_TEST_PG"]
    name = f"ownctl_fleet_{uuid.uuid4().hex[:8]}"
    admin = sqlalchemy.create_engine(base, isolation_level="AUTOCOMMIT")
    with admin.connect() as conn:
        conn.exec_driver_sql(f"CREATE DATABASE {name}")
    url = base.rsplit("/", 1)[0] + "/" + name
    try:
        _prepare(url)
        _play(url)
        with Ownctl.open(url) as robot:
            robot.reset("all")
        _play(url, Path(tempfile.mkdtemp()))
    finally:
        with admin.connect() as conn:
            conn.exec_driver_sql(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)")
        admin.dispose()
