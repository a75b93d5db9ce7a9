"""Benchmark: wall time of the paper's experiments, run in memory, as ``ownctl experiment`` runs them.

    python benchmarks/experiments.py [--trials 100] [--jobs 2] [--learner ours] [--json]
        [--only norms|norms-online|ownership|task ...]

Runs Table 1 (6 conditions plus the allow-everything baseline), Table 2 (3 conditions) and Table 3
(collectAll and trashAll), each with ``--trials`` trials per condition, on the paper's blocks world
(seed 0), and prints wall and summed trial (CPU) seconds with the headline figures.
Targets on a 2-core machine with --jobs 2: Table 1 under 5 s, Table 3 (both tasks) under 30 s.
The figures depend on how busy the machine is: run it on an idle one.

Table 1 teaches each action's permissions together (``Mind.permit_all``), which gives the rules of
teaching them one at a time; ``norms-online`` runs the same trials teaching every permission on its
own and learning after each, as a robot taught live does (``norms_trial(..., together=False)``), and
prints the same figures, so its time is the cost of learning online.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import time
from typing import Any

TARGETS = {"norms": 5.0, "task": 30.0}


def _cpu() -> float:
    """User + system CPU seconds of this process and its finished workers."""
    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _online_trial(unit: tuple[int, int, str]) -> tuple[int, Any]:
    """Trial ``t`` of Table 1 condition ``c`` with every permission taught on its own, drawn as
    ``ownctl experiment norms`` draws it: (c, its trial result)."""
    from ownctl.experiment.norms import NORM_CONDITIONS, norms_result
    from ownctl.experiment.runner import trial_rng
    from ownctl.world.generator import paper_blocks_world

    c, t, learner = unit
    rng = trial_rng(0, c, t)
    return c, norms_result(paper_blocks_world, NORM_CONDITIONS[c], learner, rng, together=False)


def _norms_online(trials: int, jobs: int, learner: str) -> list[Any]:
    """Table 1's conditions summarised as the experiment summarises them, with every permission
    taught on its own (see the module docstring)."""
    from concurrent.futures import ProcessPoolExecutor

    from ownctl.experiment.registry import get_experiment
    from ownctl.experiment.summary import summarise

    exp = get_experiment("norms")
    units = [(c, t, learner) for c in range(len(exp.conditions)) for t in range(trials)]
    with ProcessPoolExecutor(jobs) as pool:
        done = list(pool.map(_online_trial, units, chunksize=max(1, len(units) // (8 * jobs))))
    return [summarise(cond.name, c, [r for k, r in done if k == c], exp.headline, {}, {}, 0.0)
            for c, cond in enumerate(exp.conditions)]


def _headline(conditions: Any) -> dict[str, dict[str, float]]:
    """Each condition's headline accuracy, F1 and (tasks) mistakes, rounded."""
    return {c.name: {"accuracy": round(c.accuracy.mean, 3), "f1": round(c.f1.mean, 3),
                     **{k: round(v.mean, 2) for k, v in c.counts.items() if k == "mistakes"}}
            for c in conditions}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--learner", default="ours")
    parser.add_argument("--only", choices=("norms", "norms-online", "ownership", "task"), action="append")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()

    start = time.perf_counter()
    from ownctl.app.experiment import run

    import_seconds = time.perf_counter() - start
    rows = []
    for name in args.only or ("norms", "ownership", "task"):
        t0, c0 = time.perf_counter(), _cpu()
        if name == "norms-online":
            headline = _headline(_norms_online(args.trials, args.jobs, args.learner))
        else:
            headline = _headline(run(name, trials=args.trials, seed=0, jobs=args.jobs,
                                     learner=args.learner).conditions)
        wall, cpu = time.perf_counter() - t0, _cpu() - c0
        rows.append({
            "experiment": name,
            "trials": args.trials,
            "conditions": len(headline),
            "wall_seconds": round(wall, 2),
            "cpu_seconds": round(cpu, 2),
            "target_seconds": TARGETS.get(name),
            "headline": headline,
        })
    info = {"machine": platform.machine(), "cpus": os.cpu_count(), "jobs": args.jobs, "learner": args.learner,
            "import_seconds": round(import_seconds, 2), "results": rows}
    if args.json:
        print(json.dumps(info))
        return
    print(f"{info['cpus']} CPUs, jobs {args.jobs}, learner {args.learner}, "
          f"{args.trials} trials per condition")
    for r in rows:
        target = f" (target < {r['target_seconds']:.0f} s)" if r["target_seconds"] else ""
        print(f"{r['experiment']:10s} {r['conditions']} conditions: {r['wall_seconds']:6.2f} s wall{target}, "
              f"{r['cpu_seconds']:6.2f} s CPU (all processes)")
        for cond, figures in r["headline"].items():
            print(f"    {cond:22s} {figures}")


if __name__ == "__main__":
    main()
