"""Use case: run one of the paper's experiments in memory and write its optional CSV and plot.

Experiments never touch the store: trials run on the core (:mod:`ownctl.experiment`). This module
reads the world file (TOML, architecture section 11) into a picklable world factory, checks the options,
runs the trials and writes the ``--csv`` and ``--plot`` files.
"""

from __future__ import annotations

import csv
import math
import tomllib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ownctl.errors import BadValue, OwnctlError, UnknownName

if TYPE_CHECKING:
    import numpy as np

    from ownctl.experiment.runner import ExperimentResult
    from ownctl.world.model import World

TASK_CHOICES = ("collectAll", "trashAll", "both")
CALIBRATION_NOTE = (
    "calibration: the held-out (object, agent) pairs of every trial pooled; ece over 10 equal-width "
    "bins; coverage: share of pairs whose true label is in the split-conformal set (target 0.9; "
    "calibration scores by leave-one-out over the claimed objects), set_size: its mean size"
)
DEFAULT_WORLD = "paper blocks world"


class FileWorld:
    """A world file as a world factory: ``factory(rng)`` builds the world (drawing its generator
    part, if any, from ``rng``). Picklable, so trials can run in worker processes."""

    def __init__(self, data: Mapping[str, Any], source: str) -> None:
        self.data = dict(data)
        self.source = source

    def __call__(self, rng: np.random.Generator) -> World:
        from ownctl.world.spec import world_from_dict

        return world_from_dict(self.data, self.source, rng)


def load_world(path: str | Path) -> FileWorld:
    """The world factory of a TOML world file; OwnctlError if it is missing, unreadable or invalid."""
    import numpy as np

    p = Path(path)
    try:
        if not p.is_file():  # a name too long for the system is an OSError here
            raise OwnctlError(f"world file {str(p)!r} does not exist")
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise OwnctlError(f"cannot read world file {str(p)!r}: {reason}") from None
    except tomllib.TOMLDecodeError as exc:
        raise OwnctlError(f"{p}: not valid TOML: {exc}") from None
    factory = FileWorld(data, str(p))
    world = factory(np.random.default_rng(0))  # validate once, here, with a readable error
    if not world.norms:
        raise BadValue(f"{p}: the world has no norms; experiments need its true norms")
    if not world.objects:
        raise BadValue(f"{p}: the world has no objects")
    return factory


def _world_factory(world: str | Path | None) -> tuple[Callable[[np.random.Generator], World], str, bool]:
    """The factory, a name for reports, and whether the paper's published values apply to it."""
    if world is None:
        from ownctl.world.generator import paper_blocks_world

        return paper_blocks_world, DEFAULT_WORLD, True
    factory = load_world(world)
    return factory, str(world), is_paper_world(factory)


def is_paper_world(factory: FileWorld) -> bool:
    """Whether a world file describes the paper's setting: its generator alone, its agents and norms."""
    from ownctl.logic.rules import parse_norm
    from ownctl.world import generator as gen

    data = factory.data
    table = data.get("generator")
    if not isinstance(table, Mapping) or table.get("kind", "paper-blocks") != "paper-blocks":
        return False
    if table.get("objects", 20) != 20 or data.get("objects"):
        return False
    agents = tuple(data.get("agents", gen.PAPER_AGENTS))
    norms = {parse_norm(n).text() for n in data.get("norms", gen.PAPER_NORMS)}
    return agents == gen.PAPER_AGENTS and norms == {parse_norm(n).text() for n in gen.PAPER_NORMS}


def ownership_conditions(claims: str) -> list[str]:
    """The Table 2 conditions whose instructor gives ``claims`` (``all`` or ``owners``)."""
    from ownctl.experiment.ownership import CLAIM_MODES, condition_names

    if claims not in CLAIM_MODES:
        raise UnknownName("claim mode", claims, CLAIM_MODES)
    return condition_names(claims)


def task_conditions(task: str) -> list[str] | None:
    """The Table 3 conditions for ``--task`` (None = both)."""
    if task not in TASK_CHOICES:
        raise UnknownName("task", task, TASK_CHOICES)
    return None if task == "both" else [task]


def run(
    experiment: str,
    trials: int = 100,
    seed: int = 0,
    jobs: int = 1,
    world: str | Path | None = None,
    learner: str = "ours",
    task: str = "both",
    csv_path: str | Path | None = None,
    plot_path: str | Path | None = None,
    progress: Callable[[int, int], None] | None = None,
    families: int | None = None,
    family_seed: int | None = None,
    *,
    scheduler: str | None = None,
    decide: str = "map",
    claims: str = "all",
) -> ExperimentResult:
    """Run ``experiment`` (norms, ownership, task) and write the optional CSV and plot files.

    ``families``: run the norms experiment on that many generated norm families of consecutive
    seeds from ``family_seed`` (default: the start of the reserved evaluation range) instead of one
    world. ``scheduler``: run the trials on the Dask cluster at that address instead of ``jobs``
    local processes (the same results). ``decide``: learned rules decide (and are scored) on the
    most probable rule set (``map``) or marginalised over rule sets (``posterior``). ``claims``
    (ownership only): the instructor gives every agent's claims (``all``, the paper's protocol)
    or only the owners' "that's mine" (``owners``; conditions (i')-(iii')).
    """
    from ownctl.experiment.registry import get_experiment
    from ownctl.experiment.runner import check_settings, run_experiment

    exp = get_experiment(experiment)
    check_settings(trials, jobs, learner, scheduler, decide, seed)
    conditions = task_conditions(task) if exp.name == "task" else None
    if exp.name != "task" and task != "both":
        raise BadValue(f"--task only applies to the task experiment, not {exp.name!r}")
    if exp.name == "ownership":
        conditions = ownership_conditions(claims)
    elif claims != "all":
        raise BadValue(f"--claims only applies to the ownership experiment, not {exp.name!r}")
    chosen_families = _families(exp.name, families, family_seed, world)
    check_folder("csv", csv_path)
    check_plot(plot_path)
    factory, name, comparable = _world_factory(world)
    result = run_experiment(exp.name, trials, seed, jobs, factory, learner, progress, conditions, name,
                            comparable, chosen_families, scheduler, decide)
    if exp.name == "ownership":
        from ownctl.experiment.calibration import calibration

        chosen = [exp.condition_names().index(n) for n in conditions or ()]
        result.extra["calibration"] = calibration(factory, trials, seed, learner, chosen)
        result.extra["calibration_note"] = CALIBRATION_NOTE
    if csv_path is not None:
        write_csv(result, csv_path)
    if plot_path is not None:
        from ownctl.app.experiment_plot import write_plot

        write_plot(result, plot_path)
        if "calibration" in result.extra:
            from ownctl.app.experiment_plot import write_reliability

            write_reliability(result.extra["calibration"], reliability_path(plot_path))
    return result


