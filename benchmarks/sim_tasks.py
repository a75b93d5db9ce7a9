"""Benchmark: trashAll and collectAll on paper-like 20-block worlds in the headless Baxter simulation.

    python benchmarks/sim_tasks.py [--seeds N] [--json]

For each seed a fresh world (5 unowned blocks near the origin, 3 owner clusters of 5 blocks) runs
trashAll (every block not already in the trash area goes to the bin) and, in another fresh world,
collectAll (every block not already home goes home), in the blocks' id order. Prints the median wall
time per task, the median simulated time, the real-time factor and the fraction of blocks delivered.
Target: under 10 s of wall time per 20-block task and 100 % delivered.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time

import numpy as np

from sim.tasks import TaskResult, collect_all, paper_blocks, trash_all
from sim.world import PhysicsWorld


def run_task(task: str, seed: int) -> tuple[TaskResult, float]:
    """One task on a fresh world drawn from ``seed``; also returns the world's build time (s)."""
    start = time.perf_counter()
    world = PhysicsWorld(paper_blocks(np.random.default_rng(seed)), [], seed=seed)
    build = time.perf_counter() - start
    return (trash_all if task == "trash" else collect_all)(world), build


def summarize(task: str, rows: list[tuple[TaskResult, float]]) -> dict[str, object]:
    """Medians over seeds and the pooled delivered fraction of one task (wall time includes the build)."""
    results = [r for r, _ in rows]
    attempted = sum(len(r.attempted) for r in results)
    delivered = sum(len(r.delivered) for r in results)
    return {
        "task": task,
        "seeds": len(results),
        "median_wall_s": statistics.median(r.wall_seconds + b for r, b in rows),
        "median_sim_s": statistics.median(r.sim_seconds for r in results),
        "median_rtf": statistics.median(r.sim_seconds / (r.wall_seconds + b) for r, b in rows),
        "max_wall_s": max(r.wall_seconds + b for r, b in rows),
        "blocks_attempted": attempted,
        "blocks_delivered": delivered,
        "delivered_fraction": delivered / attempted if attempted else 1.0,
        "failed_steps": [f"{o.object}: {o.error}" for r in results for o in r.outcomes if not o.ok],
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10, help="number of seeds (worlds) per task")
    parser.add_argument("--json", action="store_true", help="print one JSON document instead of a table")
    args = parser.parse_args()
    summaries = []
    for task in ("trash", "collect"):
        rows = [run_task(task, seed) for seed in range(args.seeds)]
        summaries.append(summarize(task, rows))
    if args.json:
        machine = platform.processor() or platform.machine()
        print(json.dumps({"machine": machine, "cpus": os.cpu_count(), "tasks": summaries}, indent=1))
        return
    print(f"{'task':8} {'seeds':>5} {'wall s':>8} {'max s':>7} {'sim s':>7} {'RTF':>6} {'delivered':>12}")
    for s in summaries:
        frac = f"{s['blocks_delivered']}/{s['blocks_attempted']}"
        print(
            f"{s['task']:8} {s['seeds']:>5} {s['median_wall_s']:>8.2f} {s['max_wall_s']:>7.2f} "
            f"{s['median_sim_s']:>7.1f} {s['median_rtf']:>6.1f} {frac:>12} ({s['delivered_fraction']:.0%})"
        )
        for failure in s["failed_steps"]:  # type: ignore[attr-defined]
            print(f"  failed: {failure}")


if __name__ == "__main__":
    main()
