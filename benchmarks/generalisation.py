"""Benchmark: norm learning on generated norm families, ours beside the paper's learner, ProbFOIL and
allowing everything, on the very same trials.

    pip install -r benchmarks/requirements.txt    # ProbFOIL (never a dependency of ownctl)
    python benchmarks/generalisation.py [--families 100] [--trials 20] [--jobs 2 | --scheduler ADDRESS]
        [--probfoil-families 20] [--probfoil-trials 10] [--probfoil-noisy-families 10]
        [--probfoil-noisy-trials 5] [--probfoil-budget SECONDS] [--no-probfoil] [--json]
        [--decide map|posterior|window] [--paper]

Trials are drawn by ownctl's own code (``ownctl.experiment.norms.norms_setup``): trial ``t`` of
condition ``c`` of family ``s`` uses ``[seed, s, c, t]``, exactly as ``ownctl experiment norms
--families`` does, so every learner sees the same worlds, claims, permitted objects and answers.
ProbFOIL 2.1 (``probfoil``) gets, per action, the permitted objects as examples (1.0 forbidden,
0.0 allowed), their ownership claims as probabilistic facts, their colours and areas as facts, the
modes ``ownedBy(+, c)``, ``ownedBy(+, -)`` (owned by anyone), ``isColored(+, c)``, ``inArea(+, c)``
(negation on), and its default settings. Its clauses (with their rule probabilities) are scored
with ownctl's metrics on every object with its true owners, like ours.

ProbFOIL is slow (about a second per action without noise, 10-30 s with noisy ownership): its
results are cached per (family seed, condition, trial) in ``benchmarks/data/probfoil.json`` and the
run resumes from the cache; ``--probfoil-budget`` stops starting new ProbFOIL trials after that many
seconds (run it with ``nice -n 19`` on a shared machine). Ours, the paper's learner and allowing
everything run on ``--families`` families of ``--trials`` trials each, on ``--jobs`` local
processes or, with ``--scheduler tcp://host:8786``, on the workers of that Dask cluster (the same
numbers: every trial carries its seed; ProbFOIL stays on this machine, beside its cache).

Prints one table per condition group: mean over families (95% CI over families), worst family,
the number of family cells below ProbFOIL and below allowing everything, and the paired difference
ours - ProbFOIL (mean over families of the per-family mean difference, 95% CI) on the trials
ProbFOIL ran. The committed cache holds the subset run so far (``nice -n 19``, 20 families x the
three noiseless conditions x 3 trials, 10 families x the three noisy conditions x 2 trials):

    nice -n 19 python benchmarks/generalisation.py --probfoil-trials 3 --probfoil-noisy-trials 2
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ownctl.config import DECIDE_RULES  # noqa: E402
from ownctl.errors import OwnctlError  # noqa: E402
from ownctl.experiment.cluster import executor  # noqa: E402
from ownctl.experiment.metrics import ci95, rule_scores  # noqa: E402
from ownctl.experiment.norms import NORM_CONDITIONS, norms_setup, norms_trial  # noqa: E402
from ownctl.experiment.runner import trial_rng  # noqa: E402
from ownctl.world.families import EVALUATION_SEEDS, norm_family  # noqa: E402
from ownctl.world.generator import paper_blocks_world  # noqa: E402
from ownctl.world.model import positions  # noqa: E402

CACHE = ROOT / "benchmarks" / "data" / "probfoil.json"
CONDITIONS = [c for c in NORM_CONDITIONS if not c.baseline]
SEED = 0


PAPER = -1  # the "family seed" of the paper's own blocks world and norms (--paper)


def _rng(family: int, c: int, t: int) -> np.random.Generator:
    """Trial ``t`` of condition ``c``: as ``ownctl experiment norms --families`` draws it, or, for the
    paper's world, exactly as Table 1 (``ownctl experiment norms``, seed 0) does."""
    return trial_rng(SEED, c, t, None if family == PAPER else family)


def world_of(family: int) -> Any:
    """The world factory of a family seed (:data:`PAPER`: the paper's blocks world)."""
    return paper_blocks_world if family == PAPER else norm_family(family)


