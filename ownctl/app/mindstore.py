"""Load the :class:`~ownctl.mind.Mind` an instruction needs from the store, and save what it changed.

Every instruction is load -> call -> save (``docs/architecture.md``): :func:`load` reads the
objects a use case needs (all of them; or only some, with the objects that carry permissions, when
nothing needs every object) with their beliefs, the permissions on them with their percept
snapshots, every rule and the switches; the Mind does the work; :meth:`Stored.save` compares the
Mind with what was loaded (or last saved) and writes only the differences, beliefs in bulk. Loading
what was saved gives the same Mind back, bit for bit, so a store behaves exactly like a Mind kept in
memory (tested).

Stored forms: an ownership row holds the claim (with speaker, trust, time), the prior (the
prediction, with its source: ``prediction`` or ``base-rate``) and the posterior (only for objects
that carry permissions while inference is on; elsewhere the prior stands). A permission holds its
arrival rank and the object's percepts when it was given. A rule row holds its text, origin
(given, learned, allow), provenance and rank.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ownctl.app.settings import to_config
from ownctl.learn.evidence import Vocabulary
from ownctl.logic.rules import Rule, parse_norm, parse_rule
from ownctl.logic.vocab import ACTIONS
from ownctl.mind import SWITCHES, ClaimInfo, Given, Mind, RuleInfo, Switches
from ownctl.world.model import Area, ObjectSpec

if TYPE_CHECKING:
    from ownctl.app.context import AppContext
    from ownctl.store.repo import Tx


def spec_of(row: Any, categories: set[str], touches: dict[str, float]) -> ObjectSpec:
    """A stored object (plain row) as a core spec; touch times stay absolute."""
    position = None if row.x is None or row.y is None else (row.x, row.y, row.z if row.z is not None else 0.0)
    return ObjectSpec(row.name, row.color, position, frozenset(categories), dict(touches))


def seen_to_json(spec: ObjectSpec) -> dict[str, Any]:
    """A permission's percept snapshot in its stored form."""
    return {"color": spec.color, "position": None if spec.position is None else list(spec.position),
            "categories": sorted(spec.categories), "touches": dict(spec.last_touch)}


def seen_from_json(name: str, data: dict[str, Any] | None, current: ObjectSpec) -> ObjectSpec:
    """A stored percept snapshot as a spec (a permission stored without one: the current percepts)."""
    if not data:
        return current
    pos = data.get("position")
    position = None if pos is None else (float(pos[0]), float(pos[1]), float(pos[2]))
    return ObjectSpec(name, data.get("color"), position, frozenset(data.get("categories") or ()),
                      {str(a): float(t) for a, t in (data.get("touches") or {}).items()})


def rule_of(text: str, origin: str) -> Rule:
    """The rule a stored row holds (allow rows hold the allow norm's text)."""
    return parse_norm(text).rule if origin == "allow" else parse_rule(text)


def rule_text(rule: Rule, origin: str) -> str:
    """The stored text of a rule of ``origin``."""
    return rule.text("allow") if origin == "allow" else rule.text()


def switches_of(stored: dict[str, Any]) -> Switches:
    """The Mind's switches from the store's flag settings."""
    out = Switches()
    for key, (attr, when_on) in SWITCHES.items():
        on = bool(stored.get(key, False))
        setattr(out, attr, on if when_on else not on)
    return out


@dataclass
class _Base:
    """What the store holds, as last loaded or saved (the Mind is compared with it on save)."""

    agents: tuple[str, ...]
    areas: tuple[Area, ...]
    objects: dict[str, ObjectSpec]
    row: dict[str, int]  # object name -> row of the belief arrays below
    claims: np.ndarray
    claim_info: dict[tuple[str, str], ClaimInfo]
    prior: np.ndarray  # NaN where the store holds no prior
    source: np.ndarray
    posterior: np.ndarray  # NaN where the store holds no posterior
    perms: dict[str, dict[str, Given]]
    rules: dict[str, list[tuple[str, str, Any]]]
    switches: dict[str, bool]


def _rules_state(mind: Mind) -> dict[str, list[tuple[str, str, Any]]]:
    return {a: [(rule_text(r, i.origin), i.origin, dict(i.provenance)) for r, i in mind.all_rules(a)]
            for a in ACTIONS}


