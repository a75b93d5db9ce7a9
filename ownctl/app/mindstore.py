"""Load the :class:`~ownctl.mind.Mind` an instruction needs from the store, and save what it changed.

Every instruction is load -> call -> save (``docs/architecture.md``): :func:`load` reads the
objects a use case needs (all of them; or only some, with the objects that carry permissions, when
nothing needs every object) with their beliefs, the permissions on them with their percept
snapshots, every rule and the switches; the Mind does the work; :meth:`Stored.save` compares the
Mind with what was loaded (or last saved) and writes only the differences, beliefs in bulk. Loading
what was saved gives the same Mind back, bit for bit, so a store behaves exactly like a Mind kept in
memory (tested).

Stored forms: an ownership row holds the claim (with speaker, trust, time) and the posterior (only
for objects that carry permissions while inference is on; elsewhere the prior stands), and exists
only where one of them is held; the priors (the prediction, with its source: ``prediction`` or
``base-rate``) are packed per agent in chunks of object ids (``ownctl/store/packed.py``). A
permission holds its arrival rank and the object's percepts when it was given. A rule row holds its
text, origin (given, learned, allow), provenance and rank. The setting ``predict.version`` names the
predictor that wrote the priors; a store another version wrote is loaded whole, every predictor is
refitted, and the next write stores the new priors and the version.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from ownctl.app.settings import to_config
from ownctl.config import PredictConfig
from ownctl.learn.evidence import Vocabulary
from ownctl.logic.rules import Rule, parse_norm, parse_rule
from ownctl.logic.vocab import ACTIONS
from ownctl.mind import SWITCHES, ClaimInfo, Given, Mind, RuleInfo, Switches, WholeMindNeeded
from ownctl.ownership.household import Household
from ownctl.ownership.predict import PREDICTOR_VERSION
from ownctl.world.model import Area, ObjectSpec

#: The store key of :attr:`Mind.lent`, the borrowed slope the borrowers' stored priors use (an internal
#: value, not a setting of ``ownctl config``).
LENT = "predict.lent"
#: The store key of the predictor version that wrote the stored priors (``PREDICTOR_VERSION``).
VERSION = "predict.version"
#: The store keys of :attr:`Mind.scale_evidence` (agent -> log evidence per scale) and
#: :attr:`Mind.scale` (the scale the stored priors use), internal values like ``LENT``.
EVIDENCE = "predict.evidence"
SCALE = "predict.scale"
#: :attr:`Mind.silence` (what silence weighs in the stored priors), an internal value like ``LENT``.
SILENCE = "predict.silence"
#: The width of :attr:`Mind.household` (the intercepts' prior the stored priors use; its centre is
#: the configured base rate; absent: the configured width), an internal value like ``LENT``.
HOUSEHOLD = "predict.household"

T = TypeVar("T")

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
    posterior: dict[str, np.ndarray]  # object name -> its stored posteriors (NaN: none stored)
    perms: dict[str, dict[str, Given]]
    rules: dict[str, list[tuple[str, str, Any]]]
    switches: dict[str, bool]
    lent: float | None  # the slope the borrowers' stored priors use (Mind.lent)
    evidence: dict[str, tuple[float, ...]]  # Mind.scale_evidence
    scale: int  # Mind.scale
    silence: float  # Mind.silence
    household: Household  # Mind.household
    layout: int  # the Mind's layout when this was taken (same layout: same objects and agents)
    version: int | None = PREDICTOR_VERSION  # the predictor that wrote the stored priors (None: another)


def _rules_state(mind: Mind) -> dict[str, list[tuple[str, str, Any]]]:
    return {a: [(rule_text(r, i.origin), i.origin, dict(i.provenance)) for r, i in mind.all_rules(a)]
            for a in ACTIONS}


def _stored_posterior(mind: Mind) -> dict[str, np.ndarray]:
    """The posteriors as stored: for objects with permissions while inference is on (by name)."""
    if not mind.switches.inference:
        return {}
    idx, rows = mind.inferred()
    return {mind.objects[i].name: rows[k] for k, i in enumerate(idx)}


def _posterior_array(post: dict[str, np.ndarray], row: dict[str, int], shape: tuple[int, int]) -> np.ndarray:
    """Stored posteriors by name as an array of ``shape`` (rows by ``row``; NaN where none)."""
    out = np.full(shape, np.nan)
    for name, values in post.items():
        if name in row:
            out[row[name]] = values
    return out


def _switch_values(mind: Mind) -> dict[str, bool]:
    return {k: getattr(mind.switches, attr) == when_on for k, (attr, when_on) in SWITCHES.items()}


@dataclass
class Stored:
    """A Mind loaded from the store, with the store ids of its objects and agents.

    After :meth:`save` the Mind equals what loading the store would give (``docs/architecture.md``,
    section 10), so a long-running process may keep a Stored between instructions while nobody
    else writes (:meth:`ownctl.app.context.AppContext.remember`).
    """

    mind: Mind
    ids: dict[str, int]  # object name -> id
    agent_ids: dict[str, int]
    writable: np.ndarray | None = None  # the belief cells that were loaded (None: all of them)
    base: _Base = field(init=False)
    _row_ids: tuple[int, np.ndarray] | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        self.base = self._snapshot()
        self.mind.forget_edits()

    def _snapshot(self, stored_posterior: dict[str, np.ndarray] | None = None) -> _Base:
        mind = self.mind
        post = _stored_posterior(mind) if stored_posterior is None else stored_posterior
        return _Base(
            agents=mind.agents, areas=tuple(mind.areas), objects={o.name: o for o in mind.objects},
            row=dict(mind.index), claims=mind.claims.copy(), claim_info=dict(mind.claim_info),
            prior=mind.predicted.copy(), source=mind.prior_source.copy(), posterior=post,
            perms={a: dict(g) for a, g in mind.perms.items()}, rules=_rules_state(mind),
            switches=_switch_values(mind), lent=mind.lent, evidence=dict(mind.scale_evidence),
            scale=mind.scale, silence=mind.silence, household=mind.household, layout=mind.layout,
        )

    def _follow(self, edited: frozenset[str], respecified: frozenset[str],
                post: dict[str, np.ndarray]) -> None:
        """Bring the baseline up to the Mind in place, where only ``edited`` agents' belief columns
        and ``respecified`` objects can differ (the layout is unchanged)."""
        mind, base = self.mind, self.base
        cols = [mind.agents.index(a) for a in sorted(edited) if a in mind.agents]
        base.claims[:, cols] = mind.claims[:, cols]
        base.prior[:, cols] = mind.predicted[:, cols]
        base.source[:, cols] = mind.prior_source[:, cols]
        for name in respecified:
            base.objects[name] = mind.objects[mind.index[name]]
        base.claim_info = dict(mind.claim_info)
        base.posterior = post
        base.perms = {a: dict(g) for a, g in mind.perms.items()}
        base.rules = _rules_state(mind)
        base.switches = _switch_values(mind)
        base.lent = mind.lent
        base.evidence = dict(mind.scale_evidence)
        base.scale = mind.scale
        base.silence = mind.silence
        base.household = mind.household
        base.areas = tuple(mind.areas)

    # -- saving ---------------------------------------------------------------------------------
    def save(self, tx: Tx) -> None:
        """Write what changed since the last load or save, then take the Mind as the new baseline.

        While the objects and agents are the same (the Mind's layout), only the belief columns of
        the agents the Mind reports edited, the objects whose percepts were set and the objects that
        carry permissions are compared; otherwise everything is."""
        mind, base = self.mind, self.base
        mind.refresh()
        now = mind.now
        layout, edited, respecified = mind.belief_edits()
        same = layout == base.layout and mind.agents == base.agents
        self._save_agents(tx, base)
        self._save_areas(tx, base)
        self._save_objects(tx, base, respecified if same else None)
        post = _stored_posterior(mind)
        self._save_beliefs(tx, base, post, edited if same else None)
        self._save_permissions(tx, base)
        rules = _rules_state(mind)
        for action in ACTIONS:
            if rules[action] != base.rules[action]:
                tx.knowledge.replace_rules(action, rules[action], now)
        for key, value in _switch_values(mind).items():
            if value != base.switches[key]:
                tx.meta.set_setting(key, value or None)
        if mind.lent != base.lent:
            tx.meta.set_setting(LENT, mind.lent)
        if mind.scale_evidence != base.evidence:
            tx.meta.set_setting(EVIDENCE, {a: list(v) for a, v in mind.scale_evidence.items()} or None)
        if mind.scale != base.scale:
            tx.meta.set_setting(SCALE, mind.scale or None)
        if mind.silence != base.silence:
            tx.meta.set_setting(SILENCE, mind.silence or None)
        if mind.household != base.household:
            configured = mind.household == Household.configured(mind.settings.predict)
            tx.meta.set_setting(HOUSEHOLD, None if configured else mind.household.spread)
        if base.version != PREDICTOR_VERSION:
            tx.meta.set_setting(VERSION, PREDICTOR_VERSION)
            base.version = PREDICTOR_VERSION
        if same:
            self._follow(edited, respecified, post)
        else:
            self.base = self._snapshot(post)
        mind.forget_edits()

    def _save_agents(self, tx: Tx, base: _Base) -> None:
        for name in base.agents:
            if name not in self.mind.agents:
                tx.world.remove_agent(tx.world.agent(name).id)
                del self.agent_ids[name]
        for name in self.mind.agents:
            if name not in base.agents:
                self.agent_ids[name] = tx.world.add_agent(name, self.mind.now).id

    def _save_areas(self, tx: Tx, base: _Base) -> None:
        now = {a.name: a for a in self.mind.areas}
        for area in base.areas:
            if area.name not in now:
                tx.world.remove_area(tx.world.area(area.name).id)
        for area in self.mind.areas:
            if area not in base.areas:
                tx.world.add_area(area.name, area.box)

    def _save_objects(self, tx: Tx, base: _Base, respecified: frozenset[str] | None) -> None:
        """Write added, removed and changed objects (only ``respecified`` ones can have changed,
        unless None); their beliefs are written after."""
        mind = self.mind
        if respecified is None:
            current = {o.name for o in mind.objects}
            gone = [n for n in base.objects if n not in current]
            if gone:
                tx.things.remove_objects([self.ids.pop(n) for n in gone])
            added = [o for o in mind.objects if o.name not in base.objects]
            changed = mind.objects
        else:
            added, changed = [], [mind.objects[mind.index[n]] for n in sorted(respecified)]
        if added:
            ids = tx.things.add_objects([self._row(o) for o in added], mind.now)
            self.ids.update(ids)
            tx.things.add_categories([(ids[o.name], c) for o in added for c in o.categories])
            objects: list[int] = []
            agents: list[int] = []
            times: list[float] = []
            for o in added:
                if o.last_touch:
                    objects.extend([ids[o.name]] * len(o.last_touch))
                    agents.extend(map(self.agent_ids.__getitem__, o.last_touch))
                    times.extend(o.last_touch.values())
            tx.touches.add(objects, agents, times)
        for spec in changed:
            old = base.objects.get(spec.name)
            if old is None or old is spec or old == spec:
                continue
            oid = self.ids[spec.name]
            if (old.color, old.position) != (spec.color, spec.position):
                tx.things.set_percepts(oid, self._row(spec))
            if old.categories != spec.categories:
                tx.things.set_categories(oid, spec.categories)
            for agent, t in spec.last_touch.items():
                if old.last_touch.get(agent) != t:
                    tx.touches.touch(oid, self.agent_ids[agent], t)

    @staticmethod
    def _row(spec: ObjectSpec) -> dict[str, Any]:
        x, y, z = spec.position if spec.position is not None else (None, None, None)
        return {"name": spec.name, "color": spec.color, "x": x, "y": y, "z": z}

    def _ids_of_rows(self) -> np.ndarray:
        """The store id of each of the Mind's objects, by row (kept while the layout is the same)."""
        mind = self.mind
        if self._row_ids is None or self._row_ids[0] != mind.layout:
            self._row_ids = (mind.layout, np.array([self.ids[o.name] for o in mind.objects], dtype=np.int64))
        return self._row_ids[1]

    def _changed_cells(self, base: _Base, post: dict[str, np.ndarray],
                       edited: frozenset[str] | None) -> dict[str, np.ndarray]:
        """kind -> the flat indices (row * m + column) of the cells whose belief of that kind differs
        from the baseline; ``edited`` (same layout) names the only agents whose claims and priors
        can differ, None compares everything."""
        mind = self.mind
        n, m = mind.claims.shape
        if edited is None:
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

            claim = ~_same(mind.claims, old(base.claims, np.nan))
            prior = ~_same(mind.predicted, old(base.prior, np.nan))
            prior |= mind.prior_source != old(base.source, None)
            base_post = _posterior_array(base.posterior, base.row, (len(base.row), len(base.agents)))
            now_post = _posterior_array(post, mind.index, (n, m))
            posterior = ~_same(now_post, old(base_post, np.nan))
            if self.writable is not None:  # cells that were not loaded are not the Mind's to write
                claim &= self.writable
                prior &= self.writable
                posterior &= self.writable
            cells = {"claim": np.flatnonzero(claim), "prior": np.flatnonzero(prior),
                     "posterior": np.flatnonzero(posterior)}
        else:
            parts: dict[str, list[np.ndarray]] = {"claim": [], "prior": [], "posterior": []}
            for agent in sorted(edited):
                if agent not in mind.agents:
                    continue
                j = mind.agents.index(agent)
                claim = ~_same(mind.claims[:, j], base.claims[:, j])
                prior = ~_same(mind.predicted[:, j], base.prior[:, j])
                prior |= mind.prior_source[:, j] != base.source[:, j]
                if self.writable is not None:
                    claim &= self.writable[:, j]
                    prior &= self.writable[:, j]
                parts["claim"].append(np.flatnonzero(claim) * m + j)
                parts["prior"].append(np.flatnonzero(prior) * m + j)
            nothing = np.full(m, np.nan)
            for name in sorted(set(base.posterior) | set(post)):
                i = mind.index[name]
                differs = ~_same(post.get(name, nothing), base.posterior.get(name, nothing))
                if self.writable is not None:
                    differs &= self.writable[i]
                parts["posterior"].append(i * m + np.flatnonzero(differs))
            # distinct already: each part is one column's cells, or one object's
            cells = {k: np.concatenate(v) if v else np.zeros(0, dtype=int) for k, v in parts.items()}
        moved = [mind.index[name] * m + mind.agents.index(agent)
                 for name, agent in {**base.claim_info, **mind.claim_info}
                 if mind.claim_info.get((name, agent)) != base.claim_info.get((name, agent))
                 and name in mind.index and agent in mind.agents]
        if moved:
            cells["claim"] = _distinct(np.concatenate((cells["claim"], np.array(moved, dtype=int))))
        return cells

    def _save_beliefs(self, tx: Tx, base: _Base, post: dict[str, np.ndarray],
                      edited: frozenset[str] | None) -> None:
        """Write the claims, priors and posteriors that differ from the baseline, in bulk: priors
        chunk by chunk, claims and posteriors with one upsert per set of columns."""
        mind = self.mind
        m = len(mind.agents)
        cells = self._changed_cells(base, post, edited)
        row_ids = self._ids_of_rows()
        agent_ids = np.array([self.agent_ids[a] for a in mind.agents], dtype=np.int64)
        pick = cells["prior"]
        if len(pick):
            i, j = pick // m, pick % m
            tx.beliefs.write_priors(row_ids[i], agent_ids[j], mind.predicted[i, j], mind.prior_source[i, j],
                                    mind.now)
        every = _distinct(np.concatenate((cells["claim"], cells["posterior"])))  # which kinds changed: bits
        code = _within(every, cells["claim"]).astype(np.int8) | (_within(every, cells["posterior"]) * 2)
        for c in sorted(set(code.tolist())):
            pick = every[code == c]
            kinds = [k for b, k in enumerate(("claim", "posterior")) if c >> b & 1]
            i, j = pick // m, pick % m
            tx.beliefs.update_beliefs(row_ids[i].tolist(), agent_ids[j].tolist(),
                                      self._cell_values(kinds, i, j, post))

    def _cell_values(self, kinds: list[str], i: np.ndarray, j: np.ndarray,
                     post: dict[str, np.ndarray]) -> dict[str, list[Any]]:
        """column -> stored value for each cell (i[k], j[k]), for the columns of ``kinds`` (claim,
        posterior; priors are written chunk by chunk)."""
        mind, now = self.mind, self.mind.now
        count = len(i)
        values: dict[str, list[Any]] = {}
        if "claim" in kinds:
            claim = mind.claims[i, j]
            p_of: list[Any] = [None] * count
            speaker: list[Any] = [None] * count
            trust: list[Any] = [None] * count
            time: list[Any] = [None] * count
            for k in np.flatnonzero(~np.isnan(claim)).tolist():  # only the cells that hold a claim
                a, b = int(i[k]), int(j[k])
                meta = mind.claim_info.get((mind.objects[a].name, mind.agents[b])) or ClaimInfo()
                p_of[k], speaker[k], trust[k], time[k] = float(claim[k]), meta.speaker, meta.trust, meta.time
            values.update(claim_p=p_of, claim_speaker=speaker, claim_trust=trust, claim_time=time)
        if "posterior" in kinds:
            held: list[Any] = [None] * count
            stamp: list[Any] = [None] * count
            source: list[Any] = [None] * count
            by_row = {mind.index[name]: row for name, row in post.items()}
            with_post = _within(i, np.array(sorted(by_row), dtype=int))
            for k in np.flatnonzero(with_post).tolist():  # only objects with posteriors
                p = by_row[int(i[k])][int(j[k])]
                if not np.isnan(p):
                    held[k], source[k], stamp[k] = float(p), "inference", now
            values.update(posterior_p=held, posterior_source=source, posterior_time=stamp)
        return values

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


def _distinct(values: np.ndarray) -> np.ndarray:
    """The sorted distinct values of an integer array (as ``np.unique``, which imports numpy.ma:
    about 15 ms at the start of every claim)."""
    a = np.sort(np.asarray(values).ravel())
    return a[np.concatenate(([True], a[1:] != a[:-1]))] if a.size else a


def _within(values: np.ndarray, members: np.ndarray) -> np.ndarray:
    """Elementwise: is the value one of ``members`` (as ``np.isin``, without numpy.ma)."""
    held = _distinct(members)
    if not held.size:
        return np.zeros(len(values), dtype=bool)
    at = np.minimum(np.searchsorted(held, values), len(held) - 1)
    return np.asarray(held[at] == values)


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
    stored = tx.meta.settings()
    outdated = str(stored.get(VERSION)) != str(PREDICTOR_VERSION)
    if outdated:  # priors another predictor wrote: every agent is refitted, which needs every object
        only, permitted, agents = None, False, None
    refit = agents
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
    touches = tx.touches.times(ids, agent_ids=focus)
    specs = [spec_of(r, categories.get(r.id, set()), touches.get(r.id, {})) for r in rows]
    vocabulary = None
    if only is not None:
        colors, cats = tx.things.vocabulary()
        vocabulary = Vocabulary((), colors, (), cats)
    mind = Mind(tuple(names[a.id] for a in known), specs,
                [Area(a.name, (a.x0, a.y0, a.x1, a.y1)) for a in tx.world.areas()], to_config(stored),
                switches_of(stored), now=now, touch_times=True, complete=only is None, vocabulary=vocabulary,
                refit=None if focus is None else [names[a] for a in focus])
    lent = stored.get(LENT)
    mind.lent = None if lent is None else float(lent)
    evidence = stored.get(EVIDENCE) or {}
    mind.scale_evidence = {a: tuple(float(x) for x in v) for a, v in evidence.items() if a in mind.agents}
    mind.scale = stored_scale(stored)
    index = {r.id: i for i, r in enumerate(rows)}
    others = others_totals = None
    if focus is not None:  # the claims of the agents not loaded, as silence and the household need them
        mask = np.zeros(len(rows), dtype=bool)
        mask[[index[o] for o in tx.beliefs.claimed_objects(focus)]] = True
        totals = tx.beliefs.claim_totals(focus)
        owned = np.array([t[0] for t in totals], dtype=float)
        stated = np.array([t[1] for t in totals], dtype=float)
        others = (mask, float(owned.sum()), float((stated - owned).sum()))
        others_totals = (owned, stated)
    column = {a.id: j for j, a in enumerate(known)}
    stored_post = np.full(mind.claims.shape, np.nan)
    prior = np.full(mind.claims.shape, np.nan)
    source = np.full(mind.claims.shape, None, dtype=object)
    object_ids = [r.id for r in rows]
    writable = None
    if focus is None:
        beliefs = tx.beliefs.held(ids)
        priors = tx.beliefs.priors(object_ids, [a.id for a in known])
        prior[:], source[:] = priors.p, priors.source
    else:
        carrying = sorted({p.object_id for p in tx.knowledge.permission_table()})
        seen_pairs = set()
        beliefs = []
        for b in [*tx.beliefs.held(agent_ids=focus), *tx.beliefs.held(carrying)]:
            if (b.object_id, b.agent_id) not in seen_pairs:
                seen_pairs.add((b.object_id, b.agent_id))
                beliefs.append(b)
        cols = [column[a] for a in focus]
        some = tx.beliefs.priors(object_ids, focus)
        prior[:, cols], source[:, cols] = some.p, some.source
        at = [index[o] for o in carrying]
        some = tx.beliefs.priors(carrying, [a.id for a in known])
        prior[at], source[at] = some.p, some.source
        writable = np.zeros(mind.claims.shape, dtype=bool)
        writable[:, cols] = True
        writable[at, :] = True
    has_prior = ~np.isnan(prior)
    mind.predicted[has_prior] = prior[has_prior]
    mind.prior_source[has_prior] = source[has_prior]
    if beliefs:
        bi = np.array([index[b.object_id] for b in beliefs], dtype=int)
        bj = np.array([column[b.agent_id] for b in beliefs], dtype=int)
        claim = np.array([np.nan if b.claim_p is None else b.claim_p for b in beliefs], dtype=float)
        mind.claims[bi, bj] = claim
        stored_post[bi, bj] = np.array([np.nan if b.posterior_p is None else b.posterior_p for b in beliefs],
                                       dtype=float)
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
    mind.restore_silence(stored_silence(stored), others)
    mind.restore_household(stored_household(stored, mind.settings.predict), others_totals)
    out = Stored(mind, {r.name: r.id for r in rows}, agent_ids, writable)
    # compare with what the store really holds (NULL priors and posteriors are written on save)
    held = np.flatnonzero(~np.isnan(stored_post).all(axis=1))
    out.base.prior = prior
    out.base.posterior = {specs[i].name: stored_post[i] for i in held.tolist()}
    if outdated:
        mind.refit_all()
        out.base.version = None
    return out


def stored_scale(settings: dict[str, Any]) -> int:
    """The index into ``PredictConfig.scales`` of the scale the stored priors use (:attr:`Mind.scale`),
    from the store's settings."""
    return int(settings.get(SCALE) or 0)


def stored_silence(settings: dict[str, Any]) -> float:
    """What an agent's silence weighs in the stored priors (:attr:`Mind.silence`), from the
    store's settings."""
    return float(settings.get(SILENCE) or 0.0)


def stored_household(settings: dict[str, Any], cfg: PredictConfig) -> Household:
    """The prior of every agent's intercept the stored priors use (:attr:`Mind.household`), from
    the store's settings: the configured one, ``cfg``, with the stored width if any."""
    configured = Household.configured(cfg)
    value = settings.get(HOUSEHOLD)
    return configured if value is None else Household(configured.mean, float(value))


def refit_focus(tx: Tx, obj: str, agents: Sequence[str]) -> list[str] | None:
    """The agents whose predictors a claim or touch about ``obj`` by ``agents`` may refit, for a
    partial load (:func:`load`), or None (load every agent) when an agent's predictor borrows from
    the others' claims or may start to (ownctl/ownership/predict.py, "What other agents' claims
    teach"): while some agent has no claim that it owns an object other than ``obj``, and while
    silence weighs and no claim is about ``obj`` yet (every agent silent about it may learn from a
    first one; ownctl/ownership/silence.py). (Stores always share recency: the core's
    ``PredictConfig.share_recency`` has no store setting.)"""
    besides = tx.things.object(obj).id
    if stored_silence(tx.meta.settings()) > 0 and \
            all(b.claim_p is None for b in tx.beliefs.held([besides])):
        return None  # a first claim about the object: every silent agent's predictor learns of it
    owning = tx.beliefs.agents_owning(besides)
    if all(a.id in owning for a in tx.world.agents()):
        return list(agents)
    return None


@contextmanager
def changing(ctx: AppContext, payload: dict[str, Any], actor: str | None = None,
             only: Sequence[str] | None = None, permitted: bool = False,
             agents: Sequence[str] | None = None) -> Iterator[tuple[Tx, Mind]]:
    """One instruction as one write transaction: log it, load the Mind it needs (see :func:`load`;
    a caching context uses its kept whole Mind while it is the store's), let the caller change it,
    save what changed. An error leaves the store as it was."""
    with ctx.write(payload, actor=actor, through_mind=True) as tx:
        if ctx.cache and only:
            for name in only:  # unknown names are the errors a partial load raises
                tx.things.object(name)
        stored = ctx.kept(tx)
        if stored is None:
            stored = load(tx, ctx.now) if ctx.cache else load(tx, ctx.now, only, permitted, agents)
        stored.mind.at(ctx.now)
        yield tx, stored.mind
        stored.save(tx)
        ctx.remember(tx, stored)


def refitting(ctx: AppContext, payload: dict[str, Any], change: Callable[[Tx, Mind], T],
               actor: str | None = None, agents: Sequence[str] | None = None) -> T:
    """:func:`changing` for an instruction that refits only ``agents``' predictors (see
    :func:`refit_focus`; None: every agent), running ``change`` in it and returning what it
    returns. When the change moves what every predictor shares, the scale or the weight of silence,
    or gives an agent not loaded a silent row (:class:`ownctl.mind.core.WholeMindNeeded`), nothing
    was written and it runs again on the whole Mind, as a Mind kept in memory would refit them."""
    if agents is not None:
        try:
            with changing(ctx, payload, actor=actor, agents=agents) as (tx, mind):
                out = change(tx, mind)
            return out
        except WholeMindNeeded:
            pass
    with changing(ctx, payload, actor=actor) as (tx, mind):
        out = change(tx, mind)
    return out


def reading(ctx: AppContext, tx: Tx, only: Sequence[str] | None = None, permitted: bool = False) -> Mind:
    """The Mind a query reads (see :func:`load`): the kept whole Mind of a caching context while it
    is still the store's (loaded and kept when it is not), else the partial Mind asked for. The
    caller must not change it."""
    if not ctx.cache:
        return load(tx, ctx.now, only, permitted).mind
    stored = ctx.kept(tx)
    if stored is None:
        stored = load(tx, ctx.now)
        ctx.remember(tx, stored)
    return stored.mind.at(ctx.now)
