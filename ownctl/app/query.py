"""Read-only views (owners, claims, permissions, rules, the log) and removing single items.

Beliefs shown as ``p`` are the decision beliefs of :func:`ownctl.app.beliefs.decision_belief`.
"""

from __future__ import annotations

from collections import Counter
from typing import TYPE_CHECKING, Any

from ownctl.app.beliefs import decision_belief
from ownctl.app.context import AppContext, Done, use_case
from ownctl.app.mindstore import changing, load, rule_of, stored_household, stored_scale, stored_silence
from ownctl.app.settings import probability, to_config
from ownctl.errors import OwnctlError, UnknownName
from ownctl.humanize import plural

if TYPE_CHECKING:
    from ownctl.store.repo import Tx


def owners(ctx: AppContext, obj: str, coverage: float | None = None) -> dict[str, Any]:
    """``{"object", "owners": [{"agent", "p", "source", "claim", "prior", "posterior"}],
    "percept_scale", "rate_spread", "rate_spread_configured", "silence", "silent"}``, likeliest
    first; ``p`` and ``source`` are the decision belief; ``percept_scale`` how far percepts may
    move the stored predictions, as a fraction of the full reach (the scale every agent's
    predictor uses, chosen on all agents' claims); ``rate_spread`` how far an agent's rate may
    stray from the base rate (the width, in logits, of every intercept's prior, chosen on all
    agents' claims) and ``rate_spread_configured`` its configured value; ``silence`` what an
    agent's silence about an object others made claims about weighs, and ``silent`` the agents
    silent about this one while it weighs (docs/architecture.md, section 5). With ``coverage``,
    each owner row also has ``"conformal"``: its split-conformal set over {owns, does not own}
    (docs/asking.md, section 7), and ``"claims_needed"`` says how many claimed objects an agent
    needs before its sets can leave a label out."""
    with ctx.read() as tx:
        try:
            object_id = tx.things.object(obj).id
        except UnknownName as exc:
            if any(a.name == obj for a in tx.world.agents()):
                raise OwnctlError(f"{obj!r} is an agent, not an object; the objects it owns: ownctl owners "
                                  f"--agent {obj}", exc.valid) from None
            raise
        rows = owner_rows(tx, object_id)
        settings = tx.meta.settings()
        weight = stored_silence(settings)
        spoken = any(r["claim"] is not None for r in rows)
        cfg = to_config(settings).predict
        data: dict[str, Any] = {"object": obj, "owners": rows,
                                "percept_scale": cfg.scales[stored_scale(settings)],
                                "rate_spread": stored_household(settings, cfg).spread,
                                "rate_spread_configured": cfg.intercept_scale,
                                "silence": weight,
                                "silent": sorted(r["agent"] for r in rows if r["claim"] is None)
                                if weight > 0 and spoken else []}
        if coverage is not None:
            from ownctl.mind.conformal import check_coverage, claims_needed, prediction_sets

            check_coverage(coverage)
            sets = {s.agent: s.as_dict() for s in prediction_sets(load(tx, ctx.now).mind, obj, coverage)}
            for row in data["owners"]:
                row["conformal"] = sets[row["agent"]]
            data["coverage"] = coverage
            data["claims_needed"] = claims_needed(coverage)
        return data


def owner_rows(tx: Tx, object_id: int) -> list[dict[str, Any]]:
    """Every agent's beliefs about one object, likeliest owner first (inside the caller's transaction)."""
    names = {a.id: a.name for a in tx.world.agents()}
    out: list[dict[str, Any]] = []
    for b in tx.beliefs.ownership(object_id=object_id):
        p, source = decision_belief(b)
        out.append({"agent": names[b.agent_id], "p": p, "source": source, "claim": b.claim_p,
                    "prior": b.prior_p, "posterior": b.posterior_p})
    out.sort(key=lambda o: (-o["p"], o["agent"]))
    return out


