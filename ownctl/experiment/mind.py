"""A robot's beliefs in memory: claims, predicted priors, posteriors, permissions and rules.

:class:`Mind` composes the three learning components the way the paper integrates them: claims
override percept-based predictions to give the prior; rule induction sees priors; rule-based
inference turns priors and permissions into posteriors, which decisions use; inference never feeds
prediction. Experiments drive a Mind directly (no store), so trials are fast.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from ownctl.config import Settings
from ownctl.learn.evidence import Evidence, Vocabulary
from ownctl.learn.induce import Outcome, learn_norm, learn_permission
from ownctl.logic.frame import Frame
from ownctl.logic.prob import p_forbidden
from ownctl.logic.rules import Norm, Rule
from ownctl.logic.vocab import ACTIONS
from ownctl.ownership.features import agent_features
from ownctl.ownership.infer import posterior
from ownctl.ownership.predict import KernelOwnershipModel
from ownctl.world.model import Area, ObjectSpec, Position, make_frame, positions


@dataclass
class Switches:
    """The components experiments switch off (paper: disable inference / extrapolation, freeze)."""

    inference: bool = True
    prediction: bool = True
    frozen_perms: bool = False
    frozen_rules: bool = False


@dataclass
class Mind:
    """Beliefs about ``objects`` owned by ``agents``; every array is indexed (object, agent)."""

    agents: tuple[str, ...]
    objects: list[ObjectSpec]
    areas: Sequence[Area]
    settings: Settings = field(default_factory=Settings)
    switches: Switches = field(default_factory=Switches)

    def __post_init__(self) -> None:
        n, m = len(self.objects), len(self.agents)
        self.claims = np.full((n, m), np.nan)
        self.predicted = np.full((n, m), self.settings.predict.base_rate)
        self.perms: dict[str, np.ndarray] = {a: np.full(n, np.nan) for a in ACTIONS}
        self.order: dict[str, list[int]] = {a: [] for a in ACTIONS}  # arrival order of permissions
        self.rules: dict[str, tuple[Rule, ...]] = {a: () for a in ACTIONS}
        self.allows: dict[str, list[Rule]] = {a: [] for a in ACTIONS}
        self.given: dict[str, list[Rule]] = {a: [] for a in ACTIONS}
        self.index = {o.name: i for i, o in enumerate(self.objects)}
        self._base = make_frame(self.objects, self.areas, self.agents, np.zeros((n, m)))
        self._posterior: np.ndarray | None = None
        self._stale: set[int] = set()  # agents whose predictions must be refitted before use
        self._seen = self._base  # percepts as they were when each object's permissions were given
        self._permitted = np.zeros(n, dtype=bool)
        self.vocab = Vocabulary(
            self.agents,
            tuple(sorted({o.color for o in self.objects if o.color})),
            tuple(a.name for a in self.areas),
            tuple(sorted({c for o in self.objects for c in o.categories})),
        )

    # -- beliefs ----------------------------------------------------------------------------
    @property
    def prior(self) -> np.ndarray:
        """Claims where they exist, else predictions (n, m)."""
        self._refresh()
        return np.where(np.isnan(self.claims), self.predicted, self.claims)

    def _refresh(self) -> None:
        """Refit the predictors made stale by claims or moves (predictions are a pure function of
        the claims and the percepts, so computing them when first needed changes no result)."""
        for j in sorted(self._stale):
            self._predict(j)
        self._stale.clear()

    def frame(self, own: np.ndarray | None = None) -> Frame:
        """The evaluation frame of all objects with ``own`` (default: the posterior)."""
        return self._base.with_own(self.posterior() if own is None else own)

    def posterior(self) -> np.ndarray:
        """Rule-based posterior (n, m), or the prior when inference is off."""
        if self._posterior is None:
            prior = self.prior
            if not self.switches.inference:
                self._posterior = prior
            else:
                self._posterior = posterior(self._seen.with_own(prior), self.rules, self.perms,
                                            self.settings.infer.noise)
        return self._posterior

    def _changed(self) -> None:
        self._posterior = None

    # -- instructions -----------------------------------------------------------------------
    def claim(self, obj: int, agent: str, p: float = 1.0, exclusive: bool = False) -> None:
        """An ownership claim; refits that agent's predictor (if prediction is on)."""
        j = self.agents.index(agent)
        self.claims[obj, j] = p
        if exclusive:
            others = [k for k in range(len(self.agents)) if k != j]
            self.claims[obj, others] = 0.0
            self._stale.update(others)
        self._stale.add(j)
        self._changed()

    def move(self, obj: int, position: Position | None) -> None:
        """Object ``obj`` is now at ``position``: areas and percept-based predictions follow it."""
        self.objects[obj] = replace(self.objects[obj], position=position)
        n, m = len(self.objects), len(self.agents)
        self._base = make_frame(self.objects, self.areas, self.agents, np.zeros((n, m)))
        if not self._permitted[obj]:
            self._snapshot(obj)
        self._stale.update(j for j in range(m) if not np.isnan(self.claims[:, j]).all())
        self._changed()

    def _predict(self, j: int) -> None:
        if not self.switches.prediction:
            return
        cfg = self.settings.predict
        ages = np.array([o.last_touch.get(self.agents[j], np.nan) for o in self.objects])
        X = agent_features(positions(self.objects), [o.color for o in self.objects], ages,
                           self.vocab.colors, cfg)
        known = ~np.isnan(self.claims[:, j])
        model = KernelOwnershipModel(cfg).fit(X[known], self.claims[known, j])
        self.predicted[:, j] = model.predict_proba(X)

    def _snapshot(self, obj: int) -> None:
        """Remember object ``obj``'s current area membership as the state its permissions describe."""
        areas = {k: v.copy() for k, v in self._seen.areas.items()}
        for k, v in self._base.areas.items():
            areas[k][obj] = v[obj]
        self._seen = Frame(self._base.agents, self._base.own, self._base.colors, areas, self._base.categories)

    def evidence(self, action: str) -> tuple[Evidence, list[int]]:
        """The stored permissions of ``action`` (arrival order) evaluated on prior ownership.

        Each example keeps the percepts its object had when its permissions were last given: a
        permission describes the object where it was, not where the robot put it afterwards (the
        original system re-evaluated examples after moves, so ``inArea trash`` explained them).
        """
        idx = self.order[action]
        frame = self._seen.with_own(self.prior).take(idx)
        return Evidence(frame, self.perms[action][idx]), idx

    def remember(self, action: str, obj: int, value: float) -> None:
        """Restore a permission known from before (a stored one): no gate, no induction."""
        if obj not in self.order[action]:
            self.order[action].append(obj)
        self.perms[action][obj] = value
        self._permitted[obj] = True
        self._changed()

    def permit(self, action: str, obj: int, value: float) -> Outcome | None:
        """An object-specific permission (1 forbid, 0 allow): store, gate, induce, re-infer."""
        if self.switches.frozen_perms:
            return None
        if obj in self.order[action]:
            self.order[action].remove(obj)
        self.order[action].append(obj)
        self.perms[action][obj] = value
        self._permitted[obj] = True
        self._snapshot(obj)
        self._changed()
        if self.switches.frozen_rules:
            return None
        ev, idx = self.evidence(action)
        out = learn_permission(action, self.rules[action], self.allows[action], ev, len(idx) - 1,
                               self.vocab, self.settings.learn,
                               [r for r in self.given[action] if r in self.rules[action]])
        self.rules[action] = out.rules
        return out

    def instruct(self, norm: Norm) -> Outcome | None:
        """A one-shot norm: cover rule (forbid) or uncover rule (allow)."""
        if self.switches.frozen_rules:
            return None
        action = norm.rule.action
        ev, _ = self.evidence(action)
        out = learn_norm(norm, self.rules[action], ev, self.vocab, self.settings.learn,
                         self.allows[action], self.given[action])
        if norm.sign == "allow":
            self.allows[action].append(norm.rule)
        self.given[action] = list(out.given)
        self.rules[action] = out.rules
        self._changed()
        return out

    # -- decisions --------------------------------------------------------------------------
    def p_forbidden(self, action: str, own: np.ndarray | None = None) -> np.ndarray:
        """P(rules forbid ``action``) per object, on the posterior by default."""
        return p_forbidden(self.rules[action], self.frame(own))

    def forbidden(self, action: str, obj: int) -> bool:
        """The decision for one action step: the permission if any, else rules at the threshold."""
        value = self.perms[action][obj]
        if not np.isnan(value):
            return bool(value >= 0.5)
        thr = self.settings.threshold_for(action)
        return bool(p_forbidden(self.rules[action], self.frame().take([obj]))[0] >= thr)

    def decide(self, action: str, obj: int, steps: Sequence[str]) -> tuple[bool, list[str]]:
        """Is ``action`` forbidden on ``obj`` (any of ``steps`` forbidden), and which steps forbid."""
        bad = [s for s in steps if self.forbidden(s, obj)]
        return bool(bad), bad
