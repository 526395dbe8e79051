"""LADEV <-> LeRobot checkpoint mappings that need no torch (state, image, action).

Pure numpy (and PIL for resizing), so the core install tests them too; the
adapter itself (:mod:`.lerobot_policy`) runs in the LeRobot environment.

A LeRobot checkpoint declares its inputs (``observation.images.<camera>`` as
(3, H, W), ``observation.state`` as (D,)) and its output (``action`` as (D,)),
but not what the numbers mean: that is the dataset it was trained on. The
policy config says it with three names:

- ``state_layout``: which LADEV proprioception goes into ``observation.state``
  (LADEV's proprio is the robot's joint positions followed by the TCP pose
  ``[x, y, z, qw, qx, qy, qz]``);
- ``action_layout``: what the checkpoint's action vector is (an end-effector
  delta with roll-pitch-yaw or axis-angle rotation, then the gripper; or
  joint targets, passed through to a joint-position controller);
- ``gripper_convention``: how its gripper number reads (openness or
  closedness, in [0, 1] or [-1, 1]), turned into the LADEV robot's gripper
  command as :mod:`.common` does for the other adapters.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Literal

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError
from ladev_lib.policies.adapters.common import (
    EMBODIMENTS,
    Embodiment,
    StickyGripper,
    assemble_action,
    binarize_open_gripper,
    euler_to_axis_angle,
)

StateLayout = Literal["proprio", "qpos", "tcp_pose", "tcp_euler", "libero", "zeros"]
STATE_LAYOUTS: tuple[str, ...] = ("proprio", "qpos", "tcp_pose", "tcp_euler", "libero", "zeros")
ActionLayout = Literal["ee_delta_euler", "ee_delta_axis_angle", "joint_pos"]
ACTION_LAYOUTS: tuple[str, ...] = ("ee_delta_euler", "ee_delta_axis_angle", "joint_pos")
GripperConvention = Literal["open_is_1", "close_is_1", "signed_open", "signed_close"]
GRIPPER_CONVENTIONS: tuple[str, ...] = ("open_is_1", "close_is_1", "signed_open", "signed_close")

TCP_POSE_DIM = 7
"""LADEV's proprio ends with the TCP pose [x, y, z, qw, qx, qy, qz]."""

# LeRobot's LIBERO checkpoints (SmolVLA, pi0, pi0.5) were trained on a Franka Panda
# with an end-effector delta controller at 20 Hz; LADEV's Panda has ManiSkill's.
PANDA_EMBODIMENT = Embodiment(
    robot="panda",
    control_mode="pd_ee_delta_pose",
    camera="policy_camera",
    image_size=(256, 256),
    control_freq_hz=20.0,
    default_episode_steps=120,
    episode_steps={"pick_up": 120, "move_near": 160, "put_on": 160, "put_in": 160},
    gripper="absolute",
    sticky_gripper_steps=1,
    dataset_key="libero",
)

LEROBOT_EMBODIMENTS: dict[str, Embodiment] = {**EMBODIMENTS, "panda": PANDA_EMBODIMENT}
"""Robots a LeRobot checkpoint can drive: SimplerEnv's two and LADEV's Panda."""


def _choice(value: str, options: tuple[str, ...], what: str) -> str:
    if value not in options:
        raise ConfigError(f"lerobot {what} must be one of {list(options)}, got {value!r}")
    return value


# --------------------------------------------------------------------------- state


def quat_to_euler(wxyz: Array) -> Array:
    """Roll-pitch-yaw of a unit quaternion (w, x, y, z), with R = Rz(yaw) Ry(pitch) Rx(roll).

    The static-axes "sxyz" convention of :func:`.common.euler_to_axis_angle`
    (Bridge, Fractal and LIBERO's roll-pitch-yaw).
    """
    w, x, y, z = (float(v) for v in np.asarray(wxyz, dtype=np.float64).reshape(4))
    n = math.sqrt(w * w + x * x + y * y + z * z)
    if n < 1e-12:
        raise ValueError("quat_to_euler: zero quaternion")
    w, x, y, z = w / n, x / n, y / n, z / n
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return np.array([roll, pitch, yaw])


def quat_to_axis_angle(wxyz: Array) -> Array:
    """Axis-angle vector (axis * angle, angle in [0, pi]) of a quaternion (w, x, y, z)."""
    q = np.asarray(wxyz, dtype=np.float64).reshape(4)
    q = q / np.linalg.norm(q)
    if q[0] < 0:  # the same rotation with the angle in [0, pi]
        q = -q
    sin_half = float(np.linalg.norm(q[1:]))
    if sin_half < 1e-12:
        return np.zeros(3)
    angle = 2.0 * math.atan2(sin_half, float(q[0]))
    result: Array = q[1:] / sin_half * angle
    return result


