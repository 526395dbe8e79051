"""Shared VLA pre/post-processing against hand-computed values (core install, no ML stacks)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ladev_lib.errors import ConfigError
from ladev_lib.policies.adapters.common import (
    EMBODIMENTS,
    GOOGLE_ROBOT_CONTROL_MODE,
    WIDOWX_CONTROL_MODE,
    ActionEnsembler,
    EulerOpenGripperPostprocessor,
    StickyGripper,
    binarize_open_gripper,
    embodiment,
    euler_to_axis_angle,
    policy_info,
    postprocess_rt1,
    rescale_with_bounds,
    unnormalize_bounds,
    unnormalize_gaussian,
)


def test_euler_single_axes_are_their_own_axis_angle() -> None:
    np.testing.assert_allclose(euler_to_axis_angle(0.3, 0, 0), [0.3, 0, 0], atol=1e-12)
    np.testing.assert_allclose(euler_to_axis_angle(0, -0.4, 0), [0, -0.4, 0], atol=1e-12)
    np.testing.assert_allclose(euler_to_axis_angle(0, 0, -0.2), [0, 0, -0.2], atol=1e-12)
    np.testing.assert_allclose(euler_to_axis_angle(0, 0, 0), [0, 0, 0])


def test_euler_composite_by_hand() -> None:
    """Rz(pi/2) Rx(pi/2): quaternion (1/2, 1/2, 1/2, 1/2) -> 120 deg about (1, 1, 1)/sqrt(3)."""
    expected = (2 * math.pi / 3) / math.sqrt(3)
    np.testing.assert_allclose(euler_to_axis_angle(math.pi / 2, 0, math.pi / 2), [expected] * 3)


def _rodrigues(rotvec: np.ndarray) -> np.ndarray:
    angle = float(np.linalg.norm(rotvec))
    if angle < 1e-12:
        return np.eye(3)
    kx, ky, kz = rotvec / angle
    k = np.array([[0, -kz, ky], [kz, 0, -kx], [-ky, kx, 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def test_euler_matches_the_rotation_matrix_convention() -> None:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (static x, y, z), checked on the matrices."""
    rng = np.random.default_rng(0)
    for r, p, y in rng.uniform(-1.2, 1.2, size=(20, 3)):
        rotvec = euler_to_axis_angle(r, p, y)
        cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
        rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
        ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
        rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
        np.testing.assert_allclose(_rodrigues(rotvec), rz @ ry @ rx, atol=1e-9)
        assert np.linalg.norm(rotvec) <= math.pi + 1e-9


def test_rescale_with_bounds_rt1x_bridge() -> None:
    out = rescale_with_bounds(np.array([0.875, -1.75, 2.0]), -1.75, 1.75, -0.05, 0.05)
    np.testing.assert_allclose(out, [0.025, -0.05, 0.05])


def test_unnormalize_gaussian_honours_the_mask() -> None:
    stats = {"mean": [1.0, 2.0, 0.0], "std": [0.5, 2.0, 3.0], "mask": [True, False, True]}
    np.testing.assert_allclose(unnormalize_gaussian(np.array([2.0, 3.0, -1.0]), stats), [2.0, 3.0, -3.0])
    np.testing.assert_allclose(
        unnormalize_gaussian(np.array([2.0, 3.0, -1.0]), stats, use_mask=False), [2.0, 8.0, -3.0]
    )
    no_mask = {"mean": [1.0, 2.0], "std": [0.5, 2.0]}
    np.testing.assert_allclose(unnormalize_gaussian(np.array([2.0, 3.0]), no_mask), [2.0, 8.0])


def test_unnormalize_bounds_q01_q99() -> None:
    stats = {"q01": [-1.0, -1.0, 0.0], "q99": [3.0, 3.0, 1.0], "mask": [True, True, False]}
    np.testing.assert_allclose(unnormalize_bounds(np.array([0.0, 1.0, 0.7]), stats), [1.0, 3.0, 0.7])


def test_action_ensembler_uniform_weights() -> None:
    ens = ActionEnsembler(horizon=3, temperature=0.0)
    chunks = [np.array([[1.0], [2.0], [3.0]]) * 10**k for k in range(4)]
    out = [float(ens(c)[0]) for c in chunks]
    # step 1: 1; step 2: mean(2, 10); step 3: mean(3, 20, 100); step 4: mean(30, 200, 1000)
    np.testing.assert_allclose(out, [1.0, 6.0, 41.0, 410.0])
    ens.reset()
    assert float(ens(chunks[3])[0]) == 1000.0


def test_action_ensembler_exponential_weights_favour_older_predictions() -> None:
    ens = ActionEnsembler(horizon=2, temperature=1.0)
    ens(np.array([[1.0], [2.0]]))
    out = float(ens(np.array([[10.0], [20.0]]))[0])
    expected = (2.0 * 1 + 10.0 * math.exp(-1)) / (1 + math.exp(-1))
    assert out == pytest.approx(expected)


def test_action_ensembler_rejects_short_chunks() -> None:
    with pytest.raises(ValueError, match="chunk"):
        ActionEnsembler(horizon=4)(np.zeros((2, 7)))


