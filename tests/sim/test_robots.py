"""WidowX and the Google robot (asset pack): build, hold still, see the workspace."""

from __future__ import annotations

import numpy as np
import pytest
import sapien

from ladev_lib.sim.robots import get_robot
from ladev_lib.sim.validity import check_scene
from tests.sim.conftest import make_spec

pytestmark = [pytest.mark.sim, pytest.mark.assets]

OBJECTS = [
    {"name": "coke_can", "x": 0.05, "y": 0.08, "role": "source"},
    {"name": "plate", "x": -0.05, "y": -0.08, "role": "target"},
]


@pytest.mark.parametrize("robot", ["widowx", "google_robot"])
def test_pack_robot_scene(robot: str) -> None:
    from ladev_lib.sim import SimConfig, make_env

    spec = make_spec(OBJECTS, {"type": "put_on", "source": "coke_can", "target": "plate"}, robot=robot)
    env = make_env(spec, SimConfig(image_size=(128, 128)), control_mode=None)
    try:
        env.reset(seed=0)
        u = env.unwrapped
        profile = get_robot(robot)
        assert u.agent.control_mode == profile.default_control_mode
        assert u.overlay_active  # the pack has this robot's real background
        v = check_scene(u)
        assert v.valid, v.reasons
        q0 = u.agent.robot.get_qpos().clone()
        for _ in range(3):
            env.step(None)
        assert float((u.agent.robot.get_qpos() - q0).abs().max()) < 0.02  # holds its pose
        with_bg, without_bg = u.policy_image(), u.policy_image(overlay=False)
        assert with_bg.shape == (128, 128, 3)
        assert np.abs(with_bg.astype(int) - without_bg.astype(int)).mean() > 10
        if robot == "google_robot":
            # the fixed policy camera sits where SimplerEnv mounts it on link_camera
            link = u.agent.robot.links_map["link_camera"].pose
            mounted = link * sapien.Pose([0, 0, 0], [0.5, 0.5, -0.5, 0.5])
            assert np.allclose(mounted.raw_pose[0, :3].numpy(), profile.policy_camera.p, atol=2e-3)
            assert abs(float(np.dot(mounted.raw_pose[0, 3:].numpy(), profile.policy_camera.q))) > 0.999
    finally:
        env.close()
