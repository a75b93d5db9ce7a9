"""Load a store into an in-memory :class:`~ownctl.experiment.mind.Mind` and write it back.

Long-running work (a task run) drives the same Mind the experiments use, and persists what it
learned after every step, each step in its own transaction (DESIGN section 9).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ownctl.app.learning import save_rules
from ownctl.app.settings import to_config
from ownctl.experiment.mind import Mind, Switches
from ownctl.logic.rules import parse_norm, parse_rule
from ownctl.logic.vocab import ACTIONS
from ownctl.world.model import World

if TYPE_CHECKING:
    from ownctl.store.repo import Tx


def mind_from_store(tx: Tx, world: World) -> Mind:
    """A Mind over ``world``'s objects holding the store's claims, priors, permissions and rules."""
    stored = tx.settings()
    switches = Switches(
        inference=not stored.get("disabled.inference", False),
        prediction=not stored.get("disabled.prediction", False),
        frozen_perms=bool(stored.get("frozen.perms", False)),
        frozen_rules=bool(stored.get("frozen.rules", False)),
    )
    mind = Mind(world.agents, list(world.objects), world.areas, to_config(stored), switches)
    rows = {r.id: i for i, r in enumerate(tx.objects())}
    column = {a.id: world.agents.index(a.name) for a in tx.agents()}
    for b in tx.ownership():
        i, j = rows[b.object_id], column[b.agent_id]
        if b.claim_p is not None:
            mind.claims[i, j] = b.claim_p
        if b.prior_p is not None:
            mind.predicted[i, j] = b.prior_p
    for p in tx.permissions():
        mind.remember(p.action, rows[p.object_id], p.value)
    for action in ACTIONS:
        texts = tx.rules(action)
        mind.rules[action] = tuple(parse_rule(r.text) for r in texts)
        mind.given[action] = [parse_rule(r.text) for r in texts if r.origin == "given"]
        mind.allows[action] = [parse_norm(t).rule for t in stored.get(f"allow.{action}", [])]
    return mind


def save_mind(tx: Tx, mind: Mind, now: float, touched: list[int]) -> None:
    """Write the Mind's permissions, claims, beliefs, rules and the ``touched`` objects' positions."""
    rows = tx.objects()
    agents = {a.name: a.id for a in tx.agents()}
    for i in touched:
        pos = mind.objects[i].position
        if pos is not None:
            rows[i].x, rows[i].y, rows[i].z = (float(v) for v in pos)
    stored = {(p.action, p.object_id): p.value for p in tx.permissions()}
    for action, values in mind.perms.items():
        for i in mind.order[action]:
            if stored.get((action, rows[i].id)) != values[i]:
                tx.set_permission(action, rows[i].id, float(values[i]), "instructor", now)
    post = mind.posterior()
    claimed = {(b.object_id, b.agent_id): b.claim_p for b in tx.ownership()}
    permitted = np.zeros(len(rows), dtype=bool)
    for idx in mind.order.values():
        permitted[idx] = True
    beliefs: list[dict[str, Any]] = []
    for i, row in enumerate(rows):
        for j, agent in enumerate(mind.agents):
            claim = mind.claims[i, j]
            entry: dict[str, Any] = {
                "object_id": row.id, "agent_id": agents[agent],
                "prior_p": float(mind.predicted[i, j]), "prior_source": "prediction", "prior_time": now,
                "posterior_p": float(post[i, j]) if permitted[i] and mind.switches.inference else None,
                "posterior_source": "inference" if permitted[i] and mind.switches.inference else None,
                "posterior_time": now if permitted[i] else None,
            }
            if not np.isnan(claim) and claimed.get((row.id, agents[agent])) != claim:
                entry.update(claim_p=float(claim), claim_speaker="instructor", claim_trust=1.0,
                             claim_time=now)
            beliefs.append(entry)
    tx.write_beliefs(beliefs)
    for action, rules in mind.rules.items():
        ev, idx = mind.evidence(action)
        said = {r: {"given": r.text(), "during": "run"} for r in mind.given[action]}
        save_rules(tx, action, rules, ev, [mind.objects[i].name for i in idx], now, said)