def test_sticky_gripper_by_hand() -> None:
    sticky = StickyGripper(repeat=3)
    openness = [1, 1, 0, 0, 0, 0, 1, 1, 1, 1]
    out = [sticky(v) for v in openness]
    # close (prev 1 - now 0 = +1) held 3 steps, then open (-1) held 3 steps
    assert out == [0, 0, 1, 1, 1, 0, -1, -1, -1, 0]
    sticky.reset()
    assert [sticky(v) for v in (0.5, 0.3, 0.3)] == pytest.approx([0.0, 0.2, 0.0])


def test_sticky_gripper_google_robot_holds_15_steps() -> None:
    sticky = StickyGripper(repeat=EMBODIMENTS["google_robot"].sticky_gripper_steps)
    out = [sticky(v) for v in [1.0] + [0.0] * 20]
    assert out[1:16] == [1.0] * 15 and out[16:] == [0.0] * 5


def test_binarize_open_gripper() -> None:
    assert [binarize_open_gripper(v) for v in (0.51, 0.5, 0.2, 1.0)] == [1.0, -1.0, -1.0, 1.0]


def test_euler_open_gripper_postprocessor_per_robot() -> None:
    widowx = EulerOpenGripperPostprocessor(EMBODIMENTS["widowx"])
    out = widowx(np.array([0.01, -0.02, 0.03, 0.3, 0.0, 0.0, 0.9]))
    np.testing.assert_allclose(out, [0.01, -0.02, 0.03, 0.3, 0.0, 0.0, 1.0])
    assert widowx(np.array([0, 0, 0, 0, 0, 0, 0.1]))[6] == -1.0
    google = EulerOpenGripperPostprocessor(EMBODIMENTS["google_robot"], action_scale=2.0)
    first = google(np.array([0.01, 0, 0, 0, 0, 0.1, 1.0]))
    np.testing.assert_allclose(first, [0.02, 0, 0, 0, 0, 0.2, 0.0])
    assert google(np.array([0, 0, 0, 0, 0, 0, 0.0]))[6] == 1.0  # close, relative


def test_postprocess_rt1_google_robot() -> None:
    raw = {
        "world_vector": np.array([0.1, -0.2, 0.3], dtype=np.float32),
        "rotation_delta": np.array([0.05, 0.0, -0.1], dtype=np.float32),
        "gripper_closedness_action": np.array([0.005], dtype=np.float32),
        "terminate_episode": np.array([0, 1, 0], dtype=np.int32),
    }
    out = postprocess_rt1(raw, EMBODIMENTS["google_robot"])
    np.testing.assert_allclose(out, [0.1, -0.2, 0.3, 0.05, 0.0, -0.1, 0.0], atol=1e-7)
    raw["gripper_closedness_action"] = np.array([0.6], dtype=np.float32)
    assert postprocess_rt1(raw, EMBODIMENTS["google_robot"])[6] == pytest.approx(0.6)


def test_postprocess_rt1_widowx_rescales_inverts_and_binarises() -> None:
    raw = {
        "world_vector": np.array([0.875, 0.0, -3.0]),
        "rotation_delta": np.array([0.7, 0.0, 0.0]),  # -> roll 0.125
        "gripper_closedness_action": np.array([0.4]),  # closing -> WidowX -1
    }
    out = postprocess_rt1(raw, EMBODIMENTS["widowx"])
    np.testing.assert_allclose(out, [0.025, 0.0, -0.05, 0.125, 0.0, 0.0, -1.0])
    raw["gripper_closedness_action"] = np.array([-0.4])
    assert postprocess_rt1(raw, EMBODIMENTS["widowx"])[6] == 1.0


def test_embodiments_follow_simplerenv() -> None:
    google, widowx = policy_info("x", EMBODIMENTS["google_robot"]), policy_info("x", EMBODIMENTS["widowx"])
    assert google.control_mode == GOOGLE_ROBOT_CONTROL_MODE and google.camera == "overhead_camera"
    assert google.control_freq_hz == 3.0 and google.image_size == (640, 512)
    assert google.episode_steps_for("pick_up") == 80 and google.episode_steps_for("move_near") == 80
    assert widowx.control_mode == WIDOWX_CONTROL_MODE and widowx.camera == "3rd_view_camera"
    assert widowx.control_freq_hz == 5.0 and widowx.image_size == (640, 480)
    assert widowx.episode_steps_for("put_on") == 60 and widowx.episode_steps_for("put_in") == 120
    assert EMBODIMENTS["google_robot"].dataset_key == "fractal20220817_data"
    assert EMBODIMENTS["widowx"].dataset_key == "bridge_dataset"
    with pytest.raises(ConfigError, match="google_robot"):
        embodiment("panda")


def test_embodiment_overrides_apply_to_the_chosen_robot_only() -> None:
    overrides = {
        "widowx": {"camera": "cam2", "episode_steps": {"put_on": 70}, "control_freq_hz": 10},
        "google_robot": {"camera": "not used here"},
    }
    emb = embodiment("widowx", overrides)
    assert emb.camera == "cam2" and emb.episode_steps == {"put_on": 70} and emb.control_freq_hz == 10.0
    assert emb.control_mode == WIDOWX_CONTROL_MODE  # untouched settings keep SimplerEnv's values
    with pytest.raises(ConfigError, match="unknown setting"):
        embodiment("widowx", {"widowx": {"fps": 3}})
