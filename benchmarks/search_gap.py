"""Benchmark: are the learner's wrong rules its search's fault or its model's?

    python benchmarks/search_gap.py [--families 40] [--family-seed 0] [--trials 3] [--json]

On the Table 1 protocol over norm families (trials drawn as ``ownctl experiment norms --families``
draws them), each action's learned rules are compared with its true norms. Where they decide
differently on some object (true owners), the true norms' objective (``-log`` prior x likelihood of
the stated model, ``ownctl.learn.model``; the least over the calibrations of claims the learner
tries) is compared with the learned rules' objective:

- ``search``: the true norms are more probable than what the learner found: a better search
  would have found them (or something at least as probable);
- ``model``: the learned rules are at least as probable as the true norms: under the stated prior
  and likelihood the learner's answer is the better explanation of the permissions, and only
  another model (prior, noise, more examples) would change it.

Prints, per condition, the actions decided right, the two kinds of misses, and the mean objective
gap of the search misses (nats). Default family seeds 0-39: tuning families, not the reserved ones.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ownctl.experiment.metrics import rule_scores  # noqa: E402
from ownctl.experiment.norms import NORM_CONDITIONS, norms_setup, taught_mind  # noqa: E402
from ownctl.experiment.runner import trial_rng  # noqa: E402
from ownctl.learn import exact, induce  # noqa: E402
from ownctl.world.families import norm_family  # noqa: E402


def classify(family: int, c: int, t: int) -> list[tuple[str, float]]:
    """Per scored action of trial ``t`` of condition ``c`` on ``family``: ``right``, ``search`` or
    ``model``, and the objective of the learned rules minus that of the true norms."""
    setup = norms_setup(norm_family(family), NORM_CONDITIONS[c], trial_rng(0, c, t, family))
    mind = taught_mind(setup)
    out: list[tuple[str, float]] = []
    for action, true in setup.rules.items():
        if rule_scores(setup.answers[action], mind.p_rules_on(action, setup.true_frame)).accuracy == 1.0:
            out.append(("right", 0.0))
            continue
        ev, _ = mind.evidence(action)
        options = induce.calibration_choices(action, ev, mind.vocab, mind.settings.learn, [])
        found = min(option[2] for option in options.values())
        truth = min(exact.objective(ind.model, exact.canonical_order(ind.ev)[0], list(true))
                    for ind, _, _ in options.values())
        gap = found - truth
        out.append(("search" if gap > exact.SLACK else "model", gap))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--families", type=int, default=40)
    parser.add_argument("--family-seed", type=int, default=0)
    parser.add_argument("--trials", type=int, default=3)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if args.families < 1 or args.trials < 1 or args.family_seed < 0:
        parser.error("--families and --trials must be at least 1, --family-seed at least 0")
    rows: list[dict[str, Any]] = []
    for c, cond in enumerate(NORM_CONDITIONS):
        if cond.baseline:
            continue
        kinds: dict[str, int] = {"right": 0, "search": 0, "model": 0}
        gaps: list[float] = []
        for family in range(args.family_seed, args.family_seed + args.families):
            for t in range(args.trials):
                for kind, gap in classify(family, c, t):
                    kinds[kind] += 1
                    if kind == "search":
                        gaps.append(gap)
        rows.append({"condition": cond.name, **kinds,
                     "search_gap": float(np.mean(gaps)) if gaps else 0.0})
    if args.json:
        print(json.dumps({"families": args.families, "family_seed": args.family_seed,
                          "trials": args.trials, "conditions": rows}, indent=1))
        return
    print(f"{args.families} families from seed {args.family_seed}, {args.trials} trials each: actions "
          "whose learned rules decide every object right, and the misses by cause")
    print(f"{'condition':<16}{'right':>8}{'search':>8}{'model':>8}{'search gap (nats)':>20}")
    for row in rows:
        print(f"{row['condition']:<16}{row['right']:>8}{row['search']:>8}{row['model']:>8}"
              f"{row['search_gap']:>20.3f}")


if __name__ == "__main__":
    main()