def _stored_posterior(mind: Mind) -> np.ndarray:
    """The posteriors as stored: for objects with permissions while inference is on; NaN elsewhere."""
    out = np.full(mind.claims.shape, np.nan)
    idx = mind.permitted()
    if mind.switches.inference and idx:
        out[idx] = mind.posterior()[idx]
    return out


def _switch_values(mind: Mind) -> dict[str, bool]:
    return {k: getattr(mind.switches, attr) == when_on for k, (attr, when_on) in SWITCHES.items()}


@dataclass
class Stored:
    """A Mind loaded from the store, with the store ids of its objects and agents."""

    mind: Mind
    ids: dict[str, int]  # object name -> id
    agent_ids: dict[str, int]
    writable: np.ndarray | None = None  # the belief cells that were loaded (None: all of them)
    base: _Base = field(init=False)

    def __post_init__(self) -> None:
        self.base = self._snapshot()

    def _snapshot(self, stored_posterior: np.ndarray | None = None) -> _Base:
        mind = self.mind
        post = _stored_posterior(mind) if stored_posterior is None else stored_posterior
        return _Base(
            agents=mind.agents, areas=tuple(mind.areas), objects={o.name: o for o in mind.objects},
            row=dict(mind.index), claims=mind.claims.copy(), claim_info=dict(mind.claim_info),
            prior=mind.predicted.copy(), source=mind.prior_source.copy(), posterior=post,
            perms={a: dict(g) for a, g in mind.perms.items()}, rules=_rules_state(mind),
            switches=_switch_values(mind),
        )

    # -- saving ---------------------------------------------------------------------------------
    def save(self, tx: Tx) -> None:
        """Write what changed since the last load or save, then take the Mind as the new baseline."""
        mind, base = self.mind, self.base
        mind.refresh()
        now = mind.now
        self._save_agents(tx, base)
        self._save_areas(tx, base)
        self._save_objects(tx, base)
        post = _stored_posterior(mind)
        self._save_beliefs(tx, base, post)
        self._save_permissions(tx, base)
        rules = _rules_state(mind)
        for action in ACTIONS:
            if rules[action] != base.rules[action]:
                tx.knowledge.replace_rules(action, rules[action], now)
        for key, value in _switch_values(mind).items():
            if value != base.switches[key]:
                tx.meta.set_setting(key, value or None)
        self.base = self._snapshot(post)

    def _save_agents(self, tx: Tx, base: _Base) -> None:
        for name in base.agents:
            if name not in self.mind.agents:
                tx.world.remove(tx.world.agent(name))
                del self.agent_ids[name]
        for name in self.mind.agents:
            if name not in base.agents:
                self.agent_ids[name] = tx.world.add_agent(name, self.mind.now).id

    def _save_areas(self, tx: Tx, base: _Base) -> None:
        now = {a.name: a for a in self.mind.areas}
        for area in base.areas:
            if area.name not in now:
                tx.world.remove(tx.world.area(area.name))
        for area in self.mind.areas:
            if area not in base.areas:
                tx.world.add_area(area.name, area.box)

    def _save_objects(self, tx: Tx, base: _Base) -> None:
        mind = self.mind
        current = {o.name for o in mind.objects}
        gone = [n for n in base.objects if n not in current]
        if gone:
            tx.things.remove_objects([self.ids.pop(n) for n in gone])
        fresh = [o for o in mind.objects if o.name not in base.objects]
        if fresh:
            ids = tx.things.add_objects([self._row(o) for o in fresh], mind.now)
            self.ids.update(ids)
            tx.things.add_categories([(ids[o.name], c) for o in fresh for c in o.categories])
            tx.things.add_touches([(ids[o.name], self.agent_ids[a], t)
                            for o in fresh for a, t in o.last_touch.items()])
        for spec in mind.objects:
            old = base.objects.get(spec.name)
            if old is None or old == spec:
                continue
            oid = self.ids[spec.name]
            if (old.color, old.position) != (spec.color, spec.position):
                tx.things.set_percepts(oid, self._row(spec))
            if old.categories != spec.categories:
                tx.things.set_categories(oid, spec.categories)
            for agent, t in spec.last_touch.items():
                if old.last_touch.get(agent) != t:
                    tx.things.touch(oid, self.agent_ids[agent], t)

    @staticmethod
    def _row(spec: ObjectSpec) -> dict[str, Any]:
        x, y, z = spec.position if spec.position is not None else (None, None, None)
        return {"name": spec.name, "color": spec.color, "x": x, "y": y, "z": z}

    def _save_beliefs(self, tx: Tx, base: _Base, post: np.ndarray) -> None:
        """Write the claims, priors and posteriors that differ from the baseline (in bulk)."""
        mind, now = self.mind, self.mind.now
        n, m = mind.claims.shape
        rows = np.array([base.row.get(o.name, -1) for o in mind.objects], dtype=int)
        old_cols = {a: k for k, a in enumerate(base.agents)}
        cols = np.array([old_cols.get(a, -1) for a in mind.agents], dtype=int)
        known = (rows[:, None] >= 0) & (cols[None, :] >= 0)

        def old(table: np.ndarray, fill: Any) -> np.ndarray:
            out = np.full((n, m), fill, dtype=table.dtype)
            if table.size and known.any():
                picked = table[np.clip(rows, 0, None)][:, np.clip(cols, 0, None)]
                out[known] = picked[known]
            return out

        claim_changed = ~_same(mind.claims, old(base.claims, np.nan))
        prior_changed = ~_same(mind.predicted, old(base.prior, np.nan)) | (
            mind.prior_source != old(base.source, None))
        post_changed = ~_same(post, old(base.posterior, np.nan))
        if self.writable is not None:  # cells that were not loaded are not the Mind's to write
            claim_changed &= self.writable
            prior_changed &= self.writable
            post_changed &= self.writable
        for name, agent in {**base.claim_info, **mind.claim_info}:
            moved = mind.claim_info.get((name, agent)) != base.claim_info.get((name, agent))
            if moved and name in mind.index and agent in mind.agents:
                claim_changed[mind.index[name], mind.agents.index(agent)] = True
        out: list[dict[str, Any]] = []
        for i, j in np.argwhere(claim_changed | prior_changed | post_changed):
            name, agent = mind.objects[i].name, mind.agents[j]
            entry: dict[str, Any] = {"object_id": self.ids[name], "agent_id": self.agent_ids[agent]}
            if claim_changed[i, j]:
                c = mind.claims[i, j]
                meta = mind.claim_info.get((name, agent)) or ClaimInfo()
                held = not np.isnan(c)
                entry.update(claim_p=float(c) if held else None, claim_speaker=meta.speaker if held else None,
                             claim_trust=meta.trust if held else None, claim_time=meta.time if held else None)
            if prior_changed[i, j]:
                entry.update(prior_p=float(mind.predicted[i, j]), prior_source=str(mind.prior_source[i, j]),
                             prior_time=now)
            if post_changed[i, j]:
                held = not np.isnan(post[i, j])
                entry.update(posterior_p=float(post[i, j]) if held else None,
                             posterior_source="inference" if held else None,
                             posterior_time=now if held else None)
            out.append(entry)
        tx.beliefs.write_beliefs(out)

    def _save_permissions(self, tx: Tx, base: _Base) -> None:
        for action in ACTIONS:
            old, new = base.perms.get(action, {}), self.mind.perms[action]
            for name in old:
                if name not in new and name in self.ids:
                    tx.knowledge.delete_permission(action, self.ids[name])
            for name, given in new.items():
                if old.get(name) != given:
                    tx.knowledge.set_permission(action, self.ids[name], given.value, given.speaker,
                                                given.time, seq=given.seq, seen=seen_to_json(given.seen))


