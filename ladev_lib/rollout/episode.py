"""The episode loop: one (scene, instruction, policy, seed) in, one judged outcome out.

    outcome = run_episode(sim, policy, job, media)

Seed every generator (:mod:`ladev_lib.seeding`), load the scene into
the reused simulator, check it is physically valid, then step the policy with
what it declares it reads (the image at its size only if it wants one;
proprioception; privileged state only if privileged) until the policy stops or
the task's step limit, or the first success when the job says so
(``rollout.stop_on_success``; off by default, as in SimplerEnv). Success is
recorded at every step: at the final step (``success``) and at any step
(``success_any``, with the first step it held). Every failure
inside becomes an ``error`` outcome with its reason, never an exception: a
simulator exception, a policy exception, an action with NaN/inf or the wrong
shape. The one exception that propagates is a ``ConfigError`` while loading
the scene (a control mode the robot lacks, a robot whose assets are missing):
no episode could run, so the run stops with the message. Hangs are the worker's business (a heartbeat, see :class:`Heartbeat`):
a call stuck in C code cannot be interrupted from inside its own process.
"""

from __future__ import annotations

import functools
import platform
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal, Protocol, TypeVar

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError
from ladev_lib.policies.base import EpisodeContext, Policy
from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, MediaOptions
from ladev_lib.rollout.media import write_mp4, write_png
from ladev_lib.rollout.simulator import EpisodeSim
from ladev_lib.scenes import SceneSpec
from ladev_lib.seeding import seed_episode
from ladev_lib.vocabulary import EpisodeStatus

_T = TypeVar("_T")

PHASES: tuple[str, ...] = ("idle", "setup", "load", "policy", "sim", "media")


class Heartbeat(Protocol):
    """Tells whoever watches the worker which phase it is in, and for how long it may last."""

    def enter(self, phase: str, step: int, limit_s: float) -> None: ...


class NoHeartbeat:
    """For in-process runs: nobody watches."""

    def enter(self, phase: str, step: int, limit_s: float) -> None:
        del phase, step, limit_s


@dataclass(frozen=True)
class Limits:
    step_timeout_s: float = 120.0
    setup_timeout_s: float = 900.0


def choose_robot(scene_robot: str, policy_robots: tuple[str, ...]) -> str:
    """The scene's robot when the policy can drive it, else the policy's first robot."""
    if not policy_robots or scene_robot in policy_robots:
        return scene_robot
    return policy_robots[0]


def seed_everything(seed: int) -> None:
    """Seed every generator an episode may draw from (see :mod:`ladev_lib.seeding`)."""
    seed_episode(seed)


@functools.lru_cache(maxsize=1)
def host_label() -> str:
    """The machine, for the timings table: hostname and CPU model."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            cpu = next((ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")), cpu)
    except OSError:
        pass
    return f"{platform.node()} ({cpu})"


def describe_exception(where: str, exc: BaseException) -> str:
    """``where: Type: message (at file:line)`` — short enough for a table cell."""
    tb = traceback.extract_tb(exc.__traceback__)
    at = f" (at {Path(tb[-1].filename).name}:{tb[-1].lineno})" if tb else ""
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return f"{where}: {type(exc).__name__}: {text}{at}"[:500]


def check_action(action: object, shape: tuple[int, ...], step: int) -> tuple[Array | None, str | None]:
    """The action as float32 of the right shape, or the reason it is unusable."""
    try:
        arr = np.asarray(action, dtype=np.float32)
    except (TypeError, ValueError) as exc:
        return None, f"action: step {step}: not a numeric array ({exc})"
    if arr.shape != shape:
        return None, f"action: step {step}: shape {arr.shape}, the action space is {shape}"
    if not np.all(np.isfinite(arr)):
        bad = "NaN" if np.isnan(arr).any() else "inf"
        return None, f"action: step {step}: contains {bad} ({arr.tolist()})"
    return arr, None


class _Abort(Exception):
    """Ends the episode early with ``status`` and ``reason`` (never leaves this module)."""

    def __init__(self, status: EpisodeStatus, reason: str) -> None:
        super().__init__(reason)
        self.status = status
        self.reason = reason


_WHERE = {"sim": "simulator", "policy": "policy"}


@dataclass
class _Run:
    """One episode's clock and step count, and the one guarded call every phase goes through."""

    robot: str
    sim: float = 0.0
    policy: float = 0.0
    steps: int = 0
    started: float = field(default_factory=time.perf_counter)

    def timing(self) -> dict[str, float | str]:
        return {
            "sim_seconds": round(self.sim, 4),
            "policy_seconds": round(self.policy, 4),
            "total_seconds": round(time.perf_counter() - self.started, 4),
            "host": host_label(),
        }

    def guarded(self, part: Literal["sim", "policy"], call: Callable[[], _T], *, config_stops: bool = False) -> _T:
        """``call()`` timed under ``part``; any exception becomes this episode's error.

        With ``config_stops`` a :class:`ConfigError` propagates instead: no episode
        could run under that configuration, so the run stops with its message.
        """
        t = time.perf_counter()
        try:
            return call()
        except ConfigError as exc:
            if config_stops:
                raise
            raise _Abort("error", describe_exception(_WHERE[part], exc)) from exc
        except Exception as exc:  # noqa: BLE001 - any failure inside is this episode's error row
            raise _Abort("error", describe_exception(_WHERE[part], exc)) from exc
        finally:
            setattr(self, part, getattr(self, part) + time.perf_counter() - t)

    def failed(self, status: EpisodeStatus, reason: str) -> EpisodeOutcome:
        return EpisodeOutcome.failed(status, self.robot, reason, steps=self.steps, **self.timing())


