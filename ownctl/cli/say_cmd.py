"""Talking to the robot: ``say UTTERANCE`` and ``explain ACTION OBJ``."""

from __future__ import annotations

from typing import Annotated

import typer

from ownctl.cli.common import ACTION_HELP, EXIT_FAILED, EXIT_FORBIDDEN, JsonOpt, QuietOpt, app_ctx, emit


def say(
    ctx: typer.Context,
    utterance: Annotated[
        str, typer.Argument(metavar="UTTERANCE", help='What is said, e.g. "No Baxter, that\'s mine!".')
    ],
    speaker: Annotated[
        str | None, typer.Option("--as", metavar="AGENT", help="Who says it (default: the current speaker).")
    ] = None,
    about: Annotated[
        str | None,
        typer.Option(
            "--about", metavar="OBJ", help='What "this"/"that" is (default: the current target).'
        ),
    ] = None,
    physics: Annotated[
        bool, typer.Option("--physics", help="A task the utterance asks for runs in MuJoCo (else kinematic).")
    ] = False,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Say something to the robot, in English; it answers.

    What is understood is applied in one transaction. Prints the instructions understood (as
    ownctl commands) and the robot's reply. A question "Can you ...?" answered no exits 3, like
    check; a task whose physics failed exits 4.

    Examples: ownctl say "No Baxter, that's mine!" --as xuan --about mug;  ownctl say "Why not?"
    """
    from ownctl.app import say as talk

    report = talk.say(app_ctx(ctx), utterance, speaker, about, physics=physics)

    def human() -> None:
        for result in report.results:  # a result the reply already says (an explanation) is not repeated
            said = bool(result["message"]) and result["message"] in report.reply
            typer.echo(f"  {result['instruction']:<40} {'' if said else result['message']}".rstrip())
        typer.echo(f"robot: {report.reply}")

    emit(report.data, json_out, quiet, human)
    if report.run is not None and not report.run.ok:
        raise typer.Exit(EXIT_FAILED)
    if report.forbidden:
        raise typer.Exit(EXIT_FORBIDDEN)


def explain(
    ctx: typer.Context,
    action: Annotated[
        str | None,
        typer.Argument(metavar="ACTION", help=f"{ACTION_HELP} Omitted (with OBJ): the last refusal."),
    ] = None,
    obj: Annotated[str | None, typer.Argument(metavar="OBJ", help="The object.")] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Why an action is forbidden or permitted on an object.

    Names the deciding permission or rules, and where each ownership belief they read comes from
    (a claim, a prediction, inference). Without arguments: the last refusal ("why not?").
    """
    if (action is None) != (obj is None):
        raise typer.BadParameter("give both ACTION and OBJ, or neither (the last refusal)")
    from ownctl.app.explain import explain as why

    result = why(app_ctx(ctx), action, obj)
    emit(result.data, json_out, quiet, result.text)
