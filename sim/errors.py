"""Why a simulated world or step failed.

A world that cannot be laid out, or rendered, is a user error (:class:`~ownctl.errors.OwnctlError`,
exit code 1); a failed step is a :class:`~ownctl.errors.ScenarioFailed` (exit code 4 in the CLI).
"""

from __future__ import annotations

from ownctl.errors import OwnctlError, ScenarioFailed


class LayoutError(OwnctlError):
    """The blocks do not fit on the reachable table (no valid spot near a block's mapped position)."""


class SimStepFailed(ScenarioFailed):
    """A scripted skill could not be completed; the world is left as it was at the failure."""


class PhysicsUnstable(SimStepFailed):
    """MuJoCo flagged bad accelerations (``mjWARN_BADQACC``) or the state became non-finite.

    The world restores the state from before the failed action instead of MuJoCo's silent reset.
    """


class Unreachable(SimStepFailed):
    """The inverse kinematics found no joint solution for a required hand pose."""


class GraspFailed(SimStepFailed):
    """No collision-free grasp exists, or the block was not held after the lift or carry."""


class Covered(GraspFailed):
    """Another block lies on the one to pick (``blocks``: their indices, for the message)."""

    def __init__(self, blocks: tuple[int, ...]) -> None:
        super().__init__("no collision-free grasp: another block lies on top of it")
        self.blocks = blocks


class NoRoom(SimStepFailed):
    """The home area or the bin has no free spot left for another block."""


class RenderUnavailable(OwnctlError):
    """No OpenGL backend can draw here; the message names the Debian package to install."""
