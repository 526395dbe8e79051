"""The simulator as the episode loop sees it: load a scene, observe, step, judge.

:class:`EpisodeSim` is the small surface the loop needs; :class:`ManiSkillSim`
implements it on the LADEV ManiSkill env (``ladev_lib.sim``), reusing one env
across episodes (``reset(options={"spec": ..., "reconfigure": True})`` rebuilds
the scene every episode, so no episode inherits another's physics state; the
first rendered frame of a process costs seconds, later ones milliseconds). Tests use
a double that implements the same protocol.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.policies.base import Observation, PrivilegedState
from ladev_lib.scenes import SceneSpec


@dataclass(frozen=True)
class SimSetup:
    """What a simulator is built for: one robot, one control mode, one camera size."""

    sim_config: dict[str, Any]
    robot_config: dict[str, Any]
    robot: str
    control_mode: str
    image_size: tuple[int, int] | None
    """(width, height) of the policy camera; None: state only (nothing is rendered)."""
    prefer_meshes: bool = True
    """False: build stand-ins even where ``MS_ASSET_DIR`` has meshes (e.g. asset-independent checks)."""


class EpisodeSim(Protocol):
    """A reusable simulator for one :class:`SimSetup`."""

    def load(self, spec: SceneSpec, seed: int) -> None:
        """Build (or rebuild) the scene of ``spec`` and reset it with ``seed``."""

    def action_bounds(self) -> tuple[Array, Array]:
        """(low, high) of the action space, each of the action's shape."""

    def invalid_reason(self) -> str | None:
        """Why the loaded scene is physically invalid, or None when it is valid."""

    def max_steps(self, task: str) -> int:
        """Episode length for ``task``."""

    def observe(self, *, image: bool, privileged: bool) -> Observation:
        """The current observation: the image and privileged state only when asked."""

    def step(self, action: Array) -> dict[str, bool]:
        """Apply one action; the task's predicates and ``success`` after it."""

    def evaluate(self) -> dict[str, bool]:
        """The task's predicates and ``success`` now."""

    def frame(self) -> Array:
        """(H, W, 3) uint8 from the policy camera, for videos and frame files."""

    def close(self) -> None:
        """Release the simulator."""


def to_bool_dict(values: dict[str, Any]) -> dict[str, bool]:
    """ManiSkill returns batch-1 tensors; keep the boolean ones as plain bools."""
    out: dict[str, bool] = {}
    for key, value in values.items():
        v = value
        if hasattr(v, "detach"):
            v = v.detach().cpu().numpy()
        arr = np.asarray(v)
        if arr.dtype == bool and arr.size == 1:
            out[str(key)] = bool(arr.reshape(()))
    return out


class ManiSkillSim:
    """:class:`EpisodeSim` on the LADEV ManiSkill env, one env reused across episodes."""

    def __init__(self, setup: SimSetup) -> None:
        self.setup = setup
        self._env: Any = None
        self._spec: SceneSpec | None = None

    @property
    def env(self) -> Any:
        if self._env is None:
            raise RuntimeError("load() a scene first")
        return self._env

    def load(self, spec: SceneSpec, seed: int) -> None:
        if self._env is None:
            from ladev_lib.sim import make_env

            self._env = make_env(
                spec,
                self.setup.sim_config,
                control_mode=self.setup.control_mode,
                robot=self.setup.robot,
                image_size=self.setup.image_size,
                **({} if self.setup.prefer_meshes else {"prefer_meshes": False}),
            )
        # Rebuild the scene even when its layout matches the last episode's: a reused
        # physics scene keeps state (contacts, solver warm starts) from that episode, and
        # which episode came before depends on how the executor spread the work, so the
        # outcome would too.
        self._env.reset(seed=seed, options={"spec": spec, "reconfigure": True})
        self._spec = spec

    def action_bounds(self) -> tuple[Array, Array]:
        space = self.env.action_space
        return np.asarray(space.low, dtype=np.float64), np.asarray(space.high, dtype=np.float64)

    def invalid_reason(self) -> str | None:
        from ladev_lib.sim.validity import check_scene

        verdict = check_scene(self.env.unwrapped)
        return None if verdict.valid else verdict.reason or "invalid scene"

    def max_steps(self, task: str) -> int:
        from ladev_lib.sim.robots import episode_steps

        # The study's per-task lengths apply to the robot they were written for.
        overrides = None
        if self.setup.robot_config.get("name", self.setup.robot) == self.setup.robot:
            overrides = self.setup.robot_config.get("max_episode_steps") or None
        return episode_steps(self.setup.robot, task, overrides)

    def observe(self, *, image: bool, privileged: bool) -> Observation:
        u = self.env.unwrapped
        qpos = u.agent.robot.get_qpos()[0].detach().cpu().numpy().reshape(-1)
        tcp = u.agent.robot.links_map.get(u.profile.tcp_link)
        tcp_pose = tcp.pose.raw_pose[0].detach().cpu().numpy() if tcp is not None else np.zeros(0)
        priv = None
        if privileged:
            assert self._spec is not None
            from ladev_lib.sim.view import scene_view

            priv = PrivilegedState(spec=self._spec, object_poses=u.object_poses(), scene=scene_view(u))
        return Observation(
            image=u.policy_image() if image else None,
            proprio=np.concatenate([qpos, tcp_pose]).astype(np.float32),
            privileged=priv,
        )

    def step(self, action: Array) -> dict[str, bool]:
        _obs, _reward, _terminated, _truncated, info = self.env.step(action)
        return to_bool_dict(info)

    def evaluate(self) -> dict[str, bool]:
        return to_bool_dict(self.env.unwrapped.evaluate())

    def frame(self) -> Array:
        return np.asarray(self.env.unwrapped.policy_image())

    def close(self) -> None:
        if self._env is not None:
            self._env.close()
            self._env = None


def make_maniskill_sim(setup: SimSetup) -> EpisodeSim:
    """The default simulator factory of the rollout engine."""
    return ManiSkillSim(setup)
