"""The ``--plot`` figure of an experiment: each metric against the conditions, ours with 95% error
bars, the paper's published values (and other published systems) as markers. Matplotlib, Agg backend.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ownctl.errors import OwnctlError

if TYPE_CHECKING:
    from ownctl.experiment.runner import ExperimentResult
    from ownctl.experiment.summary import Cell, ConditionSummary

Panel = tuple[str, Callable[["ConditionSummary"], "Cell | None"], Callable[[Mapping[str, Any]], Any]]


def _panels(result: ExperimentResult) -> list[Panel]:
    head = result.experiment.headline
    panels: list[Panel] = [
        (f"accuracy ({head})", lambda c: c.accuracy, lambda p: p.get("accuracy")),
        (f"F1 ({head})", lambda c: c.f1, lambda p: p.get("f1")),
    ]
    if result.experiment.name == "task":
        panels.insert(0, ("mistakes", lambda c: c.counts.get("mistakes"), lambda p: p.get("mistakes")))

        def own(p: Mapping[str, Any], m: str) -> Any:
            return (p.get("ownership") or {}).get(m)

        panels += [
            ("ownership accuracy", lambda c: c.groups["ownership"].average["accuracy"],
             lambda p: own(p, "accuracy")),
            ("ownership F1", lambda c: c.groups["ownership"].average["f1"], lambda p: own(p, "f1")),
        ]
    return panels


def error_bars(means: list[float], halfwidths: list[float], bounded: bool) -> list[list[float]]:
    """Matplotlib's ``yerr`` (below, above) for intervals ``mean ± halfwidth``; a share
    (``bounded``) has its interval cut at 0 and 1, where a t-interval over few trials can reach."""
    if not bounded:
        return [list(halfwidths), list(halfwidths)]
    return [[max(0.0, min(h, m)) for m, h in zip(means, halfwidths, strict=True)],
            [max(0.0, min(h, 1.0 - m)) for m, h in zip(means, halfwidths, strict=True)]]


def write_plot(result: ExperimentResult, path: str | Path) -> None:
    """Write the figure to ``path`` (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = _panels(result)
    names = [c.name for c in result.conditions]
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels) + 1, 4.2), squeeze=False)
    xs = list(range(len(names)))
    for ax, (label, ours, paper) in zip(axes[0], panels, strict=True):
        cells = [ours(c) for c in result.conditions]
        means = [c.mean if c is not None else float("nan") for c in cells]
        errs = [c.ci95 if c is not None else 0.0 for c in cells]
        yerr = error_bars(means, errs, bounded=label != "mistakes")
        ax.bar(xs, means, yerr=yerr, capsize=4, color="#4c72b0", alpha=0.85,
               label=f"ours ({result.learner} learner)")
        published = [paper(c.paper) for c in result.conditions]
        if any(v is not None for v in published):
            ax.scatter([x for x, v in zip(xs, published, strict=True) if v is not None],
                       [v for v in published if v is not None], marker="D", color="#c44e52", zorder=3,
                       label="paper")
        for k, (ref, marker) in enumerate(zip(sorted({r for c in result.conditions for r in c.references}),
                                              "^sv", strict=False)):
            vals = [paper(c.references.get(ref, {})) for c in result.conditions]
            ax.scatter([x for x, v in zip(xs, vals, strict=True) if v is not None],
                       [v for v in vals if v is not None], marker=marker, color=f"C{k + 2}", zorder=3,
                       label=ref)
        ax.set_title(label)
        ax.set_xticks(xs)
        ax.set_xticklabels(names, rotation=35, ha="right", fontsize=8)
        if label != "mistakes":
            ax.set_ylim(0, 1.05)
        ax.grid(axis="y", alpha=0.3)
    axes[0][0].legend(fontsize=8, loc="lower left")
    fig.suptitle(f"{result.experiment.title} ({result.trials} trials, seed {result.seed}, 95% CI)")
    fig.tight_layout()
    save(fig, path)


def write_reliability(calibration: list[dict[str, Any]], path: str | Path) -> None:
    """The reliability diagram of each condition: frequency against mean prediction per bin (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(calibration), figsize=(3.8 * len(calibration), 3.9), squeeze=False)
    for ax, cond in zip(axes[0], calibration, strict=True):
        rows = [r for r in cond["reliability"] if r["count"]]
        ax.plot([0, 1], [0, 1], color="grey", lw=1, ls="--")
        ax.bar([(r["lo"] + r["hi"]) / 2 for r in rows], [r["frequency"] for r in rows], width=0.09,
               color="#4c72b0", alpha=0.8, label="frequency owned")
        ax.plot([r["mean_p"] for r in rows], [r["frequency"] for r in rows], "o", color="#c44e52",
                label="(mean p, frequency)")
        ax.set_title(f"{cond['name']}\nECE {cond['ece']:.3f}, coverage {cond['coverage']:.3f}", fontsize=9)
        ax.set_xlabel("predicted P(owns)")
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1)
    axes[0][0].set_ylabel("observed frequency")
    axes[0][0].legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    save(fig, path)


def write_ask_plot(result: dict[str, Any], path: str | Path) -> None:
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
    save(fig, path)


def save(fig: Any, path: str | Path) -> None:
    """Write ``fig`` as a PNG and close it; an unwritable path is one user error."""
    import matplotlib.pyplot as plt

    try:
        fig.savefig(path, dpi=110)
    except OSError as exc:
        raise OwnctlError(f"cannot write the plot file {str(path)!r}: {exc.strerror}") from None
    finally:
        plt.close(fig)
