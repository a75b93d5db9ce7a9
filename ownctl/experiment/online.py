"""Table 3: task-based online evaluation (docs/architecture.md, section 8).

Each trial draws a new world and runs ``collectAll`` or ``trashAll`` with nothing known up front
(no claims, permissions or rules), inference and prediction on, a kinematic executor and the oracle
instructor. Reported per trial: mistakes and the other counts of the run, rule scores over the
task's relevant actions (its steps with a true norm: the paper's average) and over every action
with a true norm, per action, and ownership scores on all objects per agent.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ownctl.config import LearnConfig, Settings
from ownctl.experiment.kinematic import KinematicExecutor
from ownctl.experiment.norms import WorldFactory
from ownctl.experiment.oracle import OracleInstructor
from ownctl.experiment.result import TrialResult
from ownctl.experiment.task import run_task
from ownctl.experiment.task_report import TaskReport
from ownctl.mind import Mind, Switches


@dataclass(frozen=True)
class TaskCondition:
    """One row of Table 3: the task to run."""

    name: str
    task: str


TASK_CONDITIONS = (TaskCondition("collectAll", "collectAll"), TaskCondition("trashAll", "trashAll"))


def task_trial(make_world: WorldFactory, cond: TaskCondition, learner: str,
               rng: np.random.Generator, decide: str = "map") -> TrialResult:
    """One task run on a fresh world; groups ``rules``, ``rules_all`` (per action), ``ownership``.
    ``decide``: how rules decide a step (``decide.rules``, docs/architecture.md section 3)."""
    world = make_world(rng)
    settings = Settings(learn=LearnConfig(learner=learner), decide_rules=decide)
    mind = Mind(world.agents, list(world.objects), world.areas, settings, Switches())
    report = run_task(mind, world, cond.task, KinematicExecutor(world), OracleInstructor(world))
    return report_result(report)


def report_result(report: TaskReport) -> TrialResult:
    """A task report as a trial result (groups and counts)."""
    groups = {
        "rules": {a: report.rules[a] for a in report.relevant},
        "rules_all": dict(report.rules),
        "ownership": dict(report.ownership),
    }
    counts = {
        "mistakes": float(report.mistakes),
        "delivered": float(len(report.delivered)),
        "skipped": float(len(report.skipped)),
        "violations": float(len(report.violations)),
        "forced": float(len(report.forced)),
    }
    return TrialResult(groups, counts)
