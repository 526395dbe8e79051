"""Configuration of the rollout stage: which policy, how episodes run, where.

Three sections of ``params.yaml`` (validated with :func:`ladev_lib.config.section`):

- ``policy.<label>``: ``{name: <registry name>, ...kwargs}`` (:class:`PolicyConfig`);
- ``executor``: ``local`` (process pool), ``ray`` (cluster) or ``serial``
  (in-process, for debugging) (:data:`ExecutorConfig`);
- ``rollout``: media, time limits, the tolerated error rate and whether episodes
  end at the first success (:class:`RolloutConfig`).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError

from ladev_lib.errors import ConfigError

VideoMode = Literal["none", "failures", "all"]


class LocalExecutorConfig(BaseModel):
    """A pool of worker processes on this machine, each reusing its simulator."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    name: Literal["local"] = "local"
    workers: int = Field(default=2, ge=1, le=256)


class RayExecutorConfig(BaseModel):
    """Ray actors, each reusing its simulator, on an existing cluster or a local one."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    name: Literal["ray"] = "ray"
    address: str | None = Field(
        default=None, description="'auto', 'ray://host:10001', or null to start a local cluster."
    )
    workers: int = Field(default=2, ge=1, le=4096)
    num_cpus_per_worker: float = Field(default=1.0, gt=0)
    num_gpus_per_worker: float = Field(
        default=0.0, ge=0, description="GPUs Ray reserves per actor (a VLA model, GPU rendering)."
    )


class SerialExecutorConfig(BaseModel):
    """Every episode in this process, one after the other (for debuggers; no hang protection)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    name: Literal["serial"] = "serial"
    workers: Literal[1] = 1


ExecutorConfig = Annotated[
    LocalExecutorConfig | RayExecutorConfig | SerialExecutorConfig, Field(discriminator="name")
]
EXECUTOR_CONFIG: TypeAdapter[LocalExecutorConfig | RayExecutorConfig | SerialExecutorConfig] = (
    TypeAdapter(ExecutorConfig)
)


def executor_config(cfg: dict[str, Any]) -> LocalExecutorConfig | RayExecutorConfig | SerialExecutorConfig:
    """Validate ``cfg["executor"]``; an error names the key and the executors there are."""
    raw = cfg.get("executor") or {"name": "local"}
    try:
        return EXECUTOR_CONFIG.validate_python(raw)
    except ValidationError as exc:
        lines = [
            "  executor." + ".".join(str(p) for p in err["loc"][1:] or err["loc"]) + f": {err['msg']}"
            for err in exc.errors()
        ]
        raise ConfigError(
            "invalid configuration in 'executor' (name: local | ray | serial):\n" + "\n".join(lines)
        ) from exc


class RolloutConfig(BaseModel):
    """How episodes run and what they leave behind (the ``rollout`` section)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    video: VideoMode = Field(
        default="none",
        description="MP4 at the policy camera: none | failures | all. Applies to episodes run now; "
        "episodes served from the store keep the media they were run with.",
    )
    frames: bool = Field(default=True, description="Save the first and last policy-camera frame (PNG).")
    video_fps: int = Field(default=10, ge=1, le=60)
    step_timeout_s: float = Field(
        default=120.0, gt=0, description="A policy or simulator step longer than this is a hang."
    )
    setup_timeout_s: float = Field(
        default=900.0,
        gt=0,
        description="Limit for building the policy, the simulator and the first frame of a worker.",
    )
    max_error_rate: float = Field(
        default=0.05, ge=0.0, le=1.0, description="The stage fails when more episodes than this end in error."
    )
    crash_retries: int = Field(
        default=1, ge=0, le=5, description="Reruns of an episode whose worker process died."
    )
    stop_on_success: bool = Field(
        default=False,
        description="End an episode at the first step the task holds. Off (as SimplerEnv): episodes "
        "run until the policy stops or the step limit, and both success at the final step and at "
        "any step are recorded.",
    )
