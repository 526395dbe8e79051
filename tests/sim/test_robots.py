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
    {"name": "green_cube", "x": 0.08, "y": 0.1, "role": "source"},
    {"name": "plate", "x": -0.05, "y": -0.08, "role": "target"},
    {"name": "coke_can", "x": -0.06, "y": 0.1},
]


@pytest.mark.parametrize("robot", ["widowx", "google_robot"])
def test_pack_robot_scene(robot: str) -> None:
    from ladev_lib.sim import SimConfig, make_env

    spec = make_spec(OBJECTS, {"type": "put_on", "source": "green_cube", "target": "plate"}, robot=robot)
    env = make_env(spec, SimConfig(image_size=(128, 128)), control_mode=None, obs_mode="rgb")
    try:
        obs, _ = env.reset(seed=0)
        u = env.unwrapped
        # image observations carry the same picture as policy_image(), real background included
        assert np.array_equal(obs["sensor_data"]["policy"]["rgb"][0].numpy(), u.policy_image())
        profile = get_robot(robot)
        assert u.agent.control_mode == profile.default_control_mode
        assert u.overlay_active  # the pack has this robot's real background
        v = check_scene(u)
        assert v.valid, v.reasons
        tcp = u.agent.robot.links_map[profile.tcp_link]
        p0 = tcp.pose.p[0].numpy().copy()
        hold = np.zeros(env.action_space.shape, dtype=np.float32)
        for _ in range(3):
            env.step(hold)
        assert np.abs(tcp.pose.p[0].numpy() - p0).max() < 0.005  # a zero delta holds the pose
        forward = hold.copy()
        forward[0] = 0.02  # end-effector delta along the robot's x: away from the robot
        for _ in range(3):
            env.step(forward)
        moved = u.world_to_workspace(tcp.pose.p[0].numpy()) - u.world_to_workspace(p0)
        assert moved[0] > 0.02 and abs(moved[1]) < 0.01
        # a cube closed between the fingers counts as grasped (ManiSkill's / SimplerEnv's check)
        env.reset(seed=0)
        body = u.objects["green_cube"]._bodies[0]
        body.disable_gravity = True
        u.teleport("green_cube", tcp.pose.p[0].numpy(), np.array([1.0, 0, 0, 0]))
        close = hold.copy()
        close[-1] = 1.0 if robot == "google_robot" else -1.0  # each robot's "close" sign
        for _ in range(6):
            env.step(close)
        body.disable_gravity = False
        for _ in range(4):
            env.step(close)
        assert {k: bool(v[0]) for k, v in u.evaluate().items()}["success"] is False  # put_on: held, not placed
        assert bool(u.is_grasped("green_cube")[0])
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
