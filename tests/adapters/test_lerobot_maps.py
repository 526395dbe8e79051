"""The LeRobot adapter's pure mappings (numpy only: core install and .venv-lerobot)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ladev_lib.errors import ConfigError
from ladev_lib.policies.adapters.common import EMBODIMENTS, embodiment
from ladev_lib.policies.adapters.lerobot_maps import (
    LEROBOT_EMBODIMENTS,
    ActionMapper,
    fit_image,
    openness,
    quat_to_euler,
    state_vector,
)

H = math.sqrt(0.5)


@pytest.mark.parametrize(
    ("wxyz", "rpy"),
    [
        ((1, 0, 0, 0), (0, 0, 0)),
        ((H, H, 0, 0), (math.pi / 2, 0, 0)),  # 90 degrees about x
        ((math.cos(0.25), 0, math.sin(0.25), 0), (0, 0.5, 0)),  # 0.5 rad about y
        ((H, 0, 0, -H), (0, 0, -math.pi / 2)),  # -90 degrees about z
        ((0, 1, 0, 0), (math.pi, 0, 0)),  # half turn about x
    ],
)
def test_quat_to_euler_hand_values(wxyz, rpy) -> None:
    np.testing.assert_allclose(quat_to_euler(np.array(wxyz, dtype=float)), rpy, atol=1e-9)


def test_state_layouts() -> None:
    proprio = np.array([0.1, 0.2, 0.3, 1.0, 2.0, 3.0, H, 0.0, 0.0, H])  # 3 joints + TCP pose
    np.testing.assert_allclose(state_vector(proprio, "proprio", 10, "observation.state"), proprio, rtol=1e-6)
    np.testing.assert_allclose(state_vector(proprio, "qpos", 3, "s"), [0.1, 0.2, 0.3], rtol=1e-6)
    np.testing.assert_allclose(state_vector(proprio, "tcp_pose", 7, "s"), proprio[3:], rtol=1e-6)
    np.testing.assert_allclose(state_vector(proprio, "tcp_euler", 6, "s"), [1, 2, 3, 0, 0, math.pi / 2], atol=1e-6)
    # LIBERO: xyz, axis-angle of a 90 degree yaw, the last two joints (the fingers)
    np.testing.assert_allclose(
        state_vector(proprio, "libero", 8, "s"), [1, 2, 3, 0, 0, math.pi / 2, 0.2, 0.3], atol=1e-6
    )
    assert state_vector(None, "zeros", 4, "s").tolist() == [0, 0, 0, 0]
    with pytest.raises(ValueError, match=r"'observation.state' has 8 values; state_layout 'qpos' gives 3"):
        state_vector(proprio, "qpos", 8, "observation.state")
    with pytest.raises(ValueError, match="no proprioception"):
        state_vector(None, "proprio", 10, "observation.state")
    with pytest.raises(ConfigError, match="state_layout"):
        state_vector(proprio, "joints", 3, "s")


def test_openness_conventions() -> None:
    assert openness(0.8, "open_is_1") == 0.8
    assert openness(0.8, "close_is_1") == pytest.approx(0.2)
    assert openness(-1.0, "signed_open") == 0.0 and openness(1.0, "signed_open") == 1.0
    assert openness(1.0, "signed_close") == 0.0 and openness(-1.0, "signed_close") == 1.0


def test_action_mapper_widowx_euler_and_panda_libero() -> None:
    widowx = ActionMapper(EMBODIMENTS["widowx"], "ee_delta_euler", "open_is_1", action_scale=1.0)
    # roll 0.3 alone is the axis-angle (0.3, 0, 0); openness 0.2 -> close (-1)
    out = widowx(np.array([0.01, 0.02, -0.03, 0.3, 0.0, 0.0, 0.2, 99.0]))  # extra (padded) value ignored
    np.testing.assert_allclose(out, [0.01, 0.02, -0.03, 0.3, 0.0, 0.0, -1.0], atol=1e-12)
    panda = ActionMapper(LEROBOT_EMBODIMENTS["panda"], "ee_delta_axis_angle", "signed_close", action_scale=0.5)
    # LIBERO: -1 = open -> +1 for ManiSkill's Panda gripper; translation and rotation halved
    np.testing.assert_allclose(panda(np.array([0.2, 0, 0, 0, 0.4, 0, -1.0])), [0.1, 0, 0, 0, 0.2, 0, 1.0])
    split = ActionMapper(LEROBOT_EMBODIMENTS["panda"], "ee_delta_axis_angle", "signed_close", 0.5, 5.0)
    np.testing.assert_allclose(split(np.array([0.2, 0, 0, 0, 0.04, 0, 1.0])), [0.1, 0, 0, 0, 0.2, 0, -1.0])
    assert ActionMapper(EMBODIMENTS["widowx"], "joint_pos")(np.arange(8.0)).tolist() == list(range(8))
    with pytest.raises(ValueError, match=">= 7 action values"):
        widowx(np.zeros(6))
    with pytest.raises(ConfigError, match="action_layout"):
        ActionMapper(EMBODIMENTS["widowx"], "joint_vel")


def test_google_robot_gripper_is_a_held_relative_command() -> None:
    mapper = ActionMapper(EMBODIMENTS["google_robot"], "ee_delta_euler", "open_is_1")
    grips = [mapper(np.array([0, 0, 0, 0, 0, 0, g]))[6] for g in (1.0, 0.0, 0.0)]
    # open, then closing: previous - current = 1 (close), held for the sticky steps
    assert grips == [0.0, 1.0, 1.0]
    mapper.reset()
    assert mapper(np.array([0, 0, 0, 0, 0, 0, 0.0]))[6] == 0.0


def test_panda_embodiment_only_for_lerobot() -> None:
    assert embodiment("panda", table=LEROBOT_EMBODIMENTS).control_mode == "pd_ee_delta_pose"
    with pytest.raises(ConfigError, match="support robots"):
        embodiment("panda")  # RT-1 / Octo / OpenVLA: SimplerEnv's robots only


def test_fit_image_resizes_to_the_declared_feature() -> None:
    img = np.zeros((480, 640, 3), dtype=np.uint8)
    img[:, 320:] = 200
    out = fit_image(img, (3, 48, 64))
    assert out.shape == (48, 64, 3) and out.dtype == np.uint8 and out.flags.writeable
    assert out[0, 0, 0] == 0 and out[0, -1, 0] == 200
    with pytest.raises(ValueError, match=r"\(3, H, W\)"):
        fit_image(img, (48, 64))
