"""Low-level control of the simulated Baxter: stepping, Cartesian moves, gripper, grasp weld.

:class:`Robot` owns the ``MjData`` being simulated. Every motion steps the physics and checks MuJoCo's
bad-acceleration warning counter after each control tick, raising :class:`PhysicsUnstable` instead of
letting MuJoCo reset the state silently. Hand moves are minimum-jerk Cartesian paths of the grip site
with a top-down hand, solved by IK at every control tick and tracked by the joint position servos.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np
from numpy.typing import NDArray

from sim import baxter
from sim import scene_config as cfg
from sim.errors import PhysicsUnstable, Unreachable
from sim.ik import Q_NOMINAL, YAW_CENTER, ArmIK, down_rotation
from sim.scene import block_body, weld_name

Vec = NDArray[np.float64]
FrameHook = Callable[[mujoco.MjData], None]

CTRL_EVERY = 5  # physics steps per control tick (10 ms)
SPEED = 0.6  # peak Cartesian speed of long moves (m/s)
YAW_SPEED = 3.0  # wrist yaw rate (rad/s)
PARK: dict[str, tuple[float, float, float]] = {  # idle hand positions: high over the strip's near corners
    "left": (0.38, 0.40, cfg.TABLE_TOP + 0.32),
    "right": (0.38, -0.40, cfg.TABLE_TOP + 0.32),
}


@dataclass(frozen=True)
class Snapshot:
    """Everything needed to put the simulation back: a copy of ``MjData`` and the arms' commands."""

    data: mujoco.MjData
    qcmd: dict[str, Vec]
    target: dict[str, Vec]
    yaw: dict[str, float]
    held: dict[str, int | None]


def min_jerk(s: float) -> float:
    """Minimum-jerk time scaling on [0, 1]: zero velocity and acceleration at both ends."""
    return 10 * s**3 - 15 * s**4 + 6 * s**5


