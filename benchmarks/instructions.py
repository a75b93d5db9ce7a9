"""Benchmark: end-to-end latency of one instruction, in-process, on one open store.

    python benchmarks/instructions.py [--quick] [--sizes 20,1000,10000] [--repeats 100] [--json]
                                      [--profile slowest|both|none]

A long-running robot process keeps one :class:`~ownctl.app.context.AppContext` open (as
``ownctl batch`` does) and calls the app functions for each instruction it hears. This measures,
on a temporary SQLite file, the wall time of

* ``forbid ACTION on OBJ`` (:func:`ownctl.app.instruct.add_permission`): store read, conflict gate,
  rule induction, ownership inference, store write, event log;
* ``claim OBJ AGENT`` (:func:`ownctl.app.instruct.add_claim`): prediction refit and bulk prior write
  for that agent, inference, store write, event log;

on the paper's world (20 objects, 3 agents, ``scenarios/paper-blocks.toml``) and on generated blocks
worlds of 1,000 and 10,000 objects with 10 agents. Instructions alternate, as an instructor would
give them: permissions on random objects with the true answer of the paper's norms (for trash,
pickUp and collect), claims of the true owner (or "not mine" for an unowned object). A warm-up of
untimed instructions comes first, so the store already holds claims, permissions and rules.

Prints median and p90 per size and operation with the targets and the original research code's
figures (which used no database), then a cProfile (top 15 by cumulative time, overall and for
ownctl's own functions) of the slowest operation at each size, measured on extra instructions after
the timed ones.
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
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ownctl.app import instruct  # noqa: E402
from ownctl.app.context import AppContext  # noqa: E402
from ownctl.app.worldfile import read_world, store_world  # noqa: E402
from ownctl.experiment.truth import true_rules  # noqa: E402
from ownctl.logic.prob import p_forbidden  # noqa: E402
from ownctl.world.generator import paper_blocks_world  # noqa: E402
from ownctl.world.model import World, make_frame  # noqa: E402

# (objects, op) -> target ms (median), from the project brief
TARGETS = {(20, "permission"): 5.0, (20, "claim"): 5.0, (1000, "permission"): 10.0, (1000, "claim"): 100.0}
# the original research code's own timings (no database)
ORIGINAL = {(20, "permission"): 0.66, (20, "claim"): 13.0, (1000, "permission"): 6.8, (1000, "claim"): 7300.0}
TEN_AGENTS = tuple(f"agent{i}" for i in range(1, 11))
START = 1_000_000.0  # the store clock at the start (seconds)


@dataclass
class Bench:
    """One store holding one world, and the instructor's answers about it."""

    world: World
    ctx: AppContext
    answers: dict[str, np.ndarray]  # action -> true forbid value per object
    truth: np.ndarray  # (n, m) true ownership
    rng: np.random.Generator
    inductions: int = 0

    def permission(self) -> None:
        """``forbid|allow ACTION on OBJ`` with the true answer, on a random object and action."""
        action = str(self.rng.choice(sorted(self.answers)))
        i = int(self.rng.integers(len(self.world.objects)))
        self.ctx.now += 1.0
        done = instruct.add_permission(self.ctx, action, self.world.objects[i].name,
                                       float(self.answers[action][i]))
        self.inductions += bool(done.data["induced"])

    def claim(self) -> None:
        """``claim OBJ OWNER`` for an owned object, ``claim OBJ AGENT --not`` for an unowned one."""
        i = int(self.rng.integers(len(self.world.objects)))
        owners = np.flatnonzero(self.truth[i] >= 0.5)
        self.ctx.now += 1.0
        if len(owners):
            instruct.add_claim(self.ctx, self.world.objects[i].name, self.world.agents[int(owners[0])])
        else:
            agent = self.world.agents[int(self.rng.integers(len(self.world.agents)))]
            instruct.add_claim(self.ctx, self.world.objects[i].name, agent, negated=True)


def make_world(n: int, seed: int) -> World:
    """The paper's world from its scenario file (20 objects), else a generated one with 10 agents."""
    if n == 20:
        return read_world(str(ROOT / "scenarios" / "paper-blocks.toml"), seed)
    return paper_blocks_world(np.random.default_rng(seed), n, agents=TEN_AGENTS)


def open_bench(n: int, folder: str, seed: int) -> Bench:
    """A fresh SQLite store in ``folder`` holding the world of size ``n``."""
    world = make_world(n, seed)
    ctx = AppContext(os.path.join(folder, f"bench-{n}.db"), now=START, interface="bench")
    ctx.store(create=True)
    with ctx.write({"op": "world.load", "world": world.name, "seed": seed}) as tx:
        store_world(tx, world, ctx.now)
    truth = world.true_ownership()
    frame = make_frame(world.objects, world.areas, world.agents, truth)
    answers = {a: p_forbidden(r, frame) for a, r in true_rules(world).items()}
    return Bench(world, ctx, answers, truth, np.random.default_rng(seed + 1))


