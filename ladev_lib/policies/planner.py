"""Arm motion planning for the Panda with mplib: screw motions first, RRT when they collide.

Works in the robot's base frame internally. mplib 0.1.1 takes a base pose, but
places attached objects (the grasped item) as if the base were at the origin;
planning in the base frame sidesteps that, so we set its base to the identity
and transform every pose and obstacle point ourselves.

Obstacles are points (the other objects' surfaces) that mplib turns into an
octree whose cells inflate them by up to one cell, a safety margin for free.
The grasped object is an attached box in the TCP frame, so transport plans keep
it clear of the scene too.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import mplib
import numpy as np
import sapien

from ladev_lib.arrays import Array
from ladev_lib.policies.geometry import transform_points

if TYPE_CHECKING:
    from ladev_lib.sim.view import RobotView

OCTREE_RESOLUTION_M = 0.006
JOINT_VEL_SCALE = 1.3
JOINT_ACC_SCALE = 2.5
RRT_TIME_S = 1.0
END_POS_TOL_M = 0.003
END_ROT_TOL_RAD = 0.05
REFINE_MAX_RAD = 0.3
"""Largest joint change the end-of-screw correction may make."""
REFINE_STEP_RAD = 0.03
JOINT_CHECK_STEP_RAD = 0.05
"""Spacing of the collision checks along a straight joint-space path."""
BRISK_PATH_STEPS = 120
"""A screw path longer than this (control steps) is compared against RRT."""


@contextlib.contextmanager
def _quiet_native_output() -> Iterator[None]:
    """Hide what OMPL prints from C++ ("invalid start state", ...) during one call."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        with contextlib.redirect_stdout(io.StringIO()):  # and mplib's own Python prints
            yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, devnull):
            os.close(fd)


@dataclass(frozen=True)
class ArmPath:
    """Arm joint positions to send one per control step, and how it was found."""

    qpos: Array
    """(T, n_arm_joints)"""
    method: str
    """"screw" or "rrt"."""


def _pose7(pose: sapien.Pose) -> Array:
    return np.concatenate([np.asarray(pose.p, dtype=float), np.asarray(pose.q, dtype=float)])


