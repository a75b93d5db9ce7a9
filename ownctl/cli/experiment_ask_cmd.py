"""Rendering of ``ownctl experiment task --ask``: mistakes per strategy and budget, and the paired
difference of ours and the entropy strategy (docs/asking.md, section 6)."""

from __future__ import annotations

import json
from typing import Any

import typer

from ownctl.cli.common import wrote
from ownctl.errors import BadValue


def run_ask(budgets: str, trials: int, seed: int, jobs: int, world: str | None, learner: str, task: str,
            json_out: bool, csv: str | None, plot: str | None, quiet: bool, kinds: str | None = None,
            temper: float | None = None, read: bool | None = None, ahead: int | None = None,
            decide: str = "map") -> None:
    """Run the asking experiment and print its tables or one JSON document."""
    from ownctl.app import experiment_ask

    if csv is not None:
        raise BadValue("--csv does not apply with --ask (JSON or tables)")
    if learner != "ours":
        raise BadValue(f"--ask runs the default learner only, got --learner {learner!r}", ("ours",))
    result = experiment_ask.run(budgets, trials, seed, jobs, task, plot, kinds=kinds, temper=temper,
                                read=read, ahead=ahead, decide=decide, world=world)
    if json_out:
        typer.echo(json.dumps(result, ensure_ascii=False))
    elif not quiet:
        render(result)
    wrote(plot, quiet)


def render(result: dict[str, Any]) -> None:
    """One table per task: mistakes (mean ± 95%) and questions per strategy and budget, then the
    paired difference ours - entropy."""
    from rich import box
    from rich.console import Console
    from rich.table import Table

    console = Console()
    for task in result["tasks"]:
        grid = Table(title=f"{task['task']}: mistakes per task (mean ± 95% CI) [questions asked]",
                     box=box.SIMPLE_HEAD)
        grid.add_column("strategy")
        for b in result["budgets"]:
            grid.add_column(f"budget {b}", justify="right")
        for s in result["strategies"]:
            rows = {r["budget"]: r for r in task["runs"] if r["strategy"] == s}
            grid.add_row(s, *(f"{rows[b]['mistakes']:.2f}±{rows[b]['ci95']:.2f} [{rows[b]['questions']:.1f}]"
                              for b in result["budgets"]))
        console.print(grid)
        for p in task["paired"]:
            console.print(f"  budget {p['budget']}: ours - entropy = {p['ours_minus_entropy']:+.2f} "
                          f"± {p['ci95']:.2f} (paired over {result['trials']} trials; ours fewer in "
                          f"{p['better']}, more in {p['worse']})")
    console.print(f"{result['trials']} trials per task on {result['world']}, seed {result['seed']}, "
                  f"min gain {result['min_gain']}, ours asks {','.join(result['kinds'])} on the rule-set "
                  f"posterior to the power {result['temper']}, ownership "
                  f"{'as the learner reads it' if result['read'] else 'as given'}, "
                  f"{result['ahead']} best valued again with the look-ahead, "
                  f"in {result['seconds']:.1f} s")