# -- ProbFOIL on one trial -----------------------------------------------------------------------
def probfoil_program(setup: Any, action: str) -> str:
    """The ProbFOIL input for one action of one trial: permitted objects only."""
    world = setup.world
    pos = positions(world.objects)[:, :2]
    lines = ["base(ownedBy(obj, agent)).", "base(isColored(obj, colour)).", "base(inArea(obj, area)).",
             f"base({action}(obj)).", "mode(ownedBy(+, c)).", "mode(ownedBy(+, -)).",
             "mode(isColored(+, c)).", "mode(inArea(+, c)).", f"learn({action}/1).", "example_mode(closed)."]
    for i in setup.chosen:
        obj = world.objects[int(i)]
        name = obj.name.lower()
        for j, agent in enumerate(world.agents):
            p = float(setup.claims[int(i), j])
            if p >= 1.0:
                lines.append(f"ownedBy({name}, {agent.lower()}).")
            elif p > 0.0:
                lines.append(f"{p:.6f}::ownedBy({name}, {agent.lower()}).")
        if obj.color:
            lines.append(f"isColored({name}, {obj.color.lower()}).")
        for area in world.areas:
            if area.contains(pos[int(i)][None])[0]:
                lines.append(f"inArea({name}, {area.name.lower()}).")
        value = float(setup.answers[action][int(i)])
        lines.append(f"{value:.1f}::{action}({name}).")
    return "\n".join(lines) + "\n"


def _literals(body: Any) -> list[Any]:
    from problog.logic import And

    out, stack = [], [body]
    while stack:
        term = stack.pop()
        if isinstance(term, And):
            stack += [term.op2, term.op1]
        else:
            out.append(term)
    return out


def clause_texts(clauses: Sequence[Any]) -> list[dict[str, Any]]:
    """Each clause as {"p": rule probability, "literals": [[negated, predicate, argument or null]]}."""
    from problog.logic import Not, Var

    out = []
    for clause in clauses:
        body = getattr(clause, "body", None)
        if body is None or str(body) == "fail":
            continue
        p = clause.head.probability
        lits = []
        for term in _literals(body):
            negated = isinstance(term, Not)
            atom = term.args[0] if negated else term
            arg = atom.args[1] if len(atom.args) > 1 else None
            name = None if arg is None or isinstance(arg, Var) else str(arg)
            lits.append([negated, str(atom.functor), name])
        out.append({"p": 1.0 if p is None else float(p), "literals": lits})
    return out


def clause_forbid(clauses: Sequence[dict[str, Any]], setup: Any) -> np.ndarray:
    """P(forbidden) per object under ProbFOIL's clauses with every object's true owners (rule
    probabilities as independent choices: 1 - prod(1 - p) over the clauses whose body holds)."""
    world = setup.world
    truth = world.true_ownership()
    pos = positions(world.objects)[:, :2]
    areas = {a.name.lower(): a.contains(pos) for a in world.areas}
    agents = [a.lower() for a in world.agents]
    n = len(world.objects)
    keep = np.ones(n)
    for clause in clauses:
        holds = np.ones(n, dtype=bool)
        for negated, pred, arg in clause["literals"]:
            if pred == "ownedBy" and arg is None:
                value = truth.sum(axis=1) > 0
            elif pred == "ownedBy":
                value = truth[:, agents.index(arg)] > 0 if arg in agents else np.zeros(n, dtype=bool)
            elif pred == "isColored":
                value = np.array([(o.color or "").lower() == arg if arg else o.color is not None
                                  for o in world.objects])
            elif arg:
                value = areas.get(arg, np.zeros(n, dtype=bool))
            else:
                value = np.any(list(areas.values()), axis=0)
            holds &= ~value if negated else value
        keep *= np.where(holds, 1.0 - clause["p"], 1.0)
    return 1.0 - keep


def run_probfoil(unit: tuple[int, int, int]) -> tuple[str, dict[str, Any]]:
    """ProbFOIL on every action of one trial: its clauses and ownctl's scores of them."""
    from probfoil.data import DataFile
    from probfoil.probfoil import ProbFOIL2
    from problog.program import PrologString

    os.nice(19) if os.nice(0) < 19 else None
    seed, c, t = unit
    family = world_of(seed)
    setup = norms_setup(family, NORM_CONDITIONS[c], _rng(seed, c, t))
    start = time.perf_counter()
    actions: dict[str, Any] = {}
    for action in setup.rules:
        learner = ProbFOIL2(DataFile(PrologString(probfoil_program(setup, action))), beam_size=5, m=1,
                            l=None, p=None, logger="probfoil")
        hyp = learner.learn()
        clauses = clause_texts(hyp.to_clauses(hyp.target.functor))
        score = rule_scores(setup.answers[action], clause_forbid(clauses, setup))
        actions[action] = {"clauses": clauses, "scores": [float(x) for x in score.as_array()]}
    return key(seed, c, t), {"actions": actions, "seconds": time.perf_counter() - start}


def key(seed: int, c: int, t: int) -> str:
    """The cache key of one trial."""
    return f"{'paper' if seed == PAPER else seed}/{NORM_CONDITIONS[c].name}/{t}"


