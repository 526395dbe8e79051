"""The VLA adapters' embodiments (numpy-only constants) match what LADEV's simulator offers:
each robot has the control mode an adapter's actions are for, and an episode steps with it."""

from __future__ import annotations

import numpy as np
import pytest

from ladev_lib.policies.adapters.common import EMBODIMENTS
from ladev_lib.sim.robots import get_robot


@pytest.mark.parametrize("robot", sorted(EMBODIMENTS))
def test_the_simulator_offers_each_adapter_control_mode(robot):
    assert EMBODIMENTS[robot].control_mode in get_robot(robot).control_modes


def test_the_lerobot_panda_embodiment_matches_the_simulator():
    from ladev_lib.policies.adapters.lerobot_maps import PANDA_EMBODIMENT

    panda = get_robot("panda")
    assert PANDA_EMBODIMENT.control_mode in panda.control_modes
    assert PANDA_EMBODIMENT.control_freq_hz == panda.control_freq_hz
    assert dict(PANDA_EMBODIMENT.episode_steps) == dict(panda.max_episode_steps)


@pytest.mark.sim
@pytest.mark.assets
@pytest.mark.parametrize("robot", sorted(EMBODIMENTS))
def test_an_adapter_action_steps_the_robot_at_its_camera_size(robot, catalog):
    from ladev_lib.scenes.sampling import sample_scene
    from ladev_lib.sim import make_env
    from ladev_lib.sim.config import SimConfig

    emb = EMBODIMENTS[robot]
    spec = sample_scene("pick_up", 2, "simpler", np.random.default_rng(0), catalog, robot=robot)
    env = make_env(spec, SimConfig(), control_mode=emb.control_mode, robot=robot, image_size=emb.image_size)
    try:
        env.reset(seed=0)
        u = env.unwrapped
        assert env.action_space.shape == (7,)
        action = np.zeros(7, dtype=np.float32)
        action[0] = 0.02  # 2 cm forward, SimplerEnv's action convention
        for _ in range(3):
            env.step(action)
        image = u.policy_image()
        assert image.shape == (emb.image_size[1], emb.image_size[0], 3) and image.dtype == np.uint8
    finally:
        env.close()
