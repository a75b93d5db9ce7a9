"""Instructions: ownership claims, object-specific permissions and norms (``docs/architecture.md``).

One function per use case; each is one transaction with one event-log entry: load the Mind the
instruction needs, call it (:class:`ownctl.mind.Mind` runs prediction, the gate, induction and
inference), save what changed (:mod:`ownctl.app.mindstore`).

- :func:`add_claim`: ``p_stored = trust * p`` (or ``1 - trust * p`` for "not mine"); an exclusive
  claim sets every other agent's claim to 0.
- :func:`add_permission`: ``forbid|allow ACTION on OBJ`` (value 1.0 / 0.0; soft values allowed);
  refused while permissions are frozen.
- :func:`add_norm`: ``forbid ACTION if ...`` (cover rule) or ``allow ACTION if ...`` (uncover rule);
  refused while rules are frozen.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ownctl.app.context import AppContext, Done, use_case
from ownctl.app.mindstore import changing, refit_focus, refitting
from ownctl.app.settings import probability
from ownctl.errors import BadValue, OwnctlError, UnknownName
from ownctl.logic.rules import ANY, Norm, Rule, parse_norm
from ownctl.logic.vocab import action as check_action

if TYPE_CHECKING:
    from ownctl.mind import Mind
    from ownctl.store.repo import Tx


@use_case
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
    with ctx.read() as tx:
        _claimed_names(tx, obj, agent)
        focus = refit_focus(tx, obj, [a.name for a in tx.world.agents()] if exclusive else [agent])

    def change(_: Tx, mind: Mind) -> tuple[float, float]:
        trust = probability("trust", mind.settings.trust)
        return trust, mind.claim(obj, agent, p, negated=negated, exclusive=exclusive, speaker=speaker)

    trust, stored = refitting(ctx, payload, change, actor=speaker, agents=focus)
    alone = " alone" if exclusive else ""
    return Done(
        f"noted: {obj} is {'not ' if negated else ''}owned by {agent}{alone} (stored p={stored:.3g})",
        {"object": obj, "agent": agent, "p": stored, "trust": trust, "exclusive": exclusive},
    )


def _claimed_names(tx: Tx, obj: str, agent: str) -> None:
    """Check a claim's object and agent exist: unknown names are errors that list the known ones,
    and an agent and an object given the other way round say so with the command to type."""
    try:
        tx.things.object(obj), tx.world.agent(agent)
    except UnknownName as exc:
        agents = {a.name for a in tx.world.agents()}
        if obj in agents and agent not in agents and _is_object(tx, agent):
            raise OwnctlError(f"{obj!r} is an agent and {agent!r} an object: the object comes first, "
                              f"ownctl claim {agent} {obj}", exc.valid) from None
        raise


def _is_object(tx: Tx, name: str) -> bool:
    try:
        tx.things.object(name)
    except UnknownName:
        return False
    return True


@use_case
def add_permission(ctx: AppContext, action: str, obj: str, value: float, speaker: str | None = None) -> Done:
    """``forbid|allow ACTION on OBJ``: store (overwrite) the permission; value 1.0 forbids, 0.0 allows.

    Reads only the objects that carry permissions (the examples and what inference may change)."""
    check_action(action)
    value = probability("a permission value", value)
    payload = {"op": "permission", "action": action, "object": obj, "value": value}
    with changing(ctx, payload, actor=speaker, only=[obj], permitted=True) as (tx, mind):
        if mind.switches.frozen_perms:
            raise OwnctlError("permissions are frozen: new permissions are refused (ownctl unfreeze perms)")
        outcome = mind.permit(action, obj, value, speaker)
        rules = [r.text() for r in mind.rules[action]]
    with ctx.read() as tx:
        permission_id = tx.knowledge.permission_id(action, tx.things.object(obj).id)
    verb = "forbidden" if value >= 0.5 else "allowed"
    learned = ""
    if outcome is not None and outcome.excepted:
        learned = (f"; an allow norm of {action} covers {obj}: an exception, decided by this permission and "
                   "not learned from")
    elif outcome is not None and outcome.induced:
        learned = "; induction ran, rules of " + action + ": " + ("; ".join(rules) or "(none)")
    elif outcome is not None:
        learned = f"; rules already agree with {outcome.accuracy:.0%} of the examples (kept for inference)"
    return Done(
        f"noted: {action} {verb} on {obj} (permission {permission_id}){learned}",
        {"id": permission_id, "action": action, "object": obj, "value": value,
         "induced": bool(outcome and outcome.induced), "exception": bool(outcome and outcome.excepted),
         "accuracy": None if outcome is None else outcome.accuracy, "rules": rules},
    )


def check_references(tx: Tx, rule: Rule) -> None:
    """Every agent and area a rule names must exist (``any`` is always fine); colours are free."""
    for lit in rule.literals:
        if lit.arg == ANY:
            continue
        if lit.pred == "ownedBy":
            tx.world.agent(lit.arg)
        elif lit.pred == "inArea":
            tx.world.area(lit.arg)


@use_case
def add_norm(ctx: AppContext, text: str, speaker: str | None = None) -> Done:
    """``forbid|allow ACTION [if LITERALS]``: a given norm, by cover rule (forbid) or uncover rule
    (allow; the allow norm is kept as a rule of origin allow and subtracted after re-induction)."""
    norm: Norm = parse_norm(text)
    canonical = norm.text()
    action = norm.rule.action
    payload = {"op": "norm", "sign": norm.sign, "text": canonical}
    with changing(ctx, payload, actor=speaker, only=[], permitted=True) as (tx, mind):
        check_references(tx, norm.rule)
        if mind.switches.frozen_rules:
            raise OwnctlError("rules are frozen: given norms are refused (ownctl unfreeze rules)")
        result = mind.instruct(norm, speaker)
        assert result is not None
    with ctx.read() as tx:
        after = [(r.id, r.text) for r in tx.knowledge.rules(action)]
    added = [r.text() for r in result.added]
    removed = sorted(r.text() for r in result.removed)
    taken = [r.text() for r in result.said]
    parts = [f"added: {t}" for t in added] + [f"removed: {t}" for t in removed]
    if not parts:
        parts = ["the rules already say so" if norm.sign == "forbid" else "no rule covered it"]
    return Done(
        f"{canonical}: " + "; ".join(parts),
        {"id": next((i for i, t in after if t == canonical), next((i for i, t in after if t in added), None)),
         "text": canonical, "sign": norm.sign, "stored": bool(added), "added": added, "removed": removed,
         "taken_as": taken, "specialised": bool(taken) and taken != [canonical],
         "rules": [{"id": i, "text": t} for i, t in after if not t.startswith("allow ")]},
    )
