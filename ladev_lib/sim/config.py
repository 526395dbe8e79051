"""What the ``sim`` and ``robot`` config groups hold, validated.

``conf/sim/<option>.yaml`` -> :class:`SimConfig`; ``conf/robot/<option>.yaml`` ->
:class:`RobotConfig`. Read them with ``ladev_lib.config.section(cfg, "sim", SimConfig)``.
A value left ``null`` means "the robot's default" (see ``ladev_lib.sim.robots``):
SimplerEnv's frequencies for WidowX (5 Hz) and the Google robot (3 Hz), ManiSkill's
for Panda (sim 100 Hz, control 20 Hz).
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from ladev_lib.vocabulary import Robot, TaskType


class SimConfig(BaseModel):
    """Simulator settings shared by every robot."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    sim_backend: Literal["cpu", "gpu"] = Field(
        default="cpu", description="PhysX backend; the scene env runs one scene per process."
    )
    render_backend: str = Field(
        default="auto",
        description="'auto' (CUDA if torch sees a GPU, else the CPU Vulkan device, e.g. lavapipe), "
        "'cpu', 'gpu', or a SAPIEN device string such as 'pci:...'.",
    )
    image_size: tuple[int, int] = Field(
        default=(256, 256), description="[width, height] of the policy camera image."
    )
    sim_freq_hz: int | None = Field(default=None, ge=20, le=2000, description="null: robot default.")
    control_freq_hz: int | None = Field(default=None, ge=1, le=100, description="null: robot default.")
    overlay: bool = Field(
        default=True,
        description="Real-background overlay (SimplerEnv visual matching) for robots that have one "
        "(WidowX, Google robot), when the images are under MS_ASSET_DIR.",
    )
    settle_s: float = Field(
        default=0.5, ge=0.0, le=5.0, description="Seconds of physics after spawning, robot held still."
    )
    settle_max_s: float = Field(
        default=3.0,
        ge=0.0,
        le=10.0,
        description="Settling continues in 0.25 s chunks while an object still moves, up to this.",
    )
    overview_size: tuple[int, int] = Field(
        default=(512, 384), description="[width, height] of the overview (render-only) camera."
    )

    @field_validator("image_size", "overview_size")
    @classmethod
    def _positive_size(cls, v: tuple[int, int]) -> tuple[int, int]:
        if min(v) < 16 or max(v) > 2048:
            raise ValueError(f"image sizes must be within [16, 2048] pixels, got {list(v)}")
        return v


class RobotConfig(BaseModel):
    """Per-robot choices a study may override; ``null`` keeps the robot's default."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    name: Robot = "panda"
    control_mode: str | None = Field(default=None, description="ManiSkill controller; null: default.")
    max_episode_steps: dict[TaskType, int] = Field(
        default_factory=dict,
        description="Episode length in control steps per task; missing tasks use the robot's default.",
    )

    @field_validator("max_episode_steps")
    @classmethod
    def _positive_steps(cls, v: dict[TaskType, int]) -> dict[TaskType, int]:
        bad = {k: n for k, n in v.items() if n < 1}
        if bad:
            raise ValueError(f"episode lengths must be at least 1 step, got {bad}")
        return v
