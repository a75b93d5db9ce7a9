"""The robot's mind: the one place where prediction, induction and inference are put together.

A :class:`Mind` holds what a robot knows and believes about a world: its objects with their
current percepts, agents and areas; ownership claims, percept-based predictions (priors) and
rule-based posteriors; object-specific permissions, each with the percepts its object had when it
was given; given norms, allow norms and learned rules, each with where it came from; and the
switches that turn components off. Every instruction is a method (see ``docs/architecture.md``):

- :meth:`claim` -> the agent's predictor is refitted (lazily) -> posteriors follow;
- :meth:`permit` -> the conflict gate -> induction on the action's examples -> posteriors follow;
- :meth:`instruct` -> cover rule (forbid) or uncover rule (allow);
- :meth:`touch`, :meth:`set_percepts`, :meth:`add_objects`, :meth:`remove_object`,
  :meth:`add_agent`, :meth:`remove_agent`, :meth:`add_area`, :meth:`remove_area`,
  :meth:`remove_permission`, :meth:`remove_rule`, :meth:`reset`, :meth:`set_switch`.

Claims override predictions to give the prior; induction sees priors; decisions see posteriors;
inference never feeds prediction (the paper's anti-bias design). Experiments, task runs, scenarios
and every store-backed command drive this class; the store only loads and saves its state.

Times are absolute seconds on one clock (:attr:`Mind.now`, the store's clock): an object's
``last_touch`` maps agents to the time of their last interaction, and predictions use the age
``now - time``. A Mind may hold only some of a store's objects (``complete=False``, with the
store-wide vocabulary given): enough for instructions that read only those objects (a permission
reads the objects that carry permissions; a check reads one object); refitting a predictor needs
every object and is refused on a partial Mind.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ownctl.config import DECIDE_RULES, PredictConfig, Settings
from ownctl.errors import DuplicateName, OwnctlError, UnknownName
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import Norm, Rule
from ownctl.logic.vocab import ACTIONS
from ownctl.ownership.features import agent_features, percept_features, recency_feature
from ownctl.ownership.household import Household, claim_totals, household_prior
from ownctl.ownership.infer import posterior
from ownctl.ownership.predict import (
    KernelOwnershipModel,
    SharedRecency,
    borrows,
    calibrated_base_rate,
    fit_scales,
    fit_shared_recency,
    owns_some,
    pooled_scale,
)
from ownctl.ownership.silence import census, silence_weight
from ownctl.world.model import Area, ObjectSpec, Position, make_frame, positions

if TYPE_CHECKING:  # the learner is imported when a Mind first learns, not to decide one action
    from ownctl.learn.induce import Outcome
    from ownctl.learn.posterior import RulePosterior

#: A permission value at or above this forbids its step (also the learner's cover threshold).
PERMISSION_CUT = 0.5
#: The switch keys of :meth:`Mind.set_switch` and the attribute of :class:`Switches` each sets.
SWITCHES = {
    "frozen.perms": ("frozen_perms", True),
    "frozen.rules": ("frozen_rules", True),
    "disabled.inference": ("inference", False),
    "disabled.prediction": ("prediction", False),
}
RESETS = ("perms", "rules", "claims", "all")
ORIGINS = ("given", "learned", "allow")
BASE_RATE = "base-rate"
KEEP: Any = object()  # "leave this percept as it is" (set_percepts)


@dataclass(frozen=True)
class _Fit:
    """One agent's predictor fitted at every scale, with its feature rows and borrowed term."""

    models: list[KernelOwnershipModel]
    X: np.ndarray
    offset: np.ndarray | None


class WholeMindNeeded(RuntimeError):
    """A Mind that may refit only some agents' predictors (a partial load) met a change that moves
    what every predictor shares (the scale, :func:`ownctl.ownership.predict.pooled_scale`; the
    weight of silence, :func:`ownctl.ownership.silence.silence_weight`; the household's prior of
    the intercepts, :func:`ownctl.ownership.household.household_prior`) or gives an agent it did
    not load a silent row: the instruction must be carried out again on the whole Mind."""


@dataclass
class Switches:
    """The components that can be switched off (paper: disable inference / extrapolation, freeze)."""

    inference: bool = True
    prediction: bool = True
    frozen_perms: bool = False
    frozen_rules: bool = False


@dataclass(frozen=True)
class Given:
    """One object-specific permission: its value (1 forbid, 0 allow), its arrival rank, the
    object's percepts when it was given (``seen``; touch times absolute), who gave it and when."""

    value: float
    seq: int
    seen: ObjectSpec
    speaker: str | None = None
    time: float = 0.0


@dataclass(frozen=True)
class RuleInfo:
    """Where a rule came from: ``origin`` (given, learned or allow) and its provenance record."""

    origin: str
    provenance: Mapping[str, Any] = field(default_factory=dict)


def decide_mode(text: str) -> str:
    """``text`` if it names a decision mode of :data:`~ownctl.config.DECIDE_RULES` (how learned
    rules decide, :meth:`Mind.decide`); else the error listing them."""
    if text not in DECIDE_RULES:
        raise UnknownName("decision mode", text, DECIDE_RULES)
    return text


@dataclass(frozen=True)
class ClaimInfo:
    """Who made a claim, with what trust, when."""

    speaker: str | None = None
    trust: float = 1.0
    time: float = 0.0


@dataclass(frozen=True)
class NormResult:
    """What a given norm changed in its action's forbid rules; ``said``: the given rules that stand
    for a forbid norm (the norm itself, or what the stored permissions specialised it into; empty
    for an allow norm, and when the learner left the norm out)."""

    outcome: Outcome
    added: tuple[Rule, ...]
    removed: tuple[Rule, ...]
    said: tuple[Rule, ...] = ()