def _same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Elementwise: equal, or both NaN."""
    return np.asarray((a == b) | (np.isnan(a) & np.isnan(b)))


# -- loading ----------------------------------------------------------------------------------------
def load(tx: Tx, now: float, only: Sequence[str] | None = None, permitted: bool = False,
         agents: Sequence[str] | None = None) -> Stored:
    """The Mind of the store at time ``now``: every object (``only`` None), or the objects named in
    ``only`` plus, with ``permitted``, every object that carries a permission (a partial Mind).

    ``agents`` (with every object) loads only what refitting those agents' predictors needs: their
    touches and beliefs, and every belief about the objects that carry permissions (what inference
    reads); the Mind may then refit only their predictors (a claim about one agent).
    """
    refit, stored = agents, tx.meta.settings()
    known = tx.world.agents()
    agent_ids = {a.name: a.id for a in known}
    names = {a.id: a.name for a in known}
    ids: list[int] | None = None
    if only is not None:
        wanted = [tx.things.object(n).id for n in only]
        if permitted:
            wanted += [p.object_id for p in tx.knowledge.permission_table()]
        ids = sorted(set(wanted))
    focus = None if refit is None or only is not None else [agent_ids[a] for a in dict.fromkeys(refit)]
    rows = tx.things.object_table(ids)
    categories = tx.things.categories(ids)
    touches = tx.things.touch_times(ids, agent_ids=focus)
    specs = [spec_of(r, categories.get(r.id, set()), touches.get(r.id, {})) for r in rows]
    vocabulary = None
    if only is not None:
        colors, cats = tx.things.vocabulary()
        vocabulary = Vocabulary((), colors, (), cats)
    mind = Mind(tuple(names[a.id] for a in known), specs,
                [Area(a.name, (a.x0, a.y0, a.x1, a.y1)) for a in tx.world.areas()], to_config(stored),
                switches_of(stored), now=now, touch_times=True, complete=only is None, vocabulary=vocabulary,
                refit=None if focus is None else [names[a] for a in focus])
    index = {r.id: i for i, r in enumerate(rows)}
    column = {a.id: j for j, a in enumerate(known)}
    stored_post = np.full(mind.claims.shape, np.nan)
    prior = np.full(mind.claims.shape, np.nan)
    writable = None
    if focus is None:
        beliefs = tx.beliefs.belief_table(ids)
    else:
        carrying = sorted({p.object_id for p in tx.knowledge.permission_table()})
        seen_pairs = set()
        beliefs = []
        for b in [*tx.beliefs.belief_table(agent_ids=focus), *tx.beliefs.belief_table(carrying)]:
            if (b.object_id, b.agent_id) not in seen_pairs:
                seen_pairs.add((b.object_id, b.agent_id))
                beliefs.append(b)
        writable = np.zeros(mind.claims.shape, dtype=bool)
        writable[:, [column[a] for a in focus]] = True
        writable[[index[o] for o in carrying], :] = True
    if beliefs:
        bi = np.array([index[b.object_id] for b in beliefs], dtype=int)
        bj = np.array([column[b.agent_id] for b in beliefs], dtype=int)
        claim = np.array([b.claim_p for b in beliefs], dtype=float)
        mind.claims[bi, bj] = claim
        prior[bi, bj] = np.array([b.prior_p for b in beliefs], dtype=float)
        stored_post[bi, bj] = np.array([b.posterior_p for b in beliefs], dtype=float)
        has_prior = ~np.isnan(prior[bi, bj])
        mind.predicted[bi[has_prior], bj[has_prior]] = prior[bi[has_prior], bj[has_prior]]
        source = np.array([b.prior_source or "prediction" for b in beliefs], dtype=object)
        mind.prior_source[bi[has_prior], bj[has_prior]] = source[has_prior]
        for k in np.flatnonzero(~np.isnan(claim)):
            b = beliefs[k]
            mind.claim_info[(specs[bi[k]].name, names[b.agent_id])] = ClaimInfo(
                b.claim_speaker, 1.0 if b.claim_trust is None else b.claim_trust,
                0.0 if b.claim_time is None else b.claim_time)
    for p in tx.knowledge.permission_rows(ids):
        i = index[p.object_id]
        seq = p.seq if p.seq is not None else p.id
        seen = seen_from_json(specs[i].name, p.seen, specs[i])
        mind.restore_permission(p.action, i, Given(p.value, seq, seen, p.speaker, p.time))
    mind.reserve_ranks(tx.knowledge.max_permission_seq())
    for row in tx.knowledge.rules():
        mind.restore_rule(row.action, rule_of(row.text, row.origin),
                          RuleInfo(row.origin, dict(row.provenance or {})))
    out = Stored(mind, {r.name: r.id for r in rows}, agent_ids, writable)
    # compare with what the store really holds (NULL priors and posteriors are written on save)
    out.base.prior, out.base.posterior = prior, stored_post
    return out


@contextmanager
def changing(ctx: AppContext, payload: dict[str, Any], actor: str | None = None,
             only: Sequence[str] | None = None, permitted: bool = False,
             agents: Sequence[str] | None = None) -> Iterator[tuple[Tx, Mind]]:
    """One instruction as one write transaction: log it, load the Mind it needs (see :func:`load`),
    let the caller change it, save what changed. An error leaves the store as it was."""
    with ctx.write(payload, actor=actor) as tx:
        stored = load(tx, ctx.now, only, permitted, agents)
        yield tx, stored.mind
        stored.save(tx)
