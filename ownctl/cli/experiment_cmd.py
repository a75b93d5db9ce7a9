"""``ownctl experiment norms|ownership|task``: the paper's Tables 1-3, run in memory, beside the paper.

Parses the options, calls :func:`ownctl.app.experiment.run` once (with a rich progress bar on
stderr unless ``--quiet``), and renders the result as rich tables or one JSON document. Nothing
heavy is imported until a command runs. Register with ``app.add_typer(experiment_app,
name="experiment")``.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Annotated, Any

import typer

from ownctl.cli.common import JsonOpt, QuietOpt, progress_bar, wrote
from ownctl.cli.help import Group
from ownctl.config import DECIDE_WINDOW
from ownctl.humanize import plural

if TYPE_CHECKING:
    from ownctl.experiment.runner import ExperimentResult
    from ownctl.experiment.summary import Cell

experiment_app = Group(help="The paper's experiments (Tables 1-3), beside its values.\n\n"
                       "Each runs in memory and prints ours and the paper's published figures side by side.")

TrialsOpt = Annotated[
    int, typer.Option("--trials", "-n", metavar="N", help="Trials per condition (1 to 100,000).")
]
SeedOpt = Annotated[
    int, typer.Option("--seed", metavar="SEED", help="Seed; trial t of condition c uses [seed, c, t].")
]
JobsOpt = Annotated[
    int, typer.Option("--jobs", "-j", metavar="N",
                      help="Worker processes, 1 to 1,024 (results do not depend on it).")
]
SchedulerOpt = Annotated[
    str | None,
    typer.Option("--scheduler", metavar="ADDRESS", help="Run the trials on a Dask cluster: its scheduler's "
                 "address, e.g. tcp://host:8786 (instead of --jobs; the same results)."),
]
WorldOpt = Annotated[
    str | None,
    typer.Option("--world", metavar="FILE", help="A TOML world file with true norms (default: the paper's "
                 "blocks world, scenarios/paper-blocks.toml)."),
]
LearnerOpt = Annotated[
    str, typer.Option("--learner", metavar="ours|paper", help="Rule learner: ours or paper.")
]
DecideOpt = Annotated[
    str, typer.Option("--decide", metavar="map|posterior|window",
                      help="Learned rules decide, and are scored, on the most probable rule set (map), "
                      "marginalised over rule sets (posterior; slower) or on the mean over the rule sets "
                      f"within {DECIDE_WINDOW:g} nats of the most probable (window; slower).")
]
CsvOpt = Annotated[str | None, typer.Option("--csv", metavar="FILE", help="Also write every figure as CSV.")]
PlotOpt = Annotated[str | None, typer.Option("--plot", metavar="FILE.png", help="Also plot the metrics.")]


def _run(experiment: str, trials: int, seed: int, jobs: int, world: str | None, learner: str, task: str,
         json_out: bool, csv: str | None, plot: str | None, quiet: bool, families: int | None = None,
         family_seed: int | None = None, scheduler: str | None = None, decide: str = "map",
         claims: str = "all") -> None:
    from ownctl.app import experiment as app

    bar = None if quiet else progress_bar(f"experiment {experiment}")
    try:  # errors are reported by the command group, like every command's
        result = app.run(experiment, trials, seed, jobs, world, learner, task, csv, plot, bar, families,
                         family_seed, scheduler=scheduler, decide=decide, claims=claims)
    finally:
        if bar is not None:
            bar.stop()
    if json_out:
        typer.echo(json.dumps(result.as_dict(), ensure_ascii=False))
    elif not quiet:
        render(result)
    for path in (csv, plot):
        wrote(path, quiet)
    if plot is not None and "calibration" in result.extra:
        from ownctl.app.experiment import reliability_path

        wrote(reliability_path(plot), quiet)


@experiment_app.command("norms")
def norms(
    trials: TrialsOpt = 100, seed: SeedOpt = 0, jobs: JobsOpt = 1, scheduler: SchedulerOpt = None,
    world: WorldOpt = None, learner: LearnerOpt = "ours", json_out: JsonOpt = False, csv: CsvOpt = None,
    plot: PlotOpt = None, quiet: QuietOpt = False,
    families: Annotated[int | None, typer.Option(
        "--families", metavar="N", help="Run on N (1 to 10,000) generated norm families instead of one world "
        "(every action scored, with or without a norm); report the mean over families and the worst."
    )] = None,
    family_seed: Annotated[int | None, typer.Option(
        "--family-seed", metavar="SEED", help="First family seed (default 1000, the evaluation range "
        "1000-1099).")] = None,
    decide: DecideOpt = "map",
) -> None:
    """Table 1: learn norms from permissions on some of the objects.

    Permissions are given on 100, 50 or 25% of the objects, with exact or noisy ownership.
    """
    _run("norms", trials, seed, jobs, world, learner, "both", json_out, csv, plot, quiet, families,
         family_seed, scheduler, decide)


@experiment_app.command("ownership")
def ownership(
    trials: TrialsOpt = 100, seed: SeedOpt = 0, jobs: JobsOpt = 1, scheduler: SchedulerOpt = None,
    world: WorldOpt = None, learner: LearnerOpt = "ours", json_out: JsonOpt = False, csv: CsvOpt = None,
    plot: PlotOpt = None, quiet: QuietOpt = False,
    claims: Annotated[str, typer.Option(
        "--claims", metavar="all|owners", help="The claims given on the claimed half: every agent's, "
        "owned or not (all, the paper's protocol), or only each owner's \"that's mine\" (owners).")] = "all",
) -> None:
    """Table 2: predict the ownership of held-out objects.

    Claims and permissions are given on half of the objects; the other half is predicted.
    """
    _run("ownership", trials, seed, jobs, world, learner, "both", json_out, csv, plot, quiet,
         scheduler=scheduler, claims=claims)


@experiment_app.command("task")
def task(
    trials: TrialsOpt = 100, seed: SeedOpt = 0, jobs: JobsOpt = 1, scheduler: SchedulerOpt = None,
    world: WorldOpt = None, learner: LearnerOpt = "ours",
    which: Annotated[
        str, typer.Option("--task", metavar="TASK", help="collectAll, trashAll or both.")
    ] = "both",
    json_out: JsonOpt = False, csv: CsvOpt = None, plot: PlotOpt = None, quiet: QuietOpt = False,
    ask: Annotated[str | None, typer.Option(
        "--ask", metavar="B,B,...", help="Instead: let the robot ask up to B questions per task (e.g. "
        "0,1,2,4,8), by value of information, by ownership entropy and at random, on the same seeds."
    )] = None,
    decide: DecideOpt = "map",
    ask_kinds: Annotated[str | None, typer.Option(
        "--ask-kinds", metavar="K,K,...", help="With --ask: the kinds of question ours may ask, of act, may, "
        "whose, rule (default act,may,whose)."
    )] = None,
    ask_temper: Annotated[float | None, typer.Option(
        "--ask-temper", metavar="T", help="With --ask: value ours' questions on the rule-set posterior "
        "raised to the power T in (0, 1] (1: the model's own posterior; default 0.5)."
    )] = None,
    ask_read: Annotated[bool | None, typer.Option(
        "--ask-read/--ask-as-given", help="With --ask: value ours' questions with ownership read "
        "through the claim calibration the learner chose (default), or as it is given."
    )] = None,
    ask_ahead: Annotated[int | None, typer.Option(
        "--ask-ahead", metavar="K", help="With --ask: value ours' K best questions (and those about the "
        "object being decided) again, counting what the robot learns from the permissions the "
        "instructor gives that object next (0: none; default: ask.ahead's default)."
    )] = None,
) -> None:
    """Table 3: collectAll and trashAll with a correcting instructor.

    Counts the robot's mistakes and scores the rules and ownership it learned.
    """
    if ask is not None:
        from ownctl.cli.experiment_ask_cmd import run_ask

        run_ask(ask, trials, seed, jobs, world, learner, which, json_out, csv, plot, quiet, ask_kinds,
                ask_temper, ask_read, ask_ahead, decide)
        return
    for flag, value in (("--ask-kinds", ask_kinds), ("--ask-temper", ask_temper),
                        ("--ask-read/--ask-as-given", ask_read), ("--ask-ahead", ask_ahead)):
        if value is not None:
            from ownctl.errors import BadValue

            raise BadValue(f"{flag} applies only with --ask")
    _run("task", trials, seed, jobs, world, learner, which, json_out, csv, plot, quiet, scheduler=scheduler,
         decide=decide)


# -- rendering ------------------------------------------------------------------------------------
def _pm(cell: Cell | None, digits: int = 3) -> str:
    """``0.975±.012``: the mean and the 95% half-width (its leading zero dropped, to fit 80 columns)."""
    if cell is None:
        return ""
    ci = f"{cell.ci95:.{digits}f}"
    return f"{cell.mean:.{digits}f}±{ci[1:] if ci.startswith('0.') else ci}"


def _num(value: Any, digits: int = 3) -> str:
    return f"{value:.{digits}f}" if isinstance(value, int | float) else ""


def _worst(c: Any, metric: str) -> str:
    """``0.812 (1042)``: the worst family's mean and its seed."""
    seed, value = c.worst[metric]
    return f"{value:.3f} ({seed})"