class Robot:
    """The two arms of a compiled scene: commanded joints ``qcmd[side]`` (7,), hand target and yaw."""

    def __init__(
        self, model: mujoco.MjModel, data: mujoco.MjData, frame_hook: FrameHook | None = None
    ) -> None:
        self.model, self.data = model, data
        self.frame_hook = frame_hook
        self.ik = {s: ArmIK(model, s) for s in baxter.SIDES}
        self.arm_act = {
            s: np.array([model.actuator(f"{s}_{j}_act").id for j in baxter.JOINTS]) for s in baxter.SIDES
        }
        self.grip_act = {
            s: np.array([model.actuator(f"{s}_gripper_{f}_act").id for f in "lr"]) for s in baxter.SIDES
        }
        self.finger_qadr = {
            s: np.array([model.jnt_qposadr[model.joint(baxter.finger_joint(s, f)).id] for f in "lr"])
            for s in baxter.SIDES
        }
        self.hand_body = {s: model.body(f"{s}_hand").id for s in baxter.SIDES}
        self.finger_geoms = {s: {model.geom(f"{s}_finger_{f}_geom").id for f in "lr"} for s in baxter.SIDES}
        self.qcmd: dict[str, Vec] = {}
        self.target: dict[str, Vec] = {}
        self.yaw: dict[str, float] = {}
        self.held: dict[str, int | None] = {s: None for s in baxter.SIDES}
        self._bad = 0

    # ----------------------------------------------------------------- setup and stepping
    def park_instantly(self, opening: float) -> None:
        """Put both arms at their park poses, grippers at ``opening``, before any stepping."""
        for side in baxter.SIDES:
            pos = np.array(PARK[side])
            res = self.ik[side].solve(pos, down_rotation(YAW_CENTER[side]), Q_NOMINAL, iters=300)
            if not res.ok:
                raise Unreachable(f"{side} park pose {PARK[side]} is out of reach")
            self.data.qpos[self.ik[side].qadr] = res.q
            self.data.ctrl[self.arm_act[side]] = res.q
            self.data.qpos[self.finger_qadr[side]] = opening
            self.data.ctrl[self.grip_act[side]] = opening
            self.qcmd[side], self.target[side], self.yaw[side] = res.q, pos, YAW_CENTER[side]
        mujoco.mj_forward(self.model, self.data)
        self._bad = self.data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number

    def step(self, n: int) -> None:
        """Advance ``n`` physics steps, calling the frame hook after each; raise if the physics broke."""
        for _ in range(n):
            mujoco.mj_step(self.model, self.data)
            if self.frame_hook is not None:
                self.frame_hook(self.data)
        bad = self.data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number
        if bad != self._bad or not np.isfinite(self.data.qpos).all():
            self._bad = bad
            raise PhysicsUnstable(f"physics became unstable at t={self.data.time:.3f} s (bad accelerations)")

    def wait(self, seconds: float) -> None:
        """Let the physics run for ``seconds`` with the current commands."""
        ticks = max(1, int(round(seconds / (self.model.opt.timestep * CTRL_EVERY))))
        for _ in range(ticks):
            self.step(CTRL_EVERY)

    def snapshot(self) -> Snapshot:
        """A deep copy of the simulation state and the arms' commands."""
        return Snapshot(
            copy.copy(self.data),
            copy.deepcopy(self.qcmd),
            copy.deepcopy(self.target),
            dict(self.yaw),
            dict(self.held),
        )

    def restore(self, snap: Snapshot) -> None:
        """Put the simulation back to ``snap`` (in place: ``self.data`` stays the same object)."""
        mujoco.mj_copyData(self.data, self.model, snap.data)
        self.qcmd, self.target = copy.deepcopy(snap.qcmd), copy.deepcopy(snap.target)
        self.yaw, self.held = dict(snap.yaw), dict(snap.held)
        mujoco.mj_forward(self.model, self.data)
        self._bad = self.data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number

    # ----------------------------------------------------------------- motion
    def grip_pos(self, side: str) -> Vec:
        """Current world position (3,) of ``side``'s grip site."""
        return self.data.site_xpos[self.ik[side].site].copy()

    def move(self, side: str, pos: Vec, yaw: float | None = None, speed: float = SPEED) -> None:
        """Move ``side``'s grip site along a straight minimum-jerk path to ``pos`` (3,), hand down.

        ``yaw`` (closing direction, rad) is interpolated alongside; raises :class:`Unreachable` if
        the end pose has no IK solution within 2 mm.
        """
        pos = np.asarray(pos, dtype=float)
        start, yaw0 = self.target[side].copy(), self.yaw[side]
        yaw1 = yaw0 if yaw is None else float(yaw)
        dist = float(np.linalg.norm(pos - start))
        duration = max(0.25, 1.875 * dist / speed, abs(yaw1 - yaw0) / YAW_SPEED)
        tick = self.model.opt.timestep * CTRL_EVERY
        ticks = max(1, int(np.ceil(duration / tick)))
        ik = self.ik[side]
        for k in range(1, ticks + 1):
            s = min_jerk(k / ticks)
            res = ik.solve(
                start + s * (pos - start), down_rotation(yaw0 + s * (yaw1 - yaw0)), self.qcmd[side], iters=15
            )
            if k == ticks and not res.ok:
                res = ik.solve(pos, down_rotation(yaw1), res.q, iters=200, tol_pos=5e-4)
                if not res.ok or res.pos_error > 2e-3:
                    raise Unreachable(f"{side} arm cannot reach {np.round(pos, 3).tolist()} (yaw {yaw1:.2f})")
            self.qcmd[side] = res.q
            self.data.ctrl[self.arm_act[side]] = res.q
            self.step(CTRL_EVERY)
        self.target[side], self.yaw[side] = pos, yaw1
        self.settle(side)

    def settle(self, side: str, tol: float = 0.003, max_seconds: float = 0.3) -> bool:
        """Step until ``side``'s joints track their command within ``tol`` rad (bounded); True if they do."""
        adr = self.ik[side].qadr
        for _ in range(int(max_seconds / (self.model.opt.timestep * CTRL_EVERY))):
            if np.abs(self.data.qpos[adr] - self.qcmd[side]).max() < tol:
                return True
            self.step(CTRL_EVERY)
        return False

    # ----------------------------------------------------------------- gripper and grasp
    def set_gripper(self, side: str, opening: float, seconds: float = 0.25) -> None:
        """Command each finger's inner face to ``opening`` m from the centre line and wait ``seconds``."""
        self.data.ctrl[self.grip_act[side]] = float(np.clip(opening, 0.0, baxter.FINGER_TRAVEL))
        self.wait(seconds)

    def touching(self, side: str, block: int) -> set[int]:
        """Finger geoms of ``side`` currently in contact with block ``block``."""
        geom = self.model.geom(f"{block_body(block)}_geom").id
        fingers = self.finger_geoms[side]
        found = set()
        for c in self.data.contact[: self.data.ncon]:
            if c.geom1 == geom and c.geom2 in fingers:
                found.add(int(c.geom2))
            elif c.geom2 == geom and c.geom1 in fingers:
                found.add(int(c.geom1))
        return found

    def attach(self, side: str, block: int) -> bool:
        """Weld ``block`` to ``side``'s hand at their current relative pose, if both fingers touch it."""
        if len(self.touching(side, block)) < 2:
            return False
        eq = self.model.equality(weld_name(side, block)).id
        hand, body = self.hand_body[side], self.model.body(block_body(block)).id
        rot = self.data.xmat[hand].reshape(3, 3)
        inv, rel = np.zeros(4), np.zeros(4)
        mujoco.mju_negQuat(inv, self.data.xquat[hand])
        mujoco.mju_mulQuat(rel, inv, self.data.xquat[body])
        self.model.eq_data[eq, 0:3] = 0.0  # anchor at the block's origin
        self.model.eq_data[eq, 3:6] = rot.T @ (self.data.xpos[body] - self.data.xpos[hand])
        self.model.eq_data[eq, 6:10] = rel
        self.model.eq_data[eq, 10] = 1.0  # torque scale
        self.model.eq_data[eq, 11] = 0.0  # mujoco 4: the relative pose above is explicit
        self.data.eq_active[eq] = 1
        self.held[side] = block
        return True

    def detach(self, side: str) -> None:
        """Switch off ``side``'s grasp weld, if any."""
        block = self.held[side]
        if block is not None:
            self.data.eq_active[self.model.equality(weld_name(side, block)).id] = 0
            self.held[side] = None