def timed(fn: Callable[[], None]) -> float:
    """Wall milliseconds of one call."""
    t0 = time.perf_counter()
    fn()
    return (time.perf_counter() - t0) * 1e3


def profile(fn: Callable[[], None], count: int, top: int = 15) -> str:
    """cProfile of ``count`` calls: the top ``top`` functions by cumulative time, then the same for
    ownctl's own functions only (the SQLAlchemy internals otherwise fill the list)."""
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


def run_size(n: int, repeats: int, warmup: int, folder: str, seed: int, with_profile: str) -> dict:
    """Set up one store, warm it up, time ``repeats`` of each op (interleaved), profile the slowest."""
    t0 = time.perf_counter()
    bench = open_bench(n, folder, seed)
    setup = time.perf_counter() - t0
    ops = {"permission": bench.permission, "claim": bench.claim}
    for _ in range(warmup):
        bench.claim()
        bench.permission()
    bench.inductions = 0
    times: dict[str, list[float]] = {op: [] for op in ops}
    for _ in range(repeats):
        for op, fn in ops.items():
            times[op].append(timed(fn))
    rows = []
    for op, ms in times.items():
        arr = np.array(ms)
        rows.append({
            "objects": n, "agents": len(bench.world.agents), "op": op, "count": len(arr),
            "median_ms": float(np.median(arr)), "p90_ms": float(np.percentile(arr, 90)),
            "target_ms": TARGETS.get((n, op)), "original_ms": ORIGINAL.get((n, op)),
        })
    slowest = max(rows, key=lambda r: r["median_ms"])["op"]
    profiled = list(ops) if with_profile == "both" else [slowest] if with_profile == "slowest" else []
    reports = {op: profile(ops[op], max(5, min(20, repeats // 5))) for op in profiled}
    with bench.ctx.read() as tx:
        rules = [r.text for r in tx.knowledge.rules()]
    bench.ctx.close()
    return {"rows": rows, "setup_seconds": setup, "inductions": bench.inductions, "rules": rules,
            "slowest": slowest, "profiles": reports}


def fmt(value: float | None) -> str:
    """Milliseconds for the table ('-' when there is no figure)."""
    if value is None:
        return "-"
    return f"{value:.3g}" if value < 100 else f"{value:.0f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a short run (fewer instructions per size)")
    parser.add_argument("--sizes", default="20,1000,10000", help="object counts, comma-separated")
    parser.add_argument("--repeats", type=int, default=None, help="timed instructions per op and size")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--profile", choices=("slowest", "both", "none"), default="slowest",
                        help="cProfile the slowest op at each size (default), both ops, or none")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",") if s]
    results = []
    with tempfile.TemporaryDirectory(prefix="ownctl-bench-") as folder:
        for n in sizes:
            repeats = args.repeats or (10 if args.quick else (100 if n <= 1000 else 30))
            warmup = 5 if args.quick or n > 1000 else 20
            results.append(run_size(n, repeats, warmup, folder, args.seed, args.profile))
    info = {"machine": platform.machine(), "cpus": os.cpu_count(), "python": platform.python_version(),
            "results": results}
    if args.json:
        print(json.dumps(info))
        return
    print(f"{info['cpus']} CPUs, Python {info['python']}; one AppContext, temporary SQLite file")
    print(f"{'objects':>8} {'agents':>6} {'op':>10} {'n':>4} {'median ms':>10} {'p90 ms':>8} "
          f"{'target ms':>10} {'original ms':>12}")
    for res in results:
        for r in res["rows"]:
            print(f"{r['objects']:>8} {r['agents']:>6} {r['op']:>10} {r['count']:>4} "
                  f"{fmt(r['median_ms']):>10} {fmt(r['p90_ms']):>8} {fmt(r['target_ms']):>10} "
                  f"{fmt(r['original_ms']):>12}")
    print("targets: median, including the store write; original: the research code, no database")
    for res in results:
        n = res["rows"][0]["objects"]
        print(f"\n{n} objects: setup {res['setup_seconds']:.1f} s, inductions during the timed permissions: "
              f"{res['inductions']}, rules at the end: {res['rules']}")
        for op, report in res["profiles"].items():
            print(f"profile of '{op}' at {n} objects (top 15 cumulative):")
            print(report)


if __name__ == "__main__":
    main()
