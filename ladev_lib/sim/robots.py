"""Embodiments: where each robot stands, what it sees, how it is driven.

A :class:`RobotProfile` fixes, per robot, the world layout (robot base, table,
the workspace frame of ``SceneSpec``), the default policy camera, the initial
joint positions, control modes and frequencies, lighting, the overlay image and
episode lengths. Profiles are registered by name in :data:`ROBOTS`.

Workspace frame -> world: ``world = origin + Rz(yaw) @ [x, y, 0]``; an object's
world yaw is ``yaw + yaw_deg``. The workspace frame's x axis points away from
the robot, so one spec means the same layout for every robot.

- ``panda``: ManiSkill's Panda on ManiSkill's table (``TableSceneBuilder``
  layout: table top at z = 0, robot base at x = -0.615 facing +x). Control 20 Hz,
  sim 100 Hz (ManiSkill's defaults). The policy camera looks across the table at the
  robot (so the robot's left is on the image's right); the robot starts with its
  gripper raised above the workspace's near edge, pointing down.
- ``widowx``: SimplerEnv's Bridge "visual matching" setup: robot on the table
  top (z = 0.87) facing -x, the Bridge 3rd-view camera (Logitech C920
  intrinsics), ``bridge_real_eval_1.png`` overlay; control 5 Hz, sim 500 Hz.
- ``google_robot``: SimplerEnv's Google robot setup: static base at
  (0.35, 0.21) facing -x, head camera, ``google_move_near_real_eval_1.png``
  overlay; control 3 Hz, sim 513 Hz.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.registry import Registry
from ladev_lib.sim.geometry import look_at, quat_mul, quat_to_matrix


@dataclass(frozen=True)
class PinholeCamera:
    """A camera pose in the world and its intrinsics at a native resolution.

    ``q`` is SAPIEN's camera convention (x forward, y left, z up), wxyz.
    Asking for another image size scales the intrinsics per axis: the image is the
    native view resized, as VLA pipelines resize their camera frames.
    """

    p: tuple[float, float, float]
    q: tuple[float, float, float, float]
    native_size: tuple[int, int]  # (width, height)
    fx: float
    fy: float
    cx: float
    cy: float
    near: float = 0.01
    far: float = 10.0

    def intrinsic(self, size: tuple[int, int]) -> Array:
        sx = size[0] / self.native_size[0]
        sy = size[1] / self.native_size[1]
        return np.array(
            [[self.fx * sx, 0.0, self.cx * sx], [0.0, self.fy * sy, self.cy * sy], [0.0, 0.0, 1.0]]
        )


@dataclass(frozen=True)
class Lighting:
    """Default lighting: ambient RGB and directional lights (direction, RGB)."""

    ambient: float
    directional: tuple[tuple[tuple[float, float, float], float], ...]


@dataclass(frozen=True)
class RobotProfile:
    name: str
    agent_uid: str
    """ManiSkill agent uid (registered by ``ladev_lib.sim.agents`` for pack robots)."""
    needs_assets: bool
    base_xyz: tuple[float, float, float]
    base_yaw: float
    workspace_origin: tuple[float, float, float]
    """World position of the workspace frame's origin (on the table top)."""
    workspace_yaw: float
    table_xy: tuple[float, float]
    """World x, y of ManiSkill's table actor (its visual is centred 1.6 cm behind this)."""
    init_qpos: dict[str, float]
    control_modes: tuple[str, ...]
    """Supported control modes; the first is the default."""
    sim_freq_hz: int
    control_freq_hz: int
    policy_camera: PinholeCamera
    lighting: Lighting
    reach_m: tuple[float, float]
    """Horizontal distance from the base within which the gripper can work on the table."""
    max_episode_steps: dict[str, int]
    overlay_image: str | None = None
    """Real background (path under MS_ASSET_DIR) for SimplerEnv-style visual matching."""
    tcp_link: str = ""
    notes: str = ""

    @property
    def default_control_mode(self) -> str:
        return self.control_modes[0]

    @property
    def table_top_z(self) -> float:
        return self.workspace_origin[2]

    def workspace_to_world(self, x: float, y: float, z: float = 0.0) -> Array:
        c, s = math.cos(self.workspace_yaw), math.sin(self.workspace_yaw)
        ox, oy, oz = self.workspace_origin
        return np.array([ox + c * x - s * y, oy + s * x + c * y, oz + z])

    def world_to_workspace(self, p: Array) -> Array:
        c, s = math.cos(self.workspace_yaw), math.sin(self.workspace_yaw)
        d = np.asarray(p, dtype=float)[:3] - np.asarray(self.workspace_origin)
        return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2]])

    def workspace_vector_to_world(self, v: tuple[float, float, float]) -> Array:
        c, s = math.cos(self.workspace_yaw), math.sin(self.workspace_yaw)
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])

    def horizontal_reach(self, world_xy: Array) -> float:
        return float(np.hypot(world_xy[0] - self.base_xyz[0], world_xy[1] - self.base_xyz[1]))


