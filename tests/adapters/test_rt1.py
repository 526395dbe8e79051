"""RT-1 adapter on a tiny RT-1-format checkpoint (runs where tensorflow + tf-agents are: make test-rt1)."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

tf = pytest.importorskip("tensorflow")
pytest.importorskip("tf_agents")

from ladev_lib.errors import ConfigError  # noqa: E402
from ladev_lib.policies import make_policy  # noqa: E402
from ladev_lib.policies.adapters.common import EMBODIMENTS  # noqa: E402
from ladev_lib.policies.base import Observation  # noqa: E402
from tests.adapters.conftest import load_frame  # noqa: E402

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def tiny_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny RT-1-format checkpoint and sentence encoder, written by tf-agents' PolicySaver."""
    writer_site = Path(sys.prefix) / "writer-site"
    if not writer_site.is_dir():
        pytest.fail(f"{writer_site} missing: build this environment with `make adapter-env-rt1`")
    out = tmp_path_factory.mktemp("rt1")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(writer_site), str(REPO)])}
    proc = subprocess.run(
        [sys.executable, "-m", "tests.adapters.tiny_rt1", str(out)],
        env=env, cwd=REPO, capture_output=True, text=True, timeout=600,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out


@pytest.fixture(scope="module")
def checkpoint(tiny_dir: Path) -> str:
    return str(tiny_dir / "rt_1_tiny")


@pytest.fixture(scope="module")
def encoder(tiny_dir: Path) -> str:
    return str(tiny_dir / "use_tiny")


@pytest.fixture(scope="module")
def policies(checkpoint: str, encoder: str) -> dict:
    return {
        robot: make_policy("rt1", checkpoint=checkpoint, sentence_encoder=encoder, robot=robot)
        for robot in ("google_robot", "widowx")
    }


def test_loads_through_the_registry_and_declares_simplerenv_settings(policies: dict) -> None:
    google = policies["google_robot"].info
    assert google.robots == ("google_robot",) and google.control_freq_hz == 3.0
    assert google.control_mode == EMBODIMENTS["google_robot"].control_mode
    assert google.camera == "overhead_camera" and google.episode_steps_for("pick_up") == 80
    assert policies["widowx"].info.episode_steps_for("put_in") == 120


def test_google_robot_action_shape_range_and_convention(policies: dict) -> None:
    policy = policies["google_robot"]
    policy.reset("pick up the coke can")
    obs = Observation(image=load_frame("google_robot"))
    step = policy.step(obs)
    raw = policy.last_raw_action
    assert step.action.shape == (7,) and np.all(np.isfinite(step.action))
    # Fractal: translation and rotation passed through (axis-angle), gripper relative in [-1, 1].
    np.testing.assert_allclose(step.action[:3], raw["world_vector"], atol=1e-6)
    np.testing.assert_allclose(step.action[3:6], raw["rotation_delta"], atol=1e-6)
    assert np.all(np.abs(step.action[:3]) <= 1.0) and np.all(np.abs(step.action[3:6]) <= math.pi / 2)
    g = float(raw["gripper_closedness_action"][0])
    assert step.action[6] == pytest.approx(0.0 if abs(g) < 0.01 else g)


def test_widowx_action_rescaled_rpy_converted_gripper_binary(policies: dict) -> None:
    policy = policies["widowx"]
    policy.reset("put the carrot on the plate")
    step = policy.step(Observation(image=load_frame("widowx")))
    assert step.action.shape == (7,)
    assert np.all(np.abs(step.action[:3]) <= 0.05 + 1e-9)
    assert np.linalg.norm(step.action[3:6]) <= math.sqrt(3) * 0.25 + 1e-9
    assert step.action[6] in (-1.0, 1.0)
    closedness = float(policy.last_raw_action["gripper_closedness_action"][0])
    assert step.action[6] == (1.0 if -closedness > 0 else -1.0)


def test_policy_state_threads_through_steps_and_terminate_flag(policies: dict) -> None:
    policy = policies["google_robot"]
    obs = Observation(image=load_frame("google_robot"))
    policy.reset("pick up the coke can")
    flags = [policy.step(obs).terminate for _ in range(4)]
    # The tiny model stops from its third step on: only possible if its state advanced.
    assert flags == [False, False, True, True]
    policy.reset("pick up the coke can")
    assert policy.step(obs).terminate is False


def test_instruction_embedding_reaches_the_model(policies: dict, encoder: str) -> None:
    policy = policies["widowx"]
    use = tf.saved_model.load(encoder)
    obs = Observation(image=load_frame("widowx"))
    for text in ("put the spoon on the towel", "put eggplant into yellow basket"):
        policy.reset(text)
        policy.step(obs)
        expected = np.tanh(use([text])[0].numpy()[:2])
        np.testing.assert_allclose(policy.last_raw_action["base_displacement_vector"], expected, atol=1e-6)


def test_resize_with_padding_to_320x256(policies: dict) -> None:
    policy = policies["widowx"]
    widowx = policy.preprocess(load_frame("widowx"))  # 640x480 -> 320x240 + 8 rows each side
    assert widowx.shape == (256, 320, 3) and widowx.dtype == np.uint8
    assert widowx[:8].max() == 0 and widowx[-8:].max() == 0 and widowx[8:248].mean() > 50
    google = policy.preprocess(load_frame("google_robot"))  # 640x512: exact 2x, no padding
    assert google.shape == (256, 320, 3) and google[0].mean() > 50 and google[-1].mean() > 50


def test_missing_checkpoint_and_encoder_are_config_errors(encoder: str, tmp_path) -> None:
    with pytest.raises(ConfigError, match="saved_model.pb"):
        make_policy("rt1", checkpoint=str(tmp_path), sentence_encoder=encoder)
    with pytest.raises(ConfigError, match="Universal Sentence Encoder"):
        make_policy("rt1", checkpoint=str(tmp_path), sentence_encoder=str(tmp_path / "nope"))


@pytest.mark.manual
def test_gpu_episode(checkpoint: str, encoder: str) -> None:
    """One short episode on a GPU through the same adapter code (LADEV_MANUAL=1, TF_SPEC with CUDA)."""
    if not tf.config.list_physical_devices("GPU"):
        pytest.skip("no GPU visible to TensorFlow (TF_SPEC='tensorflow[and-cuda]==2.15.1')")
    policy = make_policy("rt1", checkpoint=checkpoint, sentence_encoder=encoder, device="/GPU:0")
    policy.reset("pick up the coke can")
    frame = Observation(image=load_frame("google_robot"))
    steps = [policy.step(frame) for _ in range(10)]
    assert [s.terminate for s in steps[:3]] == [False, False, True]
    assert all(np.all(np.isfinite(s.action)) for s in steps)
