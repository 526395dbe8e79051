"""Pre- and post-processing the VLA adapters share, per embodiment, as SimplerEnv does it.

Pure numpy (no TensorFlow, JAX or torch), so it is importable and testable in
the core install and in every adapter environment.

The action every adapter returns is SimplerEnv's 7-vector for an end-effector
delta-pose controller: ``[dx, dy, dz, rx, ry, rz, gripper]`` with the rotation
as an axis-angle vector (axis * angle). The gripper entry depends on the robot:

- Google robot: a *relative* command in [-1, 1] (1 = close, -1 = open), for a
  target-delta gripper (SimplerEnv's ``gripper_pd_joint_target_delta_pos_interpolate_by_planner``;
  LADEV's Google robot has the same controller without the planner interpolation,
  which has no ManiSkill 3 counterpart);
- WidowX: an *absolute* target, binarised to +1 (open) or -1 (close), for
  ``gripper_pd_joint_pos``.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError
from ladev_lib.policies.base import PolicyInfo

# The controllers of LADEV's robots (ladev_lib/sim/robots.py) that take SimplerEnv's
# end-effector delta actions. Kept as strings here so this module needs no simulator;
# tests/sim/test_vla_embodiments.py checks that the simulator offers them.
GOOGLE_ROBOT_CONTROL_MODE = "arm_pd_ee_target_delta_pose_gripper_pd_joint_target_delta_pos"
WIDOWX_CONTROL_MODE = "arm_pd_ee_target_delta_pose_align2_gripper_pd_joint_pos"

ACTION_DIM = 7
"""[dx, dy, dz, axis-angle (3), gripper]."""


@dataclass(frozen=True)
class Embodiment:
    """How SimplerEnv evaluates a policy on one robot."""

    robot: str
    """LADEV robot name (``conf/robot``)."""
    control_mode: str
    """The ManiSkill controller the 7-vector action is for."""
    camera: str
    """The policy camera (SimplerEnv's name)."""
    image_size: tuple[int, int]
    """(width, height) that camera renders at; adapters resize themselves."""
    control_freq_hz: float
    default_episode_steps: int
    episode_steps: Mapping[str, int]
    """Episode length per LADEV task, as SimplerEnv's scripts set it."""
    gripper: Literal["relative", "absolute"]
    sticky_gripper_steps: int
    """How many steps a relative gripper command is repeated (Octo, OpenVLA)."""
    dataset_key: str
    """Open X-Embodiment dataset whose action statistics unnormalise actions here."""


EMBODIMENTS: dict[str, Embodiment] = {
    "google_robot": Embodiment(
        robot="google_robot",
        control_mode=GOOGLE_ROBOT_CONTROL_MODE,
        camera="overhead_camera",
        image_size=(640, 512),
        control_freq_hz=3.0,
        default_episode_steps=80,
        episode_steps={"pick_up": 80, "move_near": 80},
        gripper="relative",
        sticky_gripper_steps=15,
        dataset_key="fractal20220817_data",
    ),
    "widowx": Embodiment(
        robot="widowx",
        control_mode=WIDOWX_CONTROL_MODE,
        camera="3rd_view_camera",
        image_size=(640, 480),
        control_freq_hz=5.0,
        default_episode_steps=60,
        episode_steps={"put_on": 60, "put_in": 120},
        gripper="absolute",
        sticky_gripper_steps=1,
        dataset_key="bridge_dataset",
    ),
}


OVERRIDABLE = ("control_mode", "camera", "image_size", "control_freq_hz", "episode_steps")


def embodiment(
    robot: str,
    overrides: Mapping[str, Mapping[str, Any]] | None = None,
    table: Mapping[str, Embodiment] | None = None,
) -> Embodiment:
    """SimplerEnv's settings for ``robot``, with ``overrides[robot]`` applied.

    ``overrides`` is the ``embodiments`` entry of a policy config: per robot,
    any of control_mode, camera, image_size, control_freq_hz, episode_steps
    (task -> steps). Settings for other robots are ignored, so one config can
    name both robots and be switched with ``robot=...``. ``table``: the robots
    an adapter supports (default :data:`EMBODIMENTS`).
    """
    known = EMBODIMENTS if table is None else table
    try:
        base = known[robot]
    except KeyError:
        raise ConfigError(
            f"VLA adapters support robots {sorted(known)}, not {robot!r}"
        ) from None
    changes = dict((overrides or {}).get(robot) or {})
    unknown = sorted(set(changes) - set(OVERRIDABLE))
    if unknown:
        raise ConfigError(
            f"embodiments.{robot}: unknown setting(s) {unknown}; allowed: {list(OVERRIDABLE)}"
        )
    if "image_size" in changes:
        changes["image_size"] = tuple(int(v) for v in changes["image_size"])
    if "episode_steps" in changes:
        changes["episode_steps"] = {str(k): int(v) for k, v in changes["episode_steps"].items()}
    if "control_freq_hz" in changes:
        changes["control_freq_hz"] = float(changes["control_freq_hz"])
    return dataclasses.replace(base, **changes)


def policy_info(name: str, emb: Embodiment) -> PolicyInfo:
    """The :class:`PolicyInfo` of a VLA adapter driving ``emb``."""
    return PolicyInfo(
        name=name,
        robots=(emb.robot,),
        control_mode=emb.control_mode,
        image_size=emb.image_size,
        privileged=False,
        control_freq_hz=emb.control_freq_hz,
        max_episode_steps=emb.default_episode_steps,
        camera=emb.camera,
        max_episode_steps_by_task=dict(emb.episode_steps),
    )


def require_image(image: Array | None, who: str) -> Array:
    """The observation image as (H, W, 3) uint8, or an error naming what is wrong."""
    if image is None:
        raise ValueError(f"{who} needs an RGB image in the observation (got None)")
    arr = np.asarray(image)
    if arr.ndim != 3 or arr.shape[2] != 3 or arr.dtype != np.uint8:
        raise ValueError(f"{who} needs an (H, W, 3) uint8 image, got {arr.shape} {arr.dtype}")
    return arr


# --------------------------------------------------------------------------- rotations


def euler_to_axis_angle(roll: float, pitch: float, yaw: float) -> Array:
    """Axis-angle vector of the rotation R = Rz(yaw) @ Ry(pitch) @ Rx(roll).

    That is the static-axes "sxyz" convention (transforms3d's ``euler2axangle``
    default) the Bridge and Fractal datasets use for their rotation deltas.
    The angle is in [0, pi].
    """
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    w = cr * cp * cy + sr * sp * sy
    x = sr * cp * cy - cr * sp * sy
    y = cr * sp * cy + sr * cp * sy
    z = cr * cp * sy - sr * sp * cy
    if w < 0:  # the same rotation with the angle in [0, pi]
        w, x, y, z = -w, -x, -y, -z
    vec_norm = math.sqrt(x * x + y * y + z * z)
    if vec_norm < 1e-12:
        return np.zeros(3)
    angle = 2.0 * math.atan2(vec_norm, w)
    return np.array([x, y, z]) / vec_norm * angle


# --------------------------------------------------------------------------- normalisation


def rescale_with_bounds(
    x: Array, low: float, high: float, out_low: float, out_high: float
) -> Array:
    """Map [low, high] linearly onto [out_low, out_high] and clip (RT-1-X on Bridge)."""
    y = (np.asarray(x, dtype=np.float64) - low) / (high - low) * (out_high - out_low) + out_low
    return np.clip(y, out_low, out_high)


def _mask(stats: Mapping[str, Sequence[float] | Array], dim: int) -> Array:
    raw = stats.get("mask")
    return np.ones(dim, dtype=bool) if raw is None else np.asarray(raw, dtype=bool)[:dim]


def unnormalize_gaussian(
    action: Array, stats: Mapping[str, Sequence[float] | Array], use_mask: bool = True
) -> Array:
    """``action * std + mean`` (Octo), where ``stats["mask"]`` is true if ``use_mask``.

    Octo's own ``sample_actions`` honours the mask (the gripper is not
    normalised in training); SimplerEnv's Octo policy unnormalises all dims.
    """
    a = np.asarray(action, dtype=np.float64)
    d = a.shape[-1]
    mean = np.asarray(stats["mean"], dtype=np.float64)[:d]
    std = np.asarray(stats["std"], dtype=np.float64)[:d]
    mask = _mask(stats, d) if use_mask else np.ones(d, dtype=bool)
    return np.where(mask, a * std + mean, a)


def unnormalize_bounds(
    action: Array, stats: Mapping[str, Sequence[float] | Array]
) -> Array:
    """Map [-1, 1] onto [q01, q99] where the mask is true (OpenVLA's BOUNDS_Q99)."""
    a = np.asarray(action, dtype=np.float64)
    d = a.shape[-1]
    low = np.asarray(stats["q01"], dtype=np.float64)[:d]
    high = np.asarray(stats["q99"], dtype=np.float64)[:d]
    return np.where(_mask(stats, d), 0.5 * (a + 1.0) * (high - low) + low, a)


# --------------------------------------------------------------------------- chunks


@dataclass
class ActionEnsembler:
    """Temporal ensembling of action chunks (SimplerEnv's Octo setting).

    Each step the model predicts ``horizon`` future actions. The action for
    the current step averages the current chunk's first action with what the
    previous ``horizon - 1`` chunks predicted for this same step, weighted
    ``exp(-temperature * i)`` with i = 0 for the oldest prediction.
    """

    horizon: int
    temperature: float = 0.0
    _history: deque[Array] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if self.horizon < 1:
            raise ValueError(f"ensemble horizon must be >= 1, got {self.horizon}")
        self._history = deque(maxlen=self.horizon)

    def reset(self) -> None:
        self._history.clear()

    def __call__(self, chunk: Array) -> Array:
        chunk = np.asarray(chunk, dtype=np.float64)
        if chunk.ndim != 2 or chunk.shape[0] < self.horizon:
            raise ValueError(
                f"expected an action chunk of shape (>= {self.horizon}, D), got {chunk.shape}"
            )
        self._history.append(chunk)
        n = len(self._history)
        # The oldest chunk in the window predicted this step n - 1 steps ahead.
        preds = np.stack([c[n - 1 - i] for i, c in enumerate(self._history)])
        weights = np.exp(-self.temperature * np.arange(n))
        weights /= weights.sum()
        result: Array = (weights[:, None] * preds).sum(axis=0)
        return result


# --------------------------------------------------------------------------- gripper


@dataclass
class StickyGripper:
    """Relative gripper command with repeats (SimplerEnv's Octo/OpenVLA on the Google robot).

    The model predicts how open the gripper should be (1 open, 0 closed). The
    Google robot's controller takes a change instead (1 close, -1 open): the
    previous prediction minus the current one. A change larger than 0.5 is
    held for ``repeat`` steps, because one control step is too short for the
    gripper to finish closing.
    """

    repeat: int
    _previous: float | None = field(default=None, init=False)
    _sticky_on: bool = field(default=False, init=False)
    _sticky_value: float = field(default=0.0, init=False)
    _count: int = field(default=0, init=False)

    def reset(self) -> None:
        self._previous = None
        self._sticky_on = False
        self._sticky_value = 0.0
        self._count = 0

    def __call__(self, open_amount: float) -> float:
        current = float(open_amount)
        relative = 0.0 if self._previous is None else self._previous - current
        self._previous = current
        if abs(relative) > 0.5 and not self._sticky_on:
            self._sticky_on = True
            self._sticky_value = relative
        if self._sticky_on:
            self._count += 1
            relative = self._sticky_value
        if self._count == self.repeat:
            self._sticky_on = False
            self._count = 0
            self._sticky_value = 0.0
        return relative


def binarize_open_gripper(open_amount: float, threshold: float = 0.5) -> float:
    """+1 (open) if the predicted openness exceeds ``threshold``, else -1 (close)."""
    return 1.0 if float(open_amount) > threshold else -1.0


# --------------------------------------------------------------------------- assembly


def assemble_action(
    world_vector: Array, rot_axangle: Array, gripper: float, scale: float = 1.0
) -> Array:
    """The controller's 7-vector: translation and rotation scaled, gripper as is."""
    out = np.empty(ACTION_DIM, dtype=np.float64)
    out[:3] = np.asarray(world_vector, dtype=np.float64).reshape(3) * scale
    out[3:6] = np.asarray(rot_axangle, dtype=np.float64).reshape(3) * scale
    out[6] = gripper
    return out


# SimplerEnv's Bridge rescaling of RT-1-X outputs (its training-time action bounds).
RT1_BRIDGE_WORLD_VECTOR = (-1.75, 1.75, -0.05, 0.05)
RT1_BRIDGE_ROTATION = (-1.4, 1.4, -0.25, 0.25)
RT1_SMALL_GRIPPER = 1e-2


def postprocess_rt1(
    raw: Mapping[str, Array], emb: Embodiment, action_scale: float = 1.0
) -> Array:
    """RT-1's action dict -> the controller's 7-vector (SimplerEnv's ``rt1_model.py``).

    Google robot: the rotation delta is an axis-angle vector already (Fractal)
    and the gripper command is relative as predicted, with |g| < 0.01 zeroed.
    WidowX (RT-1-X): translation and rotation rescaled to Bridge's bounds, the
    rotation is roll-pitch-yaw, and the gripper closedness (1 = close) is
    inverted and binarised to WidowX's open (+1) / close (-1).
    """
    world = np.asarray(raw["world_vector"], dtype=np.float64).reshape(3)
    rotation = np.asarray(raw["rotation_delta"], dtype=np.float64).reshape(3)
    closedness = float(np.asarray(raw["gripper_closedness_action"]).reshape(-1)[0])
    if emb.gripper == "relative":
        gripper = 0.0 if abs(closedness) < RT1_SMALL_GRIPPER else closedness
        return assemble_action(world, rotation, gripper, action_scale)
    world = rescale_with_bounds(world, *RT1_BRIDGE_WORLD_VECTOR)
    roll, pitch, yaw = rescale_with_bounds(rotation, *RT1_BRIDGE_ROTATION)
    gripper = binarize_open_gripper(-closedness, threshold=0.0)
    return assemble_action(world, euler_to_axis_angle(roll, pitch, yaw), gripper, action_scale)


class EulerOpenGripperPostprocessor:
    """Octo and OpenVLA: [xyz, roll-pitch-yaw, openness] -> the controller's 7-vector.

    Holds the per-episode gripper state; call :meth:`reset` at each episode.
    """

    def __init__(self, emb: Embodiment, action_scale: float = 1.0) -> None:
        self.emb = emb
        self.action_scale = action_scale
        self.sticky = StickyGripper(emb.sticky_gripper_steps)

    def reset(self) -> None:
        self.sticky.reset()

    def __call__(self, raw: Array) -> Array:
        raw = np.asarray(raw, dtype=np.float64).reshape(-1)
        if raw.shape[0] < ACTION_DIM:
            raise ValueError(f"expected a 7-dim raw action, got shape {raw.shape}")
        rot = euler_to_axis_angle(raw[3], raw[4], raw[5])
        if self.emb.gripper == "relative":
            gripper = self.sticky(raw[6])
        else:
            gripper = binarize_open_gripper(raw[6])
        return assemble_action(raw[:3], rot, gripper, self.action_scale)
