"""Damped-least-squares inverse kinematics for one Baxter arm on MuJoCo Jacobians.

The solver works on a private ``MjData`` so it never disturbs the simulation: it writes only the
arm's 7 joint positions, runs forward kinematics and reads ``mj_jacSite`` of the grip site. The
target is a 6-D pose (position and a top-down rotation); a null-space term pulls the arm towards an
elbow-up posture and every iterate is clipped to the joint limits. One solve takes well under 1 ms.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
from numpy.typing import NDArray

from sim.baxter import JOINTS, joint_name

Vec = NDArray[np.float64]

# Null-space attractor: elbow up, wrist bent down (shape (7,), radians, order of JOINTS).
Q_NOMINAL: Vec = np.array([0.0, -0.55, 0.0, 1.3, 0.0, 0.8, 0.0])
# Hand yaw (closing direction, rad) that each arm reaches over the table with its wrist roll w2 near 0.
# The gripper is symmetric under a half turn, so every grasp has a yaw within pi/2 of this centre, and
# such yaws keep w2 well inside its +-3.059 rad range.
YAW_CENTER: dict[str, float] = {"left": 1.0, "right": 2.1}


def down_rotation(yaw: float) -> Vec:
    """Rotation (3, 3) of a hand pointing straight down, fingers closing along (cos yaw, sin yaw, 0)."""
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([[-s, c, 0.0], [c, s, 0.0], [0.0, 0.0, -1.0]])  # columns: y x z, y, z = down


@dataclass(frozen=True)
class IKResult:
    """A joint solution ``q`` (7,), whether it met the tolerances, and the residual errors (m, rad)."""

    q: Vec
    ok: bool
    pos_error: float
    rot_error: float


class ArmIK:
    """IK for the grip site of one arm (``side`` = "left" or "right") of a compiled scene model."""

    def __init__(self, model: mujoco.MjModel, side: str) -> None:
        self.model = model
        self.data = mujoco.MjData(model)
        self.side = side
        self.site = model.site(f"{side}_grip_site").id
        ids = [model.joint(joint_name(side, j)).id for j in JOINTS]
        self.qadr = np.array([model.jnt_qposadr[j] for j in ids])
        self.dadr = np.array([model.jnt_dofadr[j] for j in ids])
        self.lower = model.jnt_range[ids, 0].copy()
        self.upper = model.jnt_range[ids, 1].copy()
        self._jacp = np.zeros((3, model.nv))
        self._jacr = np.zeros((3, model.nv))

    def forward(self, q: Vec) -> tuple[Vec, Vec]:
        """Grip-site position (3,) and rotation (3, 3) for joint vector ``q`` (7,)."""
        self.data.qpos[self.qadr] = q
        mujoco.mj_kinematics(self.model, self.data)
        site = self.data.site(self.site)
        return site.xpos.copy(), site.xmat.reshape(3, 3).copy()

    def _errors(self, pos: Vec, target_quat: Vec) -> tuple[Vec, Vec]:
        """Position error (3,) and rotation error as an angular velocity over 1 s (3,)."""
        site = self.data.site(self.site)
        cur, inv, diff, rot = np.zeros(4), np.zeros(4), np.zeros(4), np.zeros(3)
        mujoco.mju_mat2Quat(cur, site.xmat)
        mujoco.mju_negQuat(inv, cur)
        mujoco.mju_mulQuat(diff, target_quat, inv)
        if diff[0] < 0:  # q and -q are the same rotation: take the short way round
            diff *= -1
        mujoco.mju_quat2Vel(rot, diff, 1.0)
        return pos - site.xpos, rot

    def solve(
        self,
        pos: Vec,
        rot: Vec,
        q0: Vec,
        *,
        iters: int = 60,
        tol_pos: float = 1e-3,
        tol_rot: float = 1e-2,
        damping: float = 0.05,
        null_gain: float = 0.1,
        max_step: float = 0.2,
    ) -> IKResult:
        """Joints putting the grip site at ``pos`` (3,) with rotation ``rot`` (3, 3), starting at ``q0`` (7,).

        Damped least squares ``dq = J^T (J J^T + damping^2 I)^-1 e`` on the 6-D error, plus a null-space
        pull towards ``Q_NOMINAL``; steps are capped at ``max_step`` rad and clipped to the joint limits.
        """
        target_quat = np.zeros(4)
        mujoco.mju_mat2Quat(target_quat, np.asarray(rot, float).flatten())
        pos = np.asarray(pos, float)
        q = np.clip(np.asarray(q0, float), self.lower, self.upper)
        eye6, eye7 = np.eye(6), np.eye(7)
        for _ in range(iters):
            self.data.qpos[self.qadr] = q
            mujoco.mj_kinematics(self.model, self.data)
            mujoco.mj_comPos(self.model, self.data)
            ep, er = self._errors(pos, target_quat)
            if np.linalg.norm(ep) < tol_pos and np.linalg.norm(er) < tol_rot:
                return IKResult(q, True, float(np.linalg.norm(ep)), float(np.linalg.norm(er)))
            mujoco.mj_jacSite(self.model, self.data, self._jacp, self._jacr, self.site)
            jac = np.vstack([self._jacp[:, self.dadr], self._jacr[:, self.dadr]])
            err = np.concatenate([ep, er])
            dq = jac.T @ np.linalg.solve(jac @ jac.T + damping**2 * eye6, err)
            pinv = jac.T @ np.linalg.inv(jac @ jac.T + 1e-4 * eye6)
            dq += (eye7 - pinv @ jac) @ (null_gain * (Q_NOMINAL - q))
            biggest = np.max(np.abs(dq))
            if biggest > max_step:
                dq *= max_step / biggest
            q = np.clip(q + dq, self.lower, self.upper)
        self.data.qpos[self.qadr] = q
        mujoco.mj_kinematics(self.model, self.data)
        ep, er = self._errors(pos, target_quat)
        ok = bool(np.linalg.norm(ep) < tol_pos and np.linalg.norm(er) < tol_rot)
        return IKResult(q, ok, float(np.linalg.norm(ep)), float(np.linalg.norm(er)))
