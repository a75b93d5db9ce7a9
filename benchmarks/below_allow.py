"""Benchmark: the family cells where the learned rules do worse than allowing everything, and what
deciding more cautiously among near-best rule sets would change.

    python benchmarks/below_allow.py [--family-seed 0] [--families 100] [--trials 20]
        [--conditions "noiseless 0.25,noisy 0.25"] [--ties none|min|mean] [--within NATS]
        [--jobs 2] [--json]
    python benchmarks/below_allow.py --paper [--ties ...] [--within NATS]
    python benchmarks/below_allow.py --probfoil benchmarks/data/probfoil.json [--ties ...] [--within NATS]

On the Table 1 protocol over norm families (trials drawn as ``ownctl experiment norms --families``
draws them; default family seeds 0-99, tuning families, not the reserved 1000-1099), each family's
mean accuracy over its trials and actions is compared with allowing everything, per condition.
Prints the cells (family x condition) below allowing everything, each action's accuracy there,
and per condition the count of such cells and ours' mean accuracy over families.

``--ties`` decides each action on more than the learner's rule set: with ``min`` an object is
forbidden only as far as *every* rule set whose log posterior is within ``--within`` nats of the
most probable one (and the learner's own) forbids it (the least P(forbidden) among them); with
``mean``, the average of those sets' P(forbidden), each set counted once: ownctl's
``decide.rules window`` with ``decide.window`` set to ``--within``. ``--within 1e-6`` takes exact
ties only (the learner otherwise picks one of equally probable rule sets by the canonical order of
rules). ``none``: the most probable rule set (``decide.rules map``). ``min`` is a variant measured
for docs/norm-families.md, not one of ownctl's decisions. ``--paper``: instead, Table 1's
accuracy per condition on exactly its 100 trials (the paper's blocks world and norms, ``ownctl
experiment norms``) under the decision
chosen. ``--probfoil CACHE``: instead, on every trial of ProbFOIL's cache
(``benchmarks/generalisation.py``'s), the paired difference ours - ProbFOIL per condition (mean
over families of each family's mean difference of accuracy and of F1, the trial's figure being
the mean over its actions, with a 95% interval), as that benchmark reports it.
"""

from __future__ import annotations

import argparse
import json
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ownctl.experiment.metrics import ci95, decision_scores, rule_scores  # noqa: E402
from ownctl.experiment.norms import NORM_CONDITIONS, norms_setup, taught_mind  # noqa: E402
from ownctl.experiment.runner import trial_rng  # noqa: E402
from ownctl.learn.posterior import window_p_forbidden  # noqa: E402
from ownctl.logic.frame import Frame  # noqa: E402
from ownctl.mind import Mind  # noqa: E402
from ownctl.world.families import norm_family  # noqa: E402
from ownctl.world.generator import paper_blocks_world  # noqa: E402

TIES = ("none", "min", "mean")


def cautious(mind: Mind, action: str, frame: Frame, ties: str, within: float) -> np.ndarray:
    """P(forbidden) of ``action`` on every object of ``frame``: the learner's rule set's (``none``);
    with ``mean``, ownctl's ``decide.rules window`` of width ``within`` (the mean over the learner's
    set and every rule set within ``within`` nats of the most probable, each counted once); with
    ``min``, the least P(forbidden) among those sets."""
    own = mind.p_rules_on(action, frame)
    if ties == "none" or not mind.perms[action]:
        return own
    post = mind.rule_posterior(action)
    if ties == "mean":  # what the Mind decides on under decide.rules window
        return window_p_forbidden(post, mind.rules[action], frame, within)
    top = np.flatnonzero(post.log_weights >= post.log_weights.max() - within)
    alone = [replace(post, index=post.index[k:k + 1], log_weights=post.log_weights[k:k + 1],
                     probabilities=np.ones(1)).p_forbidden(frame) for k in top.tolist()]
    out: np.ndarray = np.array([own, *alone]).min(axis=0)
    return out


def cell(family: int, c: int, trials: int, ties: str = "none", within: float = 1e-6) -> dict[str, Any]:
    """One family's condition ``c``: mean accuracy of ours and of allowing everything over its
    trials and actions, and per action (``family`` -1: the paper's world and Table 1's trials)."""
    make = paper_blocks_world if family < 0 else norm_family(family)
    ours: list[float] = []
    allow: list[float] = []
    per: dict[str, list[tuple[float, float]]] = {}
    norms: list[str] = []
    for t in range(trials):
        setup = norms_setup(make, NORM_CONDITIONS[c], trial_rng(0, c, t, None if family < 0 else family))
        mind = taught_mind(setup)
        norms = list(setup.world.norms)
        scores = {a: decision_scores(setup.answers[a], cautious(mind, a, setup.true_frame, ties, within))
                  for a in setup.rules}
        base = {a: rule_scores(setup.answers[a], np.zeros(len(setup.world.objects))) for a in setup.rules}
        ours.append(float(np.mean([s.accuracy for s in scores.values()])))
        allow.append(float(np.mean([s.accuracy for s in base.values()])))
        for a in scores:
            per.setdefault(a, []).append((scores[a].accuracy, base[a].accuracy))
    return {"family": family, "condition": NORM_CONDITIONS[c].name, "ours": float(np.mean(ours)),
            "allow": float(np.mean(allow)), "norms": norms,
            "actions": {a: [float(np.mean([o for o, _ in v])), float(np.mean([b for _, b in v]))]
                        for a, v in per.items()}}


