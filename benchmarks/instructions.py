"""Benchmark: loading a world and the latency of one instruction through the Python API.

    python benchmarks/instructions.py [--objects N] [--agents K] [--sizes 20,1000,10000]
                                      [--backend sqlite|postgresql] [--url URL] [--repeats 100]
                                      [--seed 0] [--profile slowest|all|none] [--json] [--quick]

A robot's control loop keeps one :class:`ownctl.api.Ownctl` open and calls it for every
instruction it hears and every decision it makes; the Ownctl keeps the loaded Mind between calls
while no other process writes (``docs/architecture.md``, section 6). For each size this

* creates an empty store (a temporary SQLite file, or a temporary database on the PostgreSQL
  server of ``--url`` / ``OWNCTL_TEST_PG`` with ``--backend postgresql``);
* times ``Ownctl.load_world`` of a world file whose ``[generator]`` section draws the paper's
  blocks world with that many objects and ``--agents`` agents (what ``ownctl world load FILE``
  does: the objects, their percepts and every agent's touches, the beliefs, the ground truth);
* states the world's true norms (``forbid ACTION if ...``; ``--norms learned``: no norms, rules
  are induced from the permissions), gives untimed warm-up instructions, then times ``--repeats``
  of each operation, interleaved as an
  instructor would give them: ``permit`` (forbid/allow ACTION on a random object with the true
  answer of the paper's norms), ``claim`` (the true owner of a random object, or "not mine" for an
  unowned one) and ``check`` (a random action on a random object, without recording the turn).

Sizes: ``--sizes`` (default 20, 1,000 and 10,000), up to and including ``--objects`` when given
(``--objects 100000`` reports 20 / 1,000 / 10,000 / 100,000). Without ``--agents`` the 20-object
world is the paper's file (3 agents) and larger ones have 10 agents; with it, every size has that
many. It prints median, p90 and maximum per size and operation, the load time, the growth exponent of each
operation's median (least-squares slope of log median on log objects over the sizes of 1,000 and
more), and pass/fail against the targets: at 20 objects a permission and a claim at most 10 ms, at
1,000 a permission at most 20 ms and a claim at most 100 ms, at 100,000 objects loading at most
30 s, a claim at most 200 ms, a permission and a check at most 20 ms (medians). The machine's load
average is printed with the figures, since other processes change them. ``--profile`` adds a
cProfile of the slowest operation (or of each) at each size, on extra instructions after the timed
ones.

A check that a learned rule decides also reports how sure the posterior over rule sets is of that
rule (``rule_support``); computing that posterior dominates such a check (``--norms learned``
shows it), whatever the store.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import json
import os
import platform
import pstats
import sys
import tempfile
import time
import uuid
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ownctl.api import Ownctl  # noqa: E402
from ownctl.app.context import AppContext  # noqa: E402
from ownctl.app.worldfile import read_world  # noqa: E402
from ownctl.experiment.truth import true_rules  # noqa: E402
from ownctl.logic.prob import p_forbidden  # noqa: E402
from ownctl.world.generator import PAPER_AREAS, PAPER_NORMS  # noqa: E402
from ownctl.world.model import World, make_frame  # noqa: E402

OPS = ("permit", "claim", "check")
#: (objects, op) -> target (median ms; "load": seconds)
TARGETS = {(20, "permit"): 10.0, (20, "claim"): 10.0, (1000, "permit"): 20.0, (1000, "claim"): 100.0,
           (100_000, "load"): 30.0, (100_000, "claim"): 200.0, (100_000, "permit"): 20.0,
           (100_000, "check"): 20.0}
LADDER = (20, 1000, 10_000)
START = 1_000_000.0  # the store clock at the start (seconds)
ACTIONS = ("trash", "pickUp", "collect")


def world_file(folder: str, n: int, agents: int | None) -> str:
    """A world file for ``n`` objects: the paper's (20, default agents), else a generated one."""
    if n == 20 and agents is None:
        return str(ROOT / "scenarios" / "paper-blocks.toml")
    k = agents or 10
    names = ", ".join(f'"agent{i}"' for i in range(1, k + 1))
    norms = ", ".join(f'"{t}"' for t in PAPER_NORMS)
    areas = "".join(f'\n[[areas]]\nname = "{a.name}"\nbox = {list(a.box)}\n' for a in PAPER_AREAS)
    path = os.path.join(folder, f"world-{n}-{k}.toml")
    Path(path).write_text(f'name = "blocks {n}"\nagents = [{names}]\nnorms = [{norms}]\n{areas}\n'
                          f'[generator]\nkind = "paper-blocks"\nobjects = {n}\n', encoding="utf-8")
    return path


