"""The episode engine: (scene, instruction, policy) -> judged episodes, cached and parallel.

- :mod:`~ladev_lib.rollout.episode`: the loop of one episode (``run_episode``).
- :mod:`~ladev_lib.rollout.identity`: episode ids (content hash + code fingerprint).
- :mod:`~ladev_lib.rollout.plan`: which episodes a study calls for.
- :mod:`~ladev_lib.rollout.engine`: skip what the store has, dispatch the rest, build the table.
- :mod:`~ladev_lib.rollout.executors`: ``local`` process pool, ``ray``, ``serial``.
- :mod:`~ladev_lib.rollout.stage`: the ``rollout`` stage as a function.
"""

from ladev_lib.policies.config import PolicyConfig
from ladev_lib.rollout.config import (
    LocalExecutorConfig,
    RayExecutorConfig,
    RolloutConfig,
    SerialExecutorConfig,
    executor_config,
)
from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, MediaOptions, WorkerSpec

__all__ = [
    "EpisodeJob",
    "EpisodeOutcome",
    "LocalExecutorConfig",
    "MediaOptions",
    "PolicyConfig",
    "RayExecutorConfig",
    "RolloutConfig",
    "SerialExecutorConfig",
    "WorkerSpec",
    "executor_config",
]
