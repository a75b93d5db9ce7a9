"""Scripted skills on top of :class:`~sim.robot.Robot`: pick, carry, drop in the bin, put down home, park.

A skill first plans (grasp yaw, destination, reachability of every key pose) and only then moves, so a
plan that cannot work fails before anything is touched. Hands travel between objects at ``HOVER``
height, well above every block, tower and bin wall, and go up and down only vertically over the spot
they work on, so the arm never sweeps through other blocks.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sim import scene_config as cfg
from sim.errors import Covered, GraspFailed, NoRoom, Unreachable
from sim.ik import Q_NOMINAL, YAW_CENTER, down_rotation
from sim.planner import (
    DROP_OPENING,
    PICK_OPENING,
    PLACE_OPENING,
    BlockState,
    PutDown,
    covering,
    drop_point,
    grasp_yaw,
    home_put_down,
    wall_rects,
)
from sim.robot import PARK, Robot
from sim.scene import block_body

Vec = NDArray[np.float64]

HOVER = cfg.TABLE_TOP + 0.2  # grip-site height for every horizontal move: above towers, piles and walls
SLOW = 0.25  # m/s for the last (first) APPROACH metres of a vertical approach (retreat)
APPROACH = 0.04
DROP_GAP = 0.006  # a trashed block is let go this far above the pile under it
CROSS = 0.08  # an arm puts blocks down at most this far past the midline, on the other arm's side
H = cfg.BLOCK_HALF


@dataclass
class Held:
    """A held block: index, its centre in the grip-site frame (3,), and its yaw minus the hand's yaw."""

    block: int
    offset: Vec
    yaw: float


def yaw_of(quat: Vec) -> float:
    """Rotation about world z of a unit quaternion (w, x, y, z)."""
    w, x, y, z = quat
    return float(np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z)))


