"""Benchmark: a fleet of robots writing one store at once, and proof that nothing was lost.

    python benchmarks/fleet.py [--writers 1,8,32] [--instructions 25] [--backends sqlite,postgresql]
                               [--pg URL] [--json]

For each backend and each number of writers W, a fresh temporary store (a SQLite file in a temporary
folder; on PostgreSQL a temporary database, created on the server that ``--pg`` or
``OWNCTL_TEST_PG`` names and dropped afterwards) gets two agents and W x N objects, then W writer
processes each open it through the Python API (:class:`ownctl.api.Ownctl`) and, all at the same
moment (a start signal once every process has imported ownctl and opened the store), give N
instructions each: a mix of permissions (``forbid|allow trash on OBJ``), claims (``claim OBJ
AGENT``) and touches (``object touch OBJ --by AGENT`` at a time of its own), every instruction on
an object of its own, so that a lost write would show.

Reported per run: instructions per second (successful instructions over the wall time from the
first start to the last finish), the median (p50) and p99 latency of one instruction as its writer
saw it (retries on a busy store included), the instructions that failed (each with its one-line
error), and what was lost: an instruction that succeeded but whose permission, claim or touch is
not in the store, or whose line is not in the event log exactly once. Both must be 0.

PostgreSQL is skipped, with a note, when neither ``--pg`` nor ``OWNCTL_TEST_PG`` names a server
(e.g. ``postgresql+psycopg://ownctl:ownctl@localhost/postgres``; the role needs CREATEDB).
The figures depend on the machine and on what else runs on it: quote them with its load average.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
import uuid
from collections import Counter
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ownctl.app import query, things  # noqa: E402
from ownctl.app.context import AppContext  # noqa: E402
from ownctl.app.worldfile import store_world  # noqa: E402
from ownctl.world.model import ObjectSpec, World  # noqa: E402

AGENTS = ("xuan", "jake")
START = 1_000_000.0  # the store clock when the world is loaded (seconds)
TIMEOUT = 1800.0  # seconds a whole run may take before its writers are stopped


@dataclass(frozen=True)
class Instruction:
    """Writer ``k``'s instruction ``i``: its kind, object, and what it says."""

    kind: str  # "permission", "claim" or "touch"
    obj: str
    agent: str = ""
    forbid: bool = False
    at: float = 0.0

    @property
    def command(self) -> str:
        """The line the Python API logs for it (docs/architecture.md, section 6: the event log)."""
        if self.kind == "permission":
            return f"{'forbid' if self.forbid else 'allow'} trash on {self.obj}"
        if self.kind == "claim":
            return f"claim {self.obj} {self.agent}"
        return f"object touch {self.obj} --by {self.agent}"


