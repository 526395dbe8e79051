"""The scene env: building a spec, reuse through reset options, lighting and camera."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from ladev_lib.assets import asset_dir
from ladev_lib.errors import ConfigError
from tests.sim.conftest import image_difference, make_spec

pytestmark = pytest.mark.sim

BASE = [
    {"name": "coke_can", "x": 0.05, "y": 0.12, "yaw_deg": 30.0, "role": "source"},
    {"name": "sponge", "x": -0.05, "y": -0.12, "yaw_deg": -45.0},
    {"name": "yellow_cube", "x": 0.1, "y": -0.05},
]
PICK = {"type": "pick_up", "source": "coke_can"}


def test_objects_stand_where_the_spec_puts_them(build: Any) -> None:
    u = build(make_spec(BASE, PICK))
    assert u.spec.objects[0].name == "coke_can" and u.spec.task.type == "pick_up"
    assert set(u.objects) == {"coke_can", "sponge", "yellow_cube"}
    have_meshes = asset_dir() is not None
    assert u.object_sources == {n: "mesh" if have_meshes else "standin" for n in u.objects}
    poses = u.object_poses()
    for o in BASE:
        pose = poses[o["name"]]
        assert pose.shape == (7,)
        expected = u.workspace_to_world(o["x"], o["y"])
        assert np.allclose(pose[:2], expected[:2], atol=0.005), o["name"]
        # upright, on the table: the box bottom sits on the table top
        bottom = u.box_center_world(o["name"])[2] - u.built[o["name"]].half_extents[2]
        assert abs(bottom - u.profile.table_top_z) < 0.005, o["name"]
    yaw = 2 * np.arctan2(poses["sponge"][6], poses["sponge"][3])
    assert np.isclose(np.degrees(yaw), -45.0, atol=1.0)
    assert np.allclose(u.world_to_workspace(u.workspace_to_world(0.1, -0.2, 0.05)), [0.1, -0.2, 0.05])


def test_reset_with_same_objects_reposes_without_rebuilding(panda_env: Any, build: Any) -> None:
    u = build(make_spec(BASE, PICK))
    actor = u.objects["coke_can"]
    moved = [{**o, "x": -o["x"]} for o in BASE]
    _, info = panda_env.reset(seed=3, options={"spec": make_spec(moved, PICK, seed=3).model_dump(mode="json")})
    assert bool(info["reconfigure"]) is False
    assert u.objects["coke_can"] is actor  # same actor, new pose
    assert np.allclose(u.object_poses()["coke_can"][:2], u.workspace_to_world(-0.05, 0.12)[:2], atol=0.005)
    assert u.spec.seed == 3


def test_reset_with_other_objects_rebuilds(panda_env: Any, build: Any) -> None:
    build(make_spec(BASE, PICK))
    other = make_spec(
        [
            {"name": "apple", "x": 0.0, "y": 0.1, "role": "source"},
            {"name": "basket", "x": 0.0, "y": -0.12, "role": "target"},
        ],
        {"type": "put_in", "source": "apple", "target": "basket"},
    )
    _, info = panda_env.reset(seed=0, options={"spec": other.model_dump(mode="json")})
    u = panda_env.unwrapped
    assert bool(info["reconfigure"]) is True
    assert set(u.objects) == {"apple", "basket"} and u.spec.task.type == "put_in"
    assert set(u.evaluate()) == {"inside", "not_on_table", "released", "success"}


def test_lighting_changes_the_image(build: Any) -> None:
    u = build(make_spec(BASE, PICK))
    default = u.policy_image()
    assert default.shape == (128, 128, 3) and default.dtype == np.uint8
    darker = build(make_spec(BASE, PICK, lighting={"intensity_delta": -0.5})).policy_image()
    brighter = build(make_spec(BASE, PICK, lighting={"intensity_delta": 0.5})).policy_image()
    assert darker.mean() < default.mean() - 5 < brighter.mean() - 10
    assert image_difference(default, darker) > 5


def test_camera_offset_changes_the_image(build: Any) -> None:
    default = build(make_spec(BASE, PICK)).policy_image()
    moved = build(make_spec(BASE, PICK, camera={"translation_m": [0.0, 0.05, 0.0]})).policy_image()
    turned = build(make_spec(BASE, PICK, camera={"rotation_deg": [0.0, 0.0, 5.0]})).policy_image()
    again = build(make_spec(BASE, PICK)).policy_image()
    assert image_difference(default, again) < 0.5  # the offset is undone on the next default spec
    assert image_difference(default, moved) > 3
    assert image_difference(default, turned) > 3


def test_camera_offset_follows_the_documented_directions(build: Any) -> None:
    u = build(make_spec(BASE, PICK))
    base = u.policy_camera_pose()
    u2 = build(make_spec(BASE, PICK, camera={"translation_m": [0.0, 0.03, 0.0], "rotation_deg": [0, 5, 0]}))
    moved = u2.policy_camera_pose()
    assert np.allclose(np.asarray(moved.p) - np.asarray(base.p), u.profile.workspace_vector_to_world((0, 0.03, 0)))
    fwd_base = base.to_transformation_matrix()[:3, 0]
    fwd_moved = moved.to_transformation_matrix()[:3, 0]
    assert fwd_moved[2] < fwd_base[2]  # positive pitch tilts the view down
    panned = build(make_spec(BASE, PICK, camera={"rotation_deg": [0, 0, 5]})).policy_camera_pose()
    left_base = base.to_transformation_matrix()[:3, 1]
    assert panned.to_transformation_matrix()[:3, 0] @ left_base > 0.05  # positive yaw pans left


def test_robot_override_and_bad_control_mode(build: Any) -> None:
    from ladev_lib.sim import make_env

    spec = make_spec(BASE, PICK)
    with pytest.raises(ConfigError, match="control_mode 'nonsense' is not available on panda"):
        make_env(spec, control_mode="nonsense", image_size=None)
    u = build(spec)
    with pytest.raises(ConfigError, match="one env per robot"):
        u.reset(options={"spec": spec.model_copy(update={"robot": "widowx"}).model_dump(mode="json")})


def test_state_only_env_with_robot_override() -> None:
    from ladev_lib.sim import make_env

    widowx_spec = make_spec(BASE, PICK, robot="widowx")  # simulated on Panda instead
    env = make_env(widowx_spec, image_size=None, control_mode="pd_ee_delta_pose", robot="panda")
    try:
        env.reset(seed=0)
        u = env.unwrapped
        assert u.spec.robot == "panda" and u.agent.control_mode == "pd_ee_delta_pose"
        with pytest.raises(ConfigError, match="no policy camera"):
            u.policy_image()
        obs, *_ = env.step(np.zeros(env.action_space.shape, dtype=np.float32))
        assert "tcp_pose" in obs["extra"]
        assert u.predicates() == {"is_grasped": False, "lifted": False, "success": False}
        env.reset(options={"spec": widowx_spec.model_dump(mode="json")})  # the override persists
        assert u.spec.robot == "panda"
    finally:
        env.close()
