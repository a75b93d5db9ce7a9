"""What a task run reports: one record per object and the learned beliefs' scores (reference 7.5).

:class:`TaskReport` is what :func:`ownctl.experiment.task.run_task` returns, for the in-memory
Table 3 and the MuJoCo runner alike; ``as_dict`` is the ``run`` JSON shape of docs/architecture.md, section 7.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.experiment.metrics import Scores


@dataclass(frozen=True)
class StepRecord:
    """What happened to one object: decision, truth, outcome (``delivered``, ``skipped``, ``done``)."""

    obj: int
    name: str
    outcome: str
    allowed: bool = True
    violated: bool = False
    mistake: bool = False
    forced: bool = False
    reason: str = ""
    forbidding: tuple[str, ...] = ()


@dataclass(frozen=True)
class TaskReport:
    """The outcome of a task run and the learned beliefs' quality against the ground truth.

    ``rules[action]`` scores the learned rules of every action with a true norm on the objects'
    state after the task; ``relevant`` are those among the task's steps (the paper's average);
    ``ownership[agent]`` scores the posterior on all objects (strict metric).
    """

    task: str
    records: tuple[StepRecord, ...]
    rules: dict[str, Scores] = field(default_factory=dict)
    relevant: tuple[str, ...] = ()
    ownership: dict[str, Scores] = field(default_factory=dict)

    def _names(self, pred: Callable[[StepRecord], bool]) -> list[str]:
        return [r.name for r in self.records if pred(r)]

    @property
    def mistakes(self) -> int:
        """Wrong decisions: allowed though the true norms forbid, or refused though they allow."""
        return sum(r.mistake for r in self.records)

    @property
    def delivered(self) -> list[str]:
        """Objects the robot acted on successfully."""
        return self._names(lambda r: r.outcome == "delivered")

    @property
    def skipped(self) -> list[tuple[str, str]]:
        """(object, reason) for every object left where it was."""
        return [(r.name, r.reason) for r in self.records if r.outcome == "skipped"]

    @property
    def violations(self) -> list[str]:
        """Objects acted on although the true norms forbid it."""
        return self._names(lambda r: r.outcome == "delivered" and r.violated)

    @property
    def forced(self) -> list[str]:
        """Objects the instructor made the robot act on after it refused."""
        return self._names(lambda r: r.forced)

    def rule_average(self, actions: Sequence[str] | None = None) -> Scores:
        """Rule scores averaged over ``actions`` (default: the relevant ones)."""
        return _mean([self.rules[a] for a in (self.relevant if actions is None else actions)])

    def ownership_average(self) -> Scores:
        """Ownership scores averaged over agents."""
        return _mean(list(self.ownership.values()))

    def as_dict(self) -> dict[str, Any]:
        """The ``run`` JSON shape of architecture section 7 (a runner adds its sim and wall seconds)."""
        rule, every, own = self.rule_average(), self.rule_average(list(self.rules)), self.ownership_average()
        return {
            "task": self.task,
            "delivered": self.delivered,
            "skipped": [{"object": name, "reason": reason} for name, reason in self.skipped],
            "mistakes": self.mistakes,
            "violations": self.violations,
            "forced": self.forced,
            "rule": {"accuracy": rule.accuracy, "f1": rule.f1, "actions": list(self.relevant)},
            "rule_all": {"accuracy": every.accuracy, "f1": every.f1, "actions": list(self.rules)},
            "rules": {a: {"accuracy": s.accuracy, "f1": s.f1} for a, s in self.rules.items()},
            "ownership": {"accuracy": own.accuracy, "f1": own.f1,
                          "agents": {a: {"accuracy": s.accuracy, "f1": s.f1}
                                     for a, s in self.ownership.items()}},
            "steps": [
                {"object": r.name, "outcome": r.outcome, "allowed": r.allowed, "violated": r.violated,
                 "mistake": r.mistake, "forced": r.forced, "reason": r.reason,
                 "forbidding": list(r.forbidding)}
                for r in self.records
            ],
        }


def _mean(scores: Sequence[Scores]) -> Scores:
    if not scores:
        return Scores(1.0, 1.0, 1.0, 1.0)
    return Scores(*np.mean([s.as_array() for s in scores], axis=0).tolist())