def reliability_path(plot_path: str | Path) -> Path:
    """Where ``--plot FILE.png`` of the ownership experiment puts its reliability diagram."""
    p = Path(plot_path)
    return p.with_name(f"{p.stem}-reliability{p.suffix or '.png'}")


def _families(experiment: str, count: int | None, first: int | None, world: str | Path | None) -> list[Any]:
    """The norm families of ``--families`` / ``--family-seed`` (none without ``--families``)."""
    if count is None:
        if first is not None:
            raise BadValue("--family-seed needs --families N")
        return []
    if experiment != "norms":
        raise BadValue(f"--families only applies to the norms experiment, not {experiment!r}")
    if world is not None:
        raise BadValue("--families and --world exclude each other: families draw their own worlds")
    from ownctl.experiment.runner import check_seed
    from ownctl.world.families import EVALUATION_SEEDS, norm_families

    if first is not None:
        check_seed(first, "--family-seed")
    return norm_families(count, EVALUATION_SEEDS.start if first is None else first)


CSV_COLUMNS = ("experiment", "learner", "trials", "seed", "condition", "group", "row", "metric", "mean",
               "ci95", "paper")


def csv_rows(result: ExperimentResult) -> list[dict[str, Any]]:
    """One row per (condition, group, row, metric) and per count; ``paper`` where published."""
    rows: list[dict[str, Any]] = []
    base = {"experiment": result.experiment.name, "learner": result.learner, "trials": result.trials,
            "seed": result.seed}
    for cond in result.conditions:
        for group in cond.groups.values():
            for row in (*group.rows, group.average):
                for metric, cell in row.cells.items():
                    paper = _paper_value(cond.paper, cond.headline, group.name, row.name, metric)
                    rows.append({**base, "condition": cond.name, "group": group.name, "row": row.name,
                                 "metric": metric, "mean": cell.mean, "ci95": cell.ci95, "paper": paper})
        for name, cell in cond.counts.items():
            rows.append({**base, "condition": cond.name, "group": "counts", "row": name, "metric": "mean",
                         "mean": cell.mean, "ci95": cell.ci95, "paper": cond.paper.get(name, "")})
    return rows


def _paper_value(paper: Mapping[str, Any], headline: str, group: str, row: str, metric: str) -> Any:
    if row != "average":
        return ""
    if group == headline:
        return paper.get(metric, "")
    if group == "ownership" and isinstance(paper.get("ownership"), Mapping):
        return paper["ownership"].get(metric, "")
    return ""


PLOT_FORMATS = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp")


def check_plot(path: str | Path | None) -> None:
    """BadValue / OwnctlError, before any work, if ``--plot`` names no file, a format the plots
    cannot be drawn in (by its suffix; none: PNG) or a file in a folder that does not exist."""
    if path is None:
        return
    p = Path(path)
    if p.name in ("", ".", ".."):
        raise BadValue(f"--plot needs a file name such as table.png, got {str(path)!r}")
    suffix = p.suffix.lower().removeprefix(".")
    if suffix and suffix not in PLOT_FORMATS:
        raise BadValue(f"cannot draw a plot as {p.suffix!r} ({str(path)!r}); valid suffixes: "
                       f"{', '.join('.' + f for f in PLOT_FORMATS)}", [f".{f}" for f in PLOT_FORMATS])
    check_folder("plot", path)


def check_folder(what: str, path: str | Path | None) -> None:
    """OwnctlError, before any work, if the ``what`` file ``path`` could not be written: its folder
    does not exist."""
    if path is None:
        return
    try:
        there = Path(path).parent.exists()
    except OSError as exc:  # a name too long for the system
        raise OwnctlError(f"cannot write the {what} file {str(path)!r}: {exc.strerror}") from None
    if not there:
        raise OwnctlError(f"cannot write the {what} file {str(path)!r}: its folder does not exist")


def write_csv(result: ExperimentResult, path: str | Path) -> None:
    """Write :func:`csv_rows` to ``path``."""
    try:
        with open(path, "w", newline="", encoding="utf-8") as fh:
            writer = csv.DictWriter(fh, fieldnames=CSV_COLUMNS)
            writer.writeheader()
            for row in csv_rows(result):
                writer.writerow({k: _fmt(v) for k, v in row.items()})
    except OSError as exc:
        raise OwnctlError(f"cannot write the csv file {str(path)!r}: {exc.strerror}") from None


def _fmt(value: Any) -> Any:
    if isinstance(value, float):
        return "" if math.isnan(value) else f"{value:.6g}"
    return value