@contextmanager
def store_url(backend: str, folder: str, n: int, server: str | None) -> Iterator[str]:
    """A fresh empty store for one size: a SQLite file, or a new PostgreSQL database (dropped after)."""
    if backend == "sqlite":
        yield os.path.join(folder, f"bench-{n}.db")
        return
    from sqlalchemy import create_engine, text
    from sqlalchemy.exc import DBAPIError

    if not server:
        raise SystemExit("--backend postgresql needs --url or OWNCTL_TEST_PG (a server URL whose user "
                         "may create databases)")
    name = f"ownctl_bench_{uuid.uuid4().hex[:10]}"
    admin = create_engine(server, isolation_level="AUTOCOMMIT")
    with admin.connect() as conn:
        conn.execute(text(f'CREATE DATABASE "{name}"'))
    try:
        yield f"{server.rsplit('/', 1)[0]}/{name}"
    finally:
        try:
            with admin.connect() as conn:
                conn.execute(text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        except DBAPIError as exc:  # e.g. autovacuum still works on it: leave it, say so
            print(f"could not drop database {name}: {str(exc.orig).splitlines()[0]}", file=sys.stderr)
        admin.dispose()


@dataclass
class Bench:
    """One open store holding one world, and the instructor's answers about it."""

    world: World
    api: Ownctl
    clock: list[float]
    answers: dict[str, np.ndarray]  # action -> true forbid value per object
    truth: np.ndarray  # (n, m) true ownership
    rng: np.random.Generator
    inductions: int = 0
    decisions: dict[str, int] = field(default_factory=dict)

    def _object(self) -> int:
        self.clock[0] += 1.0
        return int(self.rng.integers(len(self.world.objects)))

    def permit(self) -> None:
        """``forbid|allow ACTION on OBJ`` with the true answer, on a random object and action."""
        action = str(self.rng.choice(sorted(self.answers)))
        i = self._object()
        forbid = bool(self.answers[action][i] >= 0.5)
        done = self.api.permit(action, self.world.objects[i].name, forbid=forbid)
        self.inductions += bool(done.data["induced"])

    def claim(self) -> None:
        """``claim OBJ OWNER`` for an owned object, ``claim OBJ AGENT --not`` for an unowned one."""
        i = self._object()
        owners = np.flatnonzero(self.truth[i] >= 0.5)
        name = self.world.objects[i].name
        if len(owners):
            self.api.claim(name, self.world.agents[int(owners[0])])
        else:
            agent = self.world.agents[int(self.rng.integers(len(self.world.agents)))]
            self.api.claim(name, agent, negated=True)

    def check(self) -> None:
        """``check ACTION OBJ`` on a random object (not recorded as a turn of the conversation)."""
        action = str(self.rng.choice(ACTIONS))
        report = self.api.check(action, self.world.objects[self._object()].name, record=False)
        by = report.data["decided_by"]
        self.decisions[by] = self.decisions.get(by, 0) + 1


def timed(fn: Callable[[], None]) -> float:
    """Wall milliseconds of one call."""
    t0 = time.perf_counter()
    fn()
    return (time.perf_counter() - t0) * 1e3


def profile(fn: Callable[[], None], count: int, top: int = 15) -> str:
    """cProfile of ``count`` calls: the top ``top`` functions by cumulative time, then ownctl's own."""
    prof = cProfile.Profile()
    prof.enable()
    for _ in range(count):
        fn()
    prof.disable()
    out = io.StringIO()
    stats = pstats.Stats(prof, stream=out).sort_stats("cumulative")
    stats.print_stats(top)
    out.write("ownctl functions only:\n")
    stats.print_stats(r"/ownctl/", top)
    return "\n".join(line for line in out.getvalue().splitlines() if line.strip()) + "\n"


def run_size(n: int, args: argparse.Namespace, folder: str) -> dict:
    """Load one world into a fresh store, warm up, time each op (interleaved), profile."""
    path = world_file(folder, n, args.agents)
    world = read_world(path, args.seed)
    truth = world.true_ownership()
    frame = make_frame(world.objects, world.areas, world.agents, truth)
    answers = {a: p_forbidden(r, frame) for a, r in true_rules(world).items()}
    with store_url(args.backend, folder, n, args.url) as url:
        clock = [START]
        api = Ownctl.open(url, create=True, clock=lambda: clock[0])
        try:
            t0 = time.perf_counter()
            api.load_world(path, args.seed)
            load_seconds = time.perf_counter() - t0
            print(f"{n} objects: loaded in {load_seconds:.1f} s", file=sys.stderr, flush=True)
            bench = Bench(world, api, clock, answers, truth, np.random.default_rng(args.seed + 1))
            ops = {op: getattr(bench, op) for op in OPS}
            t0 = time.perf_counter()
            if args.norms == "stated":
                for norm in world.norms:
                    api.forbid(*norm.split(" ", 2)[1:])
            for _ in range(args.warmup):
                for fn in ops.values():
                    fn()
            warm_seconds = time.perf_counter() - t0
            bench.inductions = 0
            times: dict[str, list[float]] = {op: [] for op in ops}
            for _ in range(args.repeats):
                for op, fn in ops.items():
                    times[op].append(timed(fn))
            print(f"{n} objects: timed {args.repeats} of each op", file=sys.stderr, flush=True)
            rows = [{"objects": n, "agents": len(world.agents), "op": op, "count": len(ms),
                     "median_ms": float(np.median(ms)), "p90_ms": float(np.percentile(ms, 90)),
                     "max_ms": float(np.max(ms)),
                     "target_ms": TARGETS.get((n, op))} for op, ms in times.items()]
            slowest = max(rows, key=lambda r: r["median_ms"])["op"]
            chosen = list(ops) if args.profile == "all" else [slowest] if args.profile == "slowest" else []
            reports = {op: profile(ops[op], max(5, min(20, args.repeats // 5))) for op in chosen}
        finally:
            api.close()
        reader = AppContext(url, now=clock[0])
        try:  # the rule texts only (``rules list`` would also compute each rule's posterior)
            with reader.read() as tx:
                rules = [r.text for r in tx.knowledge.rules()]
        finally:
            reader.close()
    return {"objects": n, "agents": len(world.agents), "rows": rows, "load_seconds": load_seconds,
            "load_target_s": TARGETS.get((n, "load")), "warmup_seconds": warm_seconds,
            "inductions": bench.inductions, "decided_by": bench.decisions, "rules": rules,
            "profiles": reports}


def growth(results: list[dict]) -> dict[str, float | None]:
    """op -> slope of log(median) on log(objects) over the sizes of 1,000 objects and more."""
    out: dict[str, float | None] = {}
    for op in OPS:
        pts = [(r["objects"], row["median_ms"]) for r in results for row in r["rows"]
               if row["op"] == op and r["objects"] >= 1000]
        if len(pts) < 2:
            out[op] = None
            continue
        x, y = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
        out[op] = float(np.polyfit(x, y, 1)[0])
    return out


def verdicts(results: list[dict]) -> list[tuple[str, float, float, bool]]:
    """(what, measured, target, passed) for every target a measured size has."""
    out = []
    for res in results:
        n = res["objects"]
        if res["load_target_s"] is not None:
            out.append((f"load {n} objects (s)", res["load_seconds"], res["load_target_s"],
                        res["load_seconds"] <= res["load_target_s"]))
        for row in res["rows"]:
            if row["target_ms"] is not None:
                out.append((f"{row['op']} at {n} objects (median ms)", row["median_ms"], row["target_ms"],
                            row["median_ms"] <= row["target_ms"]))
    return out


def fmt(value: float | None) -> str:
    """Milliseconds for the table ('-' when there is no figure)."""
    if value is None:
        return "-"
    return f"{value:.3g}" if value < 100 else f"{value:.0f}"


def sizes_of(args: argparse.Namespace) -> list[int]:
    """The object counts to measure: ``--sizes``, then the ladder up to ``--objects``."""
    sizes = [int(s) for s in args.sizes.split(",") if s]
    if args.objects is not None:
        sizes = sorted({*(s for s in (*sizes, *LADDER) if s < args.objects), args.objects})
    return sizes


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--objects", type=int, default=None,
                        help="the largest world (adds the sizes below it)")
    parser.add_argument("--agents", type=int, default=None,
                        help="agents of every world (default: 3 at 20, else 10)")
    parser.add_argument("--sizes", default=",".join(map(str, LADDER)), help="object counts, comma-separated")
    parser.add_argument("--backend", choices=("sqlite", "postgresql"), default="sqlite")
    parser.add_argument("--url", default=os.environ.get("OWNCTL_TEST_PG"),
                        help="PostgreSQL server URL for --backend postgresql (default: $OWNCTL_TEST_PG)")
    parser.add_argument("--repeats", type=int, default=100, help="timed calls per op and size")
    parser.add_argument("--warmup", type=int, default=10, help="untimed rounds of every op first")
    parser.add_argument("--norms", choices=("stated", "learned"), default="stated",
                        help="the instructor states the true norms first (default), or rules are learned "
                        "from the permissions alone")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--profile", choices=("slowest", "all", "none"), default="none")
    parser.add_argument("--quick", action="store_true", help="10 timed calls per op, 3 warm-up rounds")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if args.quick:
        args.repeats, args.warmup = 10, 3
    with tempfile.TemporaryDirectory(prefix="ownctl-bench-") as folder:
        results = [run_size(n, args, folder) for n in sizes_of(args)]
    info = {"machine": platform.machine(), "cpus": os.cpu_count(), "python": platform.python_version(),
            "backend": args.backend, "load_average": os.getloadavg(), "results": results,
            "growth": growth(results), "verdicts": verdicts(results)}
    if args.json:
        print(json.dumps(info))
        return
    load = " ".join(f"{v:.2f}" for v in info["load_average"])
    print(f"{info['cpus']} CPUs, Python {info['python']}, {args.backend}, load average {load}; "
          "one Ownctl per store, medians of the timed calls")
    print(f"{'objects':>8} {'agents':>6} {'load s':>7} {'op':>7} {'n':>4} {'median ms':>10} {'p90 ms':>8} "
          f"{'max ms':>8} {'target ms':>10}")
    for res in results:
        for k, r in enumerate(res["rows"]):
            load_s = f"{res['load_seconds']:.1f}" if k == 0 else ""
            print(f"{r['objects']:>8} {r['agents']:>6} {load_s:>7} {r['op']:>7} {r['count']:>4} "
                  f"{fmt(r['median_ms']):>10} {fmt(r['p90_ms']):>8} {fmt(r['max_ms']):>8} "
                  f"{fmt(r['target_ms']):>10}")
    slopes = ", ".join(f"{op} n^{v:.2f}" if v is not None else f"{op} -" for op, v in info["growth"].items())
    print(f"growth exponent (sizes >= 1000): {slopes}")
    for what, value, target, passed in info["verdicts"]:
        print(f"{'PASS' if passed else 'FAIL'} {what}: {fmt(value)} (target {fmt(target)})")
    for res in results:
        print(f"\n{res['objects']} objects: load {res['load_seconds']:.1f} s, "
              f"warm-up {res['warmup_seconds']:.1f} s, "
              f"inductions during the timed permissions: {res['inductions']}, checks decided by "
              f"{res['decided_by']}, rules at the end: {res['rules']}")
        for op, report in res["profiles"].items():
            print(f"profile of '{op}' at {res['objects']} objects (top 15 cumulative):")
            print(report)


if __name__ == "__main__":
    main()
