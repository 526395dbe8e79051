"""Floors: a policy that acts at random and one that holds still.

Both ignore the instruction and need no image, so they run at state-only
speed. They show what a success rate means: a VLA that does no better than
``random`` on a factor has learned nothing the factor measures.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.policies.base import EpisodeContext, Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.vocabulary import ROBOTS

DEFAULT_ROBOTS: tuple[str, ...] = ROBOTS


def _finite_bounds(ctx: EpisodeContext | None, action_dim: int | None) -> tuple[Array, Array]:
    if ctx is None:
        raise RuntimeError("begin_episode() must be called before step(): the policy needs the action bounds")
    low = np.asarray(ctx.action_low, dtype=np.float64)
    high = np.asarray(ctx.action_high, dtype=np.float64)
    # An unbounded dimension is sampled in [-1, 1]: the normalised range of delta controllers.
    low = np.where(np.isfinite(low), low, -1.0)
    high = np.where(np.isfinite(high), high, 1.0)
    if action_dim is not None and low.shape != (action_dim,):
        raise ValueError(f"action_dim={action_dim} does not match the action space {low.shape}")
    return low, high


class RandomPolicy(Policy):
    """Uniform random actions in the action space of its control mode, seeded per episode."""

    def __init__(
        self,
        control_mode: str = "pd_ee_delta_pose",
        robots: Sequence[str] = DEFAULT_ROBOTS,
        action_dim: int | None = None,
    ) -> None:
        self.info = PolicyInfo(
            name="random", robots=tuple(robots), control_mode=control_mode, image_size=None
        )
        self._action_dim = action_dim
        self._ctx: EpisodeContext | None = None
        self._rng = np.random.default_rng(0)

    def begin_episode(self, ctx: EpisodeContext) -> None:
        self._ctx = ctx
        self._rng = np.random.default_rng(ctx.seed)

    def reset(self, instruction: str) -> None:
        del instruction  # a floor: the text does not matter

    def step(self, obs: Observation) -> PolicyStep:
        low, high = _finite_bounds(self._ctx, self._action_dim)
        return PolicyStep(action=self._rng.uniform(low, high).astype(np.float32))


class NoopPolicy(Policy):
    """Holds still: zero end-effector deltas, gripper left open.

    In ManiSkill's delta controllers an all-zero arm action keeps the pose;
    the gripper's normalised target is absolute, and its upper bound (the open
    position the robots start in) keeps it where it is.
    """

    def __init__(
        self,
        control_mode: str = "pd_ee_delta_pose",
        robots: Sequence[str] = DEFAULT_ROBOTS,
    ) -> None:
        self.info = PolicyInfo(
            name="noop", robots=tuple(robots), control_mode=control_mode, image_size=None
        )
        self._action: Array | None = None

    def begin_episode(self, ctx: EpisodeContext) -> None:
        low, high = _finite_bounds(ctx, None)
        action = np.clip(np.zeros_like(low), low, high)
        action[-1] = high[-1]
        self._action = action.astype(np.float32)

    def reset(self, instruction: str) -> None:
        del instruction

    def step(self, obs: Observation) -> PolicyStep:
        if self._action is None:
            raise RuntimeError("begin_episode() must be called before step()")
        return PolicyStep(action=self._action.copy())