class ArmPlanner:
    """Plans TCP motions of a ManiSkill agent among obstacle points."""

    def __init__(self, robot: RobotView, control_timestep: float, move_group: str = "panda_hand_tcp"):
        self.time_step = float(control_timestep)
        link_names = robot.link_names()
        joint_names = robot.active_joint_names()
        with contextlib.redirect_stdout(io.StringIO()):  # mplib prints SRDF notices
            self._mp = mplib.planner.Planner(
                urdf=robot.urdf_path,
                srdf=robot.urdf_path.replace(".urdf", ".srdf"),
                user_link_names=link_names,
                user_joint_names=joint_names,
                move_group=move_group,
            )
        self._mp.set_base_pose(np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]))
        self._mp.joint_vel_limits = np.asarray(self._mp.joint_vel_limits) * JOINT_VEL_SCALE
        self._mp.joint_acc_limits = np.asarray(self._mp.joint_acc_limits) * JOINT_ACC_SCALE
        self._base = robot.base_pose()
        self._base_inv = self._base.inv()
        self.n_arm = len(self._mp.move_group_joint_indices)
        self._has_obstacles = False
        self._has_attached = False

    # -- scene ---------------------------------------------------------------
    def set_obstacles(self, points_world: Array | None) -> None:
        """Replace the obstacle points (world frame); None or empty clears them."""
        if points_world is None or len(points_world) == 0:
            self._has_obstacles = False
            return
        pts = transform_points(self._base_inv, points_world)
        self._mp.update_point_cloud(pts, OCTREE_RESOLUTION_M)
        self._has_obstacles = True

    def attach_box(self, size: Array, pose_in_tcp: sapien.Pose) -> None:
        """Treat a box held in the gripper as part of the robot when planning."""
        self._mp.update_attached_box(np.asarray(size, dtype=float), _pose7(pose_in_tcp))
        self._has_attached = True

    def detach(self) -> None:
        self._has_attached = False

    # -- queries -------------------------------------------------------------
    def _to_base(self, pose_world: sapien.Pose) -> Array:
        return _pose7(self._base_inv * pose_world)

    def _flags(self, avoid: bool) -> dict[str, bool]:
        return {
            "use_point_cloud": avoid and self._has_obstacles,
            "use_attach": avoid and self._has_attached,
        }

    def screw(self, qpos: Array, goal: sapien.Pose, avoid: bool = True) -> ArmPath | None:
        """A straight screw motion of the TCP to ``goal`` (world), or None if it collides."""
        result = self._mp.plan_screw(
            self._to_base(goal),
            np.asarray(qpos, dtype=float).copy(),
            time_step=self.time_step,
            wrt_world=False,
            **self._flags(avoid),
        )
        if result["status"] != "Success":
            return None
        path = np.asarray(result["position"])
        # mplib integrates the screw with the Jacobian and never checks where it ends:
        # it drifts by millimetres, near a singularity by centimetres. Close small gaps
        # with a local IK step; give up on large ones.
        if not self._ends_at(qpos, path[-1], goal):
            fixed = self._refine_end(qpos, path[-1], goal)
            if fixed is None:
                return None
            path = np.vstack([path, fixed])
        return ArmPath(path, "screw")

    def _refine_end(self, qpos: Array, arm_q: Array, goal: sapien.Pose) -> Array | None:
        """Waypoints from ``arm_q`` to the exact IK solution of ``goal`` next to it, or None."""
        seed = self._mp.pad_qpos(np.asarray(qpos, dtype=float).copy())
        seed[: self.n_arm] = arm_q
        index = self._mp.link_name_2_idx[self._mp.move_group]
        q, ok, _ = self._mp.pinocchio_model.compute_IK_CLIK(index, self._to_base(goal), seed)
        q = np.asarray(q)[: self.n_arm]
        if not ok or not self._mp.wrap_joint_limit(np.r_[q, seed[self.n_arm:]]):
            return None
        gap = float(np.max(np.abs(q - arm_q)))
        if gap > REFINE_MAX_RAD or not self._ends_at(qpos, q, goal):
            return None
        n = max(1, int(np.ceil(gap / REFINE_STEP_RAD)))
        return np.asarray(arm_q + np.outer(np.arange(1, n + 1) / n, q - arm_q))

    def tcp_pose(self, qpos: Array) -> sapien.Pose:
        """Forward kinematics: the TCP pose (world) at this joint configuration."""
        model = self._mp.pinocchio_model
        model.compute_forward_kinematics(self._mp.pad_qpos(np.asarray(qpos, dtype=float).copy()))
        p = model.get_link_pose(self._mp.link_name_2_idx[self._mp.move_group])
        return self._base * sapien.Pose(p[:3], p[3:])

    def _ends_at(self, qpos: Array, arm_q: Array, goal: sapien.Pose) -> bool:
        full = np.asarray(qpos, dtype=float).copy()
        full[: self.n_arm] = arm_q
        end = self.tcp_pose(full)
        pos_err = float(np.linalg.norm(np.asarray(end.p) - np.asarray(goal.p)))
        dot = abs(float(np.dot(end.q, goal.q)))
        rot_err = 2 * float(np.arccos(min(1.0, dot)))
        return pos_err <= END_POS_TOL_M and rot_err <= END_ROT_TOL_RAD

    def rrt(self, qpos: Array, goal: sapien.Pose, avoid: bool = True) -> ArmPath | None:
        """A collision-free RRT-Connect path to ``goal`` (world), or None."""
        with _quiet_native_output():
            result = self._mp.plan_qpos_to_pose(
                self._to_base(goal),
                np.asarray(qpos, dtype=float).copy(),
                time_step=self.time_step,
                planning_time=RRT_TIME_S,
                wrt_world=False,
                **self._flags(avoid),
            )
        if result["status"] != "Success":
            return None
        return ArmPath(np.asarray(result["position"]), "rrt")

    def plan(self, qpos: Array, goal: sapien.Pose, avoid: bool = True) -> ArmPath | None:
        """Screw motion if it is free and brisk, else the quicker of it and an RRT path.

        A screw motion that passes near a singularity (the arm stretched out) is slowed
        down by the time parametrisation to hundreds of steps; RRT then does better.
        """
        screw = self.screw(qpos, goal, avoid)
        if screw is not None and len(screw.qpos) <= BRISK_PATH_STEPS:
            return screw
        rrt = self.rrt(qpos, goal, avoid)
        options = [p for p in (screw, rrt) if p is not None]
        return min(options, key=lambda p: len(p.qpos)) if options else None

    def _use(self, avoid: bool) -> None:
        flags = self._flags(avoid)
        self._mp.planning_world.set_use_point_cloud(flags["use_point_cloud"])
        self._mp.planning_world.set_use_attach(flags["use_attach"])

    def reachable(self, qpos: Array, goal: sapien.Pose, avoid: bool = True) -> bool:
        """True if some joint configuration reaches ``goal`` without collision."""
        return bool(self.ik_solutions(qpos, goal, avoid))

    def ik_solutions(self, qpos: Array, goal: sapien.Pose, avoid: bool = True) -> list[Array]:
        """Distinct collision-free joint configurations (full qpos) that put the TCP at ``goal``."""
        self._use(avoid)
        status, solutions = self._mp.IK(self._to_base(goal), np.asarray(qpos, dtype=float).copy())
        return [np.asarray(q, dtype=float) for q in solutions] if status == "Success" else []

    def local_ik(self, seed: Array, goal: sapien.Pose) -> Array | None:
        """The configuration reaching ``goal`` nearest ``seed`` (full qpos), within joint limits."""
        full = self._mp.pad_qpos(np.asarray(seed, dtype=float).copy())
        index = self._mp.link_name_2_idx[self._mp.move_group]
        q, ok, _ = self._mp.pinocchio_model.compute_IK_CLIK(index, self._to_base(goal), full)
        q = np.asarray(q, dtype=float)
        if not ok or not self._mp.wrap_joint_limit(q.copy()) or not self._ends_at(full, q[: self.n_arm], goal):
            return None
        return q

    def collides(self, qpos: Array, avoid: bool = True) -> bool:
        """True if the robot at ``qpos`` touches itself or (``avoid``) the obstacles."""
        self._use(avoid)
        full = self._mp.pad_qpos(np.asarray(qpos, dtype=float).copy())
        self._mp.planning_world.set_qpos_all(full[self._mp.move_group_joint_indices])
        return bool(self._mp.planning_world.collide())

    def to_qpos(self, qpos: Array, goal_q: Array, avoid: bool = True) -> ArmPath | None:
        """A path in joint space to ``goal_q``: straight if free, else RRT-Connect."""
        start = np.asarray(qpos, dtype=float)[: self.n_arm]
        end = np.asarray(goal_q, dtype=float)[: self.n_arm]
        n = max(2, int(np.ceil(np.max(np.abs(end - start)) / JOINT_CHECK_STEP_RAD)) + 1)
        line = start + np.outer(np.linspace(0.0, 1.0, n), end - start)
        full = np.asarray(qpos, dtype=float).copy()
        free = True
        for q in line[1:]:
            full[: self.n_arm] = q
            if self.collides(full, avoid):
                free = False
                break
        if free:
            _, positions, _, _, _ = self._mp.TOPP(line, self.time_step)
            return ArmPath(np.asarray(positions), "joint")
        with _quiet_native_output():
            result = self._mp.plan_qpos_to_qpos(
                [self._mp.pad_qpos(np.asarray(goal_q, dtype=float).copy())],
                np.asarray(qpos, dtype=float).copy(),
                time_step=self.time_step,
                planning_time=RRT_TIME_S,
                **self._flags(avoid),
            )
        if result["status"] != "Success":
            return None
        return ArmPath(np.asarray(result["position"]), "rrt")