def run_episode(
    sim: EpisodeSim,
    policy: Policy,
    job: EpisodeJob,
    media: MediaOptions | None = None,
    *,
    robot: str | None = None,
    heartbeat: Heartbeat | None = None,
    limits: Limits | None = None,
) -> EpisodeOutcome:
    """Run one episode in ``sim`` (already built for the policy's robot and control mode)."""
    spec = job.spec
    run = _Run(robot or choose_robot(spec.robot, policy.info.robots))
    try:
        return _episode(sim, policy, job, spec, run, media, heartbeat or NoHeartbeat(), limits or Limits())
    except _Abort as stop:
        return run.failed(stop.status, stop.reason)


def _episode(
    sim: EpisodeSim,
    policy: Policy,
    job: EpisodeJob,
    spec: SceneSpec,
    run: _Run,
    media: MediaOptions | None,
    beat: Heartbeat,
    lim: Limits,
) -> EpisodeOutcome:
    info = policy.info

    # -- scene ---------------------------------------------------------------
    seed_everything(job.seed)  # before anything of the episode draws a random number
    beat.enter("load", 0, lim.setup_timeout_s)

    def load() -> tuple[str | None, Array, Array, int]:
        sim.load(spec, job.seed)
        low, high = sim.action_bounds()
        steps = info.episode_steps_for(spec.task.type) or sim.max_steps(spec.task.type)
        return sim.invalid_reason(), low, high, steps

    invalid, low, high, max_steps = run.guarded("sim", load, config_stops=True)
    if invalid:
        return _invalid(sim, job, run, media, invalid)

    # -- policy --------------------------------------------------------------
    beat.enter("policy", 0, lim.step_timeout_s)

    def start() -> None:
        policy.begin_episode(EpisodeContext(seed=job.seed, robot=run.robot, action_low=low, action_high=high))
        policy.reset(job.instruction)

    run.guarded("policy", start)

    wants_image = info.image_size is not None
    record = media is not None and media.needs_camera
    keep_all = media is not None and media.video != "none"
    frames: list[Array] = []
    shape = tuple(low.shape)
    predicates: dict[str, bool] = {}
    first_success: int | None = None
    for step in range(max_steps):
        beat.enter("sim", step, lim.step_timeout_s)
        obs = run.guarded("sim", lambda: sim.observe(image=wants_image, privileged=info.privileged))
        obs.step = step
        if record and (keep_all or step == 0):
            frames.append(obs.image if obs.image is not None else run.guarded("sim", sim.frame))

        beat.enter("policy", step, lim.step_timeout_s)
        out = run.guarded("policy", functools.partial(policy.step, obs))
        action, problem = check_action(out.action, shape, step)
        if problem or action is None:
            raise _Abort("error", problem or "action: missing")

        beat.enter("sim", step, lim.step_timeout_s)
        predicates = run.guarded("sim", functools.partial(sim.step, action))
        run.steps = step + 1
        if first_success is None and predicates.get("success", False):
            first_success = run.steps
            if job.stop_on_success:
                break
        if out.terminate:
            break

    if not predicates:  # zero steps: judge the initial state
        predicates = run.guarded("sim", sim.evaluate)
    if record:
        frames.append(run.guarded("sim", sim.frame))

    success = bool(predicates.get("success", False))
    if first_success is None and success:  # zero steps: the initial state already holds
        first_success = run.steps
    outcome = EpisodeOutcome.model_validate(
        {
            "status": "success" if success else "failure",
            "success": success,
            "success_any": first_success is not None,
            "first_success_step": first_success,
            "predicates": predicates,
            "steps": run.steps,
            "robot": run.robot,
            **run.timing(),
        }
    )
    if media is not None and frames:
        beat.enter("media", run.steps, lim.setup_timeout_s)
        outcome = _save_media(outcome, job, media, frames)
    return outcome


def _invalid(sim: EpisodeSim, job: EpisodeJob, run: _Run, media: MediaOptions | None, reason: str) -> EpisodeOutcome:
    """An ``invalid_scene`` row, with a picture of what the check saw when frames are kept."""
    outcome = run.failed("invalid_scene", reason)
    if media is None or not media.frames:
        return outcome
    try:
        frame = sim.frame()
    except Exception as exc:  # noqa: BLE001 - the verdict stands without its picture
        return outcome.model_copy(update={"error": f"{reason} (no frame: {exc})"})
    write_png(Path(media.root) / f"{job.episode_id}_first.png", frame)
    return outcome.model_copy(update={"first_frame_path": f"{media.prefix}/{job.episode_id}_first.png"})


def _save_media(
    outcome: EpisodeOutcome, job: EpisodeJob, media: MediaOptions, frames: list[Array]
) -> EpisodeOutcome:
    root = Path(media.root)
    update: dict[str, str] = {}
    if media.frames:
        write_png(root / f"{job.episode_id}_first.png", frames[0])
        write_png(root / f"{job.episode_id}_last.png", frames[-1])
        update["first_frame_path"] = f"{media.prefix}/{job.episode_id}_first.png"
        update["last_frame_path"] = f"{media.prefix}/{job.episode_id}_last.png"
    wants_video = media.video == "all" or (media.video == "failures" and not outcome.success)
    if wants_video and len(frames) > 1:
        write_mp4(root / f"{job.episode_id}.mp4", frames, media.fps)
        update["video_path"] = f"{media.prefix}/{job.episode_id}.mp4"
    return outcome.model_copy(update=update)
