"""ManiSkill agents for the embodiments whose descriptions live in the asset pack.

ManiSkill resolves ``urdf_path`` from its own ``ASSET_DIR``, fixed when mani_skill is
imported, and *exits the process* when the file is missing. These agents read
``MS_ASSET_DIR`` when the robot is built instead (``ladev_lib.assets``), and
``ladev_lib.sim.robots`` checks the file exists before any agent is created.

- :class:`LadevWidowX`: ManiSkill's real2sim-tuned Bridge WidowX 250 S (SimplerEnv's
  PD gains and its ``arm_pd_ee_target_delta_pose_align2_gripper_pd_joint_pos``
  controller), plus a ``pd_joint_pos`` mode for planners.
- :class:`LadevGoogleRobot`: the static-base Google robot (RT-1's embodiment) from
  the pack's ``fix_wheel`` URDF, with SimplerEnv's PD gains, its
  end-effector-delta arm controller and delta gripper controller. SimplerEnv's
  "interpolate_by_planner" smoothing has no ManiSkill 3 counterpart; the
  controller here tracks the delta target directly.
"""

from __future__ import annotations

import hashlib
import os
import re
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import torch
from mani_skill.agents.base_agent import BaseAgent
from mani_skill.agents.controllers.pd_ee_pose import PDEEPoseControllerConfig
from mani_skill.agents.controllers.pd_joint_pos import (
    PDJointPosControllerConfig,
    PDJointPosMimicControllerConfig,
)
from mani_skill.agents.registration import register_agent
from mani_skill.envs.tasks.digital_twins.bridge_dataset_eval.base_env import (
    WidowX250SBridgeDatasetFlatTable,
)
from mani_skill.utils import common
from mani_skill.utils.structs.actor import Actor

from ladev_lib.assets import ROBOT_URDFS, asset_dir


def robot_urdf(robot: str) -> str:
    """Absolute URDF path of an asset-pack robot; a clear error when it is absent."""
    from ladev_lib.errors import ConfigError

    root = asset_dir()
    rel = ROBOT_URDFS[robot]
    if root is None or not (root / rel).exists():
        where = f"{root / rel}" if root else "MS_ASSET_DIR (not set)"
        raise ConfigError(
            f"robot {robot!r} needs its description from the asset pack, not found at {where}; "
            "set MS_ASSET_DIR to the asset pack (see ladev doctor) or use robot 'panda'"
        )
    return str(root / rel)


def kinematics_urdf(urdf: str) -> str:
    """A copy of ``urdf`` that the IK solver (Pinocchio's URDF parser) accepts.

    The Google robot's URDF gives its (fixed) wheel joints ``lower="-inf"`` limits, which
    Pinocchio rejects; the copy writes them as +-1e6. Only the end-effector controller
    reads the copy; the simulated robot is built from the original file.
    """
    text = Path(urdf).read_text(encoding="utf-8")
    fixed = re.sub(r'"\s*-inf\s*"', '"-1e6"', re.sub(r'"\s*\+?inf\s*"', '"1e6"', text))
    if fixed == text:
        return urdf
    digest = hashlib.sha256(fixed.encode()).hexdigest()[:12]
    out = Path(tempfile.gettempdir()) / "ladev-kinematics" / f"{Path(urdf).stem}-{digest}.urdf"
    if not out.exists():
        out.parent.mkdir(parents=True, exist_ok=True)
        tmp = out.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(fixed, encoding="utf-8")
        tmp.replace(out)  # atomic: parallel workers may race here
    return str(out)


@register_agent(override=True)
class LadevWidowX(WidowX250SBridgeDatasetFlatTable):
    uid = "ladev_widowx"

    @property
    def urdf_path(self) -> str:
        return robot_urdf("widowx")

    @property
    def _sensor_configs(self) -> list[Any]:
        return []  # the scene env owns the policy camera

    @property
    def _controller_configs(self) -> dict[str, Any]:
        configs: dict[str, Any] = dict(super()._controller_configs)
        gripper = configs["arm_pd_ee_target_delta_pose_align2_gripper_pd_joint_pos"]["gripper"]
        arm_joint_pos = PDJointPosControllerConfig(
            self.arm_joint_names,
            lower=None,
            upper=None,
            stiffness=self.arm_stiffness,
            damping=self.arm_damping,
            force_limit=self.arm_force_limit,
            normalize_action=False,
        )
        configs["pd_joint_pos"] = dict(arm=arm_joint_pos, gripper=gripper)
        return configs


# SimplerEnv's google_robot_static PD gains (arm joints in this order).
_GOOGLE_ARM_JOINTS = [
    "joint_torso",
    "joint_shoulder",
    "joint_bicep",
    "joint_elbow",
    "joint_forearm",
    "joint_wrist",
    "joint_gripper",
]
_GOOGLE_ARM_STIFFNESS = [1700.0, 1737.05, 979.98, 930.0, 1212.15, 432.97, 468.0]
_GOOGLE_ARM_DAMPING = [1059.98, 1010.47, 767.28, 680.0, 674.99, 274.61, 340.53]
_GOOGLE_ARM_FORCE = [300, 300, 100, 100, 100, 100, 100]
_GOOGLE_HEAD_JOINTS = ["joint_head_pan", "joint_head_tilt"]
_GOOGLE_FINGER_JOINTS = ["joint_finger_right", "joint_finger_left"]