# --- Panda ----------------------------------------------------------------------
_PANDA_WS = (-0.1, 0.0, 0.0)
# Across the table, facing the robot, like ManiSkill's standard Panda "base_camera" (an
# over-the-shoulder view would look through the arm). The initial joint positions hold
# the gripper 33 cm above the workspace's near edge, where it hides no object.
_PANDA_EYE = (0.25, 0.0, 0.55)
PANDA = RobotProfile(
    name="panda",
    agent_uid="panda",
    needs_assets=False,
    base_xyz=(-0.615, 0.0, 0.0),
    base_yaw=0.0,
    workspace_origin=_PANDA_WS,
    workspace_yaw=0.0,
    table_xy=(-0.12, 0.0),
    init_qpos=dict(
        zip(
            [f"panda_joint{i}" for i in range(1, 8)] + ["panda_finger_joint1", "panda_finger_joint2"],
            [0.0, -0.4, 0.0, -2.5, 0.0, 2.1, math.pi / 4, 0.04, 0.04],
            strict=True,
        )
    ),
    control_modes=(
        "pd_joint_pos",
        "pd_ee_delta_pose",
        "pd_ee_delta_pos",
        "pd_joint_delta_pos",
        "pd_ee_pose",
        "pd_ee_target_delta_pose",
        "pd_joint_vel",
    ),
    sim_freq_hz=100,
    control_freq_hz=20,
    policy_camera=PinholeCamera(
        p=_PANDA_EYE,
        q=look_at(_PANDA_EYE, _PANDA_WS),
        native_size=(512, 512),
        fx=468.9,  # 1 rad field of view
        fy=468.9,
        cx=256.0,
        cy=256.0,
    ),
    lighting=Lighting(ambient=0.3, directional=(((1, 1, -1), 1.0), ((0, 0, -1), 1.0))),
    reach_m=(0.25, 0.78),
    max_episode_steps={"pick_up": 120, "move_near": 160, "put_on": 160, "put_in": 160},
    tcp_link="panda_hand_tcp",
    notes="ManiSkill's Panda; stand-in scenes need no asset pack.",
)

# --- WidowX (Bridge) -------------------------------------------------------------
_WIDOWX_BASE = (0.147, 0.028, 0.870)
_WIDOWX_BASE_Q = (0.0, 0.0, 0.0, 1.0)  # yaw pi
_WIDOWX_CAM_LOCAL_P = (0.0, -0.16, 0.36)
_WIDOWX_CAM_LOCAL_Q = (0.8992917, -0.09263245, 0.35892478, 0.23209205)
_wx_cam_p = np.add(_WIDOWX_BASE, quat_to_matrix(_WIDOWX_BASE_Q) @ np.asarray(_WIDOWX_CAM_LOCAL_P))
WIDOWX = RobotProfile(
    name="widowx",
    agent_uid="ladev_widowx",
    needs_assets=True,
    base_xyz=_WIDOWX_BASE,
    base_yaw=math.pi,
    workspace_origin=(-0.16, 0.0, 0.870),
    workspace_yaw=math.pi,
    table_xy=(-0.317, 0.0),
    init_qpos=dict(
        zip(
            ["waist", "shoulder", "elbow", "forearm_roll", "wrist_angle", "wrist_rotate", "left_finger", "right_finger"],
            [-0.01840777, 0.0398835, 0.22242722, -0.00460194, 1.36524296, 0.00153398, 0.037, 0.037],
            strict=True,
        )
    ),
    control_modes=("arm_pd_ee_target_delta_pose_align2_gripper_pd_joint_pos", "pd_joint_pos"),
    sim_freq_hz=500,
    control_freq_hz=5,
    policy_camera=PinholeCamera(
        p=(float(_wx_cam_p[0]), float(_wx_cam_p[1]), float(_wx_cam_p[2])),
        q=quat_mul(_WIDOWX_BASE_Q, _WIDOWX_CAM_LOCAL_Q),
        native_size=(640, 480),
        fx=623.588,
        fy=623.588,
        cx=319.501,
        cy=239.545,
    ),
    lighting=Lighting(
        ambient=0.3,
        directional=(((0, 0, -1), 2.2), ((-1, -0.5, -1), 0.7), ((1, 1, -1), 0.7)),
    ),
    reach_m=(0.12, 0.52),
    max_episode_steps={"pick_up": 60, "move_near": 60, "put_on": 60, "put_in": 120},
    overlay_image="data/tasks/bridge_v2_real2sim_dataset/real_inpainting/bridge_real_eval_1.png",
    tcp_link="ee_gripper_link",
    notes="SimplerEnv Bridge flat-table setup (ManiSkill's WidowX250SBridgeDatasetFlatTable).",
)

