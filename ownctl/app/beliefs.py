"""Ownership beliefs: which number decides, and the evaluation frame built from the store.

The one place where beliefs are resolved (DESIGN section 3):

- :func:`decision_belief` (what ``check``, ``owners`` and forbid decisions use): the posterior if
  set, else the claim, else the prior, else 0.0;
- :func:`induction_belief` (what rule induction sees): the claim, else the prior, else 0.0.

:func:`after_claims` is the hook where prediction (KLR) and rule-based Bayesian inference recompute
priors and posteriors (:mod:`ownctl.app.learning`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ownctl.logic.frame import Frame
from ownctl.world.model import Area, ObjectSpec, make_frame

if TYPE_CHECKING:
    from ownctl.store.models import Ownership
    from ownctl.store.repo import Tx

Belief = Callable[["Ownership"], tuple[float, str]]


def decision_belief(row: Ownership) -> tuple[float, str]:
    """(p, source) used for decisions: posterior, else claim, else prior, else (0.0, "none")."""
    if row.posterior_p is not None:
        return row.posterior_p, row.posterior_source or "posterior"
    if row.claim_p is not None:
        return row.claim_p, "claim"
    if row.prior_p is not None:
        return row.prior_p, row.prior_source or "prior"
    return 0.0, "none"


def induction_belief(row: Ownership) -> tuple[float, str]:
    """(p, source) that rule induction sees: claim, else prior, else (0.0, "none")."""
    if row.claim_p is not None:
        return row.claim_p, "claim"
    if row.prior_p is not None:
        return row.prior_p, row.prior_source or "prior"
    return 0.0, "none"


@dataclass(frozen=True)
class Snapshot:
    """The world as the store knows it, in core types; ``own[i, j]`` for objects[i], agents[j]."""

    agents: tuple[str, ...]
    objects: tuple[ObjectSpec, ...]
    areas: tuple[Area, ...]
    ids: tuple[int, ...]  # object ids, parallel to ``objects``
    own: np.ndarray  # (n, m)
    sources: tuple[tuple[str, ...], ...]  # sources[i][j] of own[i, j]

    def frame(self) -> Frame:
        """The evaluation frame of these objects under these beliefs."""
        return make_frame(self.objects, self.areas, self.agents, self.own)


def object_spec(row: Any, categories: set[str], touches: dict[str, float], now: float) -> ObjectSpec:
    """A stored object (ORM or plain row) as a core :class:`ObjectSpec`; touch times become ages."""
    position = None if row.x is None or row.y is None else (row.x, row.y, row.z if row.z is not None else 0.0)
    return ObjectSpec(
        name=row.name,
        color=row.color,
        position=position,
        categories=frozenset(categories),
        last_touch={a: max(0.0, now - t) for a, t in touches.items()},
    )


def snapshot(
    tx: Tx,
    now: float,
    belief: Belief = decision_belief,
    only: Sequence[str] | None = None,
    ids: Sequence[int] | None = None,
) -> Snapshot:
    """Load agents, areas, objects (all, those named in ``only``, or those with ``ids``) and beliefs.

    Reads plain rows (not ORM objects), so a snapshot of many objects stays cheap.
    """
    agents = tx.agents()
    if only is not None:
        ids = [tx.object(n).id for n in only]
    rows = tx.object_table(ids)
    categories = tx.categories(ids)
    touched = tx.touch_times(ids)
    column = {a.id: j for j, a in enumerate(agents)}
    index = {r.id: i for i, r in enumerate(rows)}
    own = np.zeros((len(rows), len(agents)))
    sources = [["none"] * len(agents) for _ in rows]
    for b in tx.belief_table(ids):
        i, j = index[b.object_id], column[b.agent_id]
        own[i, j], sources[i][j] = belief(b)
    return Snapshot(
        agents=tuple(a.name for a in agents),
        objects=tuple(object_spec(r, categories.get(r.id, set()), touched.get(r.id, {}), now) for r in rows),
        areas=tuple(Area(a.name, (a.x0, a.y0, a.x1, a.y1)) for a in tx.areas()),
        ids=tuple(r.id for r in rows),
        own=own,
        sources=tuple(tuple(s) for s in sources),
    )


def after_claims(tx: Tx, agents: Sequence[str], now: float) -> None:
    """Hook after claims about ``agents`` changed: re-predict priors, then re-infer posteriors.

    Honours the settings flags ``disabled.prediction`` and ``disabled.inference``.
    """
    from ownctl.app.learning import reinfer, repredict

    repredict(tx, agents, now)
    reinfer(tx, now, clear=False)  # priors changed, permissions did not
