"""The Ray executor: one actor per worker, each reusing its simulator, on any Ray cluster.

``executor: {name: ray, address: null}`` starts a local Ray instance for the
run; ``address: auto`` or ``ray://host:10001`` joins an existing cluster (its
nodes need LADEV installed: each actor checks its code fingerprint against the
driver's, so a node with other code cannot serve stale results).

Each actor runs episodes in one thread and answers ``progress()`` from
another. The driver polls progress; an actor whose phase has outlived its
limit, or that stops answering for that long (stuck in C code holding the
GIL), is killed and replaced, and the episode becomes an error row. A dead
actor's episode is retried like a dead local worker's.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from ladev_lib.errors import MissingExtraError
from ladev_lib.rollout.executors.base import CrashLedger, OnOutcome, crash_outcome, hang_outcome
from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, WorkerSpec
from ladev_lib.rollout.worker import EpisodeWorker, WorkerSetupError, apply_thread_env

_POLL_S = 0.2
_PROGRESS_EVERY_S = 0.1


def _import_ray() -> Any:
    try:
        import ray
    except ImportError as exc:
        raise MissingExtraError("executor 'ray'", "ray", exc) from exc
    return ray


class _ClockHeartbeat:
    """Phase, step, limit and when the phase began, read by ``progress()`` from another thread."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.state: tuple[str, int, float, float] = ("idle", 0, float("inf"), time.monotonic())

    def enter(self, phase: str, step: int, limit_s: float) -> None:
        with self._lock:
            self.state = (phase, step, limit_s, time.monotonic())

    def read(self) -> tuple[str, int, float, float]:
        """(phase, step, limit, seconds spent in the phase so far)."""
        with self._lock:
            phase, step, limit, began = self.state
        return phase, step, limit, time.monotonic() - began


class RayEpisodeActor:
    """The actor body (wrapped with ``ray.remote`` at run time, so Ray stays optional)."""

    def __init__(self, spec: WorkerSpec) -> None:
        apply_thread_env(spec.thread_env)
        self.beat = _ClockHeartbeat()
        self.worker = EpisodeWorker(spec, heartbeat=self.beat)
        self.robot: str | None = None

    def fingerprint(self, policy_module: str) -> str:
        from ladev_lib.rollout.identity import code_fingerprint

        return code_fingerprint(policy_module)

    def run(self, job: EpisodeJob) -> dict[str, Any]:
        self.robot = None
        self.robot, _ = self.worker.robot_for(job)
        return self.worker.run(job).model_dump()

    def progress(self) -> tuple[str, int, float, float, str | None]:
        return (*self.beat.read(), self.robot)


@dataclass
class _Busy:
    actor: Any
    job: EpisodeJob
    # Last progress known: phase, step, limit, seconds in phase, when it was read.
    phase: str
    step: int
    limit: float
    elapsed: float
    seen_at: float
    robot: str | None = None
    progress_ref: Any = None
    last_poll: float = field(default_factory=time.monotonic)

    def overdue(self, now: float) -> bool:
        return self.elapsed + (now - self.seen_at) > self.limit