def plan(k: int, n: int) -> list[Instruction]:
    """Writer ``k``'s ``n`` instructions: permissions, claims and touches in turn, each on its own object."""
    out = []
    for i in range(n):
        obj, agent = f"o{k}_{i}", AGENTS[(i // 3) % 2]
        if i % 3 == 0:
            out.append(Instruction("permission", obj, forbid=(i // 3) % 2 == 0))
        elif i % 3 == 1:
            out.append(Instruction("claim", obj, agent))
        else:
            out.append(Instruction("touch", obj, agent, at=START + 1000.0 * k + i))
    return out


# -- one writer process ------------------------------------------------------------------------------
def writer(db: str, k: int, n: int) -> None:
    """Open the store, say "ready", wait for "go" on stdin, give the instructions, print a JSON report."""
    from ownctl.api import Ownctl
    from ownctl.errors import OwnctlError

    latencies: list[float] = []
    failures: list[str] = []
    done: list[int] = []
    with Ownctl.open(db, speaker=f"robot{k}") as robot:
        print("ready", flush=True)
        sys.stdin.readline()
        start = time.time()
        for i, ins in enumerate(plan(k, n)):
            t0 = time.perf_counter()
            try:
                if ins.kind == "permission":
                    robot.permit("trash", ins.obj, forbid=ins.forbid)
                elif ins.kind == "claim":
                    robot.claim(ins.obj, ins.agent)
                else:
                    robot.touch(ins.obj, ins.agent, ins.at)
            except OwnctlError as exc:
                failures.append(f"robot{k} {ins.command}: {exc.message}")
                continue
            except Exception as exc:  # a traceback a user would see counts as a failure too
                failures.append(f"robot{k} {ins.command}: {type(exc).__name__}: {exc}".splitlines()[0])
                continue
            latencies.append((time.perf_counter() - t0) * 1e3)
            done.append(i)
        end = time.time()
    print(json.dumps({"start": start, "end": end, "latencies": latencies, "failures": failures,
                      "done": done}), flush=True)


# -- the stores --------------------------------------------------------------------------------------
@contextmanager
def fresh_store(backend: str, pg: str | None) -> Iterator[str]:
    """A URL of a new, empty store on ``backend``, removed afterwards."""
    if backend == "sqlite":
        with tempfile.TemporaryDirectory(prefix="ownctl-fleet-") as folder:
            yield f"sqlite:///{folder}/fleet.db"
        return
    import sqlalchemy

    assert pg is not None
    name = f"ownctl_fleet_{uuid.uuid4().hex[:10]}"
    admin = sqlalchemy.create_engine(pg, isolation_level="AUTOCOMMIT")
    try:
        with admin.connect() as conn:
            conn.exec_driver_sql(f"CREATE DATABASE {name}")
        url = sqlalchemy.engine.make_url(pg).set(database=name)
        yield url.render_as_string(hide_password=False)
    finally:
        with admin.connect() as conn:
            conn.exec_driver_sql(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)")
        admin.dispose()


def prepare(db: str, writers: int, n: int) -> None:
    """The two agents and every writer's objects, in one transaction."""
    objects = tuple(ObjectSpec(f"o{k}_{i}", ("red", "blue", "green")[i % 3], (0.02 * i, 0.02 * k, 0.0))
                    for k in range(writers) for i in range(n))
    ctx = AppContext(db, now=START, interface="bench")
    try:
        ctx.store(create=True)
        with ctx.write({"op": "world.load", "world": "fleet", "seed": 0}) as tx:
            store_world(tx, World("fleet", AGENTS, objects), ctx.now)
    finally:
        ctx.close()


# -- one run -----------------------------------------------------------------------------------------
@dataclass
class Run:
    """What one backend did with one number of writers."""

    backend: str
    writers: int
    instructions: int
    ok: int = 0
    failed: int = 0
    lost_store: int = 0
    lost_log: int = 0
    seconds: float = 0.0
    per_second: float = 0.0
    p50_ms: float = 0.0
    p99_ms: float = 0.0
    failures: list[str] = field(default_factory=list)
    losses: list[str] = field(default_factory=list)


def percentile(values: Sequence[float], q: float) -> float:
    """The ``q``-th percentile (nearest rank) of ``values`` (0 when there are none)."""
    if not values:
        return 0.0
    ranked = sorted(values)
    return ranked[min(len(ranked) - 1, max(0, math.ceil(q / 100 * len(ranked)) - 1))]


def play(db: str, writers: int, n: int) -> list[dict[str, Any]]:
    """Start ``writers`` writer processes, let them go at once, and collect their reports."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    env.pop("OWNCTL_NOW", None)
    pipe = subprocess.PIPE
    env["OWNCTL_FLEET_DB"] = db  # not on the command line, where ps would show a password
    procs = [subprocess.Popen([sys.executable, __file__, "--worker", str(k), str(n)], cwd=ROOT, env=env,
                              stdin=pipe, stdout=pipe, stderr=pipe, text=True)
             for k in range(writers)]
    try:
        for p in procs:  # every writer has imported ownctl and opened the store
            assert p.stdout is not None
            line = p.stdout.readline()
            if line.strip() != "ready":
                raise RuntimeError(f"a writer did not start: {line.strip()} {p.communicate()[1].strip()}")
        for p in procs:
            assert p.stdin is not None
            p.stdin.write("go\n")
            p.stdin.flush()
        reports = []
        for k, p in enumerate(procs):
            out, err = p.communicate(timeout=TIMEOUT)
            lines = out.strip().splitlines()
            if p.returncode or not lines:
                reports.append({"start": 0.0, "end": 0.0, "latencies": [], "done": [],
                                "failures": [f"robot{k} exited with {p.returncode}: {err.strip()[-300:]}"]})
            else:
                reports.append(json.loads(lines[-1]))
        return reports
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()


def verify(db: str, writers: int, n: int, done: list[list[int]]) -> list[str]:
    """Every succeeded instruction's effect in the store, and its line in the event log exactly once."""
    ctx = AppContext(db, now=START, interface="bench")
    try:
        claims = {(c["object"], c["agent"]) for c in query.list_claims(ctx)}
        perms = {(p["object"], p["action"]): p["value"] for p in query.list_permissions(ctx)}
        touches = {o["name"]: o["last_touch"] for o in things.list_objects(ctx)}
        logged = Counter(e["command"] for e in query.events(ctx) if e["interface"] == "api")
    finally:
        ctx.close()
    lost = []
    for k in range(writers):
        steps = plan(k, n)
        for i in done[k]:
            ins = steps[i]
            if ins.kind == "permission":
                there = perms.get((ins.obj, "trash")) == (1.0 if ins.forbid else 0.0)
            elif ins.kind == "claim":
                there = (ins.obj, ins.agent) in claims
            else:
                there = touches.get(ins.obj, {}).get(ins.agent) == ins.at
            if not there:
                lost.append(f"store: robot{k} {ins.command}")
            if logged[ins.command] != 1:  # every command names an object of its own
                lost.append(f"log ({logged[ins.command]} times): robot{k} {ins.command}")
    return lost


def run_one(backend: str, pg: str | None, writers: int, n: int) -> Run:
    """One fresh store, ``writers`` concurrent writers of ``n`` instructions, verified afterwards."""
    with fresh_store(backend, pg) as db:
        prepare(db, writers, n)
        reports = play(db, writers, n)
        lost = verify(db, writers, n, [r["done"] for r in reports])
    latencies = [x for r in reports for x in r["latencies"]]
    started = [r for r in reports if r["end"]]
    seconds = (max(r["end"] for r in started) - min(r["start"] for r in started)) if started else 0.0
    failures = [f for r in reports for f in r["failures"]]
    ok = len(latencies)
    return Run(backend, writers, writers * n, ok=ok, failed=writers * n - ok, lost_store=sum(
        x.startswith("store") for x in lost), lost_log=sum(x.startswith("log") for x in lost),
        seconds=seconds, per_second=ok / seconds if seconds else 0.0,
        p50_ms=statistics.median(latencies) if latencies else 0.0, p99_ms=percentile(latencies, 99),
        failures=failures, losses=lost)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--writers", default="1,8,32", help="numbers of concurrent writer processes")
    parser.add_argument("--instructions", type=int, default=25, metavar="N", help="instructions per writer")
    parser.add_argument("--backends", default="sqlite,postgresql")
    parser.add_argument("--pg", default=os.environ.get("OWNCTL_TEST_PG"), metavar="URL",
                        help="a PostgreSQL server URL whose role may create databases "
                        "(default: OWNCTL_TEST_PG)")
    parser.add_argument("--json", action="store_true", help="print one JSON document")
    parser.add_argument("--worker", nargs=2, metavar=("K", "N"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.worker:
        writer(os.environ["OWNCTL_FLEET_DB"], int(args.worker[0]), int(args.worker[1]))
        return 0
    counts = [int(x) for x in args.writers.split(",") if x.strip()]
    backends = [b.strip() for b in args.backends.split(",") if b.strip()]
    unknown = [b for b in backends if b not in ("sqlite", "postgresql")]
    if unknown or not counts or min(counts) < 1 or args.instructions < 1:
        parser.error(f"--backends takes sqlite,postgresql (got {args.backends!r}); --writers and "
                     "--instructions take whole numbers of at least 1")
    notes, runs = [], []
    for backend in backends:
        if backend == "postgresql" and not args.pg:
            notes.append("postgresql skipped: neither --pg nor OWNCTL_TEST_PG names a server")
            continue
        for w in counts:
            run = run_one(backend, args.pg, w, args.instructions)
            runs.append(run)
            if not args.json:
                show(run)
    doc = {"machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                       "load_average": list(os.getloadavg())},
           "instructions_per_writer": args.instructions, "runs": [asdict(r) for r in runs], "notes": notes}
    if args.json:
        print(json.dumps(doc))
    else:
        for note in notes:
            print(f"note: {note}")
        print(f"load average after the runs: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    bad = sum(r.failed + r.lost_store + r.lost_log for r in runs)
    return 1 if bad else 0


def show(run: Run) -> None:
    """One run as a line (and its failures and losses below it)."""
    print(f"{run.backend:10s} {run.writers:3d} writers x {run.instructions // run.writers} instructions: "
          f"{run.per_second:7.1f} instr/s  p50 {run.p50_ms:7.1f} ms  p99 {run.p99_ms:8.1f} ms  "
          f"({run.seconds:.1f} s)  failed {run.failed}  lost {run.lost_store} in store, "
          f"{run.lost_log} in log", flush=True)
    for line in run.failures[:10] + run.losses[:10]:
        print(f"    {line}")


if __name__ == "__main__":
    sys.exit(main())
