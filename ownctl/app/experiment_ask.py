"""Use case: the asking experiment (``ownctl experiment task --ask 0,1,2,4,8``) and its plot.

Runs :func:`ownctl.experiment.asking.ask_experiment` in memory (no store) and writes the optional
``--plot`` figure: mistakes per task against the questions asked, one line per strategy, with 95%
error bars (docs/asking.md, section 6).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any


def run(budgets: str, trials: int, seed: int, jobs: int, task: str, plot_path: str | Path | None = None,
        min_gain: float | None = None, progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The experiment's JSON document (and the plot, if asked for); trials and jobs are checked by
    :func:`ownctl.experiment.asking.ask_experiment`, the plot's folder before any work."""
    from ownctl.app.experiment import check_folder, task_conditions
    from ownctl.app.settings import ASK_MIN_GAIN
    from ownctl.app.settings import min_gain as check_gain
    from ownctl.experiment.asking import ask_experiment, parse_budgets

    chosen = parse_budgets(budgets)
    names = task_conditions(task) or ["collectAll", "trashAll"]
    check_folder("plot", plot_path)
    gain = ASK_MIN_GAIN if min_gain is None else check_gain(min_gain)
    result = ask_experiment(chosen, trials, seed, jobs, names, gain, progress)
    if plot_path is not None:
        from ownctl.app.experiment_plot import write_ask_plot

        write_ask_plot(result, plot_path)
    return result