def _headline(result: ExperimentResult) -> tuple[list[str], list[list[str]]]:
    """Columns and rows of the main table: for each condition a row of ours, then the paper's."""
    task = result.experiment.name == "task"
    second = {"task": "ownership", "ownership": "all"}.get(result.experiment.name)
    columns = ["condition", "source"] + (["mistakes"] if task else []) + ["accuracy", "F1"]
    worst = any(c.worst for c in result.conditions)
    if worst:
        columns += ["worst acc", "worst F1"]
    if second:
        columns += [f"{second[:5]} acc", f"{second[:5]} F1"]
    refs = sorted({r for c in result.conditions for r in c.references})
    rows = []
    for c in result.conditions:
        ours = [c.name, "ours"] + ([_pm(c.counts.get("mistakes"), 2)] if task else [])
        ours += [_pm(c.accuracy), _pm(c.f1)]
        if worst:
            ours += [_worst(c, "accuracy"), _worst(c, "f1")]
        if second:
            avg = c.groups[second].average
            ours += [_pm(avg["accuracy"]), _pm(avg["f1"])]
        rows.append(ours)
        sources = [("paper", c.paper)] + [(r, c.references[r]) for r in refs if r in c.references]
        for label, values in sources:
            if not values:
                continue
            row = ["", label] + ([_num(values.get("mistakes"), 2)] if task else [])
            row += [_num(values.get("accuracy")), _num(values.get("f1"))]
            if second:
                nested = values.get(second, {}) if task else {}
                row += [_num(nested.get("accuracy")), _num(nested.get("f1"))]
            rows.append(row)
    return columns, rows


