"""Administration commands: init, db, config, reset, freeze/unfreeze, disable/enable."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from ownctl.cli.common import JsonOpt, QuietOpt, app_ctx, emit, table
from ownctl.cli.help import Group

db = Group(help="The store's location and schema revision.")
config = Group(help="Settings: thresholds, trust, the learner, switches.")

KEY_HELP = ("threshold, threshold.ACTION, trust, learner, decide.rules, decide.window, ask.min_gain, "
            "ask.kinds, ask.temper, ask.read, ask.ahead, frozen.*, disabled.*")


class Frozen(StrEnum):
    """What can be frozen."""

    perms = "perms"
    rules = "rules"


class Switch(StrEnum):
    """What can be disabled."""

    inference = "inference"
    prediction = "prediction"


class Reset(StrEnum):
    """What can be reset."""

    perms = "perms"
    rules = "rules"
    claims = "claims"
    all = "all"


def init(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Create the store.

    The default store is also created on first use; a store named with --db or OWNCTL_DB is
    created only by init.
    """
    from ownctl.app import admin

    done = admin.init(app_ctx(ctx))
    emit(done.data, json_out, quiet, done.message)


@db.command("path")
def db_path(ctx: typer.Context, json_out: JsonOpt = False) -> None:
    """Print where the store is (without opening it)."""
    from ownctl.app import admin

    data = admin.db_path(app_ctx(ctx))
    emit(data, json_out, False, data["path"])


@db.command("current")
def db_current(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Print the store's schema revision (and the newest one known)."""
    from ownctl.app import admin

    data = admin.db_current(app_ctx(ctx))
    emit(data, json_out, quiet, f"{data['revision']} (head: {data['head']}) {data['path']}")


@db.command("upgrade")
def db_upgrade(ctx: typer.Context, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Upgrade the store to the newest schema.

    Any command also upgrades the store it opens.
    """
    from ownctl.app import admin

    done = admin.db_upgrade(app_ctx(ctx))
    emit(done.data, json_out, quiet, done.message)


@config.command("get")
def config_get(
    ctx: typer.Context,
    key: Annotated[
        str | None,
        typer.Argument(metavar="KEY", help=KEY_HELP),
    ] = None,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Show every setting, or one."""
    from ownctl.app import admin

    data = admin.config_get(app_ctx(ctx), key)
    emit(data, json_out, quiet, table("settings", ["key", "value"], list(data.items())))


@config.command("set")
def config_set(
    ctx: typer.Context,
    key: Annotated[
        str,
        typer.Argument(metavar="KEY", help=KEY_HELP),
    ],
    value: Annotated[
        str,
        typer.Argument(metavar="VALUE", help="A number in [0, 1] (thresholds, trust), true/false, ours/paper "
                       "(learner), map/posterior/window (decide.rules), a number of nats (decide.window), "
                       "or 'default'."),
    ],
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Set a setting ('default' removes an override)."""
    from ownctl.app import admin

    done = admin.config_set(app_ctx(ctx), key, value)
    emit(done.data, json_out, quiet, done.message)


def reset(
    ctx: typer.Context,
    what: Annotated[
        Reset, typer.Argument(metavar="perms|rules|claims|all", help="claims forgets every ownership belief.")
    ],
    yes: Annotated[bool, typer.Option("--yes", help="Confirm: this deletes data.")] = False,
    json_out: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Forget permissions, rules, ownership beliefs, or all three.

    The world and the event log stay.
    """
    from ownctl.app import admin

    done = admin.reset(app_ctx(ctx), what.value, yes)
    emit(done.data, json_out, quiet, done.message)


def _flag(ctx: typer.Context, key: str, on: bool, json_out: bool, quiet: bool) -> None:
    from ownctl.app import admin

    done = admin.set_flag(app_ctx(ctx), key, on)
    emit(done.data, json_out, quiet, done.message)


FrozenArg = Annotated[
    Frozen, typer.Argument(metavar="perms|rules", help="perms: new ones are refused; rules: kept as is.")
]
SwitchArg = Annotated[
    Switch,
    typer.Argument(metavar="inference|prediction",
                   help="Rule-based ownership inference, or percept-based ownership prediction."),
]


def freeze(ctx: typer.Context, what: FrozenArg, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Freeze permissions (refuse new ones) or rules (keep them)."""
    _flag(ctx, f"frozen.{what.value}", True, json_out, quiet)


def unfreeze(ctx: typer.Context, what: FrozenArg, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Undo freeze."""
    _flag(ctx, f"frozen.{what.value}", False, json_out, quiet)


def disable(ctx: typer.Context, what: SwitchArg, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Switch off ownership inference or ownership prediction."""
    _flag(ctx, f"disabled.{what.value}", True, json_out, quiet)


def enable(ctx: typer.Context, what: SwitchArg, json_out: JsonOpt = False, quiet: QuietOpt = False) -> None:
    """Undo disable."""
    _flag(ctx, f"disabled.{what.value}", False, json_out, quiet)
