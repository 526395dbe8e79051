"""The privileged oracle: solves a scene's task by motion planning on true state.

    policy = make_policy("oracle")
    policy.reset(instruction)             # the instruction is ignored
    step = policy.step(obs)               # obs.privileged: spec, poses, the env

It reads the task (type, source, target) from ``obs.privileged.spec`` and the
objects from the simulator, never from the instruction, and drives the Panda
with :class:`~ladev_lib.policies.skills.TaskSkill`: one ``pd_joint_pos`` action
per step, each phase planned from the state it starts in. It ends the episode
(``terminate=True``) when the skill is done or has given up; ``outcome`` then
says which, and why.

This is LADEV's solvability check for generated scenes (``ladev_lib.rollout.solvability``).
"""

from __future__ import annotations

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.policies.motion import SkillOutcome
from ladev_lib.policies.skills import TaskSkill
from ladev_lib.scenes.spec import SceneBounds

ORACLE_MAX_EPISODE_STEPS = 400
"""At 20 Hz: room for a re-grasp after a slip; a clean put_on takes about 120 steps."""
PLACE_MARGIN_M = 0.06
"""move_near may put the object down this far outside the study's spawn workspace."""


class OraclePolicy(Policy):
    """Scripted motion-planning policy with access to the simulator state (Panda only)."""

    info = PolicyInfo(
        name="oracle",
        robots=("panda",),
        control_mode="pd_joint_pos",
        image_size=None,
        privileged=True,
        max_episode_steps=ORACLE_MAX_EPISODE_STEPS,
    )

    def __init__(self, max_attempts: int = 3, bounds: SceneBounds | dict[str, object] | None = None):
        if max_attempts < 1:
            raise ValueError(f"max_attempts must be at least 1, got {max_attempts}")
        self.max_attempts = max_attempts
        self.bounds = bounds if isinstance(bounds, SceneBounds) else SceneBounds.model_validate(bounds or {})
        self._skill: TaskSkill | None = None
        self._last_action: Array | None = None

    def reset(self, instruction: str) -> None:
        self._skill = None
        self._last_action = None

    @property
    def outcome(self) -> SkillOutcome | None:
        """How the current episode's skill stands; None before the first step."""
        return None if self._skill is None else self._skill.outcome

    def step(self, obs: Observation) -> PolicyStep:
        if self._skill is None:
            self._skill = self._start(obs)
        action = next(self._skill, None)
        if action is None:
            hold = self._last_action if self._last_action is not None else self._skill.hold_action()
            return PolicyStep(action=hold, terminate=True)
        self._last_action = action
        return PolicyStep(action=action)

    def _start(self, obs: Observation) -> TaskSkill:
        priv = obs.privileged
        if priv is None or priv.scene is None:
            raise ValueError(
                "the oracle needs privileged state with the scene's view "
                "(Observation.privileged.scene); run it through the episode engine"
            )
        spec, view = priv.spec, priv.scene
        if spec.robot != "panda":
            raise ValueError(f"the oracle drives the Panda only; this scene is for {spec.robot!r}")
        return TaskSkill(
            view,
            spec.task.type,
            spec.task.source,
            spec.task.target,
            region=self._region(view),
            max_attempts=self.max_attempts,
        )

    def _region(self, env: object) -> tuple[tuple[float, float], tuple[float, float]] | None:
        """The study's workspace in world coordinates, where move_near may put things down."""
        to_world = getattr(env, "workspace_to_world", None)
        if to_world is None:
            return None
        (x0, x1), (y0, y1) = self.bounds.workspace_x_m, self.bounds.workspace_y_m
        corners = np.array([to_world(x, y)[:2] for x in (x0, x1) for y in (y0, y1)])
        # Objects may be set down a little outside where scenes spawn them.
        lo, hi = corners.min(axis=0) - PLACE_MARGIN_M, corners.max(axis=0) + PLACE_MARGIN_M
        return (float(lo[0]), float(hi[0])), (float(lo[1]), float(hi[1]))