class Skills:
    """Skills of both arms over ``n_blocks`` blocks, a bin on ``bin_box``, home and bin cells (world
    frame)."""

    def __init__(
        self,
        robot: Robot,
        n_blocks: int,
        bin_box: tuple[float, float, float, float],
        home_cells: list[tuple[float, float]],
        drop_cells: list[tuple[float, float]],
        grasp: str = "weld",
    ) -> None:
        self.robot = robot
        self.bodies = [robot.model.body(block_body(i)).id for i in range(n_blocks)]
        self.walls = wall_rects(bin_box)
        self.bin_cells = drop_cells
        self.home_cells = home_cells
        self.weld = grasp == "weld"

    # ----------------------------------------------------------------- state
    def state(self, block: int) -> BlockState:
        """Current centre and yaw of ``block``."""
        body = self.bodies[block]
        pos = self.robot.data.xpos[body]
        return BlockState(
            block, (float(pos[0]), float(pos[1]), float(pos[2])), yaw_of(self.robot.data.xquat[body])
        )

    def others(self, block: int) -> list[BlockState]:
        """Every block except ``block``."""
        return [self.state(i) for i in range(len(self.bodies)) if i != block]

    def nearer_arm(self, block: int) -> str:
        """The arm on the block's side of the robot (left for y >= 0)."""
        return "left" if self.state(block).center[1] >= 0 else "right"

    @staticmethod
    def own_side(side: str, y: float) -> bool:
        """True if ``y`` is on ``side``'s half of the table or at most ``CROSS`` past the midline, where
        the arm's motions stay well inside its reach (an arm reaches further, but awkwardly)."""
        return y >= -CROSS if side == "left" else y <= CROSS

    def reachable(self, side: str, poses: list[tuple[Vec, float]]) -> bool:
        """True if IK finds every (grip position (3,), closing yaw) of ``poses`` for ``side``, chained."""
        q = Q_NOMINAL
        for pos, yaw in poses:
            res = self.robot.ik[side].solve(pos, down_rotation(yaw), q, iters=200)
            if not res.ok:
                return False
            q = res.q
        return True

    # ----------------------------------------------------------------- skills
    def plan_grasp(self, side: str, block: int) -> float:
        """Closing yaw for picking ``block`` with ``side``; raises if blocked."""
        target, others = self.state(block), self.others(block)
        above = covering(target, others)
        if above:
            raise Covered(tuple(b.index for b in above))
        yaw = grasp_yaw(target, others, self.walls, YAW_CENTER[side])
        if yaw is None:
            raise GraspFailed("no collision-free grasp: neighbours or walls too close on both sides")
        return yaw

    def pick(self, side: str, block: int, yaw: float) -> Held:
        """Open, go over ``block``, down, close (and weld), lift to hover height; raise if not held."""
        robot, target = self.robot, self.state(block)
        x, y, z = target.center
        robot.set_gripper(side, PICK_OPENING, seconds=0.0)
        robot.move(side, np.array([x, y, HOVER]), yaw)
        self.vertical(side, np.array([x, y, z]))
        robot.set_gripper(side, 0.0, seconds=0.2)
        if self.weld and not robot.attach(side, block):
            robot.set_gripper(side, PICK_OPENING, seconds=0.1)
            self.vertical(side, np.array([x, y, HOVER]))
            raise GraspFailed("the fingers did not close on the block")
        site = robot.ik[side].site
        rot = robot.data.site_xmat[site].reshape(3, 3)
        now = self.state(block)
        held = Held(
            block, rot.T @ (np.asarray(now.center) - robot.data.site_xpos[site]), now.yaw - robot.yaw[side]
        )
        self.vertical(side, np.array([x, y, HOVER]))
        if self.state(block).center[2] < cfg.TABLE_TOP + 0.06:
            self.release(side, PICK_OPENING)
            raise GraspFailed(f"the block slipped out of the {side} gripper while lifting")
        return held

    def vertical(self, side: str, goal: Vec) -> None:
        """Go straight up or down to ``goal`` (3,): slowly within ``APPROACH`` of the low end, fast
        elsewhere."""
        here = self.robot.target[side]
        goal = np.asarray(goal, dtype=float)
        drop = goal[2] - here[2]
        if abs(drop) <= APPROACH + 1e-9:
            self.robot.move(side, goal, speed=SLOW)
            return
        turn = goal.copy()
        if drop < 0:  # fast to just above the work, then slowly onto it
            turn[2] = goal[2] + APPROACH
            self.robot.move(side, turn)
            self.robot.move(side, goal, speed=SLOW)
        else:  # slowly off the work, then fast up
            turn[2] = here[2] + APPROACH
            self.robot.move(side, turn, speed=SLOW)
            self.robot.move(side, goal)

    def grip_target(self, held: Held, center: Vec, yaw: float) -> Vec:
        """Grip-site position (3,) putting the held block's centre at ``center`` with the hand at ``yaw``."""
        return np.asarray(center) - down_rotation(yaw) @ held.offset

    def release(self, side: str, opening: float) -> None:
        """Let go: switch off the weld and open the fingers to ``opening``."""
        self.robot.detach(side)
        self.robot.set_gripper(side, opening, seconds=0.15)

    def check_held(self, side: str, held: Held) -> None:
        """Raise if the held block is no longer at the hand (it was lost while carrying)."""
        site = self.robot.data.site_xpos[self.robot.ik[side].site]
        if np.linalg.norm(np.asarray(self.state(held.block).center) - site) > 0.02:
            self.release(side, PICK_OPENING)
            raise GraspFailed("the block was lost while carrying it")

    def plan_drop(self, side: str, block: int, yaw: float) -> tuple[float, float, float]:
        """Bin drop point (x, y, pile top z) for ``block`` that ``side``'s hand reaches at ``yaw``."""

        def reached(spot: tuple[float, float, float]) -> bool:
            x, y, top = spot
            return self.own_side(side, y) and self.reachable(
                side, [(np.array([x, y, HOVER]), yaw), (np.array([x, y, top + H + DROP_GAP]), yaw)]
            )

        spot = drop_point(self.bin_cells, self.others(block), reached)
        if spot is None:
            raise Unreachable(f"the {side} arm reaches no drop point in the bin")
        return spot

    def drop_in_bin(self, side: str, held: Held, spot: tuple[float, float, float]) -> None:
        """Carry the held block over ``spot``, lower it just above the pile there and let go."""
        x, y, top = spot
        yaw = self.robot.yaw[side]
        above = self.grip_target(held, np.array([x, y, HOVER]), yaw)
        self.robot.move(side, np.array([above[0], above[1], HOVER]), yaw)
        self.check_held(side, held)
        low = self.grip_target(held, np.array([x, y, top + H + DROP_GAP]), yaw)
        self.vertical(side, low)
        self.release(side, DROP_OPENING)
        self.vertical(side, np.array([low[0], low[1], HOVER]))

    def plan_home(self, side: str, block: int, held_yaw: float) -> tuple[tuple[float, float, float], float]:
        """Home put-down spot (block centre) and closing yaw that ``side`` reaches; raises :class:`NoRoom`
        if none is clear."""

        def reached(put: PutDown) -> bool:
            x, y, z = put.center
            return self.own_side(side, y) and self.reachable(
                side, [(np.array([x, y, HOVER]), put.closing_yaw), (np.array([x, y, z]), put.closing_yaw)]
            )

        choice = home_put_down(self.home_cells, self.others(block), held_yaw, YAW_CENTER[side], reached)
        if choice is None:
            raise NoRoom("no clear spot left on the home area")
        return choice.center, choice.closing_yaw

    def put_home(self, side: str, held: Held, center: tuple[float, float, float], yaw: float) -> None:
        """Carry the held block over ``center``, set it down there gently and let go."""
        over = self.grip_target(held, np.array([center[0], center[1], HOVER]), yaw)
        self.robot.move(side, np.array([over[0], over[1], HOVER]), yaw)
        self.check_held(side, held)
        place = self.grip_target(held, np.asarray(center) + np.array([0.0, 0.0, 0.001]), yaw)
        self.vertical(side, place + np.array([0.0, 0.0, 0.02]))
        self.robot.move(side, place, speed=0.05)
        self.release(side, PLACE_OPENING)
        self.robot.move(side, place + np.array([0.0, 0.0, 0.02]), speed=0.05)
        self.vertical(side, np.array([place[0], place[1], HOVER]))

    def park(self, side: str) -> None:
        """Go straight up to hover height, then to the park pose beside the table."""
        robot = self.robot
        here = robot.target[side]
        if here[2] < HOVER - 1e-6:
            self.vertical(side, np.array([here[0], here[1], HOVER]))
        robot.move(side, np.array(PARK[side]), YAW_CENTER[side])