# -- ours, the paper's learner, allowing everything ------------------------------------------------
def run_ours(unit: tuple[int, int, int, str]) -> tuple[tuple[int, int, int], dict[str, list[float]]]:
    """Mean accuracy and F1 over actions of ours, the paper learner and allow-all on one trial
    (``unit``: family seed, condition, trial, and how learned rules decide: ``decide.rules``)."""
    seed, c, t, decide = unit
    family = world_of(seed)
    out = {}
    for learner in ("ours", "paper"):
        scores = norms_trial(family, NORM_CONDITIONS[c], learner, _rng(seed, c, t), decide)
        out[learner] = [float(np.mean([s.accuracy for s in scores.values()])),
                        float(np.mean([s.f1 for s in scores.values()]))]
    setup = norms_setup(family, NORM_CONDITIONS[c], _rng(seed, c, t))
    base = [rule_scores(setup.answers[a], np.zeros(len(setup.world.objects))) for a in setup.rules]
    out["allow"] = [float(np.mean([s.accuracy for s in base])), float(np.mean([s.f1 for s in base]))]
    return (seed, c, t), out


def _family_means(values: dict[tuple[int, int, int], float], c: int) -> dict[int, float]:
    """Each family's mean over its trials of condition ``c`` (the paper's world: each trial alone, so
    that intervals and paired differences are over trials)."""
    per: dict[int, list[float]] = {}
    for (seed, cc, t), v in values.items():
        if cc == c:
            per.setdefault(t if seed == PAPER else seed, []).append(v)
    return {s: float(np.mean(v)) for s, v in per.items()}


def _cell(means: dict[int, float]) -> dict[str, Any]:
    arr = np.array(list(means.values()))
    if not len(arr):
        return {"mean": None, "ci95": None, "worst": None, "families": 0}
    worst = min(means, key=lambda s: (means[s], s))
    return {"mean": float(arr.mean()), "ci95": ci95(arr), "worst": [worst, means[worst]],
            "families": len(arr)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--families", type=int, default=100)
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--family-seed", type=int, default=EVALUATION_SEEDS.start)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--decide", choices=DECIDE_RULES, default="map",
                        help="ours and the paper learner decide on the most probable rule set, "
                        "marginalised over the rule-set posterior, or on the mean over the near-best "
                        "rule sets (decide.rules; the last two slower)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run ours, the paper's learner and allow-all on this Dask cluster (tcp://host:8786)")
    parser.add_argument("--probfoil-families", type=int, default=20)
    parser.add_argument("--probfoil-trials", type=int, default=10)
    parser.add_argument("--probfoil-noisy-families", type=int, default=10)
    parser.add_argument("--probfoil-noisy-trials", type=int, default=5)
    parser.add_argument("--probfoil-budget", type=float, default=None, metavar="SECONDS")
    parser.add_argument("--no-probfoil", action="store_true")
    parser.add_argument("--paper", action="store_true",
                        help="the paper's blocks world and norms, trials drawn exactly as Table 1's, "
                        "instead of norm families (--families and --probfoil-*families ignored)")
    parser.add_argument("--cache", default=str(CACHE))
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--table", metavar="FILE.json", help="print the table of an earlier --json run")
    args = parser.parse_args()
    if args.table:
        _print(json.loads(Path(args.table).read_text()))
        return
    if args.paper:
        args.family_seed, args.families = PAPER, 1
        args.probfoil_families = args.probfoil_noisy_families = 1
    seeds = [args.family_seed + k for k in range(args.families)]

    units = [(s, c, t) for s in seeds for c in range(len(CONDITIONS)) for t in range(args.trials)]
    try:
        with executor(args.jobs, args.scheduler) as (pool, _):
            ours = dict(pool.map(run_ours, [(*u, args.decide) for u in units], chunksize=20))
    except OwnctlError as exc:
        sys.exit(f"generalisation: {exc.message}")

    cache_path = Path(args.cache)
    cache: dict[str, Any] = json.loads(cache_path.read_text()) if cache_path.exists() else {}
    wanted = []
    for c, cond in enumerate(CONDITIONS):
        n_fam = args.probfoil_noisy_families if cond.noisy else args.probfoil_families
        n_tri = args.probfoil_noisy_trials if cond.noisy else args.probfoil_trials
        wanted += [(args.family_seed + k, c, t) for k in range(n_fam) for t in range(n_tri)]
    if not args.no_probfoil:
        todo = [u for u in wanted if key(*u) not in cache]
        start = time.perf_counter()
        with ProcessPoolExecutor(max_workers=args.jobs) as pool:
            pending = iter(todo)
            running = {}
            for unit in pending:
                spent = time.perf_counter() - start
                if args.probfoil_budget is not None and spent > args.probfoil_budget:
                    break
                running[pool.submit(run_probfoil, unit)] = unit
                if len(running) >= args.jobs:
                    done = next(iter(running))
                    k, value = done.result()
                    running.pop(done)
                    cache[k] = value
                    cache_path.write_text(json.dumps(cache, indent=1, sort_keys=True))
            for fut in running:
                k, value = fut.result()
                cache[k] = value
            cache_path.parent.mkdir(parents=True, exist_ok=True)
            cache_path.write_text(json.dumps(cache, indent=1, sort_keys=True))

    report: dict[str, Any] = {"families": len(seeds), "trials": args.trials, "decide": args.decide,
                              "first_family": args.family_seed, "conditions": []}
    for c, cond in enumerate(CONDITIONS):
        row: dict[str, Any] = {"name": cond.name}
        for metric, m in (("accuracy", 0), ("f1", 1)):
            cells = {sys_: _cell(_family_means({u: v[sys_][m] for u, v in ours.items()}, c))
                     for sys_ in ("ours", "paper", "allow")}
            pf_units = [u for u in wanted if u[1] == c and key(*u) in cache]
            pf_vals = {u: float(np.mean([a["scores"][0 if m == 0 else 3]
                                         for a in cache[key(*u)]["actions"].values()])) for u in pf_units}
            pf = _family_means(pf_vals, c)
            ours_same = _family_means({u: ours[u]["ours"][m] for u in pf_units if u in ours}, c)
            allow_same = _family_means({u: ours[u]["allow"][m] for u in pf_units if u in ours}, c)
            diffs = {s: ours_same[s] - pf[s] for s in pf if s in ours_same}
            fam_ours = _family_means({u: v["ours"][m] for u, v in ours.items()}, c)
            fam_allow = _family_means({u: v["allow"][m] for u, v in ours.items()}, c)
            row[metric] = {
                **cells,
                "probfoil": _cell(pf),
                "ours_on_probfoil_trials": _cell(ours_same),
                "allow_on_probfoil_trials": _cell(allow_same),
                "below_probfoil": sum(d < -1e-12 for d in diffs.values()),
                "below_allow": sum(fam_ours[s] < fam_allow[s] - 1e-12 for s in fam_ours),
                "paired_ours_minus_probfoil": _cell(diffs) if diffs else None,
            }
        report["conditions"].append(row)
    if args.json:
        print(json.dumps(report))
        return
    _print(report)


