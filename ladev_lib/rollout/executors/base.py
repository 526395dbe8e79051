"""What every executor does: run jobs through workers, hand each outcome back as it lands.

An executor never decides an episode's outcome (the episode loop does), so
every executor gives the same rows for the same jobs. What differs is where
workers live and how a dead or hung worker is noticed and replaced; the
bookkeeping of that (retry a crashed episode, turn a hang into an error row)
is shared here.
"""

from __future__ import annotations

import signal
from collections.abc import Callable, Sequence
from typing import Protocol

from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, WorkerSpec

OnOutcome = Callable[[EpisodeJob, EpisodeOutcome], None]


class Executor(Protocol):
    """Runs jobs and calls ``on_outcome`` once per job, in completion order."""

    def run(self, jobs: Sequence[EpisodeJob], spec: WorkerSpec, on_outcome: OnOutcome) -> None: ...


PHASE_WORDS: dict[str, str] = {
    "setup": "building the policy",
    "load": "loading the scene",
    "policy": "the policy step",
    "sim": "the simulator step",
    "media": "writing the episode's media",
}


def scene_robot(job: EpisodeJob) -> str:
    return job.spec.robot


def hang_outcome(job: EpisodeJob, robot: str | None, phase: str, step: int, limit_s: float) -> EpisodeOutcome:
    """The error row of an episode whose worker stopped answering and was killed."""
    what = PHASE_WORDS.get(phase, phase)
    return EpisodeOutcome.failed(
        "error",
        robot or scene_robot(job),
        f"timeout: {what} did not return within {limit_s:g} s (step {step}); "
        "the worker was killed and replaced",
        steps=step,
    )


def exit_description(exitcode: int | None) -> str:
    if exitcode is None:
        return "exit status unknown"
    if exitcode < 0:
        try:
            return f"killed by {signal.Signals(-exitcode).name}"
        except ValueError:
            return f"killed by signal {-exitcode}"
    return f"exit code {exitcode}"


def crash_outcome(job: EpisodeJob, robot: str | None, how: str, attempts: int) -> EpisodeOutcome:
    """The error row of an episode whose worker died on every attempt."""
    times = "once" if attempts == 1 else f"{attempts} times"
    return EpisodeOutcome.failed(
        "error",
        robot or scene_robot(job),
        f"worker: the worker process died running this episode ({how}), {times}",
    )


class CrashLedger:
    """Counts deaths per episode; says whether to retry or give up with an error row."""

    def __init__(self, retries: int) -> None:
        self.retries = retries
        self._deaths: dict[str, int] = {}

    def record(self, job: EpisodeJob) -> int:
        n = self._deaths.get(job.episode_id, 0) + 1
        self._deaths[job.episode_id] = n
        return n

    def should_retry(self, job: EpisodeJob) -> bool:
        return self._deaths.get(job.episode_id, 0) <= self.retries
