"""What crosses the process boundary: a job to run, the outcome that comes back.

:class:`EpisodeJob` is what a worker needs to run one episode; the study
metadata of the episode (factor, level, ...) stays with the engine.
:class:`EpisodeOutcome` is what an episode produced; it is the value kept in
the episode store (JSON, versioned), so it holds nothing that depends on the
study an episode was planned for: the same episode in two studies is run once.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.rollout.config import VideoMode
from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.vocabulary import EpisodeStatus

if TYPE_CHECKING:
    from ladev_lib.policies.base import Policy
    from ladev_lib.rollout.simulator import EpisodeSim, SimSetup


@dataclass(frozen=True)
class EpisodeJob:
    """One episode to run: the scene, the instruction, the seed and its content id."""

    episode_id: str
    spec: SceneSpec
    """The scene, parsed once (by the planner) and handed to the worker as the typed object."""
    instruction: str
    seed: int
    stop_on_success: bool = False
    """End the episode at the first step the task holds (SimplerEnv runs to the step limit)."""


class EpisodeOutcome(BaseModel):
    """What one episode produced (the episode store's value)."""

    model_config = ConfigDict(extra="forbid")

    schema_version: Literal[2] = 2
    status: EpisodeStatus
    success: bool | None = Field(description="Success at the final step; null for error and invalid_scene.")
    success_any: bool | None = Field(default=None, description="Success at any step; null as above.")
    first_success_step: int | None = Field(default=None, description="First step (1-based) the task held.")
    predicates: dict[str, bool] = Field(default_factory=dict)
    steps: int = 0
    robot: str
    sim_seconds: float = 0.0
    policy_seconds: float = 0.0
    total_seconds: float = 0.0
    host: str = Field(default="", description="Machine that ran the episode (for the timings table only).")
    error: str | None = None
    video_path: str | None = None
    first_frame_path: str | None = None
    last_frame_path: str | None = None

    def predicates_json(self) -> str:
        return json.dumps(self.predicates, sort_keys=True)

    @classmethod
    def failed(cls, status: EpisodeStatus, robot: str, reason: str, **timing: Any) -> EpisodeOutcome:
        """An ``error`` or ``invalid_scene`` outcome with its reason."""
        return cls(status=status, success=None, robot=robot, error=reason, **timing)


@dataclass(frozen=True)
class MediaOptions:
    """Where and what an episode writes besides its outcome."""

    root: str
    """Absolute directory for this policy's media."""
    prefix: str
    """How the directory is written in the table (relative to the repository)."""
    video: VideoMode = "none"
    frames: bool = True
    fps: int = 10

    @property
    def needs_camera(self) -> bool:
        return self.video != "none" or self.frames


def _default_sim_factory() -> Callable[[SimSetup], EpisodeSim]:
    from ladev_lib.rollout.simulator import make_maniskill_sim

    return make_maniskill_sim


@dataclass(frozen=True)
class WorkerSpec:
    """Everything a worker process needs to build its policy and simulator (picklable)."""

    policy_name: str
    policy_config: dict[str, Any]
    sim_config: dict[str, Any]
    robot_config: dict[str, Any]
    media: MediaOptions
    step_timeout_s: float = 120.0
    setup_timeout_s: float = 900.0
    thread_env: dict[str, str] = field(
        default_factory=lambda: {"LP_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    )
    """Environment set in each worker before anything heavy loads: one thread per worker."""
    sim_factory: Callable[[SimSetup], EpisodeSim] | None = None
    """Module-level callable building the simulator; None: the LADEV ManiSkill env."""
    policy_factory: Callable[..., Policy] | None = None
    """Module-level callable building the policy; None: the registry entry ``policy_name``."""
    robot_by_task: dict[str, str] = field(default_factory=dict)
    """Task -> robot the policy drives for it (built once per robot); empty: one policy."""

    def resolved_sim_factory(self) -> Callable[[SimSetup], EpisodeSim]:
        return self.sim_factory or _default_sim_factory()