def _fmt(cell: dict[str, Any] | None) -> str:
    if not cell or cell.get("mean") is None:
        return "-"
    return f"{cell['mean']:.3f}±{cell['ci95']:.3f}"


def _print(report: dict[str, Any]) -> None:
    where = ("the paper's blocks world (Table 1's trials)" if report["first_family"] == PAPER
             else f"{report['families']} norm families from seed {report['first_family']}")
    print(f"{where}, {report['trials']} trials "
          f"each (ours, paper, allow everything; rules decide by {report.get('decide', 'map')}); "
          "ProbFOIL on the trials in its cache")
    for metric in ("accuracy", "f1"):
        unit = "trial" if report["first_family"] == PAPER else "family"
        print(f"\n{metric}: mean over {unit.replace('y', 'ie')}s ± 95% CI [worst {unit}]")
        print(f"{'condition':15s} {'ours':>20s} {'paper':>20s} {'allow all':>20s} | {'ProbFOIL':>12s} "
              f"{'ours (same)':>12s} {'ours-PF':>14s} {'<PF':>4s} {'<all':>5s}")
        for row in report["conditions"]:
            r = row[metric]

            def both(cell: dict[str, Any]) -> str:
                return f"{_fmt(cell)} [{cell['worst'][1]:.2f}]" if cell.get("worst") else "-"

            cells = f"{both(r['ours']):>20s} {both(r['paper']):>20s} {both(r['allow']):>20s}"
            print(f"{row['name']:15s} {cells} | {_fmt(r['probfoil']):>12s} "
                  f"{_fmt(r['ours_on_probfoil_trials']):>12s} {_fmt(r['paired_ours_minus_probfoil']):>14s} "
                  f"{r['below_probfoil']:4d} {r['below_allow']:5d}")
        counts = ", ".join(str(row[metric]["probfoil"]["families"]) for row in report["conditions"])
        units = unit.replace("y", "ie") + "s"
        print(f"(ProbFOIL {units} per condition: {counts}; worst {units}: in the --json output)")


if __name__ == "__main__":
    main()