class RayExecutor:
    """``executor: {name: ray, address: ..., workers: N}``."""

    def __init__(
        self,
        workers: int = 2,
        address: str | None = None,
        num_cpus_per_worker: float = 1.0,
        num_gpus_per_worker: float = 0.0,
        crash_retries: int = 1,
        policy_module: str | None = None,
        expected_fingerprint: str | None = None,
    ) -> None:
        self.workers = workers
        self.address = address
        self.num_cpus_per_worker = num_cpus_per_worker
        self.num_gpus_per_worker = num_gpus_per_worker
        self.crash_retries = crash_retries
        self.policy_module = policy_module
        self.expected_fingerprint = expected_fingerprint

    def _connect(self, ray: Any) -> bool:
        """Initialise Ray; True when this run started the instance (and must stop it)."""
        if ray.is_initialized():
            return False
        if self.address:
            ray.init(address=self.address, log_to_driver=False)
        else:
            # Workers of a local instance import what the driver imports (checkouts, tests).
            path = os.pathsep.join(p for p in sys.path if p and os.path.isdir(p))
            ray.init(
                num_cpus=max(1, int(self.workers * self.num_cpus_per_worker + 0.999)),
                include_dashboard=False,
                log_to_driver=False,
                runtime_env={"env_vars": {"PYTHONPATH": path}},
            )
        return True

    def run(self, jobs: Sequence[EpisodeJob], spec: WorkerSpec, on_outcome: OnOutcome) -> None:
        pending = deque(jobs)
        if not pending:
            return
        ray = _import_ray()
        started_here = self._connect(ray)
        # One thread per actor for the renderer and BLAS, set before the actor process imports them.
        thread_env = {k: os.environ.get(k, v) for k, v in spec.thread_env.items()}
        actor_cls = ray.remote(
            num_cpus=self.num_cpus_per_worker,
            num_gpus=self.num_gpus_per_worker,
            max_concurrency=2,
            runtime_env={"env_vars": thread_env},
        )(RayEpisodeActor)
        idle: list[Any] = []
        busy: dict[Any, _Busy] = {}
        ledger = CrashLedger(self.crash_retries)
        try:
            idle = [actor_cls.remote(spec) for _ in range(min(self.workers, len(pending)))]
            self._check_code(ray, idle)
            while pending or busy:
                while idle and pending:
                    actor, job = idle.pop(), pending.popleft()
                    now = time.monotonic()
                    ref = actor.run.remote(job)
                    busy[ref] = _Busy(actor, job, "setup", 0, spec.setup_timeout_s, 0.0, now)
                ready, _ = ray.wait(list(busy), num_returns=1, timeout=_POLL_S)
                if ready:
                    ready, _ = ray.wait(list(busy), num_returns=len(busy), timeout=0)
                for ref in ready:
                    entry = busy.pop(ref)
                    self._collect(ray, ref, entry, pending, ledger, on_outcome, idle, actor_cls, spec)
                self._watch(ray, busy, on_outcome, idle, actor_cls, spec)
        finally:
            for actor in idle + [b.actor for b in busy.values()]:
                ray.kill(actor)
            if started_here:
                ray.shutdown()

    def _check_code(self, ray: Any, actors: list[Any]) -> None:
        if self.expected_fingerprint is None or self.policy_module is None:
            return
        seen = ray.get([a.fingerprint.remote(self.policy_module) for a in actors])
        if any(fp != self.expected_fingerprint for fp in seen):
            raise WorkerSetupError(
                "the Ray workers run different LADEV code than this driver (code fingerprint "
                f"{seen[0]} != {self.expected_fingerprint}); install the same version on every node"
            )

    def _collect(
        self,
        ray: Any,
        ref: Any,
        entry: _Busy,
        pending: deque[EpisodeJob],
        ledger: CrashLedger,
        on_outcome: OnOutcome,
        idle: list[Any],
        actor_cls: Any,
        spec: WorkerSpec,
    ) -> None:
        from ray.exceptions import RayActorError, RayTaskError

        try:
            payload = ray.get(ref)
        except RayActorError:
            deaths = ledger.record(entry.job)
            if ledger.should_retry(entry.job):
                pending.appendleft(entry.job)
            else:
                on_outcome(entry.job, crash_outcome(entry.job, entry.robot, "Ray actor died", deaths))
            idle.append(actor_cls.remote(spec))
            return
        except RayTaskError as exc:
            cause = exc.as_instanceof_cause()
            if isinstance(cause, WorkerSetupError):
                qualified = f"{WorkerSetupError.__module__}.{WorkerSetupError.__name__}: "
                raise WorkerSetupError(str(cause).splitlines()[-1].removeprefix(qualified)) from None
            raise
        idle.append(entry.actor)
        on_outcome(entry.job, EpisodeOutcome.model_validate(payload))

    def _watch(
        self,
        ray: Any,
        busy: dict[Any, _Busy],
        on_outcome: OnOutcome,
        idle: list[Any],
        actor_cls: Any,
        spec: WorkerSpec,
    ) -> None:
        now = time.monotonic()
        for ref, entry in list(busy.items()):
            if entry.progress_ref is not None:
                done, _ = ray.wait([entry.progress_ref], timeout=0)
                if done:
                    try:
                        phase, step, limit, elapsed, robot = ray.get(done[0])
                    except ray.exceptions.RayActorError:
                        entry.progress_ref = None
                        continue  # the run ref will report the death
                    entry.phase, entry.step, entry.limit, entry.elapsed = phase, step, limit, elapsed
                    entry.robot = robot or entry.robot
                    entry.seen_at = now
                    entry.progress_ref = None
            if entry.progress_ref is None and now - entry.last_poll >= _PROGRESS_EVERY_S:
                entry.progress_ref = entry.actor.progress.remote()
                entry.last_poll = now
            if entry.phase != "idle" and entry.overdue(now):
                ray.kill(entry.actor)
                del busy[ref]
                on_outcome(
                    entry.job,
                    hang_outcome(entry.job, entry.robot, entry.phase, entry.step, entry.limit),
                )
                idle.append(actor_cls.remote(spec))
