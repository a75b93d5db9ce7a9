"""Instructions: ownership claims, object-specific permissions and norms (DESIGN sections 2-4).

One function per use case; each is one transaction with one event-log entry, and calls the belief
hooks of :mod:`ownctl.app.beliefs`, where prediction, inference and rule induction plug in.

- :func:`add_claim`: ``p_stored = trust * p`` (or ``1 - trust * p`` for "not mine"); an exclusive
  claim sets every other agent's claim to 0.
- :func:`add_permission`: ``forbid|allow ACTION on OBJ`` (value 1.0 / 0.0; soft values allowed);
  refused while permissions are frozen.
- :func:`add_norm`: ``forbid ACTION if ...`` is stored as a given rule; ``allow ACTION if ...`` is
  logged, to be subtracted from the forbid rules by the learner (paper, Algorithm 4). Refused while
  rules are frozen.
"""

from __future__ import annotations

from typing import Any

from ownctl.app.beliefs import after_claims
from ownctl.app.context import AppContext, Done
from ownctl.app.learning import after_permission, learn_from_norm, reinfer
from ownctl.app.settings import probability
from ownctl.errors import BadValue, OwnctlError
from ownctl.logic.rules import ANY, Norm, Rule, parse_norm
from ownctl.logic.vocab import action as check_action


def add_claim(
    ctx: AppContext,
    obj: str,
    agent: str,
    p: float = 1.0,
    negated: bool = False,
    exclusive: bool = False,
    speaker: str | None = None,
) -> Done:
    """Store the claim ``[not] ownedBy(obj, agent)`` with probability ``p``, weighted by trust."""
    p = probability("the claim probability --p", p)
    if exclusive and negated:
        raise BadValue("--only (exclusive ownership) cannot be combined with --not")
    payload = {
        "op": "claim",
        "object": obj,
        "agent": agent,
        "p": p,
        "negated": negated,
        "exclusive": exclusive,
    }
    with ctx.write(payload, actor=speaker) as tx:
        row, who = tx.object(obj), tx.agent(agent)
        trust = probability("trust", tx.settings().get("trust", 1.0))
        stored = 1.0 - trust * p if negated else trust * p
        claim = {"claim_speaker": speaker, "claim_trust": trust, "claim_time": ctx.now}
        rows = [{"object_id": row.id, "agent_id": who.id, "claim_p": stored, **claim}]
        others = [a for a in tx.agents() if a.id != who.id] if exclusive else []
        rows += [{"object_id": row.id, "agent_id": a.id, "claim_p": 0.0, **claim} for a in others]
        tx.write_beliefs(rows)
        after_claims(tx, [agent, *(a.name for a in others)], ctx.now)
    alone = " alone" if exclusive else ""
    return Done(
        f"noted: {obj} is {'not ' if negated else ''}owned by {agent}{alone} (stored p={stored:.3g})",
        {"object": obj, "agent": agent, "p": stored, "trust": trust, "exclusive": exclusive},
    )


def add_permission(ctx: AppContext, action: str, obj: str, value: float, speaker: str | None = None) -> Done:
    """``forbid|allow ACTION on OBJ``: store (overwrite) the permission; value 1.0 forbids, 0.0 allows."""
    check_action(action)
    value = probability("a permission value", value)
    payload = {"op": "permission", "action": action, "object": obj, "value": value}
    with ctx.write(payload, actor=speaker) as tx:
        if tx.settings().get("frozen.perms"):
            raise OwnctlError("permissions are frozen: new permissions are refused (ownctl unfreeze perms)")
        row = tx.set_permission(action, tx.object(obj).id, value, speaker, ctx.now)
        outcome = after_permission(tx, action, row.object_id, ctx.now)
        permission_id = row.id
        rules = [r.text for r in tx.rules(action)]
    verb = "forbidden" if value >= 0.5 else "allowed"
    learned = ""
    if outcome is not None and outcome.induced:
        learned = "; induction ran, rules of " + action + ": " + ("; ".join(rules) or "(none)")
    elif outcome is not None:
        learned = f"; rules already agree with {outcome.accuracy:.0%} of the examples (kept for inference)"
    return Done(
        f"noted: {action} {verb} on {obj} (permission {permission_id}){learned}",
        {"id": permission_id, "action": action, "object": obj, "value": value,
         "induced": bool(outcome and outcome.induced),
         "accuracy": None if outcome is None else outcome.accuracy, "rules": rules},
    )


def check_references(tx: Any, rule: Rule) -> None:
    """Every agent and area a rule names must exist (``any`` is always fine); colours are free."""
    for lit in rule.literals:
        if lit.arg == ANY:
            continue
        if lit.pred == "ownedBy":
            tx.agent(lit.arg)
        elif lit.pred == "inArea":
            tx.area(lit.arg)


def add_norm(ctx: AppContext, text: str, speaker: str | None = None) -> Done:
    """``forbid|allow ACTION [if LITERALS]``: a given norm (see the module docstring)."""
    norm: Norm = parse_norm(text)
    canonical = norm.text()
    with ctx.write({"op": "norm", "sign": norm.sign, "text": canonical}, actor=speaker) as tx:
        check_references(tx, norm.rule)
        if tx.settings().get("frozen.rules"):
            raise OwnctlError("rules are frozen: given norms are refused (ownctl unfreeze rules)")
        before = {r.text for r in tx.rules(norm.rule.action)}
        learn_from_norm(tx, norm, speaker, ctx.now)
        reinfer(tx, ctx.now)
        after = [(r.id, r.text) for r in tx.rules(norm.rule.action)]
    added = [t for _, t in after if t not in before]
    removed = sorted(before - {t for _, t in after})
    parts = [f"added: {t}" for t in added] + [f"removed: {t}" for t in removed]
    if not parts:
        parts = ["the rules already say so" if norm.sign == "forbid" else "no rule covered it"]
    return Done(
        f"{canonical}: " + "; ".join(parts),
        {"id": next((i for i, t in after if t == canonical), next((i for i, t in after if t in added), None)),
         "text": canonical, "sign": norm.sign, "stored": bool(added), "added": added, "removed": removed,
         "rules": [{"id": i, "text": t} for i, t in after]},
    )