@register_agent(override=True)
class LadevGoogleRobot(BaseAgent):
    """Static-base Google robot; the head is held by stiff drives, not by a controller."""

    uid = "ladev_google_robot"
    urdf_config = dict(
        _materials=dict(
            finger=dict(static_friction=2.0, dynamic_friction=2.0, restitution=0.0),
            nail=dict(static_friction=0.1, dynamic_friction=0.1, restitution=0.0),
        ),
        link=dict(
            link_finger_left=dict(material="finger", patch_radius=0.1, min_patch_radius=0.1),
            link_finger_right=dict(material="finger", patch_radius=0.1, min_patch_radius=0.1),
            link_finger_tip_left=dict(material="finger", patch_radius=0.1, min_patch_radius=0.1),
            link_finger_tip_right=dict(material="finger", patch_radius=0.1, min_patch_radius=0.1),
            link_finger_nail_left=dict(material="nail", patch_radius=0.01, min_patch_radius=0.01),
            link_finger_nail_right=dict(material="nail", patch_radius=0.01, min_patch_radius=0.01),
        ),
    )
    ee_link_name = "link_gripper_tcp"

    @property
    def urdf_path(self) -> str:
        return robot_urdf("google_robot")

    @property
    def _controller_configs(self) -> dict[str, Any]:
        common_kwargs = dict(
            stiffness=_GOOGLE_ARM_STIFFNESS,
            damping=_GOOGLE_ARM_DAMPING,
            force_limit=_GOOGLE_ARM_FORCE,
            friction=0.0,
        )
        arm_ee_delta = PDEEPoseControllerConfig(
            _GOOGLE_ARM_JOINTS,
            pos_lower=-1.0,  # unused: normalize_action=False
            pos_upper=1.0,
            rot_lower=-np.pi / 2,
            rot_upper=np.pi / 2,
            ee_link=self.ee_link_name,
            urdf_path=kinematics_urdf(self.urdf_path),
            use_target=True,
            normalize_action=False,
            **common_kwargs,
        )
        arm_joint_pos = PDJointPosControllerConfig(
            _GOOGLE_ARM_JOINTS, lower=None, upper=None, normalize_action=False, **common_kwargs
        )
        gripper_args: dict[str, Any] = dict(
            lower=-1.3 - 0.01,
            upper=1.3 + 0.01,
            stiffness=200,
            damping=8,
            force_limit=60,
            normalize_action=True,
            mimic={"joint_finger_left": {"joint": "joint_finger_right"}},
        )
        gripper_delta = PDJointPosMimicControllerConfig(
            _GOOGLE_FINGER_JOINTS, use_delta=True, use_target=True, **gripper_args
        )
        gripper_pos = PDJointPosMimicControllerConfig(_GOOGLE_FINGER_JOINTS, **gripper_args)
        return dict(
            arm_pd_ee_target_delta_pose_gripper_pd_joint_target_delta_pos=dict(
                arm=arm_ee_delta, gripper=gripper_delta
            ),
            pd_joint_pos=dict(arm=arm_joint_pos, gripper=gripper_pos),
        )

    def _after_init(self) -> None:
        self.tcp = self.robot.links_map[self.ee_link_name]
        self.finger_links = {
            side: [self.robot.links_map[f"link_finger_{side}"], self.robot.links_map[f"link_finger_tip_{side}"]]
            for side in ("left", "right")
        }
        # No controller drives the head; without drives it would sag under gravity.
        for name in _GOOGLE_HEAD_JOINTS:
            self.robot.joints_map[name].set_drive_properties(stiffness=2000, damping=900, force_limit=100)

    def hold_head(self, qpos: dict[str, float]) -> None:
        for name in _GOOGLE_HEAD_JOINTS:
            self.robot.joints_map[name].set_drive_target(torch.tensor([qpos[name]]))

    def is_grasping(self, obj: Actor, min_force: float = 0.5, max_angle: float = 80) -> torch.Tensor:
        """Both fingers (or their tips) push the object from inside the grip (SimplerEnv's check)."""
        flags = []
        for side in ("left", "right"):
            side_ok = torch.zeros(1, dtype=torch.bool)
            for link in self.finger_links[side]:
                forces = self.scene.get_pairwise_contact_forces(link, obj)
                opening = link.pose.to_transformation_matrix()[..., :3, 1]
                angle = common.compute_angle_between(opening, forces)
                ok = (torch.linalg.norm(forces, dim=1) >= min_force) & (torch.rad2deg(angle) <= max_angle)
                side_ok = side_ok | ok.cpu()
            flags.append(side_ok)
        return flags[0] & flags[1]
