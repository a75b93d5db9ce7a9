"""``ownctl run trashAll|collectAll``: the paper's tasks with the Baxter in MuJoCo (or kinematically)."""

from __future__ import annotations

from typing import Annotated, Any

import typer

from ownctl.cli.common import EXIT_FAILED, JsonOpt, QuietOpt, app_ctx, emit, wrote
from ownctl.humanize import plural

#: how the live table shows each fate (the words the summary uses too)
MARKS = {"delivered": "[green]delivered[/]", "skipped": "[yellow]left[/]", "done": "[dim]done[/]"}


def run(
    ctx: typer.Context,
    task: Annotated[str, typer.Argument(metavar="TASK", help="The task: trashAll or collectAll.")],
    instructor: Annotated[
        str,
        typer.Option(metavar="oracle|none",
                     help="oracle: a simulated human corrects mistakes from the world's truth; none."),
    ] = "oracle",
    physics: Annotated[bool, typer.Option("--physics/--kinematic", help="MuJoCo, or teleport.")] = True,
    seed: Annotated[
        int, typer.Option(metavar="SEED", help="Seed of the blocks world loaded into an empty store.")
    ] = 0,
    layout_seed: Annotated[
        int | None,
        typer.Option(metavar="SEED", help="Add a new layout of the same world (same agents and true norms)."),
    ] = None,
    arm: Annotated[
        str, typer.Option(metavar="auto|left|right", help="auto (the nearer arm), left or right.")
    ] = "auto",
    grasp: Annotated[
        str, typer.Option(metavar="weld|friction", help="weld (fingers close, then hold) or friction.")
    ] = "weld",
    render: Annotated[str | None, typer.Option(metavar="FILE", help="Write FILE.png or FILE.mp4.")] = None,
    camera: Annotated[str, typer.Option(help="View to render: front, shoulder or top.")] = "front",
    ask: Annotated[int, typer.Option("--ask", metavar="N", help="Ask up to N questions before objects, "
                                     "when one would save ask.min_gain expected mistakes.")] = 0,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Play a task, obeying and learning the norms.

    The task runs on the store's world; an empty store (no objects, no agents) first
    receives the paper's blocks world.
    Exit 4 if a step failed.
    """
    from rich.console import Console
    from rich.live import Live
    from rich.table import Table

    from ownctl.app import run as runner

    runner.check_options(task, instructor, arm, grasp, render, camera)
    runner.check_ask(ask)
    live_rows: list[Any] = []
    shown = not (json_out or quiet)
    grid = Table("object", "fate", "reason", "mistake", title=f"{task}", expand=False)
    console = Console(stderr=True)

    def on_step(record: Any) -> None:
        live_rows.append(record)
        if shown:
            grid.add_row(record.name, MARKS.get(record.outcome, record.outcome), record.reason,
                         "yes" if record.mistake else "")

    def play() -> runner.RunReport:
        return runner.run(app_ctx(ctx), task, instructor=instructor, physics=physics, seed=seed,
                          layout_seed=layout_seed, arm=arm, grasp=grasp, render=render, camera=camera,
                          on_step=on_step, ask=ask)

    if shown:
        # transient: if the run fails, its partial table goes with it (nothing of the run was saved),
        # and the error stays the one line on stderr; on success the finished table is printed
        with Live(grid, console=console, refresh_per_second=8, transient=True):
            result = play()
        console.print(grid)
        console.print()
    else:
        result = play()
    data = result.as_json()

    def human() -> None:
        rule, own = data["rule"], data["ownership"]
        rtf = f", {data['real_time_factor']:.0f}x real time" if data["sim_seconds"] else ""
        typer.echo(
            f"{task}: {len(data['delivered'])} delivered, {len(data['skipped'])} left, "
            f"{plural(data['mistakes'], 'mistake')}, "
            f"{plural(len(data['violations']), 'norm violation')} executed\n"
            f"rules ({', '.join(rule['actions'])}): accuracy {rule['accuracy']:.3f}, F1 {rule['f1']:.3f}; "
            f"ownership: accuracy {own['accuracy']:.3f}, F1 {own['f1']:.3f}\n"
            f"sim {data['sim_seconds']:.1f} s, wall {data['wall_seconds']:.2f} s{rtf}"
        )
        for q in data["questions"]:
            typer.echo(f"asked before {q['before']}: {q['text']} -> {q['answer'] or '(not answered)'}"
                       f" (gain {q['gain']:.3f})")
        for failure in data["failed_steps"]:
            typer.echo(f"failed step: {failure}", err=True)

    emit(data, json_out, quiet, human)
    wrote(render if physics else None, quiet)
    if not result.ok:
        raise typer.Exit(EXIT_FAILED)
