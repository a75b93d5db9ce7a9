"""Read-only views (owners, claims, permissions, rules, the log) and removing single items.

Beliefs shown as ``p`` are the decision beliefs of :func:`ownctl.app.beliefs.decision_belief`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ownctl.app.beliefs import decision_belief
from ownctl.app.context import AppContext, Done
from ownctl.app.mindstore import changing, load, rule_of
from ownctl.app.settings import probability
from ownctl.errors import OwnctlError

if TYPE_CHECKING:
    from ownctl.store.repo import Tx


def owners(ctx: AppContext, obj: str) -> dict[str, Any]:
    """``{"object", "owners": [{"agent", "p", "source", "claim", "prior", "posterior"}]}``, likeliest
    first; ``p`` and ``source`` are the decision belief."""
    with ctx.read() as tx:
        return {"object": obj, "owners": owner_rows(tx, tx.things.object(obj).id)}


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
    action's stored permissions (None without any), as the conflict gate measures it.

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
        if ev.n and row.origin != "allow":
            entry["accuracy"] = ev.soft_accuracy([rule_of(row.text, row.origin)])
            entry["set_accuracy"] = ev.soft_accuracy(mind.rules[row.action])
        out.append(entry)
    return out


def remove_rule(ctx: AppContext, rule_id: int) -> Done:
    """Forget one rule or allow norm; refused while rules are frozen."""
    with ctx.read() as tx:
        row = tx.knowledge.rule(rule_id)
        action, text, origin = row.action, row.text, row.origin
    with changing(ctx, {"op": "rule.remove", "id": rule_id}, only=[], permitted=True) as (_, mind):
        mind.remove_rule(action, rule_of(text, origin))  # posteriors follow the remaining rules
    return Done(f"removed rule {rule_id}: {text}", {"id": rule_id, "text": text})


def events(ctx: AppContext, limit: int | None = None) -> list[dict[str, Any]]:
    """The last ``limit`` instructions of the event log, oldest first."""
    if limit is not None and limit < 1:
        raise OwnctlError(f"--limit must be at least 1, got {limit}")
    with ctx.read() as tx:
        return [
            {
                "id": e.id,
                "time": e.time,
                "actor": e.actor,
                "interface": e.interface,
                "command": e.command,
                "payload": e.payload,
            }
            for e in tx.meta.events(limit)
        ]
