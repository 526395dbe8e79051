"""The serial executor: every episode in this process, in order.

For debugging (breakpoints work, tracebacks are local) and for the one-episode
``ladev run``. There is no hang protection: a stuck policy stalls the run.
"""

from __future__ import annotations

from collections.abc import Sequence

from ladev_lib.rollout.executors.base import OnOutcome
from ladev_lib.rollout.jobs import EpisodeJob, WorkerSpec
from ladev_lib.rollout.worker import EpisodeWorker


class SerialExecutor:
    """``executor: {name: serial}``."""

    def run(self, jobs: Sequence[EpisodeJob], spec: WorkerSpec, on_outcome: OnOutcome) -> None:
        if not jobs:
            return
        worker = EpisodeWorker(spec)
        try:
            for job in jobs:
                on_outcome(job, worker.run(job))
        finally:
            worker.close()
