"""Benchmark: the asking experiment's "ours" with its questions valued under another prior over rule sets.

    python benchmarks/asking_prior.py [--prior length|normalised|coverage|stated] [--seed 1] [--trials 8]
        [--budget 4] [--coverage-weight 3] [--jobs 2] [--json]

The stated model's prior over rule sets (``ownctl/learn/model.py``) charges each rule for its
length but not for which rule of that length it is, so its total mass on rule sets that are not
empty grows with the number of candidate rules the posterior's space holds: with few examples,
each step's P(forbidden) on an object nobody taught about is set by that pool (on a fresh store
``ownctl ask`` expects nearly one mistake per object). ``--prior length`` values ours' questions on
the same posterior reweighted to the description-length prior (``count_weight`` 1: a rule of
``l`` literals also pays ``log N(l)``, N(l) the rules of that length; docs/learning.md), then
tempered as usual; ``--prior normalised`` keeps the stated prior's charges but normalises them over
every rule of the language, with probability 1/2 that a step has any rule (each rule of a set pays
``log Z - log(1/2)`` more, ``Z`` the sum of ``exp(-cost)`` over the language's rules);
``--prior coverage`` charges each rule of a set ``w`` times the share of the Mind's objects it
holds for (mean P(rule holds) on the current beliefs; ``--coverage-weight w``): a rule that forbids
most objects is a priori less likely, so one forbidden example no longer makes every object look
forbidden (with the stated prior, after a first "you may not collect" on a red block the step's
posterior puts 0.83-0.98 on every object). The learner and the decisions are unchanged.
``--prior stated`` is ours as it is.

Runs ours only (``benchmarks/asking.py``'s protocol: trial ``t`` of task ``c`` is the paper's
blocks world drawn with ``[seed, c, t]``) and prints mistakes per task, mean and per trial.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from multiprocessing import Pool
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import asking  # noqa: E402

import ownctl.mind.ask as ask  # noqa: E402
from ownctl.experiment.asking import DEFAULT_MIN_GAIN, TASK_KINDS, TASK_TEMPER  # noqa: E402
from ownctl.experiment.online import TASK_CONDITIONS  # noqa: E402
from ownctl.learn.model import model_for, rule_counts  # noqa: E402
from ownctl.learn.posterior import RulePosterior  # noqa: E402
from ownctl.logic.prob import p_forbidden  # noqa: E402
from ownctl.mind import Mind  # noqa: E402


def charged(rp: RulePosterior, charge: np.ndarray, temper: float) -> RulePosterior:
    """``rp`` with each set's log weight lowered by ``charge`` (nats), then tempered as the asker
    tempers (``ownctl.mind.ask.tempered``; at ``temper`` 1 only renormalised)."""
    w = (rp.log_weights - charge) * temper
    p = np.exp(w - w.max())
    return dataclasses.replace(rp, probabilities=p / p.sum())


def length_prior(mind: Mind, step: str, temper: float) -> RulePosterior:
    """The step's posterior reweighted to the description-length prior, then tempered."""
    rp = mind.rule_posterior(step)
    counts = rule_counts(tuple(mind.vocab.atoms()), mind.settings.learn.max_conditions)
    lengths = [len(r.literals) for r in rp.rules]
    charge = np.array([math.log(max(counts[n], 1)) if n < len(counts) else 0.0 for n in lengths] + [0.0])
    return charged(rp, charge[rp.index].sum(axis=1), temper)  # index -1 pads: no charge


def normalised(mind: Mind, step: str, temper: float) -> RulePosterior:
    """The step's posterior under the stated prior normalised over the language, P(some rule) = 1/2."""
    rp = mind.rule_posterior(step)
    atoms, longest = tuple(mind.vocab.atoms()), mind.settings.learn.max_conditions
    model = model_for(atoms, longest)
    log_z = math.log(sum(n * math.exp(-model.cost(k)) for k, n in enumerate(rule_counts(atoms, longest))))
    return charged(rp, (rp.index >= 0).sum(axis=1) * (log_z - math.log(0.5)), temper)


COVERAGE_WEIGHT = 3.0  # nats a rule that holds for every object pays (set by --coverage-weight)


def coverages(mind: Mind, rp: RulePosterior) -> np.ndarray:
    """Each rule of ``rp``'s space: the mean over the Mind's objects of P(it holds), on current beliefs."""
    frame = mind.frame()
    return np.array([float(p_forbidden((r,), frame).mean()) for r in rp.rules])


def coverage(mind: Mind, step: str, temper: float) -> RulePosterior:
    """The step's posterior with each rule of a set charged ``COVERAGE_WEIGHT`` times its coverage."""
    rp = mind.rule_posterior(step)
    cov = np.append(COVERAGE_WEIGHT * coverages(mind, rp), 0.0)  # index -1 pads: no charge
    return charged(rp, cov[rp.index].sum(axis=1), temper)


PRIORS = {"length": length_prior, "normalised": normalised, "coverage": coverage}


def one(unit: tuple[int, int, int, int, str, float]) -> tuple[int, int, int]:
    """Mistakes of ours on trial ``t`` of task ``c``."""
    global COVERAGE_WEIGHT
    c, t, seed, budget, prior, weight = unit
    COVERAGE_WEIGHT = weight
    if prior in PRIORS:
        ask._posterior = PRIORS[prior]  # this worker's valuation only
    mistakes, _ = asking.run(c, t, seed, "ours", budget, TASK_KINDS, DEFAULT_MIN_GAIN, TASK_TEMPER)
    return c, t, mistakes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--prior", choices=("length", "normalised", "coverage", "stated"), default="length")
    parser.add_argument("--coverage-weight", type=float, default=COVERAGE_WEIGHT)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--trials", type=int, default=8)
    parser.add_argument("--budget", type=int, default=4)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if args.coverage_weight < 0:
        parser.error(f"--coverage-weight must be at least 0, got {args.coverage_weight}")
    units = [(c, t, args.seed, args.budget, args.prior, args.coverage_weight)
             for c in range(len(TASK_CONDITIONS)) for t in range(args.trials)]
    with Pool(args.jobs) as pool:
        done = pool.map(one, units, chunksize=1)
    doc: dict[str, Any] = {"prior": args.prior, "coverage_weight": args.coverage_weight, "seed": args.seed,
                           "trials": args.trials, "budget": args.budget, "tasks": {}}
    for c, cond in enumerate(TASK_CONDITIONS):
        per = [m for cc, _, m in sorted(done) if cc == c]
        doc["tasks"][cond.name] = {"mistakes": float(np.mean(per)), "per_trial": per}
        if not args.json:
            print(f"{cond.name:10} {np.mean(per):.2f} mistakes per task with {args.budget} questions "
                  f"(per trial {per})", flush=True)
    if args.json:
        print(json.dumps(doc))


if __name__ == "__main__":
    main()
