"""``ownctl world|agent|object|area ...``: what exists (thin: parse, call one app function, render)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ownctl.cli.common import JsonOpt, ObjArg, QuietOpt, app_ctx, emit, fmt, table, wrote
from ownctl.cli.help import Group
from ownctl.cli.render import when

world = Group(help="Load and export whole worlds as TOML files.\n\n"
                   "The file format is described in docs/architecture.md.")
agent = Group(help="Agents: the possible owners.")
obj = Group(help="Objects and their percepts: colour, position, categories.")
area = Group(help="Named box areas on the table plane.")

NameArg = Annotated[
    str,
    typer.Argument(metavar="NAME", help="Its name: a letter, then letters, marks, digits, _ or -."),
]
ColorOpt = Annotated[
    str | None, typer.Option("--color", metavar="COLOUR", help="Colour name ('none' clears it).")
]
PosOpt = Annotated[
    str | None, typer.Option("--pos", metavar="X,Y[,Z]", help="Position in metres ('none' clears it).")
]
CategoryOpt = Annotated[
    list[str] | None,
    typer.Option("--category", metavar="CATEGORY", help="A category (repeatable; 'none' clears)."),
]


@world.command("load")
def world_load(
    ctx: typer.Context,
    file: Annotated[str, typer.Argument(metavar="FILE", help="World or scenario TOML file.")],
    seed: Annotated[int, typer.Option(metavar="SEED", help="Seed for a [generator] section.")] = 0,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Add a world file's agents, areas, objects and ground truth.

    A scenario file's [[steps]] are ignored (ownctl scenario play plays them).
    """
    from ownctl.app import worldfile

    done = worldfile.load(app_ctx(ctx), file, seed)
    emit(done.data, json_out, quiet, done.message)


@world.command("export")
def world_export(
    ctx: typer.Context,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", metavar="FILE", help="Write to this file, not stdout.")
    ] = None,
    name: Annotated[
        str | None, typer.Option(metavar="NAME", help="The world's name in the file (default: the name "
                                 "the store's world was loaded with).")
    ] = None,
    json_out: JsonOpt = False,
) -> None:
    """Print the store's world as TOML (or JSON with --json).

    The world is its name, agents, areas, objects and ground truth, as world load reads it back.
    """
    import json

    from ownctl.app import worldfile

    data = worldfile.export(app_ctx(ctx), name)
    text = json.dumps(data, ensure_ascii=False) + "\n" if json_out else worldfile.export_toml(data)
    if output is None:
        typer.echo(text, nl=False)
    else:
        worldfile.write_text(output, text)
        wrote(output)