def render(result: ExperimentResult) -> None:
    """Print the headline table, the per-row table, the metric definitions and the runtime."""
    from rich import box
    from rich.console import Console
    from rich.table import Table

    console = Console()
    exp = result.experiment
    columns, rows = _headline(result)
    comparable = result.extra.get("paper_comparable", True)
    also = " and the paper" if comparable else " (the paper's values are for its blocks world only)"
    if "families" in result.extra:
        also = " over norm families"
    modes = {"map": "", "posterior": ", decisions marginalised over rule sets",
             "window": ", decisions on the near-best rule sets"}
    mode = modes.get(result.decide, f", decide {result.decide}")
    head = Table(title=f"{exp.title}: ours ({result.learner} learner{mode}, mean±95% CI){also}",
                 caption=f"accuracy, F1 = {exp.headline}: {exp.groups.get(exp.headline, '')}",
                 box=box.SIMPLE_HEAD, collapse_padding=True, pad_edge=False)
    for col in columns:
        head.add_column(col, justify="left" if col in ("condition", "source") else "right")
    for row in rows:
        head.add_row(*row, end_section=row[1] != "ours" and row is not rows[-1]
                     and (rows[rows.index(row) + 1][0] != ""))
    console.print(head)
    detail = Table(title=f"per {exp.rows}, each group, ours", box=box.SIMPLE_HEAD, collapse_padding=True,
                   pad_edge=False)
    for col in ("condition", "group", exp.rows, "accuracy", "precision", "recall", "F1"):
        detail.add_column(col, justify="left" if col in ("condition", "group", exp.rows) else "right")
    for c in result.conditions:
        first = True
        for group in c.groups.values():
            for r in (*group.rows, group.average):
                detail.add_row(c.name if first else "", group.name, r.name, _pm(r["accuracy"]),
                               _pm(r["precision"]), _pm(r["recall"]), _pm(r["f1"]),
                               end_section=r is group.average)
                first = False
    console.print(detail)
    notes = [*exp.metrics, *([result.extra["family_note"]] if "family_note" in result.extra else [])]
    for note in notes:
        console.print(f"[dim]* {note}[/dim]", markup=True)
    for cal in result.extra.get("calibration", ()):
        console.print(f"calibration {cal['name']}: ECE {cal['ece']:.3f} over {cal['pairs']} held-out pairs; "
                      f"conformal coverage {cal['coverage']:.3f} (target {cal['coverage_target']}), "
                      f"mean set size {cal['set_size']:.2f}")
    n = len(result.conditions)
    where = f"scheduler {result.scheduler}" if result.scheduler else f"jobs {result.jobs}"
    console.print(f"{plural(result.trials, 'trial')} x {plural(n, 'condition')} on {result.world} "
                  f"(seed {result.seed}, {where}) in {result.seconds:.2f} s", markup=False)
