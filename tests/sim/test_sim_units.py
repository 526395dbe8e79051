"""Pure parts of the simulation core (no scene is built): config, frames, stand-in shapes."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.config import compose_config, section
from ladev_lib.errors import ConfigError, UnknownNameError
from ladev_lib.sim.config import RobotConfig, SimConfig
from ladev_lib.sim.geometry import look_at
from ladev_lib.sim.robots import ROBOTS, episode_steps, get_robot


@pytest.mark.parametrize("robot", ["panda", "widowx", "google_robot"])
def test_conf_groups_validate(robot: str) -> None:
    cfg = compose_config([f"robot={robot}"])
    sim = section(cfg, "sim", SimConfig)
    rob = section(cfg, "robot", RobotConfig)
    assert sim.image_size == (256, 256) and rob.name == robot
    profile = get_robot(robot)
    for task, steps in rob.max_episode_steps.items():
        assert steps == profile.max_episode_steps[task]  # the yaml documents the defaults
    assert episode_steps(robot, "put_in", {"put_in": 7}) == 7


def test_bad_sim_config_names_the_key() -> None:
    with pytest.raises(ConfigError, match="sim.image_size"):
        section({"sim": {"image_size": [4, 4]}}, "sim", SimConfig)
    with pytest.raises(ConfigError, match="sim.settle_s"):
        section({"sim": {"settle_s": -1}}, "sim", SimConfig)
    with pytest.raises(UnknownNameError, match="known: google_robot, panda, widowx"):
        get_robot("ur5")


@pytest.mark.parametrize("name", ["panda", "widowx", "google_robot"])
def test_workspace_frame_round_trip_and_axes(name: str) -> None:
    r = get_robot(name)
    p = r.workspace_to_world(0.1, -0.2, 0.03)
    assert np.allclose(r.world_to_workspace(p), [0.1, -0.2, 0.03])
    # +x of the workspace points away from the robot base
    near, far = r.workspace_to_world(-0.1, 0.0), r.workspace_to_world(0.1, 0.0)
    assert r.horizontal_reach(far[:2]) > r.horizontal_reach(near[:2])
    # +y is the robot's left: counter-clockwise from +x seen from above
    fwd = r.workspace_vector_to_world((1, 0, 0))
    left = r.workspace_vector_to_world((0, 1, 0))
    assert np.cross(fwd, left)[2] > 0.99
    # the default workspace centre is within reach
    lo, hi = r.reach_m
    assert lo < r.horizontal_reach(r.workspace_to_world(0, 0)[:2]) < hi
    assert r.default_control_mode in r.control_modes and "pd_joint_pos" in r.control_modes


def test_look_at_points_the_camera_x_axis_at_the_target() -> None:
    import sapien

    eye, target = (0.3, 0.1, 0.6), (-0.1, -0.05, 0.0)
    m = sapien.Pose(q=list(look_at(eye, target))).to_transformation_matrix()[:3, :3]
    d = np.subtract(target, eye) / np.linalg.norm(np.subtract(target, eye))
    assert np.allclose(m[:, 0], d, atol=1e-6)
    assert abs(m[2, 1]) < 1e-6  # no roll: the left axis stays horizontal


def test_intrinsics_scale_with_the_image() -> None:
    cam = get_robot("widowx").policy_camera
    k = cam.intrinsic((320, 240))
    assert k[0, 0] == pytest.approx(cam.fx / 2) and k[1, 2] == pytest.approx(cam.cy / 2)


def test_standin_shapes_match_catalog_sizes() -> None:
    from ladev_lib.sim.objects import _standin_shapes

    for obj in load_catalog():
        parts, half = _standin_shapes(obj)
        assert parts, obj.id
        assert np.all(2 * half <= np.asarray(obj.size_m) * 1.25 + 1e-9), obj.id
        if obj.shape == "container":
            assert len(parts) == 5  # floor and four walls: open at the top


def test_kinematics_urdf_rewrites_infinite_limits(tmp_path: Path) -> None:
    from ladev_lib.sim.agents import kinematics_urdf

    src = tmp_path / "r.urdf"
    src.write_text('<robot><joint><limit lower="-inf" upper="inf"/></joint></robot>')
    out = Path(kinematics_urdf(str(src)))
    assert out != src and 'lower="-1e6" upper="1e6"' in out.read_text()
    clean = tmp_path / "c.urdf"
    clean.write_text('<robot><joint><limit lower="-1" upper="1"/></joint></robot>')
    assert kinematics_urdf(str(clean)) == str(clean)


def test_every_task_and_robot_is_registered() -> None:
    from ladev_lib.sim.tasks import TASKS, get_task

    assert TASKS.names() == ["move_near", "pick_up", "put_in", "put_on"]
    assert all(get_task(n).name == n for n in TASKS.names())
    assert ROBOTS.names() == ["google_robot", "panda", "widowx"]
    assert "Success Conditions" in (type(get_task("put_on")).__doc__ or "")
    assert math.isclose(get_robot("panda").table_top_z, 0.0)
