"""Executors by name: ``local`` (process pool), ``ray`` (cluster), ``serial`` (in-process).

    executor = make_executor(executor_config(cfg), rollout_config)
    executor.run(jobs, worker_spec, on_outcome)
"""

from __future__ import annotations

from ladev_lib.registry import Registry
from ladev_lib.rollout.config import (
    LocalExecutorConfig,
    RayExecutorConfig,
    RolloutConfig,
    SerialExecutorConfig,
)
from ladev_lib.rollout.executors.base import Executor, OnOutcome

EXECUTORS: Registry[type] = Registry("executor")
EXECUTORS.add_lazy("local", "ladev_lib.rollout.executors.local:LocalPoolExecutor")
EXECUTORS.add_lazy("ray", "ladev_lib.rollout.executors.ray_executor:RayExecutor", extra="ray")
EXECUTORS.add_lazy("serial", "ladev_lib.rollout.executors.serial:SerialExecutor")


def make_executor(
    config: LocalExecutorConfig | RayExecutorConfig | SerialExecutorConfig,
    rollout: RolloutConfig | None = None,
    *,
    policy_module: str | None = None,
    code_fingerprint: str | None = None,
) -> Executor:
    """The executor ``config`` names, with the crash policy of ``rollout``."""
    retries = (rollout or RolloutConfig()).crash_retries
    cls = EXECUTORS.get(config.name)
    if isinstance(config, LocalExecutorConfig):
        executor: Executor = cls(workers=config.workers, crash_retries=retries)
    elif isinstance(config, RayExecutorConfig):
        executor = cls(
            workers=config.workers,
            address=config.address,
            num_cpus_per_worker=config.num_cpus_per_worker,
            num_gpus_per_worker=config.num_gpus_per_worker,
            crash_retries=retries,
            policy_module=policy_module,
            expected_fingerprint=code_fingerprint,
        )
    else:
        executor = cls()
    return executor


__all__ = ["EXECUTORS", "Executor", "OnOutcome", "make_executor"]
