"""Privileged policies see the scene through a read-only view, never the env."""

from __future__ import annotations

import numpy as np
import pytest

from ladev_lib.scenes.spec import SceneSpec


@pytest.mark.sim
def test_the_privileged_observation_carries_a_read_only_view() -> None:
    from ladev_lib.rollout.solvability import solvability_sim
    from ladev_lib.sim.view import SceneView

    spec = SceneSpec.model_validate({
        "objects": [
            {"name": "green_cube", "id": "green_cube", "x": -0.1, "y": 0.05, "role": "source"},
            {"name": "plate", "id": "plate", "x": -0.1, "y": -0.15, "role": "target"},
        ],
        "task": {"type": "put_on", "source": "green_cube", "target": "plate"},
    })
    sim = solvability_sim(prefer_meshes=False)
    try:
        sim.load(spec, 0)
        obs = sim.observe(image=False, privileged=True)
        assert obs.privileged is not None
        view = obs.privileged.scene
        assert isinstance(view, SceneView)
        # Nothing on it steps, resets or edits the simulation.
        public = {n for n in dir(view) if not n.startswith("_")}
        assert public == {"control_timestep", "robot", "object_names", "object_pose", "surface_points",
                          "is_grasping"}
        assert not any(hasattr(view.robot, n) for n in ("set_qpos", "step", "reset", "_env"))
        assert view.object_names() == ("green_cube", "plate")
        # The cube's surface points sit around its pose, a few centimetres across.
        pose = view.object_pose("green_cube")
        points = view.surface_points("green_cube", 500)
        assert points.shape[1] == 3 and len(points) >= 500
        assert np.allclose(points.mean(axis=0)[:2], pose[:2], atol=0.01)
        assert 0.02 < float(np.ptp(points[:, 0])) < 0.08
        np.testing.assert_allclose(pose, obs.privileged.object_poses["green_cube"])
        assert not view.is_grasping("green_cube")
        assert view.robot.qpos().shape == (9,) and view.robot.urdf_path.endswith(".urdf")
        lower, upper = view.robot.gripper_limits()
        assert lower < 0 < upper
        assert 0 < view.control_timestep < 0.2
    finally:
        sim.close()
