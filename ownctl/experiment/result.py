"""What one trial of any experiment returns: scores per group and row, plus scalar counts.

A *group* is one evaluation (e.g. ``rules`` over the task's actions, ``test`` ownership on the
held-out half); its *rows* are the actions or agents it is scored per, averaged afterwards like the
paper (mean over trials, then over rows). ``counts`` carries per-trial numbers such as mistakes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ownctl.experiment.metrics import Scores


@dataclass(frozen=True)
class TrialResult:
    """``groups[group][row]`` scores and ``counts[name]`` numbers of one trial."""

    groups: Mapping[str, Mapping[str, Scores]]
    counts: Mapping[str, float] = field(default_factory=dict)
    notes: Mapping[str, int] = field(default_factory=dict)
