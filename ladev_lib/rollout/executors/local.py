"""The local executor: a pool of worker processes, each reusing one simulator.

Each worker is a spawned process with its own pipe and a small shared array
it writes before every phase of an episode (deadline, phase, step). The
parent sends a job, waits on the pipes, and watches two things per busy
worker: that its process is alive (a death is retried, then an error row),
and that its current phase has not passed its deadline (a hang, even one
stuck in C code that no signal handler would interrupt: the process is
killed, the episode becomes an error row, a fresh worker takes its place).
Pipes, not a shared queue: a worker killed mid-write breaks only its own pipe.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import multiprocessing.connection as mpc
import time
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from multiprocessing.process import BaseProcess
from typing import Any

from ladev_lib.rollout.episode import PHASES
from ladev_lib.rollout.executors.base import (
    CrashLedger,
    OnOutcome,
    crash_outcome,
    exit_description,
    hang_outcome,
)
from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, WorkerSpec
from ladev_lib.rollout.worker import EpisodeWorker, WorkerSetupError, apply_thread_env, child_env

# Layout of the shared heartbeat array.
_DEADLINE, _PHASE, _STEP, _LIMIT = range(4)
_POLL_S = 0.2


class SharedHeartbeat:
    """Writes the current phase into memory the parent reads (no locks: one writer)."""

    def __init__(self, beat: Any) -> None:
        self.beat = beat

    def enter(self, phase: str, step: int, limit_s: float) -> None:
        self.beat[_LIMIT] = limit_s
        self.beat[_STEP] = step
        self.beat[_PHASE] = PHASES.index(phase)
        self.beat[_DEADLINE] = time.monotonic() + limit_s


def _worker_main(spec: WorkerSpec, conn: mpc.Connection, beat: Any) -> None:
    apply_thread_env(spec.thread_env)
    worker = EpisodeWorker(spec, heartbeat=SharedHeartbeat(beat))
    try:
        while True:
            job = conn.recv()
            if job is None:
                break
            try:
                conn.send(("start", job.episode_id, worker.robot_for(job)[0]))
                outcome = worker.run(job)
            except WorkerSetupError as exc:
                conn.send(("fatal", job.episode_id, str(exc)))
                break
            conn.send(("done", job.episode_id, outcome.model_dump()))
    except (EOFError, BrokenPipeError, KeyboardInterrupt):
        pass  # the parent is gone or stopping us: nothing to report to
    finally:
        worker.close()


@dataclass
class _Slot:
    process: BaseProcess
    conn: mpc.Connection
    beat: Any
    job: EpisodeJob | None = None
    robot: str | None = None


class LocalPoolExecutor:
    """``executor: {name: local, workers: N}``."""

    def __init__(self, workers: int = 2, crash_retries: int = 1) -> None:
        self.workers = workers
        self.crash_retries = crash_retries
        self._ctx = mp.get_context("spawn")  # fork after SAPIEN/torch load is unsafe

    def _start(self, spec: WorkerSpec) -> _Slot:
        parent, child = self._ctx.Pipe(duplex=True)
        beat = self._ctx.RawArray("d", 4)
        beat[_DEADLINE] = float("inf")
        process = self._ctx.Process(
            target=_worker_main, args=(spec, child, beat), name="ladev-episode-worker", daemon=True
        )
        with child_env(spec.thread_env):  # set before the child imports numpy, torch, SAPIEN
            process.start()
        child.close()
        return _Slot(process, parent, beat)

    @staticmethod
    def _stop(slot: _Slot, timeout_s: float = 10.0) -> None:
        with contextlib.suppress(BrokenPipeError, OSError):  # a dead worker needs no goodbye
            slot.conn.send(None)
        slot.process.join(timeout_s)
        if slot.process.is_alive():
            slot.process.kill()
            slot.process.join(5.0)
        slot.conn.close()

    @staticmethod
    def _kill(slot: _Slot) -> None:
        slot.process.kill()
        slot.process.join(5.0)
        slot.conn.close()

    def run(self, jobs: Sequence[EpisodeJob], spec: WorkerSpec, on_outcome: OnOutcome) -> None:
        pending = deque(jobs)
        if not pending:
            return
        ledger = CrashLedger(self.crash_retries)
        slots = [self._start(spec) for _ in range(min(self.workers, len(pending)))]
        try:
            while pending or any(s.job is not None for s in slots):
                for slot in slots:
                    if slot.job is None and pending:
                        self._assign(slot, pending.popleft(), spec)
                busy = [s for s in slots if s.job is not None]
                for conn in mpc.wait([s.conn for s in busy], timeout=_POLL_S):
                    slot = next(s for s in busy if s.conn is conn)
                    self._receive(slot, on_outcome)
                replaced = [s for s in slots if s.job is not None and self._check_health(s, pending, ledger, on_outcome)]
                for slot in replaced:
                    slots.remove(slot)
                    if pending and len(slots) < self.workers:
                        slots.append(self._start(spec))
        finally:
            for slot in slots:
                self._stop(slot)

    def _assign(self, slot: _Slot, job: EpisodeJob, spec: WorkerSpec) -> None:
        # Until the worker reports its first phase, building the policy and scene may take long.
        slot.beat[_LIMIT] = spec.setup_timeout_s
        slot.beat[_PHASE] = PHASES.index("setup")
        slot.beat[_STEP] = 0
        slot.beat[_DEADLINE] = time.monotonic() + spec.setup_timeout_s
        slot.job, slot.robot = job, None
        slot.conn.send(job)

    def _receive(self, slot: _Slot, on_outcome: OnOutcome) -> bool:
        """Handle one message; False when the pipe is closed (the worker died)."""
        try:
            kind, episode_id, payload = slot.conn.recv()
        except (EOFError, OSError):
            return False  # _check_health handles the death
        job = slot.job
        if job is None or episode_id != job.episode_id:
            raise RuntimeError(f"worker answered for {episode_id}, expected {job and job.episode_id}")
        if kind == "start":
            slot.robot = str(payload)
        elif kind == "done":
            slot.job = None
            on_outcome(job, EpisodeOutcome.model_validate(payload))
        elif kind == "fatal":
            raise WorkerSetupError(str(payload))
        return True

    def _check_health(
        self, slot: _Slot, pending: deque[EpisodeJob], ledger: CrashLedger, on_outcome: OnOutcome
    ) -> bool:
        """Handle a dead or hung worker; True when the slot needs a new process."""
        job = slot.job
        assert job is not None
        if not slot.process.is_alive():
            # An answer may have been sent just before the process exited.
            while slot.job is not None and slot.conn.poll() and self._receive(slot, on_outcome):
                pass
            if slot.job is None:
                return True
            deaths = ledger.record(job)
            if ledger.should_retry(job):
                pending.appendleft(job)
            else:
                how = exit_description(slot.process.exitcode)
                on_outcome(job, crash_outcome(job, slot.robot, how, deaths))
            slot.conn.close()
            return True
        if time.monotonic() > slot.beat[_DEADLINE]:
            phase = PHASES[int(slot.beat[_PHASE])]
            step, limit = int(slot.beat[_STEP]), float(slot.beat[_LIMIT])
            self._kill(slot)
            on_outcome(job, hang_outcome(job, slot.robot, phase, step, limit))
            return True
        return False
