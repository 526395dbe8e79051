"""A worker: one policy and its reused simulators, running episodes one at a time.

Every executor runs episodes through an :class:`EpisodeWorker`: the local pool
keeps one per process, Ray one per actor, the serial executor one in the
calling process. The policy is built once, on the first episode; a simulator
is built once per (robot, control mode, camera size) and reused after.
"""

from __future__ import annotations

import contextlib
import logging
import os
from collections.abc import Iterator
from typing import TYPE_CHECKING

from ladev_lib.errors import ConfigError, LadevError
from ladev_lib.rollout.episode import (
    Heartbeat,
    Limits,
    NoHeartbeat,
    choose_robot,
    describe_exception,
    run_episode,
)
from ladev_lib.rollout.jobs import EpisodeJob, EpisodeOutcome, WorkerSpec
from ladev_lib.rollout.simulator import EpisodeSim, SimSetup

if TYPE_CHECKING:
    from ladev_lib.policies.base import Policy

log = logging.getLogger(__name__)


class WorkerSetupError(LadevError):
    """The policy or the simulator cannot be built as configured: fix the configuration.

    Not an episode's failure: every episode would fail the same way, so the run stops.
    """


def apply_thread_env(env: dict[str, str]) -> None:
    """One thread per worker for the software renderer and BLAS, unless the user chose otherwise."""
    for key, value in env.items():
        os.environ.setdefault(key, value)


@contextlib.contextmanager
def child_env(env: dict[str, str]) -> Iterator[None]:
    """Environment for processes started inside the block (numpy reads it when a child imports it).

    Keys the user has set are left alone; the parent's environment is restored after.
    """
    added = {k: v for k, v in env.items() if k not in os.environ}
    os.environ.update(added)
    try:
        yield
    finally:
        for key in added:
            os.environ.pop(key, None)


class EpisodeWorker:
    """Runs episodes for one policy; keeps the policy and simulators between episodes."""

    def __init__(self, spec: WorkerSpec, heartbeat: Heartbeat | None = None) -> None:
        self.spec = spec
        self.heartbeat: Heartbeat = heartbeat or NoHeartbeat()
        self.limits = Limits(spec.step_timeout_s, spec.setup_timeout_s)
        self._policies: dict[str | None, Policy] = {}
        self._sims: dict[tuple[str, str, tuple[int, int] | None], EpisodeSim] = {}

    @property
    def policy(self) -> Policy:
        """The policy as configured (its own default robot)."""
        return self.policy_for(None)

    def policy_for(self, robot: str | None) -> Policy:
        """The policy built for ``robot`` (None: as configured); built once, then kept.

        A policy whose config sets ``robot_by_task`` drives a different embodiment per task
        (the paper: pick up and move near on the Google robot, put on and put in on WidowX);
        it is built once per robot, with ``robot=<robot>`` added to its config.
        """
        if robot not in self._policies:
            self.heartbeat.enter("setup", 0, self.spec.setup_timeout_s)
            factory = self.spec.policy_factory
            config = dict(self.spec.policy_config)
            if robot is not None:
                config["robot"] = robot
            try:
                if factory is None:
                    from ladev_lib.policies import POLICIES

                    factory = POLICIES.get(self.spec.policy_name)
                self._policies[robot] = factory(**config)
            except Exception as exc:
                raise WorkerSetupError(
                    f"cannot build policy {self.spec.policy_name!r} with config "
                    f"{config}: {type(exc).__name__}: {exc}"
                ) from exc
        return self._policies[robot]

    def sim_for(self, robot: str, policy: Policy | None = None) -> EpisodeSim:
        info = (policy or self.policy).info
        # Every policy gets a policy camera, even one that reads no image: the validity
        # check's visibility test needs it (the same verdict for every policy), and so do
        # the episode's frames. It renders only when asked, a few times per episode.
        image_size = info.image_size
        if image_size is None:
            size = self.spec.sim_config.get("image_size") or (256, 256)
            image_size = (int(size[0]), int(size[1]))
        key = (robot, info.control_mode, image_size)
        sim = self._sims.get(key)
        if sim is None:
            sim_config = dict(self.spec.sim_config)
            if info.control_freq_hz and sim_config.get("control_freq_hz") is None:
                # The frequency the policy was trained at, unless the study fixes one.
                sim_config["control_freq_hz"] = round(info.control_freq_hz)
            setup = SimSetup(
                sim_config=sim_config,
                robot_config=self.spec.robot_config,
                robot=robot,
                control_mode=info.control_mode,
                image_size=image_size,
            )
            sim = self._sims[key] = self.spec.resolved_sim_factory()(setup)
        return sim

    def robot_for(self, job: EpisodeJob) -> tuple[str, Policy]:
        """The robot ``job`` runs with, and the policy to drive it: the robot the policy's config
        names for the task (``robot_by_task``), else the scene's robot, or the policy's first
        robot if it cannot drive the scene's."""
        spec = job.spec
        by_task = self.spec.robot_by_task.get(spec.task.type)
        if by_task is not None:
            return by_task, self.policy_for(by_task)
        return choose_robot(spec.robot, self.policy.info.robots), self.policy

    def run(self, job: EpisodeJob) -> EpisodeOutcome:
        """Run one episode. Raises :class:`WorkerSetupError` only for a configuration no episode can run with."""
        robot, policy = self.robot_for(job)
        try:
            sim = self.sim_for(robot, policy)
        except ConfigError as exc:
            raise WorkerSetupError(f"cannot build the simulator for {robot}: {exc}") from exc
        except Exception as exc:  # noqa: BLE001 - a simulator that cannot be built fails this episode
            return EpisodeOutcome.failed("error", robot, describe_exception("simulator", exc))
        try:
            outcome = run_episode(
                sim, policy, job, self.spec.media, robot=robot, heartbeat=self.heartbeat, limits=self.limits
            )
        except ConfigError as exc:
            raise WorkerSetupError(f"cannot simulate with {robot}: {exc}") from exc
        finally:
            self.heartbeat.enter("idle", 0, float("inf"))
        if outcome.status == "error" and (outcome.error or "").startswith("simulator"):
            # A simulator that raised may be left half-built: the next episode gets a fresh one.
            self._drop_sim(sim)
        return outcome

    def _drop_sim(self, sim: EpisodeSim) -> None:
        for key, value in list(self._sims.items()):
            if value is sim:
                del self._sims[key]
        try:
            sim.close()
        except Exception as exc:  # noqa: BLE001 - a broken simulator may fail to close; it is discarded
            log.warning("closing a failed simulator raised %s: %s", type(exc).__name__, exc)

    def close(self) -> None:
        for sim in self._sims.values():
            sim.close()
        self._sims.clear()
        for policy in self._policies.values():
            policy.close()
        self._policies.clear()
