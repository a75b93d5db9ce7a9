"""PhysicsWorld: the simulated table the rest of ownctl drives, one object-level action at a time.

    world = PhysicsWorld([SimBlock("block1", "red", (0.3, 0.2, 0.0))], [SimArea("home", (-.1, -.1, .1, .1))])
    outcome = world.trash("block1")          # StepOutcome(ok=True, action="trash", ...)
    world.position("block1")                 # workspace coordinates, inside the trash area

Inputs and outputs are in workspace coordinates (:mod:`sim.workspace`). Each action either succeeds,
or fails with a reason in its :class:`StepOutcome`; physics instability restores the state from
before the action (never MuJoCo's silent reset) and fails the step.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from ownctl.errors import BadValue, DuplicateName, UnknownName
from sim import baxter
from sim.errors import Covered, PhysicsUnstable, SimStepFailed, Unreachable
from sim.ik import YAW_CENTER
from sim.layout import SPACING, home_slots, map_for, place_blocks
from sim.planner import PICK_OPENING, bin_cells
from sim.render import Recorder
from sim.robot import Robot, Snapshot
from sim.scene import DEFAULT_CAMERA, BlockSpec, block_body, check_camera, scene_xml
from sim.skills import HOVER, Held, Skills
from sim.workspace import SimArea, SimBlock, WorkspaceMap, with_default_areas

__all__ = ["PhysicsWorld", "SimArea", "SimBlock", "StepOutcome", "WorkspaceMap"]

ARMS = ("auto", "left", "right")
GRASPS = ("weld", "friction")
SETTLE = 0.3  # seconds the world runs after an action before the result is checked
STILL = 0.003  # metres: a block closer than this to its start has not moved
STOP_SHORT = 0.07  # metres above a block's centre where a stopped reach halts
PAUSE = 0.5  # seconds a stopped reach holds still before going back


@dataclass(frozen=True)
class StepOutcome:
    """Result of one action on one object; ``error`` says why when ``ok`` is False."""

    ok: bool
    action: str
    object: str
    error: str | None
    sim_seconds: float


def _quiet_mujoco_log() -> None:
    """Stop MuJoCo from writing MUJOCO_LOG.TXT into the working directory or printing warnings."""
    config = mujoco.MjLogConfig.get()
    config.logto_file = False
    config.logto_console = False
    config.set()


class PhysicsWorld:
    """A Baxter, a table, one block per :class:`SimBlock`, a bin on the trash area and a home mat.

    ``arm`` is "auto" (the arm on the object's side), "left" or "right"; ``grasp`` is "weld" (fingers
    close, then a weld holds the block while both fingers touch it) or "friction". ``render`` is None
    (headless, no frames), a ``.png`` path (nothing captured while acting) or a ``.mp4``/``.gif`` path
    (frames captured while acting; write them with :meth:`finish_video`), seen from ``camera`` (one of
    :data:`sim.scene.CAMERAS`, or "top").

    Blocks start where the workspace map puts them unless they had to be moved apart (``nudged``
    names them) or had no position (a free spot drawn from ``seed``). :meth:`position` reports a block
    that has not moved since the start at the position it was given, so a layout that had to make
    room never changes where the store says a block is; a moved block is reported at the inverse map
    of where it is now.
    """

    def __init__(
        self,
        blocks: Sequence[SimBlock],
        areas: Sequence[SimArea] = (),
        *,
        seed: int = 0,
        arm: str = "auto",
        grasp: str = "weld",
        render: str | None = None,
        camera: str = DEFAULT_CAMERA,
        workspace_map: WorkspaceMap | None = None,
    ) -> None:
        if arm not in ARMS:
            raise BadValue(f"unknown arm {arm!r}; known arms: {', '.join(ARMS)}", ARMS)
        if grasp not in GRASPS:
            raise BadValue(f"unknown grasp {grasp!r}; known grasps: {', '.join(GRASPS)}", GRASPS)
        check_camera(camera)
        self.camera = camera
        names = [b.name for b in blocks]
        repeated = sorted({n for n in names if names.count(n) > 1})
        if repeated:
            raise DuplicateName(f"block names must be unique; repeated: {', '.join(repeated)}")
        _quiet_mujoco_log()
        self.areas = with_default_areas(list(areas))
        self.map = workspace_map or map_for(self.areas, blocks)
        self.arm, self.seed = arm, seed
        self.names = names
        self.index = {name: i for i, name in enumerate(names)}
        placements = place_blocks(blocks, self.areas, self.map, np.random.default_rng(seed))
        self.nudged = {p.name: p.nudged for p in placements}
        self.trash_box = self.map.box_to_world(self.areas["trash"].box)
        self.home_box = self.map.box_to_world(self.areas["home"].box)
        specs = [
            BlockSpec(block_body(i), b.color, p.position)
            for i, (b, p) in enumerate(zip(blocks, placements, strict=True))
        ]
        self.xml = scene_xml(specs, self.trash_box, self.home_box)
        self.model = mujoco.MjModel.from_xml_string(self.xml)
        self.data = mujoco.MjData(self.model)
        self.recorder = Recorder.for_target(self.model, render, camera)
        self.robot = Robot(self.model, self.data, self.recorder.hook if self.recorder.video else None)
        self.robot.park_instantly(PICK_OPENING)
        self.skills = Skills(self.robot, len(names), self.trash_box, home_slots(self.home_box),
                             bin_cells(self.trash_box, SPACING), grasp)
        self._bodies = [self.model.body(block_body(i)).id for i in range(len(names))]
        self._start = {p.name: np.array(p.position) for p in placements}
        self._given = {b.name: b.position for b in blocks if b.position is not None}

    # ----------------------------------------------------------------- queries
    @property
    def sim_time(self) -> float:
        """Seconds of simulated time so far."""
        return float(self.data.time)

    def _check_name(self, name: str) -> int:
        if name not in self.index:
            raise UnknownName("object", name, self.index)
        return self.index[name]

    def position(self, name: str) -> tuple[float, float, float]:
        """Current workspace coordinates of block ``name``: as given while it has not moved, else the
        inverse map of its centre."""
        here = self.world_position(name)
        given = self._given.get(name)
        if given is not None and np.linalg.norm(np.subtract(here, self._start[name])) < STILL:
            return (float(given[0]), float(given[1]), float(given[2]))
        p = self.map.to_workspace(here)
        return (float(p[0]), float(p[1]), float(p[2]))

    def world_position(self, name: str) -> tuple[float, float, float]:
        """Current world coordinates (metres, simulator frame) of block ``name``'s centre."""
        p = self.data.xpos[self._bodies[self._check_name(name)]]
        return (float(p[0]), float(p[1]), float(p[2]))

    def positions(self) -> dict[str, tuple[float, float, float]]:
        """Workspace coordinates of every block, by name."""
        return {name: self.position(name) for name in self.names}

    def in_area(self, name: str, area: str) -> bool:
        """True if block ``name``'s (x, y) lies inside area ``area`` (workspace box)."""
        if area not in self.areas:
            raise UnknownName("area", area, self.areas)
        return self.areas[area].contains(self.position(name))

    # ----------------------------------------------------------------- actions
    def trash(self, name: str) -> StepOutcome:
        """Find block ``name``, pick it up, carry it to the bin and drop it in."""
        return self._act("trash", name, self._trash)

    def collect(self, name: str) -> StepOutcome:
        """Find block ``name``, pick it up, go home and put it down inside the home area."""
        return self._act("collect", name, self._collect)

    def stop_short(self, name: str) -> StepOutcome:
        """Reach for block ``name``, stop short above it and go back, leaving it where it is: what a
        refusal looks like when the robot is stopped as it reaches ("No Baxter, that's mine!")."""
        return self._act("stopShort", name, self._stop_short)

    def go_home(self) -> None:
        """Move both hands up and back to their park poses beside the table.

        Raises :class:`PhysicsUnstable` (after restoring the state from before the call) if the
        physics breaks on the way.
        """
        snapshot = self.robot.snapshot()
        try:
            for side in baxter.SIDES:
                self.skills.park(side)
        except PhysicsUnstable:
            self.robot.restore(snapshot)
            raise

    def _side(self, block: int) -> str:
        return self.skills.nearer_arm(block) if self.arm == "auto" else self.arm

    def _trash(self, block: int) -> str:
        side = self._side(block)
        yaw = self.skills.plan_grasp(side, block)
        spot = self.skills.plan_drop(side, block, yaw)
        self._require_reach(side, block, yaw, [(np.array([spot[0], spot[1], HOVER]), yaw)])
        held = self.skills.pick(side, block, yaw)
        self.skills.drop_in_bin(side, held, spot)
        self.skills.park(side)
        return "trash"

    def _collect(self, block: int) -> str:
        side = self._side(block)
        yaw = self.skills.plan_grasp(side, block)
        state = self.skills.state(block)
        center, put_yaw = self.skills.plan_home(side, block, state.yaw - yaw)
        self._require_reach(
            side,
            block,
            yaw,
            [(np.array([center[0], center[1], HOVER]), put_yaw), (np.asarray(center), put_yaw)],
        )
        held: Held = self.skills.pick(side, block, yaw)
        center, put_yaw = self.skills.plan_home(side, block, held.yaw)
        self.skills.put_home(side, held, center, put_yaw)
        self.skills.park(side)
        return "home"

    def _stop_short(self, block: int) -> None:
        side = self._side(block)
        yaw = YAW_CENTER[side]
        x, y, z = self.skills.state(block).center
        self._require_reach(side, block, yaw, [])
        self.robot.set_gripper(side, PICK_OPENING, seconds=0.0)
        self.robot.move(side, np.array([x, y, HOVER]), yaw)
        self.skills.vertical(side, np.array([x, y, z + STOP_SHORT]))
        self.robot.wait(PAUSE)
        self.skills.park(side)

    def _require_reach(self, side: str, block: int, yaw: float, more: list[tuple[np.ndarray, float]]) -> None:
        x, y, z = self.skills.state(block).center
        poses = [(np.array([x, y, HOVER]), yaw), (np.array([x, y, z]), yaw), *more]
        if not self.skills.reachable(side, poses):
            raise Unreachable(f"the {side} arm cannot reach every pose of this action")

    def _act(self, action: str, name: str, body: Callable[[int], str | None]) -> StepOutcome:
        """Run one action; turn failures into a failed outcome, restoring the state on instability.

        ``body`` returns the area the block must end in (None: no area to check)."""
        block = self._check_name(name)
        start = self.sim_time
        snapshot = self.robot.snapshot()
        try:
            area = body(block)
            self.robot.wait(SETTLE)
        except PhysicsUnstable as exc:
            elapsed = self.sim_time - start
            self.robot.restore(snapshot)
            return StepOutcome(False, action, name, str(exc), elapsed)
        except SimStepFailed as exc:
            elapsed = self._recover(snapshot) + self.sim_time - start
            return StepOutcome(False, action, name, self._failure(exc), elapsed)
        if area is not None and not self.in_area(name, area):
            message = f"{name} ended outside the {area} area"
            return StepOutcome(False, action, name, message, self.sim_time - start)
        return StepOutcome(True, action, name, None, self.sim_time - start)

    def _failure(self, exc: SimStepFailed) -> str:
        """Why a step failed, naming the blocks in the way when there are some."""
        if isinstance(exc, Covered):
            names = [self.names[i] for i in exc.blocks]
            verb = "lies" if len(names) == 1 else "lie"
            return f"no collision-free grasp: {', '.join(names)} {verb} on top of it"
        return str(exc)

    def _recover(self, snapshot: Snapshot) -> float:
        """After a failed skill: let go and park both arms; if that breaks the physics, restore ``snapshot``.

        Returns the sim time lost to a restore (0 otherwise), so outcomes still count it.
        """
        for side in baxter.SIDES:
            self.robot.detach(side)
        try:
            for side in baxter.SIDES:
                self.robot.set_gripper(side, PICK_OPENING, seconds=0.0)
                self.skills.park(side)
        except PhysicsUnstable:
            lost = self.sim_time - snapshot.data.time
            self.robot.restore(snapshot)
            return lost
        return 0.0

    def close(self) -> None:
        """Release the renderer's OpenGL context, if one was made."""
        self.recorder.close()

    # ----------------------------------------------------------------- rendering
    def render_png(self, path: str | Path, camera: str | None = None) -> Path:
        """Render the current scene to a PNG at ``path`` (needs an OpenGL backend, e.g. MUJOCO_GL=osmesa)."""
        return self.recorder.png(self.data, Path(path), camera or self.camera)

    def finish_video(self, path: str | Path | None = None) -> Path:
        """Write the frames captured so far to ``path`` (default: the ``render`` target) as MP4 or GIF.

        If nothing was captured yet (no action), the video is one frame of the current scene.
        """
        return self.recorder.write_video(Path(path) if path is not None else None, self.data)
