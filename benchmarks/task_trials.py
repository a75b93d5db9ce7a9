"""Benchmark: Table 3's mistakes trial by trial, and paired against another version's.

    python benchmarks/task_trials.py [--seeds 0,1,2,3,4] [--trials 100] [--jobs 2] --out FILE.json
    python benchmarks/task_trials.py --paired BEFORE.json AFTER.json

The first form runs Table 3's trials (``ownctl experiment task``: trial ``t`` of task ``c`` for seed
``s`` draws from ``[s, c, t]``, so seed 0 is Table 3 itself) for every seed given and writes each
trial's mistakes. It imports ``ownctl`` from wherever Python finds it, so the same file run with
another version of ownctl on the path (``PYTHONPATH=/path/to/other/checkout``) measures that one
on the very same trials. The second form prints, per task and over all seeds, both means and the
paired difference AFTER - BEFORE with its 95% interval and how many trials went each way.
"""

from __future__ import annotations

import argparse
import json
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

TASKS = ("collectAll", "trashAll")


def _mistakes(unit: tuple[int, int, int]) -> tuple[str, float]:
    """The mistakes of one trial (seed, task index, trial) with the default learner."""
    from ownctl.experiment.online import TASK_CONDITIONS, task_trial
    from ownctl.world.generator import paper_blocks_world

    seed, c, t = unit
    # the generator ownctl.experiment.runner.trial_rng makes, spelled out: versions of ownctl older
    # than that function are measured with this file too
    result = task_trial(paper_blocks_world, TASK_CONDITIONS[c], "ours", np.random.default_rng([seed, c, t]))
    return f"{seed}/{TASKS[c]}/{t}", float(result.counts["mistakes"])


def run(seeds: list[int], trials: int, jobs: int) -> dict[str, float]:
    """Every trial's mistakes, keyed ``seed/task/trial``."""
    units = [(s, c, t) for s in seeds for c in range(len(TASKS)) for t in range(trials)]
    with ProcessPoolExecutor(jobs) as pool:
        return dict(pool.map(_mistakes, units, chunksize=10))


def paired(before: dict[str, float], after: dict[str, float]) -> list[str]:
    """Lines of the paired comparison on the trials both runs have."""
    lines = []
    for task in TASKS:
        keys = sorted(k for k in before if k.split("/")[1] == task and k in after)
        if not keys:
            continue
        x, y = np.array([before[k] for k in keys]), np.array([after[k] for k in keys])
        d = y - x
        half = 1.96 * d.std(ddof=1) / np.sqrt(len(d)) if len(d) > 1 else float("nan")
        lines.append(f"{task}: {len(keys)} trials, before {x.mean():.3f}, after {y.mean():.3f}, "
                     f"after - before {d.mean():+.3f} ± {half:.3f} (fewer in {int((d < 0).sum())}, "
                     f"more in {int((d > 0).sum())})")
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0,1,2,3,4")
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", metavar="FILE.json")
    parser.add_argument("--paired", nargs=2, metavar=("BEFORE.json", "AFTER.json"))
    args = parser.parse_args()
    if args.paired:
        before, after = (json.loads(Path(p).read_text()) for p in args.paired)
        print("\n".join(paired(before, after)))
        return
    try:
        seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        parser.error(f"--seeds takes comma-separated integers, not {args.seeds!r}")
    if not args.out or args.trials < 1 or args.jobs < 1 or min(seeds) < 0:
        parser.error("--out is required; --trials and --jobs must be at least 1, seeds at least 0")
    Path(args.out).write_text(json.dumps(run(seeds, args.trials, args.jobs), indent=0, sort_keys=True))


if __name__ == "__main__":
    main()