@agent.command("add")
def agent_add(ctx: typer.Context, name: NameArg, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Introduce an agent (a possible owner)."""
    from ownctl.app import things

    done = things.add_agent(app_ctx(ctx), name)
    emit(done.data, json_out, quiet, done.message)


@agent.command("list")
def agent_list(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """List the agents."""
    from ownctl.app import things

    rows = things.list_agents(app_ctx(ctx))
    emit(
        rows,
        json_out,
        quiet,
        table("agents", ["name", "objects touched"], [[r["name"], r["touched"]] for r in rows]),
    )


@agent.command("remove")
def agent_remove(
    ctx: typer.Context,
    name: Annotated[str, typer.Argument(metavar="AGENT", help="The agent.")],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Forget an agent and every belief about it.

    Refused while a rule names the agent.
    """
    from ownctl.app import things

    done = things.remove_agent(app_ctx(ctx), name)
    emit(done.data, json_out, quiet, done.message)


@obj.command("add")
def object_add(
    ctx: typer.Context,
    name: NameArg,
    color: ColorOpt = None,
    pos: PosOpt = None,
    category: CategoryOpt = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Add an object with its percepts."""
    from ownctl.app import things

    done = things.add_object(app_ctx(ctx), name, color, pos, category or [])
    emit(done.data, json_out, quiet, done.message)


@obj.command("set")
def object_set(
    ctx: typer.Context,
    name: ObjArg,
    color: ColorOpt = None,
    pos: PosOpt = None,
    category: CategoryOpt = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Change an object's percepts (only those given).

    --category replaces the object's set of categories.
    """
    from ownctl.app import things

    done = things.set_object(app_ctx(ctx), name, color, pos, category or [])
    emit(done.data, json_out, quiet, done.message)


@obj.command("list")
def object_list(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """List the objects, their percepts and their last touch."""
    from ownctl.app import things

    rows = things.list_objects(app_ctx(ctx))
    cells = [[r["name"], r["color"], r["position"], r["categories"], _last_touch(r["last_touch"])]
             for r in rows]
    emit(
        rows,
        json_out,
        quiet,
        table("objects", ["name", "colour", "position", "categories", "last touch"], cells,
              whole={"last touch"}),
    )


def _last_touch(touches: dict[str, float]) -> str | None:
    """Who touched the object last, and when (``object show`` and --json list every agent's touch)."""
    if not touches:
        return None
    agent = max(touches, key=lambda a: (touches[a], a))
    return f"{agent} {when(touches[agent])}"


@obj.command("show")
def object_show(
    ctx: typer.Context, name: ObjArg, json_out: JsonOpt = False, quiet: QuietOpt = False
) -> None:
    """Show one object: percepts, permissions and who probably owns it."""
    from ownctl.app import things

    data = things.show_object(app_ctx(ctx), name)

    def human() -> None:
        for key in ("name", "color", "position", "categories", "last_touch"):
            typer.echo(f"{key:11} {fmt(when(data[key])) if data[key] not in (None, [], {}) else '-'}")
        for p in data["permissions"]:
            typer.echo(f"permission  {p['id']}: {p['action']} = {fmt(p['value'])}")
        table(None, ["agent", "p", "source"], [[o["agent"], o["p"], o["source"]] for o in data["owners"]])()

    emit(data, json_out, quiet, human)


@obj.command("remove")
def object_remove(
    ctx: typer.Context, name: ObjArg, json_out: JsonOpt = False, quiet: QuietOpt = False
) -> None:
    """Forget an object with its beliefs and permissions."""
    from ownctl.app import things

    done = things.remove_object(app_ctx(ctx), name)
    emit(done.data, json_out, quiet, done.message)


@obj.command("touch")
def object_touch(
    ctx: typer.Context,
    name: ObjArg,
    by: Annotated[str, typer.Option("--by", metavar="AGENT", help="The agent who interacted with it.")],
    at: Annotated[
        float | None,
        typer.Option("--at", metavar="SECONDS", help="When, in store seconds (default: now)."),
    ] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Record that an agent touched an object.

    How recently each agent touched an object is a percept of ownership prediction.
    """
    from ownctl.app import things

    done = things.touch(app_ctx(ctx), name, by, at)
    emit(done.data, json_out, quiet, done.message)


@area.command("add")
def area_add(
    ctx: typer.Context,
    name: NameArg,
    box: Annotated[str, typer.Option("--box", metavar="X0,Y0,X1,Y1", help="The box, in workspace metres.")],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Add a named box area."""
    from ownctl.app import things

    done = things.add_area(app_ctx(ctx), name, box)
    emit(done.data, json_out, quiet, done.message)


@area.command("list")
def area_list(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """List the areas."""
    from ownctl.app import things

    rows = things.list_areas(app_ctx(ctx))
    emit(
        rows,
        json_out,
        quiet,
        table("areas", ["name", "box (x0, y0, x1, y1)"], [[r["name"], r["box"]] for r in rows]),
    )


@area.command("remove")
def area_remove(
    ctx: typer.Context,
    name: Annotated[str, typer.Argument(metavar="AREA", help="The area.")],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Forget an area (refused while a rule names it)."""
    from ownctl.app import things

    done = things.remove_area(app_ctx(ctx), name)
    emit(done.data, json_out, quiet, done.message)
