"""LeRobot adapter on tiny, randomly initialised ACT checkpoints (make test-lerobot).

Every checkpoint is built from LeRobot's own config and policy classes,
written with LeRobot's own ``save_pretrained`` (policy and processors with
their statistics) and loaded back through the adapter's real path
(``PreTrainedConfig.from_pretrained`` -> ``get_policy_class`` ->
``make_pre_post_processors(pretrained_path=...)``), as a downloaded
checkpoint directory would be. The observation is a rendered LADEV frame.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch")
pytest.importorskip("lerobot", reason="the LeRobot environment: make test-lerobot")

from ladev_lib.errors import ConfigError  # noqa: E402
from ladev_lib.policies import make_policy  # noqa: E402
from ladev_lib.policies.base import EpisodeContext, Observation  # noqa: E402
from tests.adapters.conftest import load_frame  # noqa: E402
from tests.adapters.tiny_lerobot import ACTION_MEAN, build_tiny_act, state_stats  # noqa: E402

STATE_DIM = 15  # e.g. WidowX: 8 joint positions + the 7-value TCP pose


@pytest.fixture(scope="module")
def exact(tmp_path_factory: pytest.TempPathFactory) -> str:
    """Action std 0: every unnormalised action is exactly ACTION_MEAN."""
    return str(build_tiny_act(tmp_path_factory.mktemp("act") / "exact", state_dim=STATE_DIM))


@pytest.fixture(scope="module")
def noisy(tmp_path_factory: pytest.TempPathFactory) -> str:
    return str(build_tiny_act(tmp_path_factory.mktemp("act") / "noisy", state_dim=STATE_DIM, action_std=0.05))


def _proprio(n: int = STATE_DIM) -> np.ndarray:
    # joints, then the TCP pose [x, y, z, qw, qx, qy, qz] (a 90 degree yaw)
    joints = np.linspace(-1.0, 1.0, n - 7)
    half = math.sqrt(0.5)
    return np.concatenate([joints, [0.3, -0.1, 0.2, half, 0.0, 0.0, half]]).astype(np.float32)


def _obs(robot: str = "widowx") -> Observation:
    return Observation(image=load_frame(robot), proprio=_proprio())


def _policy(checkpoint: str, robot: str = "widowx", **kw):
    return make_policy("lerobot", checkpoint=checkpoint, robot=robot, device="cpu", **kw)


def test_loads_through_lerobot_and_returns_the_mapped_action(exact: str) -> None:
    policy = _policy(exact, "widowx")
    assert policy.cfg.type == "act" and policy.cfg.device == "cpu"
    assert next(policy.model.parameters()).device.type == "cpu"
    assert policy.info.robots == ("widowx",) and policy.info.camera == "3rd_view_camera"
    policy.reset("put the spoon on the towel")
    step = policy.step(_obs("widowx"))
    # The postprocessor's unnormaliser gives mean + 0 * output: ACTION_MEAN exactly.
    np.testing.assert_allclose(policy.last_raw_action, ACTION_MEAN, atol=1e-6)
    # Hand-computed: xyz as is; roll 0, pitch 0, yaw -0.2 -> axis-angle (0, 0, -0.2);
    # openness 0.9 > 0.5 -> WidowX's absolute gripper target +1 (open).
    np.testing.assert_allclose(step.action, [0.02, -0.01, 0.005, 0.0, 0.0, -0.2, 1.0], atol=1e-6)
    assert step.action.shape == (7,) and step.terminate is False


def test_google_robot_gripper_is_relative_and_conventions_flip(exact: str) -> None:
    policy = _policy(exact, "google_robot", action_scale=2.0)
    policy.reset("pick up the coke can")
    first, second = policy.step(_obs("google_robot")), policy.step(_obs("google_robot"))
    # Relative gripper: no previous prediction, then 0.9 - 0.9: no change both times.
    np.testing.assert_allclose(first.action, [0.04, -0.02, 0.01, 0.0, 0.0, -0.4, 0.0], atol=1e-6)
    assert second.action[6] == 0.0
    # LIBERO's convention (+1 close): 0.9 is almost closed -> WidowX closes (-1).
    closing = _policy(exact, "widowx", gripper_convention="signed_close")
    closing.reset("close it")
    assert closing.step(_obs("widowx")).action[6] == -1.0
    # The rotation read as axis-angle is passed through unchanged.
    axang = _policy(exact, "widowx", action_layout="ee_delta_axis_angle")
    axang.reset("x")
    np.testing.assert_allclose(axang.step(_obs("widowx")).action[3:6], [0.0, 0.0, -0.2], atol=1e-6)


def test_observation_reaches_the_model_as_the_checkpoint_declares(exact: str) -> None:
    policy = _policy(exact, "widowx", task_template="{instruction}.")
    policy.reset("  Put the carrot on the plate ")
    frame = load_frame("widowx")
    batch = policy.batch(Observation(image=frame, proprio=_proprio()))
    assert batch["task"] == ["Put the carrot on the plate."]
    image = batch["observation.images.image"]
    assert tuple(image.shape) == (1, 3, 64, 64) and image.dtype == torch.float32
    assert float(image.min()) >= 0.0 and float(image.max()) <= 1.0
    processed = policy.preprocessor(batch)
    # The checkpoint's statistics, applied by its own normaliser: (x - mean) / std.
    st = state_stats(STATE_DIM)
    expected_state = (_proprio().astype(np.float64) - st["mean"]) / st["std"]
    np.testing.assert_allclose(processed["observation.state"].numpy()[0], expected_state, rtol=1e-5, atol=1e-6)
    expected_image = (image.numpy() - 0.5) / 0.25
    np.testing.assert_allclose(processed["observation.images.image"].numpy(), expected_image, atol=1e-5)


def test_state_layouts_and_a_wrong_dimension_names_the_feature(tmp_path: Path) -> None:
    ckpt = str(build_tiny_act(tmp_path / "euler", state_dim=6))
    policy = _policy(ckpt, "widowx", state_layout="tcp_euler")
    policy.reset("x")
    state = policy.batch(_obs())["observation.state"].numpy()[0]
    # TCP at (0.3, -0.1, 0.2), quaternion (cos 45, 0, 0, sin 45): a yaw of pi/2.
    np.testing.assert_allclose(state, [0.3, -0.1, 0.2, 0.0, 0.0, math.pi / 2], atol=1e-6)
    wrong = _policy(ckpt, "widowx", state_layout="proprio")
    wrong.reset("x")
    with pytest.raises(ValueError, match=r"'observation.state' has 6 values; state_layout 'proprio' gives 15"):
        wrong.step(_obs())


def test_action_chunks_are_predicted_every_n_action_steps(noisy: str) -> None:
    policy = _policy(noisy, "widowx")
    calls = []
    original = policy.model.predict_action_chunk

    def counted(batch):
        calls.append(1)
        return original(batch)

    policy.model.predict_action_chunk = counted
    policy.begin_episode(EpisodeContext(seed=3, robot="widowx", action_low=np.full(7, -1.0),
                                        action_high=np.full(7, 1.0)))
    policy.reset("put the spoon on the towel")
    raws = []
    for _ in range(8):
        policy.step(_obs())
        raws.append(policy.last_raw_action.copy())
    assert len(calls) == 2  # chunk_size = n_action_steps = 4: LeRobot's queue
    # Within a chunk the actions differ (a trajectory), and stay in range of the statistics.
    assert not np.allclose(raws[0], raws[1])
    assert all(np.all(np.abs(r - ACTION_MEAN) < 0.05 * 10) for r in raws)
    policy.reset("again")  # reset empties the queue: the next step predicts anew
    policy.step(_obs())
    assert len(calls) == 3
    shorter = _policy(noisy, "widowx", n_action_steps=2)
    assert shorter.cfg.n_action_steps == 2
    with pytest.raises(ConfigError, match="n_action_steps"):
        _policy(noisy, "widowx", n_action_steps=5)


def test_inputs_ladev_cannot_give_are_named(tmp_path: Path) -> None:
    two = str(build_tiny_act(tmp_path / "two", cameras=("image", "wrist_image")))
    with pytest.raises(ConfigError, match=r"observation.images.image, observation.images.wrist_image"):
        _policy(two)
    with pytest.raises(ConfigError, match=r"needs camera\(s\) \['observation.images.wrist_image'\]"):
        _policy(two, image_features=["observation.images.image"])
    env = str(build_tiny_act(tmp_path / "env", env_state_dim=4))
    with pytest.raises(ConfigError, match=r"'observation.environment_state'"):
        _policy(env)


def test_config_errors(exact: str) -> None:
    with pytest.raises(ConfigError, match="'smolvla'"):
        _policy(exact, policy_type="smolvla")
    with pytest.raises(ConfigError, match="state_layout"):
        _policy(exact, state_layout="joint_angles")
    with pytest.raises(ConfigError, match="not visual inputs"):
        _policy(exact, image_features=["observation.images.wrist"])
    with pytest.raises(ConfigError, match="support robots"):
        _policy(exact, robot="ur5")


def test_diffusion_keeps_an_observation_history_and_runs_chunks(tmp_path: Path) -> None:
    from tests.adapters.tiny_lerobot import build_tiny_diffusion

    ckpt = str(build_tiny_diffusion(tmp_path / "diffusion", state_dim=STATE_DIM))
    policy = _policy(ckpt, "widowx")
    assert policy.cfg.type == "diffusion" and policy.cfg.n_obs_steps == 2
    chunks = []
    original = policy.model.diffusion.generate_actions

    def counted(batch, **kw):
        chunks.append(batch["observation.state"].shape)
        return original(batch, **kw)

    policy.model.diffusion.generate_actions = counted
    policy.reset("put the carrot on the plate")
    actions = [policy.step(_obs()).action for _ in range(6)]
    # One chunk of n_action_steps = 4 actions, then the next; each sees 2 observations.
    assert len(chunks) == 2 and all(tuple(c)[:2] == (1, 2) for c in chunks)
    for action in actions:
        assert action.shape == (7,) and np.all(np.isfinite(action)) and action[6] in (-1.0, 1.0)
    # Diffusion normalises actions min-max (the statistics' min/max are mean -+ 1) and
    # clips its sample to [-1, 1]: the unnormalised action lies within [min, max].
    assert policy.cfg.normalization_mapping["ACTION"].value == "MIN_MAX"
    raw = policy.last_raw_action
    assert np.all(np.abs(raw - ACTION_MEAN) <= 1.0 + 1e-6)


def test_rotate_image_180_turns_the_frame_round(exact: str) -> None:
    frame = load_frame("widowx")[:64, :64].copy()  # the checkpoint's size: no resize
    upright = _policy(exact, "widowx")
    turned = _policy(exact, "widowx", rotate_image_180=True)
    for p in (upright, turned):
        p.reset("x")
    a = upright.batch(Observation(image=frame, proprio=_proprio()))["observation.images.image"]
    b = turned.batch(Observation(image=frame, proprio=_proprio()))["observation.images.image"]
    np.testing.assert_array_equal(b.numpy(), np.flip(a.numpy(), axis=(2, 3)))
    assert not np.array_equal(a.numpy(), b.numpy())
    full = turned.batch(Observation(image=load_frame("widowx"), proprio=_proprio()))  # resized too
    assert tuple(full["observation.images.image"].shape) == (1, 3, 64, 64)
