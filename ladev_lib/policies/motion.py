"""Arm motion for the skills: joint-target streams, planned moves, the gripper.

``ArmMotion`` is the part of a skill that knows how to move the Panda: it turns
planned paths into one ``pd_joint_pos`` action per control step, waits for the
PD controller to arrive, opens and closes the gripper, and plans straight or
around obstacles with :class:`~ladev_lib.policies.planner.ArmPlanner`. Its
generator methods are composed with ``yield from`` by the task logic in
:mod:`ladev_lib.policies.skills`; the caller steps the simulator between actions.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Literal

import numpy as np
import sapien

from ladev_lib.arrays import Array
from ladev_lib.policies.geometry import ObjectGeometry
from ladev_lib.policies.planner import BRISK_PATH_STEPS, ArmPath, ArmPlanner

if TYPE_CHECKING:
    from ladev_lib.sim.view import RobotView, SceneView

RETREAT_HEIGHT_M = 0.08
MAX_SETTLE_STEPS = 20
JOINT_TOLERANCE_RAD = 0.02
PRECISE_TOLERANCE_RAD = 0.004
PRECISE_SPEED_RAD_S = 0.02


@dataclass
class SkillOutcome:
    """How a skill ended (or where it is)."""

    status: Literal["running", "done", "failed"] = "running"
    reason: str = ""
    phase: str = "start"
    attempts: int = 0
    log: list[str] = field(default_factory=list)
    phase_steps: dict[str, int] = field(default_factory=dict)
    """Actions emitted per phase (all attempts together)."""


class SkillFailure(Exception):
    """A phase that cannot be planned or did not work; the message says why.

    ``final`` marks failures another attempt cannot change (the scene is as it was:
    no grasp fits, no free spot); the skill then stops instead of retrying.
    """

    def __init__(self, message: str, final: bool = False):
        super().__init__(message)
        self.final = final


@dataclass(frozen=True)
class _GripperMap:
    """Finger opening (m, between pads) <-> normalised gripper action of the mimic controller."""

    lower: float
    upper: float

    @classmethod
    def of(cls, robot: RobotView) -> _GripperMap:
        lower, upper = robot.gripper_limits()
        return cls(lower, upper)

    @property
    def max_opening(self) -> float:
        return 2 * self.upper

    @property
    def min_opening(self) -> float:
        """Fully closed: the controller's lower limit squeezes below zero for grip force."""
        return 2 * self.lower

    def action(self, opening: float) -> float:
        joint = float(np.clip(opening / 2, self.lower, self.upper))
        return 2 * (joint - self.lower) / (self.upper - self.lower) - 1


class ArmMotion:
    """Moves the Panda of the scene ``view``, recording what it does in ``outcome``.

    It reads the scene through its read-only view; the caller steps the simulator.
    """

    def __init__(self, view: SceneView) -> None:
        self.view = view
        self.outcome = SkillOutcome()
        self.planner = ArmPlanner(view.robot, view.control_timestep)
        self._gripper = _GripperMap.of(view.robot)
        self._arm_target = self._qpos()[: self.planner.n_arm]
        self._gripper_action = self._gripper.action(self._gripper.max_opening)

    def hold_action(self) -> Array:
        """The action that keeps the arm and gripper where they were last sent."""
        return self._action()

    # -- state ---------------------------------------------------------------
    def _qpos(self) -> Array:
        return self.view.robot.qpos()

    def _qvel(self) -> Array:
        return self.view.robot.qvel()

    def _tcp(self) -> sapien.Pose:
        return self.view.robot.tcp_pose()

    def _geometries(self) -> dict[str, ObjectGeometry]:
        return {n: ObjectGeometry.of(self.view, n) for n in self.view.object_names()}

    def _note(self, text: str) -> None:
        self.outcome.log.append(f"[{self.outcome.phase}] {text}")

    # -- action streams ------------------------------------------------------
    def _action(self) -> Array:
        return np.concatenate([self._arm_target, [self._gripper_action]]).astype(np.float32)

    def _follow(self, path: ArmPath, precise: bool = False) -> Iterator[Array]:
        """Send the path's joint targets, then wait for the arm to catch up.

        ``precise``: wait until the arm has (nearly) stopped at the end, as before
        closing or opening the gripper: a hand still moving pushes what it lets go.
        """
        for q in path.qpos:
            self._arm_target = np.asarray(q, dtype=float)
            yield self._action()
        tolerance = PRECISE_TOLERANCE_RAD if precise else JOINT_TOLERANCE_RAD
        for _ in range(MAX_SETTLE_STEPS):  # let the PD controller catch up
            error = np.max(np.abs(self._qpos()[: self.planner.n_arm] - self._arm_target))
            speed = np.max(np.abs(self._qvel()[: self.planner.n_arm]))
            if error < tolerance and (not precise or speed < PRECISE_SPEED_RAD_S):
                break
            yield self._action()

    def _gripper_steps(self, opening: float, steps: int) -> Iterator[Array]:
        self._gripper_action = self._gripper.action(opening)
        for _ in range(steps):
            yield self._action()

    def _wait(self, steps: int) -> Iterator[Array]:
        for _ in range(steps):
            yield self._action()

    def _plan_from(self, qpos: Array, goal: sapien.Pose, *, avoid: bool, what: str) -> ArmPath:
        path = self.planner.plan(qpos, goal, avoid)
        if path is None:
            raise SkillFailure(f"no collision-free path to {what} at {np.round(goal.p, 3).tolist()}")
        self._note(f"{what}: {path.method}, {len(path.qpos)} steps")
        return path

    def _straight(self, goal: sapien.Pose, what: str, obstacles: Array,
                  held: ObjectGeometry | None = None) -> ArmPath:
        """Straight to ``goal``; around the obstacles (with what is held) if straight is blocked."""
        path = self.planner.screw(self._qpos(), goal, avoid=False)
        if path is None or len(path.qpos) > BRISK_PATH_STEPS:
            # Joint limits or a near-singular stretch on the straight line: go around.
            self.planner.set_obstacles(obstacles)
            if held is not None:
                self._attach(held)
            around = self.planner.rrt(self._qpos(), goal, avoid=True)
            self.planner.detach()
            if around is not None and (path is None or len(around.qpos) < len(path.qpos)):
                path = around
        if path is None:
            raise SkillFailure(f"no path to {what} at {np.round(goal.p, 3).tolist()}")
        self._note(f"{what}: {path.method}, {len(path.qpos)} steps")
        return path

    def _padded(self, arm_q: Array) -> Array:
        q = self._qpos()
        q[: self.planner.n_arm] = arm_q
        return q

    def _phase(self, name: str) -> None:
        self.outcome.phase = name

    def _finish(self) -> None:
        self.outcome.status = "done"
        self._phase("done")

    def _retreat(self) -> Iterator[Array]:
        """Straight up, away from what was just grasped or let go."""
        self._phase("retreat")
        up = sapien.Pose([0.0, 0.0, RETREAT_HEIGHT_M]) * self._tcp()
        path = self.planner.screw(self._qpos(), up, avoid=False)
        if path is not None:
            yield from self._follow(path)

    def _attach(self, src: ObjectGeometry) -> None:
        """Plan with the held object as part of the hand (its box in the TCP frame)."""
        tcp = self._tcp()
        local = (src.points - np.asarray(tcp.p)) @ tcp.to_transformation_matrix()[:3, :3]
        lo, hi = local.min(axis=0), local.max(axis=0)
        self.planner.attach_box(hi - lo, sapien.Pose((lo + hi) / 2))