# --- Google robot ----------------------------------------------------------------
# Head camera: SimplerEnv mounts it on link_camera with local q (0.5, 0.5, -0.5, 0.5).
# The head does not move during an episode, so the camera is fixed in the world at
# link_camera's pose for the initial joint positions below (computed with the robot's
# forward kinematics; tests/sim/test_robots.py checks it when the asset pack is present).
_GOOGLE_BASE_YAW = math.pi - 0.09
GOOGLE_ROBOT = RobotProfile(
    name="google_robot",
    agent_uid="ladev_google_robot",
    needs_assets=True,
    base_xyz=(0.35, 0.21, 0.06205 + 0.017),
    base_yaw=_GOOGLE_BASE_YAW,
    workspace_origin=(-0.235, 0.20, 0.87),
    workspace_yaw=math.pi,
    table_xy=(-0.62, 0.2),
    init_qpos={
        "joint_torso": -0.2639457174606611,
        "joint_shoulder": 0.0831913360274175,
        "joint_bicep": 0.5017611504652179,
        "joint_elbow": 1.156859026208673,
        "joint_forearm": 0.028583671314766423,
        "joint_wrist": 1.592598203487462,
        "joint_gripper": -1.080652960128774,
        "joint_finger_right": 0.0,
        "joint_finger_left": 0.0,
        "joint_head_pan": -0.00285961,
        "joint_head_tilt": 0.7851361,
    },
    control_modes=("arm_pd_ee_target_delta_pose_gripper_pd_joint_target_delta_pos", "pd_joint_pos"),
    sim_freq_hz=513,
    control_freq_hz=3,
    policy_camera=PinholeCamera(
        p=(0.2046, 0.2235, 1.2924),
        q=(0.0429, -0.3822, 0.0178, 0.9229),
        native_size=(640, 512),
        fx=425.0,
        fy=425.0,
        cx=320.0,
        cy=256.0,
    ),
    lighting=Lighting(
        ambient=0.3,
        directional=(((0, 0, -1), 2.2), ((-1, -0.5, -1), 0.7), ((1, 1, -1), 0.7)),
    ),
    reach_m=(0.3, 0.85),
    max_episode_steps={"pick_up": 80, "move_near": 80, "put_on": 80, "put_in": 80},
    overlay_image="data/tasks/bridge_v2_real2sim_dataset/real_inpainting/google_move_near_real_eval_1.png",
    tcp_link="link_gripper_tcp",
    notes="SimplerEnv google_robot_static, visual-matching base pose.",
)

ROBOTS: Registry[RobotProfile] = Registry("robot")
for _profile in (PANDA, WIDOWX, GOOGLE_ROBOT):
    ROBOTS.add(_profile.name, _profile)


def get_robot(name: str) -> RobotProfile:
    """The profile of robot ``name``; an unknown name lists the known ones."""
    return ROBOTS.get(name)


def episode_steps(robot: str, task: str, overrides: dict[str, int] | None = None) -> int:
    """Episode length in control steps for ``task`` on ``robot`` (config overrides first)."""
    if overrides and task in overrides:
        return int(overrides[task])
    return get_robot(robot).max_episode_steps[task]
