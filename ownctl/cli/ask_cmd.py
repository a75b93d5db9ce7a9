"""``ownctl ask``: the questions that would most reduce the robot's expected mistakes, or put the best.

Parses the options, calls :mod:`ownctl.app.ask` once and renders a table or one JSON document
(docs/asking.md). Listing writes nothing; ``--put`` stores the best question as pending for the
speaker, whose next ``ownctl say`` is read as its answer.
"""

from __future__ import annotations

from typing import Annotated, Any

import typer

from ownctl.cli.common import JsonOpt, QuietOpt, app_ctx, emit, progress_bar, table
from ownctl.humanize import plural


def ask(
    ctx: typer.Context,
    task: Annotated[
        str, typer.Option("--task", metavar="TASK", help="trashAll, collectAll or an object action "
                          "(find, pickUp, trash, collect): whose decisions the questions are for.")
    ] = "trashAll",
    objects: Annotated[
        str | None, typer.Option("--objects", metavar="OBJ,OBJ", help="Only these objects (default: those "
                                 "the task would still act on; every object for an action).")
    ] = None,
    top: Annotated[int, typer.Option("--top", metavar="K", help="How many questions to list.")] = 3,
    put: Annotated[bool, typer.Option("--put", help="Put the best question to the speaker: ownctl say "
                                      "then reads their next words as the answer. Nothing is put when "
                                      "it would save less than ask.min_gain.")] = False,
    speaker: Annotated[
        str | None, typer.Option("--as", metavar="AGENT", help="With --put: whom to ask (default: the "
                                 "current speaker).")
    ] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """The questions that would most reduce a task's mistakes.

    Each question ("Whose is OBJ?", "May I ACTION OBJ?", "Does RULE hold?") is listed with its
    expected gain: the expected mistakes now minus after its answer, over the answers' predicted
    probabilities.
    """
    from ownctl.app import ask as app

    names = None if objects is None else [o.strip() for o in objects.split(",") if o.strip()]
    if speaker is not None and not put:
        raise typer.BadParameter("--as only applies with --put")
    bar = None if quiet else progress_bar("valuing questions")
    try:
        if put:
            done = app.put(app_ctx(ctx), task, names, speaker, bar)
        else:
            data = app.questions(app_ctx(ctx), task, names, top, bar)
    finally:
        if bar is not None:
            bar.stop()
    if put:
        emit(done.data, json_out, quiet, done.message)
        return
    rows = [[q["text"], _mistakes(q["gain"]), _answers(q["answers"])] for q in data["questions"]]
    title = (f"{data['task']}: {data['expected_mistakes']:.2f} expected mistakes on "
             f"{plural(len(data['objects']), 'object')}")
    listing = table(title, ["question", "gain", "answers (p)"], rows)

    def show() -> None:
        if not data["objects"]:  # nothing to decide, so nothing to value
            typer.echo(f"{data['task']}: no object is left to decide, so there is nothing to ask.")
            return
        listing()
        if not data["permissions"]:  # docs/asking.md, section 4: a task asks only after its first one
            typer.echo(f"No permission of {', '.join(data['steps'])} is known yet: these gains rest on the "
                       "prior over rule sets, and a task asks only after its first permission.")
        below = sum(not q["worth_asking"] for q in data["questions"])
        if below:  # docs/asking.md, section 4: what run --ask and ask --put would skip
            typer.echo(f"{below} of these would save less than ask.min_gain ({data['min_gain']:g}): neither "
                       "run --ask nor ask --put asks them (a gain below 0: the answer is expected to "
                       "lead the robot's decisions to more mistakes, by its model).")

    emit(data, json_out, quiet, show)


def _mistakes(value: float) -> str:
    """An expected number of mistakes to the thousandth (a gain within half of it of 0 is 0.000)."""
    text = f"{value:.3f}"
    return "0.000" if text == "-0.000" else text


SHOWN_ANSWERS = 4  # the most probable answers a table row lists (--json has them all)


def _answers(answers: list[dict[str, Any]]) -> str:
    """The most probable answers with their probabilities, and how many more there are."""
    ranked = sorted(answers, key=lambda a: -a["p"])
    text = ", ".join(f"{a['answer']} ({a['p']:.2f})" for a in ranked[:SHOWN_ANSWERS])
    rest = len(ranked) - SHOWN_ANSWERS
    return f"{text} (+{rest} less likely)" if rest > 0 else text
