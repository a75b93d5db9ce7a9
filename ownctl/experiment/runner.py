"""Running an experiment's trials, serially or on a process pool, reproducibly.

Trial ``t`` of condition ``c`` (its index in the experiment's full condition list) draws all its
randomness from ``np.random.default_rng([seed, c, t])``, so results depend only on the seed, never
on the number of worker processes or the order in which trials finish. Trials are sent to workers
in chunks (a few per worker) so process overhead stays small.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.errors import BadValue, UnknownName
from ownctl.experiment.norms import WorldFactory
from ownctl.experiment.registry import Experiment, get_experiment
from ownctl.experiment.result import TrialResult
from ownctl.experiment.summary import ConditionSummary, summarise

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

    def as_dict(self) -> dict[str, Any]:
        """The JSON document (docs/architecture.md, section 7 shape, plus groups, counts and settings)."""
        exp = self.experiment
        return {
            "experiment": exp.name,
            "title": exp.title,
            "trials": self.trials,
            "seed": self.seed,
            "jobs": self.jobs,
            "learner": self.learner,
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
    return out


def select_conditions(exp: Experiment, names: Sequence[str] | None) -> list[int]:
    """Indices of the named conditions (all when ``names`` is None); UnknownName otherwise."""
    all_names = exp.condition_names()
    if names is None:
        return list(range(len(all_names)))
    out = []
    for n in names:
        if n not in all_names:
            raise UnknownName("condition", n, all_names)
        out.append(all_names.index(n))
    return out


def run_trial(exp: Experiment, world_factory: WorldFactory, learner: str, seed: int, c: int,
              t: int) -> TrialResult:
    """Trial ``t`` of condition ``c``: the one place a trial's random generator is made."""
    rng = np.random.default_rng([seed, c, t])
    return exp.trial(world_factory, exp.conditions[c], learner, rng)


def _run_chunk(name: str, world_factory: WorldFactory, learner: str, seed: int,
               pairs: Sequence[tuple[int, int]]) -> list[tuple[int, int, TrialResult, float]]:
    exp = get_experiment(name)
    out = []
    for c, t in pairs:
        start = time.perf_counter()
        result = run_trial(exp, world_factory, learner, seed, c, t)
        out.append((c, t, result, time.perf_counter() - start))
    return out


def _chunks(pairs: list[tuple[int, int]], jobs: int) -> list[list[tuple[int, int]]]:
    size = max(1, math.ceil(len(pairs) / (jobs * CHUNKS_PER_JOB)))
    return [pairs[i : i + size] for i in range(0, len(pairs), size)]


def check_settings(trials: int, jobs: int, learner: str) -> None:
    """BadValue / UnknownName for a trial count or job count below 1, or an unknown learner."""
    if trials < 1:
        raise BadValue(f"trials must be at least 1, got {trials}")
    if jobs < 1:
        raise BadValue(f"jobs must be at least 1, got {jobs}")
    if learner not in LEARNERS:
        raise UnknownName("learner", learner, LEARNERS)


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
) -> ExperimentResult:
    """Run ``trials`` trials of every (selected) condition of experiment ``name``.

    ``world_factory(rng)`` draws a world with its ground truth; with ``jobs > 1`` it must be
    picklable (a module-level function or a picklable object). ``progress(done, total)`` is called
    as trials finish. ``compare``: attach the paper's published values (only meaningful on the
    paper's blocks world with its norms).
    """
    exp = get_experiment(name)
    check_settings(trials, jobs, learner)
    chosen = select_conditions(exp, conditions)
    pairs = [(c, t) for t in range(trials) for c in chosen]  # interleaved: chunks of equal cost
    total = len(pairs)
    start = time.perf_counter()
    done: dict[tuple[int, int], tuple[TrialResult, float]] = {}
    if progress:
        progress(0, total)
    if jobs == 1:
        for c, t, result, secs in _iterate_serial(exp.name, world_factory, learner, seed, pairs):
            done[(c, t)] = (result, secs)
            if progress:
                progress(len(done), total)
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            futures = [pool.submit(_run_chunk, exp.name, world_factory, learner, seed, chunk)
                       for chunk in _chunks(pairs, jobs)]
            for fut in as_completed(futures):
                for c, t, result, secs in fut.result():
                    done[(c, t)] = (result, secs)
                if progress:
                    progress(len(done), total)
    summaries = []
    for c in chosen:
        cond = exp.conditions[c]
        results = [done[(c, t)][0] for t in range(trials)]
        secs = sum(done[(c, t)][1] for t in range(trials))
        refs = {k: v[cond.name] for k, v in exp.references.items() if cond.name in v and compare}
        paper = exp.paper.get(cond.name, {}) if compare else {}
        summaries.append(summarise(cond.name, c, results, exp.headline, paper, refs, secs))
    return ExperimentResult(exp, trials, seed, jobs, learner, tuple(summaries),
                            time.perf_counter() - start, world, {"paper_comparable": compare})


def _iterate_serial(name: str, world_factory: WorldFactory, learner: str, seed: int,
                    pairs: Sequence[tuple[int, int]]) -> Iterator[tuple[int, int, TrialResult, float]]:
    for pair in pairs:
        yield from _run_chunk(name, world_factory, learner, seed, [pair])
