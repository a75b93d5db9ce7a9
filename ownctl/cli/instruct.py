"""Instructions: ``claim``, ``claims list``, ``forbid`` and ``allow`` (on an object, or if a condition)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated

import typer

from ownctl.cli.common import ActionArg, JsonOpt, ObjArg, QuietOpt, app_ctx, emit, table
from ownctl.cli.help import Group
from ownctl.cli.render import when
from ownctl.errors import RuleSyntaxError

if TYPE_CHECKING:
    from ownctl.app.context import Done

claims = Group(help="Ownership claims.")

SpeakerOpt = Annotated[
    str | None, typer.Option("--as", metavar="AGENT", help="Who says it (a name, kept with the instruction).")
]
Words = Annotated[
    list[str] | None,
    typer.Argument(metavar="WORDS", help="'on OBJ', or 'if LITERAL [and LITERAL]...' (see the README)."),
]



def claim(
    ctx: typer.Context,
    obj: ObjArg,
    agent: Annotated[str, typer.Argument(metavar="AGENT", help="The agent who owns it.")],
    p: Annotated[float, typer.Option("--p", metavar="P", help="How sure the speaker is, in [0, 1].")] = 1.0,
    negated: Annotated[
        bool, typer.Option("--not", help="The agent does NOT own it (stores 1 - trust*p).")
    ] = False,
    only: Annotated[
        bool, typer.Option("--only", help="Exclusive: every other agent's claim becomes 0.")
    ] = False,
    speaker: SpeakerOpt = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Claim that AGENT owns OBJ ("that's mine").

    The claim is weighted by the trust setting; it refits AGENT's ownership prediction and updates
    what is inferred from the permissions.
    """
    from ownctl.app import instruct

    done = instruct.add_claim(app_ctx(ctx), obj, agent, p, negated, only, speaker)
    emit(done.data, json_out, quiet, done.message)


@claims.command("list")
def claims_list(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """List the stored claims."""
    from ownctl.app import query

    rows = query.list_claims(app_ctx(ctx))
    cells = [[r["object"], r["agent"], r["p"], r["speaker"], r["trust"], when(r["time"])] for r in rows]
    emit(rows, json_out, quiet, table("claims", ["object", "agent", "p", "speaker", "trust", "time"], cells,
                                      whole={"time"}))


def _instruct(
    ctx: typer.Context, sign: str, action: str, words: list[str], p: float, speaker: str | None
) -> Done:
    from ownctl.app import instruct

    if words and words[0] == "on":
        if len(words) != 2:
            raise RuleSyntaxError(f"'{sign} {action} on' takes exactly one object, got {words[1:] or 'none'}")
        value = p if sign == "forbid" else 1.0 - p
        return instruct.add_permission(app_ctx(ctx), action, words[1], value, speaker)
    if words and words[0] != "if":
        hint = f" (one object: '{sign} {action} on {words[0]}')" if len(words) == 1 else ""
        raise RuleSyntaxError(f"'{sign} {action} {' '.join(words)}': after the action, expected 'on OBJ' or "
                              f"'if CONDITION', got {words[0]!r}{hint}; expected one of: if, on",
                              ["if", "on"])
    return instruct.add_norm(app_ctx(ctx), " ".join([sign, action, *words]), speaker)


def forbid(
    ctx: typer.Context,
    action: ActionArg,
    words: Words = None,
    p: Annotated[
        float, typer.Option("--p", metavar="P", help="With 'on': how sure, in [0, 1] (stored value p).")
    ] = 1.0,
    speaker: SpeakerOpt = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Forbid ACTION on one object, or whenever a condition holds.

    'on OBJ' stores a permission (the conflict gate decides whether it teaches the rules or the
    ownership beliefs); 'if ...' states a norm, added to the rules as given.

    Examples: ownctl forbid trash on wallet;  ownctl forbid pickUp if ownedBy xuan and not isColored red
    """
    done = _instruct(ctx, "forbid", action, words or [], p, speaker)
    emit(done.data, json_out, quiet, done.message)


def allow(
    ctx: typer.Context,
    action: ActionArg,
    words: Words = None,
    p: Annotated[
        float, typer.Option("--p", metavar="P", help="With 'on': how sure, in [0, 1] (stored value 1 - p).")
    ] = 1.0,
    speaker: SpeakerOpt = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Allow ACTION on one object, or state an allow norm.

    'on OBJ' stores a permission; 'if ...' is an allow norm, subtracted from the forbid rules.

    Examples: ownctl allow trash on mug;  ownctl allow trash if isColored red
    """
    done = _instruct(ctx, "allow", action, words or [], p, speaker)
    emit(done.data, json_out, quiet, done.message)
