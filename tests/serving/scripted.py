"""A scripted policy whose actions reveal what it was given (for server tests)."""

from __future__ import annotations

import time

import numpy as np

from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep


class ScriptedPolicy(Policy):
    """action = [step in episode, len(instruction), image mean, sum(proprio), resets, 0, 0].

    ``delay_s`` makes each step slow; ``fail_at_step`` raises at that step;
    it asks to terminate at step ``terminate_at``.
    """

    def __init__(
        self, delay_s: float = 0.0, fail_at_step: int | None = None, terminate_at: int = 3
    ) -> None:
        self.info = PolicyInfo(
            name="scripted",
            robots=("widowx",),
            control_mode="arm_pd_ee_target_delta_pose_align2_gripper_pd_joint_pos",
            image_size=(64, 48),
            control_freq_hz=5.0,
            max_episode_steps=60,
            camera="3rd_view_camera",
            max_episode_steps_by_task={"put_in": 120},
        )
        self.delay_s = delay_s
        self.fail_at_step = fail_at_step
        self.terminate_at = terminate_at
        self.instruction = ""
        self.t = 0
        self.resets = 0

    def reset(self, instruction: str) -> None:
        self.instruction = instruction
        self.t = 0
        self.resets += 1

    def step(self, obs: Observation) -> PolicyStep:
        if self.delay_s:
            time.sleep(self.delay_s)
        if self.fail_at_step is not None and self.t == self.fail_at_step:
            raise ValueError(f"scripted failure at step {self.t}")
        image_mean = float(obs.image.mean()) if obs.image is not None else -1.0
        proprio = float(np.sum(obs.proprio)) if obs.proprio is not None else -1.0
        action = np.array([self.t, len(self.instruction), image_mean, proprio, self.resets, 0, 0])
        self.t += 1
        return PolicyStep(action=action, terminate=self.t >= self.terminate_at)
