"""Benchmark: the error of the rule-set posterior's truncated pool, against a widened enumeration.

    python benchmarks/posterior.py [--trials 5] [--pool 40] [--wide 160] [--json]

On Table 1 trials of the paper's blocks world (every condition, ``--trials`` each), builds the
posterior over rule sets of each action (``ownctl.learn.posterior.rule_posterior``) on a pool of the
``--pool`` best supported rules and on a pool of ``--wide``, and prints per condition the largest
and the mean absolute difference of P(forbidden) over all 20 objects (prior ownership), the total
variation distance between the two posteriors' P(rule's decisions) on the learned rules, and the
time per posterior. The widened posterior is the reference: it contains every rule set of the
narrow one and more.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ownctl.config import LearnConfig  # noqa: E402
from ownctl.experiment.norms import NORM_CONDITIONS, noisy_labels  # noqa: E402
from ownctl.experiment.truth import true_rules  # noqa: E402
from ownctl.learn.posterior import rule_posterior  # noqa: E402
from ownctl.logic.prob import p_forbidden  # noqa: E402
from ownctl.mind import Mind, Switches  # noqa: E402
from ownctl.world.generator import paper_blocks_world  # noqa: E402
from ownctl.world.model import make_frame  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=5)
    parser.add_argument("--pool", type=int, default=40)
    parser.add_argument("--wide", type=int, default=160)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    rows = []
    for c, cond in enumerate(NORM_CONDITIONS[:-1]):
        diffs, support_gaps, secs = [], [], []
        for t in range(args.trials):
            rng = np.random.default_rng([0, c, t])
            world = paper_blocks_world(rng)
            truth = world.true_ownership()
            rules = true_rules(world)
            true_frame = make_frame(world.objects, world.areas, world.agents, truth)
            mind = Mind(world.agents, list(world.objects), world.areas,
                        switches=Switches(inference=False, prediction=False))
            mind.claims[:] = noisy_labels(truth, rng) if cond.noisy else truth
            chosen = rng.permutation(20)[: int(round(cond.fraction * 20))]
            answers = {a: p_forbidden(r, true_frame) for a, r in rules.items()}
            for obj in chosen:
                for a in rules:
                    mind.permit(a, int(obj), float(answers[a][obj]))
            prior = mind.frame(mind.prior)
            for a in rules:
                ev, _ = mind.evidence(a)
                start = time.perf_counter()
                narrow = rule_posterior(ev, a, mind.vocab, LearnConfig(), mind.rules[a], size=args.pool)
                secs.append(time.perf_counter() - start)
                wide = rule_posterior(ev, a, mind.vocab, LearnConfig(), mind.rules[a], size=args.wide)
                diffs.append(np.abs(narrow.p_forbidden(prior) - wide.p_forbidden(prior)))
                support_gaps += [abs(narrow.support(r, prior) - wide.support(r, prior))
                                 for r in mind.rules[a]]
        d = np.concatenate(diffs)
        rows.append({"condition": cond.name, "max_abs_p_forbidden": float(d.max()),
                     "mean_abs_p_forbidden": float(d.mean()),
                     "max_abs_support": float(max(support_gaps, default=0.0)),
                     "ms_per_posterior": 1000 * float(np.median(secs))})
    if args.json:
        print(json.dumps({"pool": args.pool, "wide": args.wide, "trials": args.trials, "rows": rows}))
        return
    print(f"pool {args.pool} against pool {args.wide}, {args.trials} trials per condition, "
          "paper blocks world")
    print(f"{'condition':16s} {'max |dP|':>9s} {'mean |dP|':>10s} {'max |dsupport|':>15s} {'ms':>6s}")
    for r in rows:
        print(f"{r['condition']:16s} {r['max_abs_p_forbidden']:9.4f} {r['mean_abs_p_forbidden']:10.5f} "
              f"{r['max_abs_support']:15.4f} {r['ms_per_posterior']:6.1f}")


if __name__ == "__main__":
    main()