def owned_by(ctx: AppContext, agent: str, min_p: float = 0.5) -> list[dict[str, Any]]:
    """The objects ``agent`` owns with probability >= ``min_p``, likeliest first."""
    min_p = probability("--min", min_p)
    with ctx.read() as tx:
        who = tx.world.agent(agent)
        names = {o.id: o.name for o in tx.things.objects()}
        rows = [(names[b.object_id], *decision_belief(b)) for b in tx.beliefs.ownership(agent_id=who.id)]
    rows.sort(key=lambda r: (-r[1], r[0]))
    return [{"object": o, "p": p, "source": s} for o, p, s in rows if p >= min_p]


def list_claims(ctx: AppContext) -> list[dict[str, Any]]:
    """Every stored claim."""
    with ctx.read() as tx:
        objects = {o.id: o.name for o in tx.things.objects()}
        agents = {a.id: a.name for a in tx.world.agents()}
        return [
            {
                "object": objects[b.object_id],
                "agent": agents[b.agent_id],
                "p": b.claim_p,
                "speaker": b.claim_speaker,
                "trust": b.claim_trust,
                "time": b.claim_time,
            }
            for b in tx.beliefs.ownership()
            if b.claim_p is not None
        ]


def _permission_dict(p: Any, objects: dict[int, str]) -> dict[str, Any]:
    sign = "forbid" if p.value >= 0.5 else "allow"
    return {
        "id": p.id,
        "action": p.action,
        "object": objects[p.object_id],
        "value": p.value,
        "text": f"{sign} {p.action} on {objects[p.object_id]}",
        "speaker": p.speaker,
        "time": p.time,
    }


def list_permissions(ctx: AppContext) -> list[dict[str, Any]]:
    """Every object-specific permission, oldest first."""
    with ctx.read() as tx:
        objects = {o.id: o.name for o in tx.things.objects()}
        return [_permission_dict(p, objects) for p in tx.knowledge.permissions()]


@use_case
def remove_permission(ctx: AppContext, permission_id: int) -> Done:
    """Forget one permission."""
    with ctx.read() as tx:
        row = tx.knowledge.permission(permission_id)
        name = tx.things.object_name(row.object_id)
        data = _permission_dict(row, {row.object_id: name})
    payload = {"op": "permission.remove", "id": permission_id}
    with changing(ctx, payload, only=[name], permitted=True) as (_, mind):
        mind.remove_permission(row.action, name)  # the posterior no longer rests on it
    return Done(f"removed permission {permission_id} ({data['text']})", data)


def list_rules(ctx: AppContext) -> list[dict[str, Any]]:
    """Every rule (forbid rules, then allow norms, per action) with its soft accuracy on its
    action's stored permissions (None without any), as the conflict gate measures it, and its
    ``posterior``: how sure the posterior over rule sets is of what the rule says on those examples.

    ``accuracy`` is the rule's own mean agreement between each permission and P(rule holds) over
    the action's examples (prior ownership, the percepts of when each permission was given);
    ``set_accuracy`` is the same for the action's whole rule set. Allow norms carry neither.
    """
    with ctx.read() as tx:
        rows = tx.knowledge.rules()
        mind = load(tx, ctx.now, only=[], permitted=True).mind
    evidence = {a: mind.evidence(a)[0] for a in sorted({r.action for r in rows})}
    out = []
    for row in rows:
        entry: dict[str, Any] = {"id": row.id, "text": row.text, "action": row.action, "origin": row.origin}
        entry.update(accuracy=None, set_accuracy=None, provenance=row.provenance, created=row.created)
        ev = evidence[row.action]
        entry["posterior"] = None
        if ev.n and row.origin != "allow":
            rule = rule_of(row.text, row.origin)
            entry["accuracy"] = ev.soft_accuracy([rule])
            entry["set_accuracy"] = ev.soft_accuracy(mind.rules[row.action])
            entry["posterior"] = mind.rule_support(row.action, rule)
        out.append(entry)
    return out


