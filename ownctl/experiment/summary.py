"""Aggregating trials into the tables: means and 95% t-intervals, per row and averaged over rows.

Like the paper, a row's figure is the mean over trials, and a group's figure is the mean of its
rows (equal to the mean over trials of the per-trial row averages, whose spread gives the
interval). Conditions carry the paper's published values for display beside ours.

Over norm families, each family's condition is first aggregated over its trials; a condition's
figure is then the mean over families of those means, its interval the 95% t-interval over
families, and the worst family the one with the lowest mean (:func:`summarise_families`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ownctl.experiment.metrics import Scores, ci95
from ownctl.experiment.result import TrialResult

FIELDS = ("accuracy", "precision", "recall", "f1")
FAMILY_NOTE = (
    "families: a condition's figure is the mean over families of each family's mean over its trials "
    "(ci95 over families); worst = the family with the lowest mean (its seed in brackets); every "
    "action a family names is scored, with or without a norm"
)


@dataclass(frozen=True)
class Cell:
    """A mean over trials and the half-width of its 95% t-interval."""

    mean: float
    ci95: float

    @staticmethod
    def of(values: Sequence[float] | np.ndarray) -> Cell:
        """The cell of ``values`` (one per trial)."""
        arr = np.asarray(values, dtype=float)
        return Cell(float(arr.mean()) if len(arr) else float("nan"), ci95(arr))

    def as_dict(self) -> dict[str, float]:
        """``{"mean", "ci95"}``."""
        return {"mean": self.mean, "ci95": self.ci95}


@dataclass(frozen=True)
class Row:
    """One row of a group (an action, an agent, or ``average``): a cell per metric."""

    name: str
    cells: Mapping[str, Cell]

    def __getitem__(self, metric: str) -> Cell:
        return self.cells[metric]

    def as_dict(self) -> dict[str, Any]:
        """Means by metric name plus ``ci95`` by metric name."""
        out: dict[str, Any] = {"name": self.name}
        out.update({m: c.mean for m, c in self.cells.items()})
        out["ci95"] = {m: c.ci95 for m, c in self.cells.items()}
        return out


@dataclass(frozen=True)
class Group:
    """A group's rows and their average."""

    name: str
    rows: tuple[Row, ...]
    average: Row

    def as_dict(self) -> dict[str, Any]:
        """``{"rows": [...], "average": {...}}``."""
        return {"rows": [r.as_dict() for r in self.rows], "average": self.average.as_dict()}


@dataclass(frozen=True)
class ConditionSummary:
    """Everything measured for one condition, with the paper's values beside it."""

    name: str
    index: int
    trials: int
    groups: Mapping[str, Group]
    counts: Mapping[str, Cell]
    headline: str
    paper: Mapping[str, Any] = field(default_factory=dict)
    references: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    seconds: float = 0.0  # summed trial time (CPU of the workers)
    worst: Mapping[str, tuple[int, float]] = field(default_factory=dict)  # metric -> (family, mean)

    @property
    def accuracy(self) -> Cell:
        """The headline accuracy (the headline group's average)."""
        return self.groups[self.headline].average["accuracy"]

    @property
    def f1(self) -> Cell:
        """The headline F1."""
        return self.groups[self.headline].average["f1"]


def summarise(name: str, index: int, trials: Sequence[TrialResult], headline: str,
              paper: Mapping[str, Any], references: Mapping[str, Mapping[str, Any]],
              seconds: float) -> ConditionSummary:
    """Aggregate one condition's trials (rows in the order of the first trial)."""
    groups: dict[str, Group] = {}
    for g in trials[0].groups if trials else ():
        row_names = list(trials[0].groups[g])
        table = np.array([[[t.groups[g][r].as_array()[k] for k in range(4)] for r in row_names]
                          for t in trials])  # (trials, rows, 4)
        rows = tuple(
            Row(r, {m: Cell.of(table[:, j, k]) for k, m in enumerate(FIELDS)})
            for j, r in enumerate(row_names)
        )
        avg = table.mean(axis=1) if row_names else np.ones((len(trials), 4))
        average = Row("average", {m: Cell.of(avg[:, k]) for k, m in enumerate(FIELDS)})
        groups[g] = Group(g, rows, average)
    count_names = list(trials[0].counts) if trials else []
    counts = {c: Cell.of([t.counts[c] for t in trials]) for c in count_names}
    return ConditionSummary(name, index, len(trials), groups, counts, headline, paper, references, seconds)


def family_means(summary: ConditionSummary) -> TrialResult:
    """One family's condition as a single result: each row's scores and each count averaged over
    its trials."""
    groups = {g: {r.name: Scores(*(r[m].mean for m in FIELDS)) for r in grp.rows}
              for g, grp in summary.groups.items()}
    return TrialResult(groups, {k: v.mean for k, v in summary.counts.items()})


def summarise_families(per_family: Sequence[ConditionSummary], seeds: Sequence[int]) -> ConditionSummary:
    """One condition over norm families: the mean over families (rows and counts) with 95% intervals
    over families, and the worst family by headline accuracy and by headline F1 (lowest mean; the
    first family on ties)."""
    first = per_family[0]
    summary = summarise(first.name, first.index, [family_means(s) for s in per_family], first.headline,
                        {}, {}, sum(s.seconds for s in per_family))
    worst: dict[str, tuple[int, float]] = {}
    for metric in ("accuracy", "f1"):
        values = [getattr(s, metric).mean for s in per_family]
        k = int(np.argmin(values))
        worst[metric] = (int(seeds[k]), float(values[k]))
    return ConditionSummary(summary.name, summary.index, summary.trials, summary.groups, summary.counts,
                            summary.headline, {}, {}, summary.seconds, worst)
