"""Running an experiment's trials, serially, on a process pool or on a Dask cluster, reproducibly.

Trial ``t`` of condition ``c`` (its index in the experiment's full condition list) draws all its
randomness from ``np.random.default_rng([seed, c, t])``, so results depend only on the seed, never
on the number of worker processes, the cluster, or the order in which trials finish. Trials are
sent to workers in chunks (a few per worker) so process overhead stays small
(:mod:`ownctl.experiment.cluster` picks the workers).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import as_completed
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.cluster import executor
from ownctl.experiment.norms import WorldFactory
from ownctl.experiment.registry import Experiment, get_experiment
from ownctl.experiment.result import TrialResult
from ownctl.experiment.summary import FAMILY_NOTE, ConditionSummary, summarise, summarise_families
from ownctl.mind.core import decide_mode
from ownctl.world.families import NormFamily

Progress = Callable[[int, int], None]  # (trials done, trials in total)
CHUNKS_PER_JOB = 6

LEARNERS = ("ours", "paper")


@dataclass(frozen=True)
class ExperimentResult:
    """All conditions of one experiment run, with the settings that reproduce it."""

    experiment: Experiment
    trials: int
    seed: int
    jobs: int
    learner: str
    conditions: tuple[ConditionSummary, ...]
    seconds: float
    world: str = "paper blocks world"
    extra: dict[str, Any] = field(default_factory=dict)
    scheduler: str | None = None  # the Dask scheduler the trials ran on (None: this machine)
    decide: str = "map"  # how learned rules decided and were scored (decide.rules)

    def as_dict(self) -> dict[str, Any]:
        """The JSON document (docs/architecture.md, section 7 shape, plus groups, counts and settings)."""
        exp = self.experiment
        return {
            "experiment": exp.name,
            "title": exp.title,
            "trials": self.trials,
            "seed": self.seed,
            "jobs": self.jobs,
            "scheduler": self.scheduler,
            "learner": self.learner,
            "decide": self.decide,
            "world": self.world,
            "headline": exp.headline,
            "conditions": [_condition_dict(c) for c in self.conditions],
            "metrics": list(exp.metrics),
            "seconds": self.seconds,
            **self.extra,
        }


def _condition_dict(c: ConditionSummary) -> dict[str, Any]:
    out: dict[str, Any] = {
        "name": c.name,
        "accuracy": c.accuracy.mean,
        "f1": c.f1.mean,
        "ci95": {"accuracy": c.accuracy.ci95, "f1": c.f1.ci95},
        "paper": dict(c.paper),
    }
    if c.references:
        out["references"] = {k: dict(v) for k, v in c.references.items()}
    out["counts"] = {k: v.as_dict() for k, v in c.counts.items()}
    out["groups"] = {k: g.as_dict() for k, g in c.groups.items()}
    out["trials"] = c.trials
    out["trial_seconds"] = c.seconds
    if c.worst:
        out["worst_family"] = {m: {"seed": seed, "mean": value} for m, (seed, value) in c.worst.items()}
    return out


def select_conditions(exp: Experiment, names: Sequence[str] | None) -> list[int]:
    """Indices of the named conditions (when ``names`` is None, all but the experiment's optional
    ones); UnknownName otherwise."""
    all_names = exp.condition_names()
    if names is None:
        return [all_names.index(n) for n in exp.default_names()]
    out = []
    for n in names:
        if n not in all_names:
            raise UnknownName("condition", n, all_names)
        out.append(all_names.index(n))
    return out


def trial_rng(seed: int, c: int, t: int, family: int | None = None) -> np.random.Generator:
    """The random generator of trial ``t`` of condition ``c`` (of norm family ``family``, if given):
    the one place a trial's generator is made, for the experiments and for the benchmarks that run
    other learners or versions on the very same trials."""
    return np.random.default_rng([seed, c, t] if family is None else [seed, family, c, t])


def run_trial(exp: Experiment, world_factory: WorldFactory, learner: str, seed: int, c: int,
              t: int, family: int | None = None, decide: str = "map") -> TrialResult:
    """Trial ``t`` of condition ``c`` (of norm family ``family``, if given), on :func:`trial_rng`."""
    return exp.trial(world_factory, exp.conditions[c], learner, trial_rng(seed, c, t, family), decide)


Unit = tuple[int, int, int]  # (world factory index, condition index, trial)


def _run_chunk(name: str, factories: Sequence[WorldFactory], learner: str, seed: int,
               units: Sequence[Unit], decide: str = "map") -> list[tuple[Unit, TrialResult, float]]:
    exp = get_experiment(name)
    out = []
    for unit in units:
        f, c, t = unit
        factory = factories[f]
        family = factory.seed if isinstance(factory, NormFamily) else None
        start = time.perf_counter()
        result = run_trial(exp, factories[f], learner, seed, c, t, family, decide)
        out.append((unit, result, time.perf_counter() - start))
    return out


def _chunks(pairs: list[Unit], jobs: int) -> list[list[Unit]]:
    size = max(1, math.ceil(len(pairs) / (jobs * CHUNKS_PER_JOB)))
    return [pairs[i : i + size] for i in range(0, len(pairs), size)]


MAX_TRIALS = 100_000  # per condition: every trial is planned before the first runs
MAX_JOBS = 1024  # worker processes on one machine (a cluster is given by --scheduler)


def check_settings(trials: int, jobs: int, learner: str, scheduler: str | None = None,
                   decide: str = "map", seed: int = 0) -> None:
    """BadValue / UnknownName for a trial count outside 1..MAX_TRIALS or a job count outside
    1..MAX_JOBS, a negative seed, an unknown learner, both local jobs and a scheduler, or an unknown
    decision mode."""
    if not 1 <= trials <= MAX_TRIALS:
        raise BadValue(f"--trials must be an integer from 1 to {MAX_TRIALS:,}, got {trials}")
    if not 1 <= jobs <= MAX_JOBS:
        raise BadValue(f"--jobs must be an integer from 1 to {MAX_JOBS:,}, got {jobs}")
    check_seed(seed)
    if learner not in LEARNERS:
        raise UnknownName("learner", learner, LEARNERS)
    if scheduler is not None and jobs != 1:
        raise BadValue(f"--jobs {jobs} and --scheduler {scheduler} are alternatives: give one of them")
    if scheduler is not None and not scheduler.strip():
        raise BadValue("--scheduler needs an address such as tcp://host:8786")
    decide_mode(decide)


def check_seed(seed: int, option: str = "--seed") -> int:
    """``seed`` if it is a non-negative integer (what numpy's generators take); BadValue naming
    ``option`` otherwise."""
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise BadValue(f"{option} must be a non-negative integer, got {seed!r}")
    return seed


def run_trials(name: str, factories: Sequence[WorldFactory], learner: str, seed: int, units: Sequence[Unit],
               jobs: int = 1, scheduler: str | None = None, progress: Progress | None = None,
               decide: str = "map") -> dict[Unit, tuple[TrialResult, float]]:
    """Every unit's trial result and its seconds: in this process (``jobs`` 1, no ``scheduler``), on
    ``jobs`` local processes, or on the Dask cluster of ``scheduler``; the same results for all.
    ``decide``: how learned rules decide and are scored (``map`` or ``posterior``)."""
    done: dict[Unit, tuple[TrialResult, float]] = {}
    total = len(units)
    if jobs == 1 and scheduler is None:
        for unit, result, secs in _iterate_serial(name, factories, learner, seed, units, decide):
            done[unit] = (result, secs)
            if progress:
                progress(len(done), total)
        return done
    with executor(jobs, scheduler) as (pool, slots):
        futures = [pool.submit(_run_chunk, name, factories, learner, seed, chunk, decide)
                   for chunk in _chunks(list(units), slots)]
        for fut in as_completed(futures):
            for unit, result, secs in fut.result():
                done[unit] = (result, secs)
            if progress:
                progress(len(done), total)
    return done


def run_experiment(
    name: str,
    trials: int,
    seed: int,
    jobs: int,
    world_factory: WorldFactory,
    learner: str,
    progress: Progress | None = None,
    conditions: Sequence[str] | None = None,
    world: str = "paper blocks world",
    compare: bool = True,
    families: Sequence[NormFamily] = (),
    scheduler: str | None = None,
    decide: str = "map",
) -> ExperimentResult:
    """Run ``trials`` trials of every (selected) condition of experiment ``name``.

    ``world_factory(rng)`` draws a world with its ground truth; with ``jobs > 1`` it must be
    picklable (a module-level function or a picklable object). ``progress(done, total)`` is called
    as trials finish. ``compare``: attach the paper's published values (only meaningful on the
    paper's blocks world with its norms). With ``families``, the trials run on each norm family
    instead of ``world_factory`` (trial ``t`` of condition ``c`` of family ``s`` draws from
    ``[seed, s, c, t]``), and each condition reports the mean over families, with its 95% interval
    over families, and the worst family (:func:`~ownctl.experiment.summary.summarise_families`).
    ``scheduler`` (``tcp://host:8786``) runs the trials on that Dask cluster instead of ``jobs``
    local processes. ``decide``: how learned rules decide and are scored (``map`` or ``posterior``).
    """
    exp = get_experiment(name)
    check_settings(trials, jobs, learner, scheduler, decide, seed)
    chosen = select_conditions(exp, conditions)
    factories: list[WorldFactory] = list(families) or [world_factory]
    units = [(f, c, t) for f in range(len(factories)) for t in range(trials) for c in chosen]
    start = time.perf_counter()
    if progress:
        progress(0, len(units))
    done = run_trials(exp.name, factories, learner, seed, units, jobs, scheduler, progress, decide)
    per_factory = [[_condition(exp, c, [done[(f, c, t)] for t in range(trials)], compare) for c in chosen]
                   for f in range(len(factories))]
    extra: dict[str, Any] = {"paper_comparable": compare and not families}
    if not families:
        summaries = per_factory[0]
    else:
        summaries = [summarise_families([per_factory[f][k] for f in range(len(families))],
                                        [fam.seed for fam in families])
                     for k in range(len(chosen))]
        extra["family_note"] = FAMILY_NOTE
        extra["families"] = [_family_dict(fam, per_factory[f]) for f, fam in enumerate(families)]
        world = f"{len(families)} norm families (seeds {families[0].seed}-{families[-1].seed})"
    return ExperimentResult(exp, trials, seed, jobs, learner, tuple(summaries),
                            time.perf_counter() - start, world, extra, scheduler, decide)


def _condition(exp: Experiment, c: int, results: Sequence[tuple[TrialResult, float]],
               compare: bool) -> ConditionSummary:
    """One condition's trials aggregated, with the published values when ``compare``."""
    cond = exp.conditions[c]
    refs = {k: v[cond.name] for k, v in exp.references.items() if cond.name in v and compare}
    paper = exp.paper.get(cond.name, {}) if compare else {}
    return summarise(cond.name, c, [r for r, _ in results], exp.headline, paper, refs,
                     sum(secs for _, secs in results))


def _family_dict(family: NormFamily, conditions: Sequence[ConditionSummary]) -> dict[str, Any]:
    """A family and its per-condition headline means (the JSON document's ``families``)."""
    return {
        "seed": family.seed,
        "norms": list(family.norms),
        "actions": list(family.actions),
        "features": sorted(family.features()),
        "rare": list(family.rare),
        "home_agent": family.home_agent,
        "conditions": {c.name: {"accuracy": c.accuracy.mean, "f1": c.f1.mean} for c in conditions},
    }


def _iterate_serial(name: str, factories: Sequence[WorldFactory], learner: str, seed: int,
                    units: Sequence[Unit], decide: str = "map") -> Iterator[tuple[Unit, TrialResult, float]]:
    for unit in units:
        yield from _run_chunk(name, factories, learner, seed, [unit], decide)
