"""The paper's three experiments as a registry: conditions, trial function, headline, paper values.

Each experiment names the group of scores its headline accuracy/F1 come from (Table 1: the learned
rules over the true norms' actions; Table 2: ownership on the held-out half; Table 3: the rules over
the task's relevant actions, as the paper averaged them) and carries the published numbers beside
which ours are shown.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.errors import UnknownName
from ownctl.experiment.norms import NORM_CONDITIONS, WorldFactory, norms_result
from ownctl.experiment.online import TASK_CONDITIONS, task_trial
from ownctl.experiment.ownership import OWNERSHIP_CONDITIONS, ownership_trial
from ownctl.experiment.result import TrialResult

TrialFn = Callable[[WorldFactory, Any, str, np.random.Generator, str], TrialResult]  # ..., decide
Paper = Mapping[str, Mapping[str, Any]]

RULE_METRICS = (
    "rules: per action, an object counts as correct when (true - 0.5)(learned - 0.5) >= 0, with both "
    "rule sets evaluated on the object's true owners; positive = forbidden; precision and recall are 1 "
    "when their class is empty, so where an action forbids nothing F1 is 1 if the learned rules forbid "
    "nothing there either and 0 if they forbid anything; averaged over trials, then over actions"
)
OWNERSHIP_METRICS = (
    "ownership: per agent, the posterior p is correct only when (true - 0.5)(p - 0.5) > 0 (strict: "
    "0.5 is always wrong); positive = owned; averaged over trials, then over agents"
)
CI_NOTE = "ci95: half-width of the 95% t-interval over trials (of the per-trial average over rows)"


@dataclass(frozen=True)
class Experiment:
    """One table of the paper: how to run a trial and how to present the result."""

    name: str
    title: str
    conditions: tuple[Any, ...]
    trial: TrialFn
    headline: str  # the group whose row average is the condition's accuracy/F1
    rows: str  # what the rows of a group are: "action" or "agent"
    paper: Paper  # condition name -> {"accuracy", "f1", ...}
    references: Mapping[str, Paper] = field(default_factory=dict)  # other published systems
    metrics: tuple[str, ...] = ()
    groups: Mapping[str, str] = field(default_factory=dict)  # group -> description
    optional: frozenset[str] = frozenset()  # conditions run only when named (another protocol)

    def condition_names(self) -> list[str]:
        """Names of the conditions, in order."""
        return [c.name for c in self.conditions]

    def default_names(self) -> list[str]:
        """Names of the conditions run when none are named: all but the optional ones."""
        return [n for n in self.condition_names() if n not in self.optional]


NORMS = Experiment(
    name="norms",
    title="Table 1: norm learning from permissions",
    conditions=NORM_CONDITIONS,
    trial=norms_result,
    headline="rules",
    rows="action",
    paper={
        "noiseless 1.00": {"accuracy": 0.995, "f1": 0.995},
        "noiseless 0.50": {"accuracy": 0.945, "f1": 0.875},
        "noiseless 0.25": {"accuracy": 0.787, "f1": 0.523},
        "noisy 1.00": {"accuracy": 0.889, "f1": 0.840},
        "noisy 0.50": {"accuracy": 0.842, "f1": 0.724},
        "noisy 0.25": {"accuracy": 0.761, "f1": 0.519},
        "allow everything": {"accuracy": 0.583, "f1": 0.000},
    },
    references={
        "probfoil": {
            "noiseless 1.00": {"accuracy": 1.000, "f1": 1.000},
            "noiseless 0.50": {"accuracy": 0.983, "f1": 0.949},
            "noiseless 0.25": {"accuracy": 0.885, "f1": 0.732},
            "noisy 1.00": {"accuracy": 0.969, "f1": 0.979},
            "noisy 0.50": {"accuracy": 0.912, "f1": 0.869},
            "noisy 0.25": {"accuracy": 0.801, "f1": 0.637},
        }
    },
    metrics=(RULE_METRICS, CI_NOTE),
    groups={"rules": "learned rules vs the true norms on all objects"},
)

OWNERSHIP = Experiment(
    name="ownership",
    title="Table 2: ownership prediction and inference",
    conditions=OWNERSHIP_CONDITIONS,
    trial=ownership_trial,
    headline="test",
    rows="agent",
    paper={
        "(i) no inference": {"accuracy": 0.904, "f1": 0.757},
        "(ii) rules learned": {"accuracy": 0.897, "f1": 0.747},
        "(iii) rules given": {"accuracy": 0.896, "f1": 0.744},
    },
    metrics=(OWNERSHIP_METRICS, CI_NOTE),
    groups={"test": "ownership on the held-out half", "all": "ownership on all objects"},
    optional=frozenset(c.name for c in OWNERSHIP_CONDITIONS if c.claims != "all"),
)

TASK = Experiment(
    name="task",
    title="Table 3: task-based online evaluation",
    conditions=TASK_CONDITIONS,
    trial=task_trial,
    headline="rules",
    rows="action",
    paper={
        "collectAll": {"accuracy": 0.975, "f1": 0.937, "mistakes": 6.30,
                       "ownership": {"accuracy": 0.344, "f1": 0.273}},
        "trashAll": {"accuracy": 0.877, "f1": 0.812, "mistakes": 6.32,
                     "ownership": {"accuracy": 0.822, "f1": 0.511}},
    },
    metrics=(
        "mistakes: decisions the true norms contradict (allowed though forbidden, or refused though "
        "allowed), per run of the task over 20 objects",
        RULE_METRICS + "; 'rules' = the task's relevant actions (its steps with a true norm, as the "
        "paper averaged), 'rules_all' = every action with a true norm; objects in their state after "
        "the task",
        OWNERSHIP_METRICS + "; on all objects",
        CI_NOTE,
    ),
    groups={
        "rules": "learned rules over the task's relevant actions",
        "rules_all": "learned rules over every action with a true norm",
        "ownership": "ownership on all objects",
    },
)

EXPERIMENTS: dict[str, Experiment] = {e.name: e for e in (NORMS, OWNERSHIP, TASK)}


def get_experiment(name: str) -> Experiment:
    """The experiment called ``name``; UnknownName listing them otherwise."""
    try:
        return EXPERIMENTS[name]
    except KeyError:
        raise UnknownName("experiment", name, EXPERIMENTS) from None
