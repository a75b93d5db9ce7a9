"""Administration: creating and upgrading the store, settings, resets, freezing and switches.

``reset`` keeps the world (agents, objects, areas), the ground truth, the settings and the event
log: ``perms`` forgets permissions, ``rules`` the rules (forbid rules and allow norms), ``claims``
every claim (priors return to the calibrated base rate), ``all`` all of these and the conversation
context. Resets and switches are instructions of the Mind, so predictions and posteriors follow.
"""

from __future__ import annotations

from typing import Any

from ownctl.app.context import AppContext, Done, use_case
from ownctl.app.mindstore import changing
from ownctl.app.settings import FLAGS, check_key, effective, parse_value
from ownctl.errors import OwnctlError
from ownctl.humanize import plural
from ownctl.mind import RESETS


def init(ctx: AppContext) -> Done:
    """Create the store named by ``ctx`` (explicit stores are created only here)."""
    store = ctx.store(create=True)
    if store.created:
        with ctx.write({"op": "init"}):
            pass
    state = "created" if store.created else "already exists:"
    data = {"path": store.location.display, "created": store.created, "revision": store.revision()}
    return Done(f"ownctl store {state} {store.location.display}", data)


def db_path(ctx: AppContext) -> dict[str, Any]:
    """Where the store is (without opening it)."""
    from ownctl.store.engine import locate

    location = locate(ctx.db)
    return {"path": location.display, "url": location.url, "explicit": location.explicit}


def db_current(ctx: AppContext) -> dict[str, Any]:
    """The store's schema revision and the newest one this ownctl knows."""
    from ownctl.store.migrate import head_revision

    store = ctx.store()
    revision = store.revision()
    return {
        "path": store.location.display,
        "revision": revision,
        "head": head_revision(),
        "current": revision == head_revision(),
    }


def db_upgrade(ctx: AppContext) -> Done:
    """Upgrade the store to the newest schema (opening already does; this reports what happened)."""
    store = ctx.store()
    revision = store.revision()
    if store.previous == revision:
        return Done(
            f"store {store.location.display} is at the newest revision {revision}",
            {"from": revision, "to": revision},
        )
    return Done(
        f"upgraded store {store.location.display} from {store.previous} to {revision}",
        {"from": store.previous, "to": revision},
    )


def config_get(ctx: AppContext, key: str | None = None) -> dict[str, Any]:
    """Every setting with its effective value, or just ``key``."""
    if key is not None:
        check_key(key)
    with ctx.read() as tx:
        values = effective(tx.meta.settings())
    if key is None:
        return values
    return {key: values.get(key)}


@use_case
def config_set(ctx: AppContext, key: str, text: str) -> Done:
    """Set ``key`` to the value in ``text`` ("default" removes an override)."""
    value = parse_value(key, text)
    if key in FLAGS:  # a switch takes effect the same way as disable/enable/freeze/unfreeze
        return set_flag(ctx, key, bool(value))
    with ctx.write({"op": "config.set", "key": key, "value": value}) as tx:
        tx.meta.set_setting(key, value)
    shown = "its default" if value is None else value
    return Done(f"{key} set to {shown}", {"key": key, "value": value})


@use_case
def set_flag(ctx: AppContext, key: str, on: bool) -> Done:
    """freeze/unfreeze perms|rules, disable/enable inference|prediction."""
    if key not in FLAGS:
        raise OwnctlError(f"unknown switch {key!r}; valid: {', '.join(FLAGS)}", FLAGS)
    with changing(ctx, {"op": "flag", "key": key, "value": on}) as (_, mind):
        mind.set_switch(key, on)
    kind, what = key.split(".")
    word = {"frozen": ("frozen", "unfrozen"), "disabled": ("disabled", "enabled")}[kind][0 if on else 1]
    return Done(f"{what} {word}", {"key": key, "value": on})


@use_case
def reset(ctx: AppContext, what: str, yes: bool) -> Done:
    """Forget permissions, rules, claims or all of them (see the module docstring); needs ``yes``."""
    if what not in RESETS:
        raise OwnctlError(f"unknown reset {what!r}; valid: {', '.join(RESETS)}", RESETS)
    if not yes:
        raise OwnctlError(f"reset {what} deletes data; repeat with --yes to confirm")
    with changing(ctx, {"op": "reset", "what": what}) as (tx, mind):
        counts = mind.reset(what)
        if what == "all":
            tx.meta.clear("context")
    listing = ", ".join(plural(n, k.removesuffix("s")) for k, n in counts.items())
    return Done(f"reset {what}: forgot {listing}", {"reset": what, **counts})