class _Percepts:
    """The objects' percepts as arrays, for prediction over every object without a Python loop per
    prediction: positions (n, 3; NaN unknown), colours, the palette and categories, and per agent
    the absolute times of its last touches (NaN: never), each built on first use."""

    def __init__(self, objects: Sequence[ObjectSpec]) -> None:
        self._objects = objects
        self.positions = positions(objects)
        self.colors: list[str | None] = [o.color for o in objects]
        self._touches: dict[str, np.ndarray] = {}
        self._palette: tuple[tuple[str, ...], tuple[str, ...]] | None = None
        self._shared: tuple[Any, np.ndarray] | None = None

    def shared_features(self, palette: Sequence[str | None], cfg: PredictConfig) -> np.ndarray:
        """The predictor features every agent shares (position, colour), kept until percepts change."""
        key = (tuple(palette), cfg)
        if self._shared is None or self._shared[0] != key:
            self._shared = (key, percept_features(self.positions, self.colors, palette, cfg))
        return self._shared[1]

    def palette(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The sorted distinct colours and categories of the objects."""
        if self._palette is None:
            colors = tuple(sorted({c for c in self.colors if c}))
            cats = tuple(sorted({c for o in self._objects for c in o.categories}))
            self._palette = (colors, cats)
        return self._palette

    def touch_times(self, agent: str) -> np.ndarray:
        """(n,) absolute time of ``agent``'s last touch of each object, NaN where it never touched.

        The first request reads every agent's touches in one pass over the objects (a claim refits
        one agent, loading a world every agent: one pass costs about what one agent's does)."""
        if not self._touches:
            self._touches = self._all_touches()
        if agent not in self._touches:  # touched nothing when the pass was made
            self._touches[agent] = np.array([o.last_touch.get(agent, np.nan) for o in self._objects],
                                            dtype=float)
        return self._touches[agent]

    def _all_touches(self) -> dict[str, np.ndarray]:
        rows: list[int] = []
        names: list[str] = []
        times: list[float] = []
        for i, o in enumerate(self._objects):
            if o.last_touch:
                rows.extend([i] * len(o.last_touch))
                names.extend(o.last_touch)
                times.extend(o.last_touch.values())
        agents = sorted(set(names))
        column = {a: j for j, a in enumerate(agents)}
        table = np.full((len(agents), len(self._objects)), np.nan)
        table[np.fromiter(map(column.__getitem__, names), dtype=np.intp, count=len(names)),
              np.asarray(rows, dtype=np.intp)] = times
        return {a: table[j] for j, a in enumerate(agents)}

    def touched(self, i: int, agent: str, time: float) -> None:
        """Object ``i`` was touched by ``agent`` at ``time``."""
        if agent in self._touches:
            self._touches[agent][i] = time

    def respecified(self, i: int, spec: ObjectSpec) -> None:
        """Object ``i`` has new percepts ``spec``."""
        self.positions[i] = positions([spec])[0]
        self.colors[i] = spec.color
        self._palette = None
        self._shared = None
        for agent, times in self._touches.items():
            times[i] = spec.last_touch.get(agent, np.nan)


def _names_rule(rule: Rule, pred: str, name: str) -> bool:
    return any(lit.atom == (pred, name) for lit in rule.literals)


class Mind:
    """Beliefs about ``objects`` owned by ``agents``; belief arrays are indexed (object, agent).

    ``objects``' ``last_touch`` values are ages at ``now`` (as world descriptions give them) unless
    ``touch_times`` is true, when they are absolute times. ``vocabulary`` fixes the colours and
    categories induction may use (the store-wide ones, for a partial Mind); by default they are
    those of the objects held. ``refit`` (default: every agent) names the agents whose predictors
    may be refitted: a Mind loaded for a claim holds only those agents' touches and beliefs, and
    the beliefs of the objects that carry permissions.
    """

    def __init__(
        self,
        agents: Sequence[str],
        objects: Sequence[ObjectSpec],
        areas: Sequence[Area],
        settings: Settings | None = None,
        switches: Switches | None = None,
        *,
        now: float = 0.0,
        touch_times: bool = False,
        complete: bool = True,
        vocabulary: Vocabulary | None = None,
        refit: Sequence[str] | None = None,
    ) -> None:
        self.settings = settings or Settings()
        self.switches = switches or Switches()
        self.now = float(now)
        self.complete = complete
        self.agents: tuple[str, ...] = tuple(agents)
        self.areas: list[Area] = list(areas)
        self.objects: list[ObjectSpec] = [
            o if touch_times else replace(o, last_touch={a: self.now - t for a, t in o.last_touch.items()})
            for o in objects
        ]
        self._fixed_vocab = vocabulary
        self._refit = None if refit is None else frozenset(refit)  # agents whose predictors may be refitted
        n, m = len(self.objects), len(self.agents)
        base = self._base_rate()
        self.claims = np.full((n, m), np.nan)
        self.claim_info: dict[tuple[str, str], ClaimInfo] = {}
        self.predicted = np.full((n, m), base)
        self.prior_source = np.full((n, m), BASE_RATE, dtype=object)
        self.perms: dict[str, dict[str, Given]] = {a: {} for a in ACTIONS}
        self.rules: dict[str, tuple[Rule, ...]] = {a: () for a in ACTIONS}
        self.allows: dict[str, list[Rule]] = {a: [] for a in ACTIONS}
        self.info: dict[str, dict[Rule, RuleInfo]] = {a: {} for a in ACTIONS}
        self._seq = 0
        self._rule_posteriors: dict[str, RulePosterior] = {}
        self.layout = 0  # advanced whenever the objects, agents or areas change (see belief_edits)
        self._edited: set[str] = set()  # agents whose belief columns may have changed
        self._respecified: set[str] = set()  # objects whose percepts changed (not added or removed)
        self._reindex()
        self._stale: set[str] = set()  # agents whose predictions must be refitted before use
        self._lending: dict[tuple[int, ...], SharedRecency | None] | None = None  # during refresh
        self._lenders: list[int] | None = None  # the lenders' columns, during refresh
        # the borrowed slope every borrower's predictions use (None: nobody borrows); see _follow_lenders
        self.lent: float | None = None
        # each agent's log evidence at each of settings.predict.scales, as of its last own refit,
        # and the index of the scale every predictor uses (pooled_scale of them); see _follow_scale
        self.scale_evidence: dict[str, tuple[float, ...]] = {}
        self.scale = 0
        self._rescore = False  # the agents changed: choose the scale again
        # what an agent's silence about an object others made claims about weighs (kappa of
        # ownctl/ownership/silence.py) as every predictor uses it, the objects examined (claimed by
        # some agent) as of the last refresh, and their rows during one; see _follow_silence
        self.silence = 0.0
        self._examined: frozenset[str] = frozenset()
        self._examined_rows: np.ndarray | None = None
        self._others: tuple[np.ndarray, float, float] | None = None  # a partial Mind: the others' census
        # the prior of every agent's intercept (ownctl/ownership/household.py), and for a partial
        # Mind the claims' per-agent totals of the agents it did not load; see _follow_household
        self.household = Household.configured(self.settings.predict)
        self._others_totals: tuple[np.ndarray, np.ndarray] | None = None
        self._posterior: np.ndarray | None = None
        self._inferred: tuple[list[int], np.ndarray] | None = None

    # -- structure ---------------------------------------------------------------------------
    def _reindex(self) -> None:
        self.index = {o.name: i for i, o in enumerate(self.objects)}
        self._frame: Frame | None = None
        self._percepts: _Percepts | None = None
        self.layout += 1
        self._changed()

    def percepts(self) -> _Percepts:
        """The objects' percepts as arrays (kept until the objects change; see :class:`_Percepts`)."""
        if self._percepts is None:
            self._percepts = _Percepts(self.objects)
        return self._percepts

    def belief_edits(self) -> tuple[int, frozenset[str], frozenset[str]]:
        """What may have changed since :meth:`forget_edits`: the layout (compare it), the agents whose
        claims, predictions or prior sources may differ, and the objects whose percepts were set.
        Every other belief cell and object is as it was (posteriors are not tracked)."""
        return self.layout, frozenset(self._edited), frozenset(self._respecified)

    def forget_edits(self) -> None:
        """Start tracking edits afresh (after the state was saved)."""
        self._edited.clear()
        self._respecified.clear()

    def _base_rate(self) -> float:
        return calibrated_base_rate(self.settings.predict)

    @property
    def vocab(self) -> Vocabulary:
        """The atoms induction may use: agents, colours, areas and categories."""
        if self._fixed_vocab is not None:
            colors, cats = self._fixed_vocab.colors, self._fixed_vocab.categories
        else:
            colors, cats = self.percepts().palette()
        return Vocabulary(self.agents, colors, tuple(a.name for a in self.areas), cats)

    def at(self, now: float) -> Mind:
        """Set the clock to ``now`` (the time of the next instruction); returns self."""
        self.now = float(now)
        return self

    def obj(self, ref: int | str) -> int:
        """The index of an object given by index or name (KeyError naming it if unknown)."""
        if isinstance(ref, str):
            if ref not in self.index:
                raise KeyError(ref)
            return self.index[ref]
        return int(ref)

    def _column(self, agent: str) -> int:
        if agent not in self.agents:
            raise KeyError(agent)
        return self.agents.index(agent)

    # -- beliefs -----------------------------------------------------------------------------
    @property
    def prior(self) -> np.ndarray:
        """Claims where they exist, else predictions (n, m)."""
        self.refresh()
        return np.where(np.isnan(self.claims), self.predicted, self.claims)

    def prior_rows(self, rows: Sequence[int]) -> np.ndarray:
        """The prior of the objects at ``rows`` only (len(rows), m): ``prior[rows]``, computed alone."""
        self.refresh()
        idx = np.asarray(rows, dtype=int)
        claims = self.claims[idx]
        out: np.ndarray = np.where(np.isnan(claims), self.predicted[idx], claims)
        return out

    def refresh(self) -> None:
        """Refit the predictors made stale by claims, touches or percepts (predictions are a pure
        function of the claims and the percepts, so computing them when first needed changes no
        result)."""
        self._lending = {}  # the lenders' recency fit, computed once for every borrower refitted here
        self._lenders = None
        try:
            if self._stale or self._rescore:
                self._follow_silence()
                self._follow_household()
            if self._stale:
                self._follow_lenders()
            fits = {a: self._fit(a) for a in sorted(self._stale) if a in self.agents}
            if fits or self._rescore:
                self._follow_scale(fits)
            for agent, fit in fits.items():
                self._predict(self.agents.index(agent), fit)
        finally:
            self._lending = None
            self._lenders = None
            self._examined_rows = None
        self._stale.clear()
        self._rescore = False

    def census(self) -> tuple[np.ndarray, float, float]:
        """Which objects some claim is about (n,), and the claims' total weight for "owns" and for
        "does not own", over every agent (:func:`ownctl.ownership.silence.census`; a partial Mind
        adds the store's count of the agents it did not load, :meth:`restore_silence`)."""
        if self._others is None or self._refit is None:
            return census(self.claims)
        cols = [j for j, a in enumerate(self.agents) if a in self._refit]
        mask, owned, not_owned = census(self.claims[:, cols])
        their_mask, their_owned, their_not = self._others
        return mask | their_mask, owned + their_owned, not_owned + their_not

    def restore_silence(self, kappa: float, others: tuple[np.ndarray, float, float] | None = None) -> None:
        """The weight of silence the stored priors use, and for a partial Mind the census of the
        claims of the agents it did not load (examined objects (n,), weight for "owns", for "does
        not own"): the state a store holds (ownctl/app/mindstore.py)."""
        self._others = others
        self.silence = float(kappa)
        mask, _, _ = self.census()
        self._examined = frozenset(self.objects[i].name for i in np.flatnonzero(mask))

    def _follow_silence(self) -> None:
        """Choose the weight of silence again from every agent's claims
        (:func:`~ownctl.ownership.silence.silence_weight`) and refit the predictors it moves: every
        agent's when it changes, else, while silence weighs, those of the agents silent about an
        object some claim is now about, or no longer (their silent rows changed). A partial Mind
        that did not load them raises :class:`WholeMindNeeded`."""
        if not self.switches.prediction:
            return
        mask, owned, not_owned = self.census()
        kappa = silence_weight(int(mask.sum()), len(self.agents), owned, not_owned, self.settings.predict)
        names = frozenset(self.objects[i].name for i in np.flatnonzero(mask))
        stale: set[str] = set()
        if kappa != self.silence:
            stale = set(self.agents)
        elif kappa > 0 and names != self._examined:
            changed = names ^ self._examined
            if any(n not in self.index for n in changed):
                stale = set(self.agents)
            else:
                rows = [self.index[n] for n in changed]
                stale = {a for j, a in enumerate(self.agents) if np.isnan(self.claims[rows, j]).any()}
        fresh = stale - self._stale
        if fresh and self._refit is not None and not fresh <= self._refit:
            raise WholeMindNeeded(f"silence now weighs {kappa:g} (was {self.silence:g}) or is about other "
                                  "objects: the agents' predictors are refitted")
        self._stale.update(fresh)
        self._edited.update(fresh)
        self.silence, self._examined, self._examined_rows = kappa, names, mask

    def totals(self) -> tuple[np.ndarray, np.ndarray]:
        """The claims' total weight for "owns" and their number, one entry per agent: the loaded
        agents' and, for a partial Mind, the store's for the others (:meth:`restore_household`)."""
        if self._others_totals is None or self._refit is None:
            return claim_totals(self.claims)
        cols = [j for j, a in enumerate(self.agents) if a in self._refit]
        owned, stated = claim_totals(self.claims[:, cols])
        their_owned, their_stated = self._others_totals
        return np.concatenate([owned, their_owned]), np.concatenate([stated, their_stated])

    def restore_household(self, household: Household,
                          others: tuple[np.ndarray, np.ndarray] | None = None) -> None:
        """The intercept's prior the stored priors use, and for a partial Mind the per-agent claim
        totals of the agents it did not load (weight for "owns", number): the state a store holds
        (ownctl/app/mindstore.py)."""
        self.household, self._others_totals = household, others

    def _follow_household(self) -> None:
        """Estimate the household's prior of every intercept again from every agent's claims
        (:func:`~ownctl.ownership.household.household_prior`, after the weight of silence); when it
        moves, every agent is refitted. A partial Mind that did not load them raises
        :class:`WholeMindNeeded`."""
        if not self.switches.prediction:
            return
        owned, stated = self.totals()
        household = household_prior(owned, stated, self.settings.predict, self.silence)
        if household == self.household:
            return
        fresh = set(self.agents) - self._stale
        if fresh and self._refit is not None and not fresh <= self._refit:
            raise WholeMindNeeded(f"the width of every agent's intercept prior moves to {household.spread:g} "
                                  f"(was {self.household.spread:g}): the agents' predictors are refitted")
        self._stale.update(fresh)
        self._edited.update(fresh)
        self.household = household

    def _follow_scale(self, fits: dict[str, _Fit | None]) -> None:
        """Take the refitted agents' evidence and choose the scale every predictor uses again
        (:func:`pooled_scale`); when it moves, every agent is refitted at the new one (the others
        keep the evidence of their last own refit, so the choice does not move again). A partial
        Mind raises :class:`WholeMindNeeded` instead."""
        cfg = self.settings.predict
        if not self.switches.prediction:
            return
        for agent, fit in fits.items():
            if fit is not None:
                self.scale_evidence[agent] = tuple(float(m.evidence_) for m in fit.models)
        none = (0.0,) * len(cfg.scales)
        chosen = pooled_scale((self.scale_evidence.get(a, none) for a in self.agents), cfg)
        if chosen == self.scale:
            return
        if self._refit is not None:
            raise WholeMindNeeded(f"the predictors' shared scale moves from {cfg.scales[self.scale]:g} "
                                  f"to {cfg.scales[chosen]:g}: every agent is refitted")
        self.scale = chosen
        for agent in self.agents:
            if agent not in fits:
                fits[agent] = self._fit(agent)
                self._edited.add(agent)

    def _follow_lenders(self) -> None:
        """When something changed, whether the borrowers' predictions must follow the lenders: the
        slope the lenders' claims teach (rounded, :func:`ownctl.ownership.predict.rounded`) is
        computed again, and when it is not the one the borrowers use (:attr:`lent`) every borrower
        is refitted. A partial Mind refits only agents that do not borrow
        (:func:`ownctl.app.mindstore.refit_focus`) and leaves :attr:`lent` as it is."""
        if self._refit is not None or not self.complete:
            return
        borrowers = self._borrowers()
        shared = self._lent(None) if borrowers else None
        current = None if shared is None else shared.slope
        if borrowers and current != self.lent:
            self._stale.update(borrowers)
            self._edited.update(borrowers)
        self.lent = current

    def refit_all(self) -> None:
        """Refit every agent's predictor when its priors are next needed (priors restored from a
        store that another version of the predictor wrote; needs every object)."""
        self._stale_agents(self.agents)

    def _stale_agents(self, agents: Iterable[str]) -> None:
        fresh = set(agents)
        self._edited.update(fresh)
        if fresh and self.switches.prediction:
            if not self.complete:
                raise RuntimeError("refitting a predictor needs every object; load the whole store")
            if self._refit is not None and not fresh <= self._refit:
                raise RuntimeError(f"the predictors of {sorted(fresh - self._refit)} were not loaded")
        self._stale.update(fresh)
        self._changed()

    def _claimed_agents(self) -> list[str]:
        """The agents whose predictors learn from something: a claim, or silence where it weighs."""
        if self.silence > 0 and self._examined:
            return list(self.agents)
        return [a for j, a in enumerate(self.agents) if not np.isnan(self.claims[:, j]).all()]

    def features(self, agent: str) -> tuple[np.ndarray, np.ndarray]:
        """The agent's predictor inputs: feature rows of every object and which objects carry a
        claim (docs/architecture.md, section 5); the last column is the recency feature."""
        j = self._column(agent)
        seen = self.percepts()
        times = seen.touch_times(agent)
        ages = np.maximum(0.0, self.now - times)  # NaN (never touched) stays NaN
        cfg = self.settings.predict
        X = agent_features(seen.positions, seen.colors, ages, self.vocab.colors, cfg,
                           shared=seen.shared_features(self.vocab.colors, cfg))
        return X, ~np.isnan(self.claims[:, j])

    def _borrowers(self) -> list[str]:
        """The agents whose predictors borrow recency from the others' claims: none when sharing is
        off or prediction is, else those no claim says own anything (:func:`borrows`)."""
        if not (self.switches.prediction and self.settings.predict.share_recency):
            return []
        lending = self._owning()
        return [a for k, a in enumerate(self.agents) if k not in lending]

    def _owning(self) -> list[int]:
        """The columns of the agents some claim says own something (the lenders, :func:`borrows`);
        kept during one refresh."""
        if self._lenders is not None:
            return self._lenders
        owning: list[int] = np.flatnonzero(owns_some(self.claims)).tolist()
        if self._lending is not None:
            self._lenders = owning
        return owning

    def _recency(self, agent: str, rows: np.ndarray | None = None) -> np.ndarray:
        """(n,) the agent's weighted standardised log-recency over every object (a predictor input),
        or (len(rows),) at ``rows`` only."""
        times = self.percepts().touch_times(agent)
        return recency_feature(np.maximum(0.0, self.now - times), self.settings.predict, rows)[:, 0]

    def borrowed_term(self, agent: str, own: np.ndarray,
                      recency: np.ndarray | None = None) -> np.ndarray | None:
        """(n,) the logit term the agent's predictor adds when its claims ``own`` borrow
        recency from the other agents' claims (ownctl/ownership/predict.py, "What other agents'
        claims teach"; docs/architecture.md, section 5); None when they do not borrow, when no
        other agent's claim says it owns something, or when the term is 0 everywhere (to 1e-9).
        ``recency``: the agent's recency feature (the last column of :meth:`features`), when the
        caller has it."""
        if not self.settings.predict.share_recency or not borrows(own):
            return None
        if self._refit is not None:
            raise RuntimeError(f"the predictor of {agent} borrows from every agent's claims; "
                               "load the whole store")
        shared = self._lent(agent)
        term = None if shared is None else shared.term(self._recency(agent) if recency is None else recency)
        # an agent whose touches do not vary (none at all) has nothing to borrow: its term is 0 up to rounding
        return term if term is not None and bool(np.any(np.abs(term) > 1e-9)) else None

    def _lent(self, besides: str | None) -> SharedRecency | None:
        """The recency fit of the claims of the *lenders*, the agents other than ``besides`` that
        some claim says own something (:func:`fit_shared_recency`); kept during one refresh."""
        lenders = [k for k in self._owning() if self.agents[k] != besides]
        key = tuple(lenders)
        if self._lending is not None and key in self._lending:
            return self._lending[key]
        recency, claims = [], []
        for k in lenders:
            known = ~np.isnan(self.claims[:, k])
            recency.append(self._recency(self.agents[k], np.flatnonzero(known)))
            claims.append(self.claims[known, k])
        shared = fit_shared_recency(np.concatenate(recency), np.concatenate(claims),
                                    self.settings.predict) if lenders else None
        if self._lending is not None:
            self._lending[key] = shared
        return shared

    def fit_inputs(self, agent: str, without: np.ndarray | None = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
        """What the agent's predictor learns from: the feature rows of every object (n, d), the
        rows it is fitted on (n,), their targets (the claims; NaN where the agent is silent about
        an object some claim is about, while silence weighs) and the borrowed term over every
        object (None: none). ``without`` (n,): objects the agent's rows leave out, claimed or
        silent, as objects nobody spoke of (the conformal scores, ownctl/mind/conformal.py, score
        claimed objects as the predictions they calibrate are made: of unclaimed objects)."""
        j = self._column(agent)
        X, known = self.features(agent)
        if without is not None:
            known = known & ~without
        offset = self.borrowed_term(agent, self.claims[known, j], X[:, -1])
        rows = known
        if self.silence > 0:  # the agent's silence about objects others made claims about
            rows = known | (self.census()[0] if self._examined_rows is None else self._examined_rows)
            if without is not None:
                rows = rows & ~without
        return X, rows, np.where(known, self.claims[:, j], np.nan)[rows], offset

    def _fit(self, agent: str) -> _Fit | None:
        """The agent's predictor fitted at every scale (None while prediction is off)."""
        if not self.switches.prediction:
            return None
        X, rows, targets, offset = self.fit_inputs(agent)
        models = fit_scales(X[rows], targets, None if offset is None else offset[rows], self.settings.predict,
                            self.silence, self.household)
        return _Fit(models, X, offset)

    def _predict(self, j: int, fit: _Fit | None) -> None:
        """Predict agent ``j``'s ownership of every object with its model at the chosen scale."""
        if fit is None:
            return
        model = fit.models[self.scale]
        self.predicted[:, j] = model.predict_proba(fit.X, fit.offset)
        self.prior_source[:, j] = model.source_

    def frame(self, own: np.ndarray | None = None) -> Frame:
        """The evaluation frame of all objects (current percepts) with ``own`` (default: posterior)."""
        if self._frame is None:
            n, m = len(self.objects), len(self.agents)
            self._frame = make_frame(self.objects, self.areas, self.agents, np.zeros((n, m)))
        return self._frame.with_own(self.posterior() if own is None else own)

    def frame_of(self, rows: Sequence[int]) -> Frame:
        """The evaluation frame of the objects at ``rows`` only, on their posteriors
        (``frame().take(rows)``, without computing every object's posterior)."""
        return make_frame([self.objects[i] for i in rows], self.areas, self.agents, self.posterior_rows(rows))

    def permitted(self) -> list[int]:
        """Indices of the objects that carry some permission, ascending."""
        return sorted({self.index[name] for given in self.perms.values() for name in given})

    def posterior(self) -> np.ndarray:
        """Rule-based posterior (n, m): the prior, conditioned on each object's permissions (each
        evaluated on the percepts its object had when it was given); the prior when inference is off."""
        if self._posterior is None:
            out = self.prior
            idx, rows = self.inferred()
            if idx:
                out[idx] = rows
            self._posterior = out
        return self._posterior

    def inferred(self) -> tuple[list[int], np.ndarray]:
        """The objects that carry permissions (ascending) and their posterior rows; only they differ
        from the prior (they are the prior too while inference is off)."""
        if self._inferred is None:
            idx = self.permitted()
            prior = self.prior_rows(idx)
            rows = prior
            if self.switches.inference and idx:
                where = {i: k for k, i in enumerate(idx)}
                values: dict[str, np.ndarray] = {}
                seen: dict[str, Frame] = {}
                for action, given in self.perms.items():
                    if not given:
                        continue
                    vec = np.full(len(idx), np.nan)
                    specs = [self.objects[i] for i in idx]
                    for name, g in given.items():
                        k = where[self.index[name]]
                        vec[k], specs[k] = g.value, g.seen
                    values[action] = vec
                    seen[action] = make_frame(specs, self.areas, self.agents, prior)
                current = make_frame([self.objects[i] for i in idx], self.areas, self.agents, prior)
                rows = posterior(current, self.rules, values, self.settings.infer.noise, seen)
            self._inferred = (idx, rows)
        return self._inferred

    def posterior_rows(self, rows: Sequence[int]) -> np.ndarray:
        """``posterior()[rows]``, computed for those objects only."""
        idx, inferred = self.inferred()
        where = {i: k for k, i in enumerate(idx)}
        out = self.prior_rows(rows)
        for r, i in enumerate(rows):
            if i in where:
                out[r] = inferred[where[i]]
        return out

    def _changed(self) -> None:
        self._posterior = None
        self._inferred = None
        self._rule_posteriors = {}

    def _keep_posteriors(self, action: str) -> dict[str, RulePosterior]:
        """The cached rule posteriors of every action but ``action``: an instruction about one
        action changes neither the priors nor another action's examples and rules, so theirs stay."""
        return {a: p for a, p in self._rule_posteriors.items() if a != action}

    def fork(self) -> Mind:
        """An independent copy to try instructions on (what-if questions, ``ownctl.mind.ask``):
        beliefs, permissions, rules and switches are copied, immutable parts and caches shared."""
        new = copy.copy(self)
        new.switches = replace(self.switches)
        new.objects, new.areas, new.index = list(self.objects), list(self.areas), dict(self.index)
        new.claims, new.predicted = self.claims.copy(), self.predicted.copy()
        new.prior_source = self.prior_source.copy()
        new.claim_info = dict(self.claim_info)
        new.perms = {a: dict(g) for a, g in self.perms.items()}
        new.rules = dict(self.rules)
        new.allows = {a: list(r) for a, r in self.allows.items()}
        new.info = {a: dict(i) for a, i in self.info.items()}
        new._rule_posteriors = dict(self._rule_posteriors)
        new._stale = set(self._stale)
        new._edited, new._respecified = set(self._edited), set(self._respecified)
        new.scale_evidence = dict(self.scale_evidence)
        return new

    def rule_posterior(self, action: str) -> RulePosterior:
        """The posterior over the action's rule sets given its permissions (prior ownership), around
        the current rules; the stated norms are in every set (:mod:`ownctl.learn.posterior`)."""
        if action not in self._rule_posteriors:
            from ownctl.learn.posterior import rule_posterior

            ev, _ = self.evidence(action)
            self._rule_posteriors[action] = rule_posterior(
                ev, action, self.vocab, self.settings.learn, self.rules[action], self.given(action),
                self.allows[action])
        return self._rule_posteriors[action]

    def rule_support(self, action: str, rule: Rule, obj: int | str | None = None) -> float:
        """How sure the posterior over rule sets is of what ``rule`` says: on the object ``obj``
        (posterior ownership), or on the action's examples (prior ownership). 1 with no examples."""
        ev, _ = self.evidence(action)
        if ev.n == 0:
            return 1.0
        frame = ev.frame if obj is None else self.frame_of([self.obj(obj)])
        return self.rule_posterior(action).support(rule, frame)

    def p_rules(self, action: str, obj: int | str) -> float:
        """P(the action's rules forbid it on the object), posterior ownership (:meth:`p_rules_on`)."""
        return float(self.p_rules_on(action, self.frame_of([self.obj(obj)]))[0])

    def p_rules_on(self, action: str, frame: Frame) -> np.ndarray:
        """P(the action's rules forbid it) for every object of ``frame``: on the learned rule set;
        once the action has permissions, with ``decide_rules = "posterior"`` marginalised over the
        posterior of rule sets, with ``"window"`` the mean over the near-best rule sets
        (:func:`ownctl.learn.posterior.window_p_forbidden`)."""
        if self._rules_alone(action):
            return p_forbidden(self.rules[action], frame)
        post = self.rule_posterior(action)
        if self.settings.decide_rules == "posterior":
            return post.p_forbidden(frame)
        from ownctl.learn.posterior import window_p_forbidden

        return window_p_forbidden(post, self.rules[action], frame, self.settings.decide_window)

    def _rules_alone(self, action: str) -> bool:
        """Whether the learned rule set alone decides the action (``map``, or no permissions yet)."""
        return self.settings.decide_rules == "map" or not self.perms[action]

    def deciding_sets(self, action: str) -> int | None:
        """How many rule sets the action's rule decisions rest on when that is not the learned set
        alone (``decide_rules`` other than ``map``, once the action has permissions), else None."""
        if self._rules_alone(action):
            return None
        post = self.rule_posterior(action)
        if self.settings.decide_rules == "posterior":
            return int((post.probabilities > 0).sum())
        from ownctl.learn.posterior import window_size

        return window_size(post, self.rules[action], self.settings.decide_window)

    # -- knowledge ---------------------------------------------------------------------------
    def given(self, action: str) -> list[Rule]:
        """The action's forbid rules that stand for what instructors said."""
        return [r for r in self.rules[action] if self.info[action][r].origin == "given"]

    def ordered(self, action: str) -> list[tuple[str, Given]]:
        """The action's permissions as (object name, permission), in arrival order."""
        return sorted(self.perms[action].items(), key=lambda kv: kv[1].seq)

    def evidence(self, action: str) -> tuple[Evidence, list[int]]:
        """The action's permissions (arrival order) as examples on prior ownership, and their objects.

        Each example keeps the percepts its object had when the permission was given: a permission
        describes the object where it was, not where the robot put it afterwards.
        """
        given = self.ordered(action)
        idx = [self.index[name] for name, _ in given]
        frame = make_frame([g.seen for _, g in given], self.areas, self.agents, self.prior_rows(idx))
        return Evidence(frame, [g.value for _, g in given]), idx

    def _set_rules(self, action: str, rules: Sequence[Rule], ev: Evidence, idx: Sequence[int],
                   said: Mapping[Rule, Mapping[str, Any]]) -> None:
        """Make ``rules`` the action's forbid rules. Rules kept keep their origin; rules in ``said``
        (what an instructor just stated, or its pieces) are given; other new rules are learned, with
        the forbidden examples they cover as provenance."""
        old = self.info[action]
        info: dict[Rule, RuleInfo] = {r: i for r, i in old.items() if i.origin == "allow"}
        unique = list(dict.fromkeys(rules))
        for rule in unique:
            if rule in said and (rule not in old or old[rule].origin != "given"):
                info[rule] = RuleInfo("given", dict(said[rule]))
            elif rule in old and old[rule].origin != "allow":
                info[rule] = old[rule]
            else:
                covered = ev.prob(ev.truth(rule)) >= PERMISSION_CUT
                names = [self.objects[i].name for i, c, pos in zip(idx, covered, ev.positives, strict=True)
                         if c and pos]
                info[rule] = RuleInfo("learned", {"examples": names, "learned_at": self.now})
        self.rules[action] = tuple(unique)
        self.info[action] = info
        self._changed()

    # -- instructions: ownership ---------------------------------------------------------------
    def claim(self, obj: int | str, agent: str, p: float = 1.0, *, negated: bool = False,
              exclusive: bool = False, speaker: str | None = None) -> float:
        """An ownership claim, weighted by trust (``1 - trust * p`` for "not mine"); an exclusive
        claim sets every other agent's claim to 0. Returns the stored probability."""
        i, j = self.obj(obj), self._column(agent)
        trust = self.settings.trust
        stored = 1.0 - trust * p if negated else trust * p
        name, meta = self.objects[i].name, ClaimInfo(speaker, trust, self.now)
        self.claims[i, j] = stored
        self.claim_info[(name, agent)] = meta
        changed = [agent]
        if exclusive:
            for k, other in enumerate(self.agents):
                if k != j:
                    self.claims[i, k] = 0.0
                    self.claim_info[(name, other)] = meta
                    changed.append(other)
        self._stale_agents(changed)
        return stored

    def touch(self, obj: int | str, agent: str, time: float) -> None:
        """``agent`` interacted with the object at absolute ``time`` (a percept of prediction)."""
        i = self.obj(obj)
        self._column(agent)
        spec = self.objects[i]
        self.objects[i] = replace(spec, last_touch={**spec.last_touch, agent: float(time)})
        self._respecified.add(spec.name)
        if self._percepts is not None:
            self._percepts.touched(i, agent, float(time))
        self._stale_agents([agent])

    def set_percepts(self, obj: int | str, *, color: Any = KEEP, position: Any = KEEP,
                     categories: Any = KEEP) -> None:
        """Change an object's percepts (KEEP leaves one as it is): areas and predictions follow."""
        i = self.obj(obj)
        spec = self.objects[i]
        if color is not KEEP:
            spec = replace(spec, color=color)
        if position is not KEEP:
            x, y, z = (float(v) for v in position) if position is not None else (0.0, 0.0, 0.0)
            spec = replace(spec, position=None if position is None else (x, y, z))
        if categories is not KEEP:
            spec = replace(spec, categories=frozenset(categories))
        if spec == self.objects[i]:
            return
        palette = self.vocab.colors
        self.objects[i] = spec
        self._respecified.add(spec.name)
        self._frame = None
        if self._percepts is not None:
            self._percepts.respecified(i, spec)
        stale = self.agents if self.vocab.colors != palette else self._claimed_agents()
        self._stale_agents(stale)  # also forgets what the old percepts implied

    def move(self, obj: int | str, position: Position | None) -> None:
        """The object is now at ``position``."""
        self.set_percepts(obj, position=position)

    # -- instructions: permissions and norms ---------------------------------------------------
    def permit(self, action: str, obj: int | str, value: float, speaker: str | None = None) -> Outcome | None:
        """An object-specific permission (1 forbid, 0 allow): store, gate, induce, re-infer.

        Ignored (None) while permissions are frozen; stored without induction while rules are.
        """
        return self.permit_all(action, [(obj, value)], speaker)

    def permit_all(self, action: str, given: Sequence[tuple[int | str, float]], speaker: str | None = None
                   ) -> Outcome | None:
        """Permissions for one action given together, as (object, value) in arrival order: stored,
        then learned from once (the outcome of the last induction; None if none ran).

        The default learner's rules depend only on the set of permissions (docs/learning.md), so
        learning once after the last is learning after each; the paper's learner depends on their
        order by design and learns after each, as :meth:`permit` does.
        """
        if self.switches.frozen_perms or not given:
            return None
        rows = [self.obj(obj) for obj, _ in given]  # every object known before anything is stored
        kept = self._keep_posteriors(action)
        once = self.settings.learn.learner == "ours"
        out: Outcome | None = None
        for i, (_, value) in zip(rows, given, strict=True):
            name = self.objects[i].name
            self.perms[action].pop(name, None)
            self._seq += 1
            self.perms[action][name] = Given(float(value), self._seq, self.objects[i], speaker, self.now)
            self._changed()
            self._rule_posteriors.update(kept)
            if not once:
                out = self._learn_permission(action, kept)
        return self._learn_permission(action, kept) if once else out

    def _learn_permission(self, action: str, kept: dict[str, RulePosterior]) -> Outcome | None:
        """Induce the action's rules after its newest permission (none while rules are frozen)."""
        if self.switches.frozen_rules:
            return None
        from ownctl.learn.induce import learn_permission

        ev, idx = self.evidence(action)
        out = learn_permission(action, self.rules[action], self.allows[action], ev, len(idx) - 1,
                               self.vocab, self.settings.learn, self.given(action))
        if out.induced and out.rules != self.rules[action]:
            self._set_rules(action, out.rules, ev, idx, {})
            self._rule_posteriors.update(kept)
        return out

    def instruct(self, norm: Norm, speaker: str | None = None) -> NormResult | None:
        """A one-shot norm: cover rule (forbid) or uncover rule (allow); None while rules are frozen.

        An allow norm is kept as a rule of origin ``allow`` and subtracted again after re-induction.
        """
        if self.switches.frozen_rules:
            return None
        action = norm.rule.action
        from ownctl.learn.induce import learn_norm

        kept = self._keep_posteriors(action)
        ev, idx = self.evidence(action)
        before, old_given = self.rules[action], self.given(action)
        out = learn_norm(norm, before, ev, self.vocab, self.settings.learn, self.allows[action], old_given,
                         self.frame())
        said: dict[Rule, dict[str, Any]] = {}
        for r in out.given:
            if r in old_given:
                continue
            if norm.sign == "allow":
                parent = next((g for g in old_given if g.conditions <= r.conditions), None)
                said[r] = {"given": parent.text() if parent else None, "minus": norm.text(),
                           "speaker": speaker}
            else:
                said[r] = {"given": norm.text(), "speaker": speaker, "specialised": r != norm.rule}
        self._set_rules(action, out.rules, ev, idx, said)
        if norm.sign == "allow" and norm.rule not in self.allows[action]:
            self.allows[action].append(norm.rule)
            self.info[action][norm.rule] = RuleInfo("allow", {"given": norm.text(), "speaker": speaker})
        self._rule_posteriors.update(kept)
        added = tuple(r for r in self.rules[action] if r not in before)
        removed = tuple(r for r in before if r not in self.rules[action])
        stands = () if norm.sign == "allow" else tuple(said) or tuple(
            r for r in out.given if r in (norm.rule, norm.rule.simplified()))
        return NormResult(out, added, removed, stands)

    def remove_permission(self, action: str, obj: int | str) -> None:
        """Forget one permission (the rules stay; posteriors follow)."""
        name = self.objects[self.obj(obj)].name
        if name not in self.perms[action]:
            raise KeyError(f"{action} on {name}")
        del self.perms[action][name]
        self._changed()

    def remove_rule(self, action: str, rule: Rule) -> None:
        """Forget one forbid or allow rule; refused while rules are frozen."""
        if self.switches.frozen_rules:
            raise OwnctlError("rules are frozen: rules are not changed (ownctl unfreeze rules)")
        if rule in self.allows[action]:
            self.allows[action].remove(rule)
        elif rule in self.rules[action]:
            self.rules[action] = tuple(r for r in self.rules[action] if r != rule)
        else:
            raise KeyError(rule.text())
        del self.info[action][rule]
        self._changed()

    def restore_permission(self, action: str, obj: int | str, given: Given) -> None:
        """Put back a permission known from before (a stored one): no gate, no induction."""
        self.perms[action][self.objects[self.obj(obj)].name] = given
        self._seq = max(self._seq, given.seq)
        self._changed()

    def restore_rule(self, action: str, rule: Rule, info: RuleInfo) -> None:
        """Put back a rule known from before, after the action's others (no induction)."""
        if info.origin not in ORIGINS:
            raise OwnctlError(f"unknown rule origin {info.origin!r}; valid: {', '.join(ORIGINS)}", ORIGINS)
        self.info[action][rule] = info
        if info.origin == "allow":
            self.allows[action].append(rule)
        else:
            self.rules[action] = (*self.rules[action], rule)
        self._changed()

    def reserve_ranks(self, top: int) -> None:
        """Let new permissions rank after ``top`` (permissions not held by a partial Mind)."""
        self._seq = max(self._seq, top)

    def all_rules(self, action: str) -> list[tuple[Rule, RuleInfo]]:
        """The action's forbid rules then its allow rules, each with where it came from."""
        return [(r, self.info[action][r]) for r in (*self.rules[action], *self.allows[action])]

    # -- instructions: the world -----------------------------------------------------------------
    def _grow(self, rows: int = 0, cols: int = 0) -> None:
        self.layout += 1
        base = self._base_rate()
        n, m = self.claims.shape
        if rows:
            self.claims = np.vstack([self.claims, np.full((rows, m), np.nan)])
            self.predicted = np.vstack([self.predicted, np.full((rows, m), base)])
            self.prior_source = np.vstack([self.prior_source, np.full((rows, m), BASE_RATE, dtype=object)])
        if cols:
            n = self.claims.shape[0]
            self.claims = np.hstack([self.claims, np.full((n, cols), np.nan)])
            self.predicted = np.hstack([self.predicted, np.full((n, cols), base)])
            self.prior_source = np.hstack([self.prior_source, np.full((n, cols), BASE_RATE, dtype=object)])

    def add_objects(self, specs: Sequence[ObjectSpec]) -> None:
        """New objects (``last_touch`` as absolute times); every agent's predictions cover them."""
        taken = set(self.index)
        for spec in specs:
            if spec.name in taken:
                raise DuplicateName(f"object {spec.name!r} already exists; choose another name")
            taken.add(spec.name)
        if not specs:
            return
        self.objects.extend(specs)
        self._grow(rows=len(specs))
        self._reindex()
        self._stale_agents(self.agents)

    def remove_object(self, obj: int | str) -> None:
        """Forget an object with its claims and permissions; predictions follow."""
        i = self.obj(obj)
        name = self.objects[i].name
        palette = self.vocab.colors
        had_claims = [a for j, a in enumerate(self.agents) if not np.isnan(self.claims[i, j])]
        del self.objects[i]
        self.claims = np.delete(self.claims, i, axis=0)
        self.predicted = np.delete(self.predicted, i, axis=0)
        self.prior_source = np.delete(self.prior_source, i, axis=0)
        self.claim_info = {k: v for k, v in self.claim_info.items() if k[0] != name}
        for given in self.perms.values():
            given.pop(name, None)
        self._reindex()
        stale = self.agents if self.vocab.colors != palette else had_claims
        self._stale_agents(stale)

    def add_agent(self, name: str) -> None:
        """A new possible owner, with the calibrated base rate as its prior everywhere."""
        if name in self.agents:
            raise DuplicateName(f"agent {name!r} already exists; choose another name")
        self.agents = (*self.agents, name)
        self._grow(cols=1)
        self._frame = None
        self._stale_agents([name])

    def _refuse_named(self, kind: str, pred: str, name: str) -> None:
        users = [r.text() for a in ACTIONS for r, _ in self.all_rules(a) if _names_rule(r, pred, name)]
        if users:
            raise OwnctlError(f"{kind} {name!r} is named by the rules {users}; remove them first "
                              "(ownctl rules remove ID)")

    def remove_agent(self, name: str) -> None:
        """Forget an agent and its beliefs; refused while a rule names it."""
        j = self._column(name)
        self._refuse_named("agent", "ownedBy", name)
        self.agents = tuple(a for a in self.agents if a != name)
        self.claims = np.delete(self.claims, j, axis=1)
        self.predicted = np.delete(self.predicted, j, axis=1)
        self.prior_source = np.delete(self.prior_source, j, axis=1)
        self.claim_info = {k: v for k, v in self.claim_info.items() if k[1] != name}
        self.objects = [replace(o, last_touch={a: t for a, t in o.last_touch.items() if a != name})
                        if name in o.last_touch else o for o in self.objects]
        self._edited.discard(name)
        self._stale.discard(name)
        self.scale_evidence.pop(name, None)
        self._rescore = True
        self._reindex()

    def add_area(self, area: Area) -> None:
        """A new named area (rules and examples see it at once)."""
        if any(a.name == area.name for a in self.areas):
            raise DuplicateName(f"area {area.name!r} already exists; choose another name")
        self.areas.append(area)
        self.areas.sort(key=lambda a: a.name)
        self._reindex()

    def remove_area(self, name: str) -> None:
        """Forget an area; refused while a rule names it."""
        if all(a.name != name for a in self.areas):
            raise KeyError(name)
        self._refuse_named("area", "inArea", name)
        self.areas = [a for a in self.areas if a.name != name]
        self._reindex()

    # -- instructions: administration ----------------------------------------------------------
    def reset(self, what: str) -> dict[str, int]:
        """Forget permissions, rules (forbid and allow), claims, or all three; returns the counts."""
        if what not in RESETS:
            raise OwnctlError(f"unknown reset {what!r}; valid: {', '.join(RESETS)}", RESETS)
        counts: dict[str, int] = {}
        if what in ("perms", "all"):
            counts["permissions"] = sum(len(g) for g in self.perms.values())
            self.perms = {a: {} for a in ACTIONS}
        if what in ("rules", "all"):
            counts["rules"] = sum(len(self.rules[a]) + len(self.allows[a]) for a in ACTIONS)
            self.rules = {a: () for a in ACTIONS}
            self.allows = {a: [] for a in ACTIONS}
            self.info = {a: {} for a in ACTIONS}
        if what in ("claims", "all"):
            counts["claims"] = int((~np.isnan(self.claims)).sum())
            self.claims[:] = np.nan
            self.claim_info.clear()
            self.predicted[:] = self._base_rate()
            self.prior_source[:] = BASE_RATE
            self._stale_agents(self.agents)
        self._changed()
        return counts

    def set_switch(self, key: str, on: bool) -> None:
        """freeze/unfreeze perms|rules, disable/enable inference|prediction (keys of SWITCHES)."""
        if key not in SWITCHES:
            raise OwnctlError(f"unknown switch {key!r}; valid: {', '.join(SWITCHES)}", tuple(SWITCHES))
        attr, when_on = SWITCHES[key]
        was = getattr(self.switches, attr)
        setattr(self.switches, attr, on if when_on else not on)
        if attr == "prediction" and self.switches.prediction and not was:
            self._stale_agents(self.agents)  # predictions catch up
        self._changed()

    # -- decisions ---------------------------------------------------------------------------
    def p_forbidden(self, action: str, own: np.ndarray | None = None) -> np.ndarray:
        """P(rules forbid ``action``) per object, on the posterior by default."""
        return p_forbidden(self.rules[action], self.frame(own))

    def permission(self, action: str, obj: int | str) -> Given | None:
        """The object's permission for ``action``, if any."""
        return self.perms[action].get(self.objects[self.obj(obj)].name)

    def forbidden(self, action: str, obj: int | str) -> bool:
        """The decision for one action step: the permission if any, else rules at the threshold."""
        i = self.obj(obj)
        given = self.permission(action, i)
        if given is not None:
            return bool(given.value >= PERMISSION_CUT)
        return bool(self.p_rules(action, i) >= self.settings.threshold_for(action))

    def decide(self, action: str, obj: int | str, steps: Sequence[str]) -> tuple[bool, list[str]]:
        """Is ``action`` forbidden on the object (any of ``steps`` forbidden), and which steps forbid."""
        bad = [s for s in steps if self.forbidden(s, obj)]
        return bool(bad), bad

