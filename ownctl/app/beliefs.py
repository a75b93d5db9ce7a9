"""Which stored number a reader sees, and where each belief comes from (``docs/architecture.md``).

- :func:`decision_belief` (what ``check``, ``owners`` and decisions use): the posterior if set,
  else the claim, else the prior (the prediction or the calibrated base rate);
- :func:`induction_belief` (what rule induction sees): the claim, else the prior;
- :func:`belief_sources`: the same labels for the beliefs a :class:`~ownctl.mind.Mind` holds.

These only read what :mod:`ownctl.app.mindstore` saved; the numbers themselves are computed by the
Mind.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ownctl.mind.core import BASE_RATE
from ownctl.ownership.predict import calibrated_base_rate

if TYPE_CHECKING:
    from ownctl.mind import Mind



def decision_belief(row: Any) -> tuple[float, str]:
    """(p, source) used for decisions: posterior, else claim, else prior."""
    if row.posterior_p is not None:
        return row.posterior_p, row.posterior_source or "inference"
    return induction_belief(row)


def induction_belief(row: Any) -> tuple[float, str]:
    """(p, source) that rule induction sees: claim, else prior (the base rate when none is stored)."""
    if row.claim_p is not None:
        return row.claim_p, "claim"
    if row.prior_p is not None:
        return row.prior_p, row.prior_source or "prediction"
    return calibrated_base_rate(), BASE_RATE  # a NULL prior (an older store) reads as the base rate


def belief_sources(mind: Mind, i: int) -> list[str]:
    """Where each agent's decision belief about object ``i`` comes from: ``inference`` (the object
    carries permissions and inference is on), else ``claim``, else the prior's source."""
    inferred = mind.switches.inference and any(mind.objects[i].name in g for g in mind.perms.values())
    out = []
    for j in range(len(mind.agents)):
        if inferred:
            out.append("inference")
        elif not np.isnan(mind.claims[i, j]):
            out.append("claim")
        else:
            out.append(str(mind.prior_source[i, j]))
    return out
