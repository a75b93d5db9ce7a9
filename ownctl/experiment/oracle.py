"""The paper's simulated human instructor for task runs (reference 7.5), built on the ground truth.

On every attempt it gives the true permission of each of the action's object-targeted steps (when
the robot was right, this is the paper's "the predicted permission is added as an example"). On a
mistake (allowed though the true norms forbid, or refused though they allow) it also states the
true ownership (0 or 1) of every agent that an ``ownedBy`` literal of those steps' true rules
names (``any`` = every agent), then stops the action (allowed but forbidden) or forces it (refused
but allowed).
"""

from __future__ import annotations

from ownctl.experiment.task import Attempt, Verdict
from ownctl.experiment.truth import TrueNorms
from ownctl.mind import Mind
from ownctl.world.model import World


class OracleInstructor:
    """Corrects with true permissions and, on mistakes, true ownership claims.

    ``claims_first``: on a mistake, state ownership before the permissions, so the permissions are
    learned from with the corrected owners (the original code sent the permissions first).
    """

    def __init__(self, world: World, claims_first: bool = True) -> None:
        self.truth = TrueNorms(world)
        self.claims_first = claims_first

    def react(self, attempt: Attempt, mind: Mind) -> Verdict:
        """Teach ``mind`` about this attempt and say whether to stop or force it."""
        i = attempt.obj
        values = self.truth.forbidden(i, mind.objects[i], attempt.steps)
        violated = any(v >= 0.5 for v in values.values())
        mistake = attempt.allowed == violated
        if mistake and self.claims_first:
            self._claim(mind, attempt)
        for step in attempt.steps:
            mind.permit(step, i, values[step])
        if mistake and not self.claims_first:
            self._claim(mind, attempt)
        if not mistake:
            return Verdict()
        return Verdict("skip" if attempt.allowed else "force")

    def _claim(self, mind: Mind, attempt: Attempt) -> None:
        row = self.truth.owner_row(attempt.obj)
        for agent in self.truth.referenced_agents(attempt.steps):
            mind.claim(attempt.obj, agent, float(row[self.truth.world.agents.index(agent)]))
