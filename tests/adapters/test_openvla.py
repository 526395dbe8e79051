"""OpenVLA adapter on a tiny stand-in checkpoint with remote code (make test-openvla).

The stand-in (``tiny_openvla/``) has OpenVLA's interface, not its architecture:
OpenVLA's modeling code ships only inside its checkpoint and cannot be
obtained here. What is real is the adapter's whole path: AutoProcessor /
AutoModelForVision2Seq with trust_remote_code from a local directory, dtype,
device and attention implementation, the prompt, the 224x224 area resize,
``predict_action(unnorm_key=...)`` and SimplerEnv's post-processing.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

transformers = pytest.importorskip("transformers")
torch = pytest.importorskip("torch")
if int(transformers.__version__.split(".")[0]) >= 5:
    pytest.skip(
        "OpenVLA's remote code needs transformers 4.40 (this is "
        f"{transformers.__version__}): run make test-openvla",
        allow_module_level=True,
    )

pytestmark = pytest.mark.filterwarnings("ignore:the load_module:DeprecationWarning")

from ladev_lib.errors import ConfigError  # noqa: E402
from ladev_lib.policies import make_policy  # noqa: E402
from ladev_lib.policies.adapters.common import euler_to_axis_angle  # noqa: E402
from ladev_lib.policies.adapters.openvla import resize_area  # noqa: E402
from ladev_lib.policies.base import Observation  # noqa: E402
from tests.adapters.conftest import load_frame  # noqa: E402
from tests.adapters.tiny_openvla.build import NORM_STATS, build_tiny_openvla  # noqa: E402


@pytest.fixture(scope="module")
def checkpoint(tmp_path_factory: pytest.TempPathFactory) -> str:
    return str(build_tiny_openvla(tmp_path_factory.mktemp("openvla") / "tiny-openvla"))


def _policy(checkpoint: str, robot: str, **kw):
    return make_policy("openvla", checkpoint=checkpoint, robot=robot, device="cpu", dtype="float32", **kw)


def test_widowx_step_shape_range_and_convention(checkpoint: str) -> None:
    policy = _policy(checkpoint, "widowx", attn_implementation="eager")
    assert policy.info.camera == "3rd_view_camera" and policy.info.control_freq_hz == 5.0
    assert policy.model.config._attn_implementation == "eager"
    policy.reset("Put the carrot on the plate")
    step = policy.step(Observation(image=load_frame("widowx")))
    assert step.action.shape == (7,) and step.terminate is False
    # Unnormalised with bridge_orig's q01/q99 (the default unnorm key for WidowX).
    stats = NORM_STATS["bridge_orig"]["action"]
    assert np.all(step.action[:3] >= np.array(stats["q01"][:3]) - 1e-9)
    assert np.all(step.action[:3] <= np.array(stats["q99"][:3]) + 1e-9)
    assert step.action[6] in (-1.0, 1.0)
    # The prompt OpenVLA was trained with, and the image at 224x224.
    assert policy.processor.last_prompt == (
        "In: What action should the robot take to put the carrot on the plate?\nOut:"
    )
    assert policy.processor.last_image_size == (224, 224)
    words = policy.processor.tokenizer.convert_ids_to_tokens(policy.model.last_input_ids[0].tolist())
    assert words[:4] == ["<s>", "in", ":", "what"] and "carrot" in words


def test_rotation_and_gripper_postprocessing_match_the_raw_prediction(checkpoint: str) -> None:
    policy = _policy(checkpoint, "widowx")
    policy.reset("put the spoon on the towel")
    image = load_frame("widowx")
    raw = policy.predict_raw(image)
    step = policy.step(Observation(image=image))
    np.testing.assert_allclose(step.action[:3], raw[:3])
    np.testing.assert_allclose(step.action[3:6], euler_to_axis_angle(*raw[3:6]))
    assert step.action[6] == (1.0 if raw[6] > 0.5 else -1.0)


def test_google_robot_uses_fractal_statistics_and_a_relative_gripper(checkpoint: str) -> None:
    policy = _policy(checkpoint, "google_robot")
    assert policy.unnorm_key == "fractal20220817_data"
    assert policy.info.control_freq_hz == 3.0 and policy.info.episode_steps_for("move_near") == 80
    policy.reset("move the apple near the sponge")
    step = policy.step(Observation(image=load_frame("google_robot")))
    stats = NORM_STATS["fractal20220817_data"]["action"]
    assert np.all(np.abs(step.action[:3]) <= np.array(stats["q99"][:3]) + 1e-9)
    assert step.action[6] == 0.0  # first step: no previous openness, no relative command


def test_bfloat16_weights_and_inputs(checkpoint: str) -> None:
    policy = make_policy("openvla", checkpoint=checkpoint, robot="widowx", device="cpu", dtype="bfloat16")
    assert next(policy.model.parameters()).dtype == torch.bfloat16
    policy.reset("put eggplant into yellow basket")
    step = policy.step(Observation(image=load_frame("widowx")))
    assert step.action.shape == (7,) and np.all(np.isfinite(step.action))


def test_unknown_unnorm_key_lists_the_known_ones(checkpoint: str) -> None:
    with pytest.raises(ConfigError, match="bridge_orig, fractal20220817_data"):
        _policy(checkpoint, "widowx", unnorm_key="libero_spatial")


def test_prompt_template_must_take_the_instruction(checkpoint: str) -> None:
    with pytest.raises(ConfigError, match="instruction"):
        _policy(checkpoint, "widowx", prompt_template="What should the robot do?")


def test_area_resize_averages_blocks() -> None:
    image = np.zeros((448, 448, 3), dtype=np.uint8)
    image[::2, ::2] = 200  # one bright pixel in each 2x2 block
    out = resize_area(image, (224, 224))
    assert out.shape == (224, 224, 3) and np.all(out == 50)


def test_missing_checkpoint_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(OSError):
        _policy(str(tmp_path / "nope"), "widowx", local_files_only=True)


@pytest.mark.manual
def test_gpu_episode(checkpoint: str) -> None:
    """One short episode on a GPU through the same adapter code (LADEV_MANUAL=1, CUDA torch)."""
    if not torch.cuda.is_available():
        pytest.skip("no CUDA device (TORCH_SPEC must name a CUDA build of torch)")
    policy = make_policy("openvla", checkpoint=checkpoint, robot="google_robot", device="cuda:0",
                         dtype="bfloat16", attn_implementation="sdpa")
    assert next(policy.model.parameters()).device.type == "cuda"
    policy.reset("pick up the coke can")
    frame = Observation(image=load_frame("google_robot"))
    actions = [policy.step(frame).action for _ in range(10)]
    assert all(a.shape == (7,) and np.all(np.isfinite(a)) for a in actions)