def state_vector(proprio: Array | None, layout: str, dim: int, feature: str) -> Array:
    """The checkpoint's ``feature`` (shape (dim,)) from LADEV's proprio, in ``layout``.

    proprio (qpos of n joints, then the TCP pose xyz + wxyz), tcp_pose (the last
    7), tcp_euler (xyz + roll-pitch-yaw), qpos (the joints), libero (LIBERO's
    8 values: TCP xyz, its orientation as axis-angle, the two gripper finger
    joints, which are the last two joints of LADEV's Panda), zeros (the
    checkpoint's state is not one LADEV can give: a constant, said so in the config).
    """
    _choice(layout, STATE_LAYOUTS, "state_layout")
    if layout == "zeros":
        return np.zeros(dim, dtype=np.float32)
    if proprio is None:
        raise ValueError(
            f"the checkpoint expects {feature!r} but the observation carries no proprioception"
        )
    p = np.asarray(proprio, dtype=np.float64).reshape(-1)
    if p.shape[0] < TCP_POSE_DIM:
        raise ValueError(f"proprio has {p.shape[0]} values; expected joints then a 7-value TCP pose")
    tcp = p[-TCP_POSE_DIM:]
    if layout == "proprio":
        out = p
    elif layout == "qpos":
        out = p[:-TCP_POSE_DIM]
    elif layout == "tcp_pose":
        out = tcp
    elif layout == "libero":
        out = np.concatenate([tcp[:3], quat_to_axis_angle(tcp[3:]), p[:-TCP_POSE_DIM][-2:]])
    else:  # tcp_euler
        out = np.concatenate([tcp[:3], quat_to_euler(tcp[3:])])
    if out.shape[0] != dim:
        raise ValueError(
            f"the checkpoint's {feature!r} has {dim} values; state_layout {layout!r} gives "
            f"{out.shape[0]} for this robot (options: {list(STATE_LAYOUTS)})"
        )
    return out.astype(np.float32)


# --------------------------------------------------------------------------- image


def fit_image(image: Array, shape: tuple[int, ...]) -> Array:
    """The (H, W, 3) uint8 camera image at the (3, H, W) size a visual feature declares."""
    from PIL import Image

    if len(shape) != 3 or shape[0] != 3:
        raise ValueError(f"expected a (3, H, W) visual feature, got shape {tuple(shape)}")
    height, width = int(shape[1]), int(shape[2])
    if image.shape[:2] == (height, width):
        return np.array(image, dtype=np.uint8)  # a writable copy: torch wraps it as is
    resized = Image.fromarray(image).resize((width, height), Image.Resampling.BILINEAR)
    return np.array(resized, dtype=np.uint8)


# --------------------------------------------------------------------------- action


def openness(value: float, convention: str) -> float:
    """The gripper number in ``convention`` as openness in [0, 1] (1 = fully open)."""
    _choice(convention, GRIPPER_CONVENTIONS, "gripper_convention")
    g = float(value)
    if convention == "open_is_1":
        return g
    if convention == "close_is_1":
        return 1.0 - g
    if convention == "signed_open":
        return (g + 1.0) / 2.0
    return (1.0 - g) / 2.0  # signed_close: +1 close, -1 open (LIBERO)


class ActionMapper:
    """The checkpoint's action vector -> the LADEV robot's controller action.

    ee_delta_euler / ee_delta_axis_angle: ``[dx, dy, dz, rotation (3), gripper]``
    -> :mod:`.common`'s 7-vector (axis-angle rotation; translation times
    ``action_scale``, rotation times ``rotation_scale`` (default: the same),
    for a checkpoint whose controller had other units; the gripper as the
    robot takes it: a relative command held for a few steps on the Google
    robot, a binary +1 open / -1 close target on WidowX and the Panda).
    Extra entries (padded action dimensions) are ignored. joint_pos: the vector
    as is, for a joint-position controller (set ``control_mode``).
    """

    def __init__(
        self,
        emb: Embodiment,
        layout: str = "ee_delta_euler",
        gripper_convention: str = "open_is_1",
        action_scale: float = 1.0,
        rotation_scale: float | None = None,
    ) -> None:
        self.emb = emb
        self.layout = _choice(layout, ACTION_LAYOUTS, "action_layout")
        self.gripper_convention = _choice(gripper_convention, GRIPPER_CONVENTIONS, "gripper_convention")
        self.action_scale = float(action_scale)
        self.rotation_scale = self.action_scale if rotation_scale is None else float(rotation_scale)
        self.sticky = StickyGripper(emb.sticky_gripper_steps)

    def reset(self) -> None:
        self.sticky.reset()

    def __call__(self, raw: Array) -> Array:
        a = np.asarray(raw, dtype=np.float64).reshape(-1)
        if self.layout == "joint_pos":
            return a.copy()
        if a.shape[0] < 7:
            raise ValueError(
                f"action_layout {self.layout!r} needs >= 7 action values "
                f"[xyz, rotation, gripper], the checkpoint gave {a.shape[0]}"
            )
        rot = euler_to_axis_angle(*a[3:6]) if self.layout == "ee_delta_euler" else a[3:6]
        open_amount = openness(a[6], self.gripper_convention)
        if self.emb.gripper == "relative":
            gripper = self.sticky(open_amount)
        else:
            gripper = binarize_open_gripper(open_amount)
        out = assemble_action(a[:3], rot, gripper, self.action_scale)
        out[3:6] = np.asarray(rot, dtype=np.float64) * self.rotation_scale
        return out


def describe_features(features: Mapping[str, tuple[str, tuple[int, ...]]]) -> str:
    """``name (TYPE, shape)`` list, for error messages."""
    return ", ".join(f"{k} ({t}, {tuple(s)})" for k, (t, s) in sorted(features.items())) or "none"
