"""The policy interface: what the episode engine asks of every policy.

Before each episode the engine calls :meth:`Policy.begin_episode` (seed,
robot, action bounds; optional to implement), then the policy is reset with
the instruction, then asked for one action per control
step from an :class:`Observation`. It declares, in :class:`PolicyInfo`, the
robots it can drive, the ManiSkill control mode its actions are in, the image
size it wants, and whether it needs privileged simulator state (only
baselines such as the oracle do; a VLA sees the image, the instruction and,
optionally, proprioception).
"""

from __future__ import annotations

import abc
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ladev_lib.arrays import Array

if TYPE_CHECKING:
    from ladev_lib.scenes import SceneSpec
    from ladev_lib.sim.view import SceneView


@dataclass(frozen=True)
class PolicyInfo:
    """What a policy needs and produces."""

    name: str
    robots: tuple[str, ...]
    """Robots it can drive ("panda", "widowx", "google_robot"); the first is its default."""
    control_mode: str
    """ManiSkill controller its actions are for, e.g. "pd_joint_pos", "pd_ee_delta_pose"."""
    image_size: tuple[int, int] | None = (256, 256)
    """(width, height) of the policy-camera image it wants; None if it needs no image."""
    privileged: bool = False
    """True if it reads simulator state (object poses, the scene spec) instead of pixels."""
    control_freq_hz: float | None = None
    """Control frequency the policy was trained at; None: the simulator's default."""
    max_episode_steps: int | None = None
    """Episode length it is evaluated with; None: the task's default."""
    camera: str | None = None
    """Name of the camera it was trained with (e.g. SimplerEnv's "overhead_camera"); None: any."""
    max_episode_steps_by_task: Mapping[str, int] = field(default_factory=dict, hash=False)
    """Per-task episode lengths (task name -> steps) overriding ``max_episode_steps``."""

    def episode_steps_for(self, task: str) -> int | None:
        """The episode length for ``task``: per task if given, else ``max_episode_steps``."""
        return self.max_episode_steps_by_task.get(task, self.max_episode_steps)


@dataclass(frozen=True)
class PrivilegedState:
    """Ground truth handed to privileged policies only."""

    spec: SceneSpec
    object_poses: dict[str, Array]
    """Instance name -> world pose [x, y, z, qw, qx, qy, qz]."""
    scene: SceneView | None = None
    """A read-only view of the simulated scene (object geometry, the robot model and state),
    for planners such as the oracle; never the env itself."""


@dataclass
class Observation:
    """One step's input to a policy."""

    image: Array | None
    """(H, W, 3) uint8 RGB from the policy camera, or None if the policy wants no image."""
    proprio: Array | None = None
    """Robot state: joint positions followed by the TCP pose [x, y, z, qw, qx, qy, qz]."""
    privileged: PrivilegedState | None = None
    step: int = 0
    extras: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class EpisodeContext:
    """What the engine tells a policy before each episode, besides the instruction."""

    seed: int
    """The episode seed: a policy that samples must draw from it, so reruns match."""
    robot: str
    """The robot the episode runs with (one of ``PolicyInfo.robots``)."""
    action_low: Array
    """Lower bound of the action space of the declared control mode (may be -inf)."""
    action_high: Array
    """Upper bound of the action space (may be +inf)."""


@dataclass(frozen=True)
class PolicyStep:
    """One step's output: an action in the declared control mode, and a stop flag."""

    action: Array
    terminate: bool = False


class Policy(abc.ABC):
    """Base class of every policy. Subclasses set ``info`` and implement two methods."""

    info: PolicyInfo

    @abc.abstractmethod
    def reset(self, instruction: str) -> None:
        """Start an episode with this instruction."""

    @abc.abstractmethod
    def step(self, obs: Observation) -> PolicyStep:
        """Return the action for this observation."""

    def begin_episode(self, ctx: EpisodeContext) -> None:  # noqa: B027 - optional hook
        """Called before :meth:`reset` with the episode's seed, robot and action bounds."""

    def close(self) -> None:  # noqa: B027 - optional hook
        """Release resources (models, connections)."""

    def __enter__(self) -> Policy:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
