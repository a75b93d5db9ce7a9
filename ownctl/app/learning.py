"""Learning in every instruction: prediction, rule induction and inference against the store.

The store-facing half of the paper's integration (the core half is :mod:`ownctl.learn` and
:mod:`ownctl.ownership`):

- :func:`repredict` refits one agent's KLR on its claims and writes that agent's priors for every
  object with one bulk statement (``disabled.prediction`` turns it off);
- :func:`learn_from_permission` runs the conflict gate and induction on the stored examples of one
  action, which see *prior* ownership (claims, else predictions);
- :func:`learn_from_norm` runs cover rule / uncover rule for a given norm; allow norms are kept in the
  setting ``allow.ACTION`` so the learner can subtract them again after re-induction;
- :func:`reinfer` recomputes the posterior of the objects that carry permissions and clears stale
  posteriors elsewhere (an object without permissions has its prior as posterior); decisions see
  these posteriors. ``disabled.inference`` clears every posterior.

Every function works inside the caller's transaction (``tx``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ownctl.app.beliefs import Snapshot, induction_belief, snapshot
from ownctl.app.settings import to_config
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import Outcome, learn_norm, learn_permission
from ownctl.logic.rules import Norm, Rule, parse_rule
from ownctl.logic.vocab import ACTIONS
from ownctl.ownership.features import agent_features
from ownctl.ownership.infer import posterior
from ownctl.ownership.predict import KernelOwnershipModel

if TYPE_CHECKING:
    from ownctl.store.repo import Tx


def _vocabulary(snap: Any) -> Vocabulary:
    return Vocabulary(
        snap.agents,
        tuple(sorted({o.color for o in snap.objects if o.color})),
        tuple(a.name for a in snap.areas),
        tuple(sorted({c for o in snap.objects for c in o.categories})),
    )


def repredict(
    tx: Tx, agents: Sequence[str] | None, now: float, object_ids: Sequence[int] | None = None
) -> None:
    """Refit the predictors of ``agents`` (None: every agent) on their claims and store the priors
    of every object (or only of ``object_ids``) for them.

    Reads only what one agent's predictor needs (every object's percepts, that agent's touches and
    claims) and writes that agent's priors with one bulk statement. An agent without claims gets the
    calibrated base rate (DESIGN section 5), never an empty prior.
    """
    stored = tx.settings()
    if stored.get("disabled.prediction"):
        return
    cfg = to_config(stored).predict
    rows = tx.object_table()
    if not rows:
        return
    ids = [r.id for r in rows]
    colors_of = [r.color for r in rows]
    palette = tuple(sorted({c for c in colors_of if c}))
    pos = np.array([[np.nan if v is None else v for v in (r.x, r.y, r.z if r.z is not None else 0.0)]
                    for r in rows], dtype=float)
    pos[np.isnan(pos[:, 0]) | np.isnan(pos[:, 1])] = np.nan
    index = {oid: i for i, oid in enumerate(ids)}
    agent_ids = {a.name: a.id for a in tx.agents()}
    agents = list(agent_ids) if agents is None else agents
    wanted = set(ids if object_ids is None else object_ids)
    out: list[dict[str, Any]] = []
    for agent in agents:
        aid = agent_ids[agent]
        ages = np.full(len(ids), np.nan)
        for (oid, _), t in tx.touches(agent_id=aid).items():
            ages[index[oid]] = max(0.0, now - t)
        beliefs = tx.belief_table(agent_id=aid)
        claimed = [(index[b.object_id], b.claim_p) for b in beliefs if b.claim_p is not None]
        X = agent_features(pos, colors_of, ages, palette, cfg)
        known = np.array([i for i, _ in claimed], dtype=int)
        targets = np.array([p for _, p in claimed], dtype=float)
        model = KernelOwnershipModel(cfg).fit(X[known], targets)
        p = model.predict_proba(X)
        out += [
            {"object_id": oid, "agent_id": aid, "prior_p": float(v), "prior_source": model.source_,
             "prior_time": now}
            for oid, v in zip(ids, p, strict=True)
            if oid in wanted
        ]
    tx.write_beliefs(out)


def _evidence(
    tx: Tx, action: str, now: float, perms: Sequence[Any] | None = None, snap: Snapshot | None = None
) -> tuple[Evidence, list[int], Snapshot]:
    """The stored permissions of ``action`` (oldest first) on prior beliefs, their object ids, the snapshot.

    ``perms`` and ``snap`` may be passed in when the caller already loaded them (all permissions,
    and a snapshot holding at least their objects).
    """
    mine = [p for p in (tx.permission_table() if perms is None else perms) if p.action == action]
    if snap is None:
        snap = snapshot(tx, now, induction_belief, ids=sorted({p.object_id for p in mine}))
    index = {oid: i for i, oid in enumerate(snap.ids)}
    frame = snap.frame().take([index[p.object_id] for p in mine])
    return Evidence(frame, [p.value for p in mine]), [p.object_id for p in mine], snap


def save_rules(
    tx: Tx, action: str, rules: Sequence[Rule], ev: Evidence, names: list[str], now: float,
    said: dict[Rule, dict[str, Any]] | None = None,
) -> None:
    """Store ``rules`` as the action's rule set. Rules kept keep their origin; rules in ``said``
    (what an instructor just stated, or its pieces) are given, with that provenance; other new rules
    are learned, with the examples they cover as provenance."""
    old = {r.text: r for r in tx.rules(action)}
    said = said or {}
    out = []
    for rule in rules:
        text = rule.text()
        if rule in said and (text not in old or old[text].origin != "given"):
            out.append((text, "given", said[rule]))
        elif text in old:
            out.append((text, old[text].origin, old[text].provenance))
        else:
            covered = ev.prob(ev.truth(rule)) >= 0.5
            examples = [n for n, c, pos in zip(names, covered, ev.positives, strict=True) if c and pos]
            out.append((text, "learned", {"examples": examples, "learned_at": now}))
    tx.replace_rules(action, out, now)


def _rules(tx: Tx, action: str) -> tuple[list[Rule], list[Rule]]:
    rows = tx.rules(action)
    return [parse_rule(r.text) for r in rows], [parse_rule(r.text) for r in rows if r.origin == "given"]


def _allows(tx: Tx, action: str) -> list[Rule]:
    from ownctl.logic.rules import parse_norm

    return [parse_norm(t).rule for t in tx.settings().get(f"allow.{action}", [])]


def learn_from_permission(
    tx: Tx, action: str, object_id: int, now: float,
    perms: Sequence[Any] | None = None, snap: Snapshot | None = None,
) -> Outcome | None:
    """The gate and induction after the permission of ``action`` on ``object_id`` was stored."""
    stored = tx.settings()
    if stored.get("frozen.rules"):
        return None
    ev, object_ids, snap = _evidence(tx, action, now, perms, snap)
    if ev.n == 0:
        return None
    rules, given = _rules(tx, action)
    names = [snap.objects[snap.ids.index(oid)].name for oid in object_ids]
    out = learn_permission(
        action,
        rules,
        _allows(tx, action),
        ev,
        object_ids.index(object_id),
        _vocabulary(snap),
        to_config(stored).learn,
        given,
    )
    if out.induced:
        save_rules(tx, action, out.rules, ev, names, now)
    return out


def after_permission(tx: Tx, action: str, object_id: int, now: float) -> Outcome | None:
    """A permission was stored: gate and induction on this action's examples, then posteriors.

    Unchanged rules change no other object's posterior, so then only this object is re-inferred,
    from the same snapshot; new rules re-infer every object with permissions.
    """
    perms = tx.permission_table()
    snap = snapshot(tx, now, induction_belief, ids=sorted({p.object_id for p in perms if p.action == action}))
    outcome = learn_from_permission(tx, action, object_id, now, perms, snap)
    if outcome is not None and outcome.induced:
        reinfer(tx, now, perms)
    else:
        reinfer(tx, now, perms, snap, only=[object_id])
    return outcome


def learn_from_norm(tx: Tx, norm: Norm, speaker: str | None, now: float) -> Outcome:
    """Cover rule (forbid) or uncover rule (allow) for a given norm, against the stored examples."""
    action = norm.rule.action
    ev, object_ids, snap = _evidence(tx, action, now)
    rules, given = _rules(tx, action)
    old_given = {r: row for r, row in zip(rules, tx.rules(action), strict=True) if row.origin == "given"}
    out = learn_norm(norm, rules, ev, _vocabulary(snap), to_config(tx.settings()).learn,
                     _allows(tx, action), given)
    names = [snap.objects[snap.ids.index(oid)].name for oid in object_ids]
    said: dict[Rule, dict[str, Any]] = {}
    for r in out.given:
        if r in old_given:
            continue
        if norm.sign == "allow":
            parent = next((g for g in old_given if g.conditions <= r.conditions), None)
            said[r] = {"given": parent.text() if parent else None, "minus": norm.text(), "speaker": speaker}
        else:
            said[r] = {"given": norm.text(), "speaker": speaker, "specialised": r != norm.rule}
    if norm.sign == "allow":
        key = f"allow.{action}"
        texts = list(tx.settings().get(key, []))
        if norm.text() not in texts:
            tx.set_setting(key, [*texts, norm.text()])
    save_rules(tx, action, out.rules, ev, names, now, said)
    return out


def reinfer(
    tx: Tx, now: float, perms: Sequence[Any] | None = None, snap: Snapshot | None = None,
    only: Sequence[int] | None = None, clear: bool = True,
) -> None:
    """Posteriors for objects with permissions; NULL elsewhere (the prior stands).

    ``perms`` and ``snap`` (all permissions; a prior-belief snapshot of their objects) may be passed
    in when the caller already loaded them; ``only`` limits the work to those objects (when nothing
    else changed); ``clear=False`` skips clearing the posteriors of objects without permissions
    (when no permission was removed, there are none to clear).
    """
    stored = tx.settings()
    perms = tx.permission_table() if perms is None else perms
    object_ids = sorted({p.object_id for p in perms})
    if stored.get("disabled.inference") or not perms:
        tx.clear_posteriors()
        return
    if only is not None:
        wanted_ids = set(only)
        perms = [p for p in perms if p.object_id in wanted_ids]
    elif clear:
        tx.clear_posteriors(keep=object_ids)
    rules: dict[str, list[Rule]] = {a: [] for a in ACTIONS}
    for row in tx.rules():
        rules[row.action].append(parse_rule(row.text))
    if snap is None:
        snap = snapshot(tx, now, induction_belief, ids=object_ids if only is None else sorted(only))
    index = {oid: i for i, oid in enumerate(snap.ids)}
    values = {a: np.full(len(snap.ids), np.nan) for a in ACTIONS}
    for p in perms:
        values[p.action][index[p.object_id]] = p.value
    post = posterior(snap.frame(), rules, values, to_config(stored).infer.noise)
    agent_ids = {a.name: a.id for a in tx.agents()}
    wanted = set(object_ids if only is None else only)
    rows = [
        {"object_id": oid, "agent_id": agent_ids[a], "posterior_p": float(post[i, j]),
         "posterior_source": "inference", "posterior_time": now}
        for i, oid in enumerate(snap.ids) if oid in wanted
        for j, a in enumerate(snap.agents)
    ]
    tx.write_beliefs(rows)