@use_case
def remove_rule(ctx: AppContext, rule_id: int) -> Done:
    """Forget one rule or allow norm; refused while rules are frozen."""
    with ctx.read() as tx:
        row = tx.knowledge.rule(rule_id)
        action, text, origin = row.action, row.text, row.origin
    with changing(ctx, {"op": "rule.remove", "id": rule_id}, only=[], permitted=True) as (_, mind):
        mind.remove_rule(action, rule_of(text, origin))  # posteriors follow the remaining rules
    return Done(f"removed rule {rule_id}: {text}", {"id": rule_id, "text": text})


def instructions(ctx: AppContext, limit: int | None = None) -> list[dict[str, Any]]:
    """The event log, one row per instruction, oldest first: the last ``limit`` instructions.

    Consecutive events of one command line (same store time, actor, interface and command text:
    a task run's steps, a world it generated) form one row ``{"first", "last", "time", "actor",
    "interface", "command", "summary", "events"}``; ``events`` are the row's events as
    :func:`events` lists them. A run's steps are the robot's doing, so a run without a speaker has
    ``robot`` as its actor.
    """
    if limit is not None and limit < 1:
        raise OwnctlError(f"--limit must be at least 1, got {limit}")
    with ctx.read() as tx:
        if limit is None:
            return _group(tx.meta.events())
        fetch = limit
        while True:  # read back until the oldest row shown is known to be whole
            rows = tx.meta.events(fetch)
            groups = _group(rows)
            if len(groups) > limit or len(rows) < fetch:
                return groups[-limit:]
            fetch *= 4


def events(ctx: AppContext, limit: int | None = None) -> list[dict[str, Any]]:
    """The events of the last ``limit`` instructions (see :func:`instructions`), oldest first."""
    return [e for row in instructions(ctx, limit) for e in row["events"]]


RUN_OPS = frozenset({"run.step", "world.generate"})  # what a task run logs


def _group(rows: list[Any]) -> list[dict[str, Any]]:
    groups: list[dict[str, Any]] = []
    for e in rows:
        event = {"id": e.id, "time": e.time, "actor": e.actor, "interface": e.interface,
                 "command": e.command, "payload": e.payload}
        last = groups[-1] if groups else None
        if last is not None and all(last[k] == event[k] for k in ("time", "actor", "interface", "command")):
            last["events"].append(event)
            last["last"] = e.id
        else:
            groups.append({"first": e.id, "last": e.id, "time": e.time, "actor": e.actor,
                           "interface": e.interface, "command": e.command, "events": [event]})
    for group in groups:
        ops = [(ev["payload"] or {}).get("op", "") for ev in group["events"]]
        if group["actor"] is None and ops and set(ops) <= RUN_OPS and "run.step" in ops:
            group["actor"] = "robot"
        group["summary"] = _summary(group["events"], ops)
    return groups


def _summary(events: list[dict[str, Any]], ops: list[str]) -> str:
    """What a row's events did, in a few words (empty for a single instruction)."""
    if len(events) == 1:
        return ""
    steps = [(ev["payload"] or {}) for ev in events if (ev["payload"] or {}).get("op") == "run.step"]
    parts = [op if n == 1 else f"{n} x {op}" for op, n in Counter(ops).items() if op != "run.step"]
    if steps:
        fates = Counter(_FATES.get(s.get("outcome", ""), s.get("outcome", "")) for s in steps)
        mistakes = sum(1 for s in steps if s.get("mistake"))
        detail = ", ".join(f"{n} {fate}" for fate, n in fates.items())
        parts.append(f"{plural(len(steps), 'step')}: {detail}, {plural(mistakes, 'mistake')}")
    return "; ".join(parts)


_FATES = {"skipped": "left"}  # a step's outcome as the run's summary and table say it
