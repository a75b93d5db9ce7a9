"""Queries: ``check``, ``owners``, ``rules``, ``perms`` and ``log``."""

from __future__ import annotations

from typing import Annotated

import typer

from ownctl.cli.common import EXIT_FORBIDDEN, ActionArg, JsonOpt, ObjArg, QuietOpt, app_ctx, emit, fmt, table
from ownctl.cli.help import Group
from ownctl.cli.render import when

rules = Group(help="The forbid rules (given or learned).")
perms = Group(help="Object-specific permissions.")



def check(
    ctx: typer.Context,
    action: ActionArg,
    obj: ObjArg,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Is ACTION permitted on OBJ? Exit 3 if forbidden.

    Prints the decision, what decided it (a permission or the rules) and, for an action with
    prerequisite steps, each step's decision.
    """
    from ownctl.app import decide

    report = decide.check(app_ctx(ctx), action, obj)
    data = report.data

    def human() -> None:
        typer.echo(
            f"{data['decision']}: {action} {obj} (p_forbidden={data['p_forbidden']:.3g}); {report.reason}"
        )
        if len(data["steps"]) > 1:
            typer.echo(step_lines(data["steps"]))

    emit(data, json_out, quiet, human)
    if report.forbidden:
        raise typer.Exit(EXIT_FORBIDDEN)


def step_lines(steps: list[dict]) -> str:
    """Each step's decision on a line of aligned columns (plain text: a decision prints without rich)."""
    head = ("step", "decision", "decided by", "p_forbidden", "threshold", "rules")
    rows = [head] + [(s["action"], s["decision"], s["decided_by"], fmt(s["p_forbidden"]), fmt(s["threshold"]),
                      fmt([r["id"] for r in s["rules"]])) for s in steps]
    widths = [max(len(row[i]) for row in rows) for i in range(len(head))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip()
                     for row in rows)


def owners(
    ctx: typer.Context,
    obj: Annotated[str | None, typer.Argument(metavar="OBJ", help="The object whose owners to show.")] = None,
    agent: Annotated[
        str | None, typer.Option("--agent", metavar="AGENT", help="Instead: the objects this agent owns.")
    ] = None,
    min_p: Annotated[
        float, typer.Option("--min", metavar="P", help="With --agent: the least probability listed.")
    ] = 0.5,
    coverage: Annotated[
        float | None, typer.Option("--coverage", metavar="P", help="Also each agent's conformal set over "
                                   "{owns, does not own} holding the truth with probability P (e.g. 0.9).")
    ] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Who probably owns OBJ, or which objects an agent owns.

    Lists each agent's claim, prior and posterior and which of them the decisions use.
    """
    from ownctl.app import query

    if (obj is None) == (agent is None):
        raise typer.BadParameter("give either an OBJ or --agent AGENT")
    if coverage is not None and agent is not None:
        raise typer.BadParameter("--coverage applies to OBJ, not --agent")
    if agent is not None:
        rows = query.owned_by(app_ctx(ctx), agent, min_p)
        emit(
            rows,
            json_out,
            quiet,
            table(f"owned by {agent}", ["object", "p", "source"], [list(r.values()) for r in rows]),
        )
        return
    data = query.owners(app_ctx(ctx), obj, coverage)  # type: ignore[arg-type]
    columns = ["agent", "p", "source", "claim", "prior", "posterior"]
    cells = [
        [o["agent"], o["p"], o["source"], o["claim"], o["prior"], o["posterior"]] for o in data["owners"]
    ]
    note = ""
    if coverage is not None:
        columns.append(f"set ({coverage:g})")
        for row, o in zip(cells, data["owners"], strict=True):
            row.append(" or ".join(o["conformal"]["set"]) or "(empty)")
        few = [o["agent"] for o in data["owners"] if o["conformal"]["calibration"] < data["claims_needed"]]
        if few:
            note = (f"{', '.join(few)}: fewer than {data['claims_needed']} claimed objects, too few for "
                    f"coverage {coverage:g}; their sets hold both labels unless claimed")
    shown = table(f"owners of {obj}", columns, cells)
    if data["silent"]:
        note = "\n".join(filter(None, [note, (
            f"{', '.join(data['silent'])} said nothing of {obj} while others made claims about it: "
            f"their silence weighs {data['silence']:g} (people say \"mine\", seldom \"not mine\")")]))
    reach = data["percept_scale"]
    predicted = any(o["source"] == "prediction" for o in data["owners"])
    if reach < 1 and predicted:
        note = "\n".join(filter(None, [note, (
            f"percepts move these predictions at {reach:.0%} of their full reach: the claims so far say that "
            "position, colour and recency tell little of who owns what here")]))
    if data["rate_spread"] < data["rate_spread_configured"] and predicted:
        note = "\n".join(filter(None, [note, (
            f"the claims so far say the agents own things about equally often: each agent's rate is held "
            f"within {data['rate_spread']:g} logits of the base rate ({data['rate_spread_configured']:g} "
            "where agents differ)")]))

    def human() -> None:
        shown()
        if note:
            typer.echo(note)

    emit(data, json_out, quiet, human)


@rules.command("list")
def rules_list(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """List the rules in canonical text, with their accuracy and posterior.

    The accuracy is the rule's soft agreement with its action's stored permissions; the posterior,
    how sure the posterior over rule sets is of what the rule says on them (docs/learning.md).
    Both are blank for an action without permissions and for allow norms.
    """
    from ownctl.app import query

    rows = query.list_rules(app_ctx(ctx))
    cells = [[r["id"], r["text"], r["origin"], _provenance(r.get("provenance") or {}), r["accuracy"],
              r["posterior"]] for r in rows]
    emit(rows, json_out, quiet, table("rules", ["id", "rule", "origin", "from", "accuracy", "posterior"],
                                      cells))


def _provenance(prov: dict) -> str:
    """Where a rule came from, in a few words: the examples it was learned from, or who said it."""
    if prov.get("examples") is not None:
        shown = prov["examples"][:4]
        more = len(prov["examples"]) - len(shown)
        return "examples " + ", ".join(shown) + (f" (+{more})" if more > 0 else "") if shown else "examples"
    if prov.get("minus"):
        return f"{prov.get('given')!r} minus {prov['minus']!r}"
    if prov.get("given"):
        who = f" by {prov['speaker']}" if prov.get("speaker") else ""
        return f"said{who}" + (" (specialised)" if prov.get("specialised") else "")
    return prov.get("during", "")


@rules.command("remove")
def rules_remove(
    ctx: typer.Context,
    rule_id: Annotated[int, typer.Argument(metavar="ID", help="The rule's id (see rules list).")],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Forget one rule (by id, see rules list)."""
    from ownctl.app import query

    done = query.remove_rule(app_ctx(ctx), rule_id)
    emit(done.data, json_out, quiet, done.message)


@perms.command("list")
def perms_list(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """List the object-specific permissions."""
    from ownctl.app import query

    rows = query.list_permissions(app_ctx(ctx))
    cells = [[r["id"], r["text"], r["value"], r["speaker"]] for r in rows]
    emit(rows, json_out, quiet, table("permissions", ["id", "permission", "value", "speaker"], cells))


@perms.command("remove")
def perms_remove(
    ctx: typer.Context,
    perm_id: Annotated[int, typer.Argument(metavar="ID", help="The permission's id (see perms list).")],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Forget one permission (by id, see perms list)."""
    from ownctl.app import query

    done = query.remove_permission(app_ctx(ctx), perm_id)
    emit(done.data, json_out, quiet, done.message)


def log(
    ctx: typer.Context,
    limit: Annotated[
        int | None, typer.Option("--limit", "-n", metavar="N", help="Only the last N instructions.")
    ] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Show the event log, one line per instruction.

    Each line says when, who (--as, or the robot for a task run), through which interface, and
    the instruction as typed; a task run's steps share their run's line. --json lists every event.
    """
    from ownctl.app import query

    rows = query.instructions(app_ctx(ctx), limit)

    def human() -> None:  # one line per instruction, like a version-control log: nothing is cut
        for r in rows:
            summary = f"  ({r['summary']})" if r["summary"] else ""
            typer.echo(f"{_ids(r):>5}  {when(r['time'])}  {r['actor'] or '-':<8} {r['interface']:<8} "
                       f"{r['command']}{summary}")

    emit([e for r in rows for e in r["events"]], json_out, quiet, human)


def _ids(row: dict) -> str:
    """``7``, or ``3-22`` for a row of several events."""
    return str(row["first"]) if row["first"] == row["last"] else f"{row['first']}-{row['last']}"


__all__ = ["check", "fmt", "log", "owners", "perms", "rules"]
