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
        min_gain: float | None = None, progress: Callable[[int, int], None] | None = None,
        kinds: str | None = None, temper: float | None = None, read: bool | None = None,
        ahead: int | None = None, decide: str = "map", world: str | Path | None = None) -> dict[str, Any]:
    """The experiment's JSON document (and the plot, if asked for); trials and jobs are checked by
    :func:`ownctl.experiment.asking.ask_experiment`, the plot's folder, ``kinds`` ("act,may,whose")
    and ``temper`` (in (0, 1]; default: the task asker's) before any work; ``read``: whether ours
    values questions with ownership read as the learner reads it (default: the task asker's);
    ``ahead``: how many of ours' best questions are valued again with the look-ahead (a whole number,
    checked before any work; default: the task asker's); ``decide``: ``decide.rules`` of every robot;
    ``world``: a TOML world file whose trials replace the paper's blocks world (read and checked
    before any work, as for every experiment)."""
    from ownctl.app.experiment import check_plot, load_world, task_conditions
    from ownctl.app.settings import ASK_MIN_GAIN
    from ownctl.app.settings import min_gain as check_gain
    from ownctl.experiment.asking import (
        PAPER_TRIALS,
        TASK_AHEAD,
        TASK_KINDS,
        TASK_READ,
        TASK_TEMPER,
        ask_experiment,
        parse_budgets,
        parse_kinds,
    )
    from ownctl.mind.ask import check_ahead, check_temper
    from ownctl.world.generator import paper_blocks_world

    chosen = parse_budgets(budgets)
    names = task_conditions(task) or ["collectAll", "trashAll"]
    check_plot(plot_path)
    gain = ASK_MIN_GAIN if min_gain is None else check_gain(min_gain)
    chosen_kinds = TASK_KINDS if kinds is None else parse_kinds(kinds)
    power = TASK_TEMPER if temper is None else check_temper(temper)
    looked = TASK_AHEAD if ahead is None else check_ahead(ahead)
    make_world = paper_blocks_world if world is None else load_world(world)
    result = ask_experiment(chosen, trials, seed, jobs, names, gain, progress, chosen_kinds, power,
                            TASK_READ if read is None else read, looked, decide, make_world,
                            PAPER_TRIALS if world is None else str(world))
    if plot_path is not None:
        from ownctl.app.experiment_plot import write_ask_plot

        write_ask_plot(result, plot_path)
    return result
