"""Use case: the asking experiment (``ownctl experiment task --ask 0,1,2,4,8``) and its plot.

Runs :func:`ownctl.experiment.asking.ask_experiment` in memory (no store) and writes the optional
``--plot`` figure: mistakes per task against the questions asked, one line per strategy, with 95%
error bars (docs/asking.md, section 6).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from ownctl.errors import BadValue, OwnctlError


def run(budgets: str, trials: int, seed: int, jobs: int, task: str, plot_path: str | Path | None = None,
        min_gain: float | None = None, progress: Callable[[int, int], None] | None = None) -> dict[str, Any]:
    """The experiment's JSON document (and the plot, if asked for)."""
    from ownctl.app.experiment import task_conditions
    from ownctl.app.settings import ASK_MIN_GAIN
    from ownctl.app.settings import min_gain as check_gain
    from ownctl.experiment.asking import ask_experiment, parse_budgets

    chosen = parse_budgets(budgets)
    names = task_conditions(task) or ["collectAll", "trashAll"]
    if trials < 1 or jobs < 1:
        raise BadValue(f"trials and jobs must be at least 1, got {trials} and {jobs}")
    if plot_path is not None and not Path(plot_path).parent.exists():
        raise OwnctlError(f"cannot write the plot file {str(plot_path)!r}: its folder does not exist")
    gain = ASK_MIN_GAIN if min_gain is None else check_gain(min_gain)
    result = ask_experiment(chosen, trials, seed, jobs, names, gain, progress)
    if plot_path is not None:
        write_plot(result, plot_path)
    return result


def write_plot(result: dict[str, Any], path: str | Path) -> None:
    """Mistakes against questions asked, per task, a line per strategy (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tasks = result["tasks"]
    fig, axes = plt.subplots(1, len(tasks), figsize=(4.6 * len(tasks), 4.0), squeeze=False)
    for ax, task in zip(axes[0], tasks, strict=True):
        for k, strategy in enumerate(result["strategies"]):
            rows = [r for r in task["runs"] if r["strategy"] == strategy]
            ax.errorbar([r["questions"] for r in rows], [r["mistakes"] for r in rows],
                        yerr=[r["ci95"] for r in rows], marker="o", capsize=3, color=f"C{k}", label=strategy)
        ax.set_title(task["task"])
        ax.set_xlabel("questions asked per task (mean)")
        ax.set_ylabel("mistakes per task")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.suptitle(f"Asking during the task ({result['trials']} trials, seed {result['seed']}, 95% CI)")
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=110)
    except OSError as exc:
        raise OwnctlError(f"cannot write the plot file {str(path)!r}: {exc.strerror}") from None
    finally:
        plt.close(fig)