def paired(cache: dict[str, Any], ties: str, within: float, jobs: int) -> dict[str, dict[str, Any]]:
    """Ours - ProbFOIL on every trial of ProbFOIL's ``cache`` (keys ``family/condition/trial``),
    per condition: mean over families of the per-family mean difference, accuracy and F1."""
    names = {c.name: i for i, c in enumerate(NORM_CONDITIONS)}
    keys = [k for k in cache if k.split("/")[0] != "paper"]
    units = [(int(k.split("/")[0]), names[k.split("/")[1]], int(k.split("/")[2]), ties, within) for k in keys]
    with ProcessPoolExecutor(max_workers=max(jobs, 1)) as pool:
        ours = list(pool.map(_trial_scores, units))
    diffs: dict[str, dict[int, list[tuple[float, float]]]] = {}
    for k, (f, c, _, _, _), (acc, f1) in zip(keys, units, ours, strict=True):
        theirs = [v["scores"] for v in cache[k]["actions"].values()]
        d = (acc - float(np.mean([x[0] for x in theirs])), f1 - float(np.mean([x[3] for x in theirs])))
        diffs.setdefault(NORM_CONDITIONS[c].name, {}).setdefault(f, []).append(d)
    out = {}
    for name, fams in diffs.items():
        per = np.array([np.mean(v, axis=0) for v in fams.values()])
        out[name] = {"families": len(per), "accuracy": [float(per[:, 0].mean()), ci95(per[:, 0])],
                     "f1": [float(per[:, 1].mean()), ci95(per[:, 1])]}
    return out


def _trial_scores(args: tuple[int, int, int, str, float]) -> tuple[float, float]:
    """Ours' mean accuracy and F1 over the actions of one trial (family, condition, trial)."""
    family, c, t, ties, within = args
    setup = norms_setup(norm_family(family), NORM_CONDITIONS[c], trial_rng(0, c, t, family))
    mind = taught_mind(setup)
    scores = [decision_scores(setup.answers[a], cautious(mind, a, setup.true_frame, ties, within))
              for a in setup.rules]
    return float(np.mean([x.accuracy for x in scores])), float(np.mean([x.f1 for x in scores]))


def _cell(args: tuple[int, int, int, str, float]) -> dict[str, Any]:
    return cell(*args)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--family-seed", type=int, default=0)
    parser.add_argument("--families", type=int, default=100)
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--conditions", default="noiseless 0.25,noisy 0.25")
    parser.add_argument("--ties", choices=TIES, default="none")
    parser.add_argument("--within", type=float, default=1e-6)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--paper", action="store_true")
    parser.add_argument("--probfoil", type=Path, metavar="CACHE")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if args.probfoil is not None:
        result = paired(json.loads(args.probfoil.read_text()), args.ties, args.within, args.jobs)
        if args.json:
            print(json.dumps({"ties": args.ties, "within": args.within, "paired": result}, indent=2))
            return
        for name, r in result.items():
            print(f"{name}: ours - ProbFOIL accuracy {r['accuracy'][0]:+.4f} ± {r['accuracy'][1]:.4f}, "
                  f"F1 {r['f1'][0]:+.4f} ± {r['f1'][1]:.4f} ({r['families']} families)")
        return
    names = {c.name: i for i, c in enumerate(NORM_CONDITIONS) if not c.baseline}
    wanted = [s.strip() for s in args.conditions.split(",") if s.strip()]
    for name in wanted:
        if name not in names:
            parser.error(f"unknown condition {name!r}; valid conditions: {', '.join(names)}")
    if args.paper:
        wanted, args.trials = list(names), 100
    families = [-1] if args.paper else list(range(args.family_seed, args.family_seed + args.families))
    units = [(f, names[n], args.trials, args.ties, args.within) for f in families for n in wanted]
    with ProcessPoolExecutor(max_workers=max(args.jobs, 1)) as pool:
        cells = list(pool.map(_cell, units))
    summary = {n: {"below": sum(1 for x in cells if x["condition"] == n and x["ours"] < x["allow"]),
                   "families": sum(1 for x in cells if x["condition"] == n),
                   "ours": float(np.mean([x["ours"] for x in cells if x["condition"] == n]))}
               for n in wanted}
    below = [x for x in cells if x["ours"] < x["allow"]]
    if args.json:
        print(json.dumps({"ties": args.ties, "within": args.within, "first_family": args.family_seed,
                          "trials": args.trials, "summary": summary, "below": below}, indent=2))
        return
    for x in below:
        print(f"family {x['family']}, {x['condition']}: ours {x['ours']:.3f}, allow all {x['allow']:.3f}; "
              f"norms: {'; '.join(x['norms'])}")
        for a, (o, b) in x["actions"].items():
            print(f"    {a}: ours {o:.3f}, allow all {b:.3f}")
    for n, s in summary.items():
        if args.paper:
            print(f"Table 1, {n}: ours {s['ours']:.4f} accuracy")
            continue
        print(f"{n}: {s['below']} of {s['families']} family cells below allowing everything; "
              f"ours {s['ours']:.4f} mean accuracy")


if __name__ == "__main__":
    main()
