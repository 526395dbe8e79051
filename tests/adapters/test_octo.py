"""Octo adapter (make test-octo: JAX 0.4.20, Flax 0.7.5, TF 2.15).

Octo's model code is not obtainable here (not on PyPI), so the model is an
in-memory stand-in with OctoModel's interface (``tiny_octo.py``); everything
the adapter does around it is real: resizing, the two-frame history, RNG
handling, ensembling, unnormalisation, rotation and gripper conventions.
"""

from __future__ import annotations

import numpy as np
import pytest

from ladev_lib.errors import ConfigError, MissingExtraError

jax = pytest.importorskip("jax")
pytest.importorskip("flax")

from ladev_lib.policies import make_policy  # noqa: E402
from ladev_lib.policies.adapters.common import (  # noqa: E402
    ActionEnsembler,
    StickyGripper,
    euler_to_axis_angle,
)
from ladev_lib.policies.adapters.octo import resize_lanczos  # noqa: E402
from ladev_lib.policies.base import Observation  # noqa: E402
from tests.adapters.conftest import load_frame  # noqa: E402
from tests.adapters.tiny_octo import STATS, TinyOctoModel  # noqa: E402


def _policy(robot: str = "widowx", **kw):
    return make_policy("octo", robot=robot, model=TinyOctoModel(), **kw)


def test_without_octo_code_the_error_says_where_to_get_it() -> None:
    try:
        import octo.model.octo_model  # noqa: F401
    except ImportError:
        with pytest.raises(MissingExtraError, match="unrelated"):
            make_policy("octo", checkpoint="/nonexistent")
    else:
        pytest.skip("Octo's model code is installed here")


def test_two_frame_history_of_256x256_images() -> None:
    policy = _policy()
    policy.reset("put the carrot on the plate")
    frame = load_frame("widowx")
    for _ in range(3):
        policy.step(Observation(image=frame))
    shapes = [c["images"].shape for c in policy.model.calls]
    assert shapes == [(1, 1, 256, 256, 3), (1, 2, 256, 256, 3), (1, 2, 256, 256, 3)]
    assert all(np.all(c["pad_mask"] == 1) for c in policy.model.calls)
    policy.reset("put the carrot on the plate")
    policy.step(Observation(image=frame))
    assert policy.model.calls[-1]["images"].shape == (1, 1, 256, 256, 3)


def test_a_fresh_key_each_step_and_the_same_keys_each_episode() -> None:
    policy = _policy()
    frame = Observation(image=load_frame("widowx"))
    episodes = []
    for _ in range(2):
        policy.reset("put the spoon on the towel")
        episodes.append([policy.step(frame).action for _ in range(3)])
    keys = [c["rng"].tolist() for c in policy.model.calls]
    assert keys[0] != keys[1] != keys[2] and keys[:3] == keys[3:]
    np.testing.assert_allclose(episodes[0], episodes[1])


@pytest.mark.parametrize("use_action_mask", [False, True])
def test_ensembled_unnormalised_and_converted_by_hand(use_action_mask: bool) -> None:
    policy = _policy(robot="widowx", use_action_mask=use_action_mask)
    policy.reset("put eggplant into yellow basket")
    frame = Observation(image=load_frame("widowx"))
    model, stats = policy.model, STATS["bridge_dataset"]["action"]
    ensembler = ActionEnsembler(4)
    for _ in range(5):
        step = policy.step(frame)
        chunk = np.asarray(
            model.module.apply(
                model.params,
                model.calls[-1]["images"],
                model.calls[-1]["pad_mask"],
                policy._task["language_instruction"],
            )
            + 0.1 * jax.random.normal(model.calls[-1]["rng"], (1, 4, 7))
        )[0]
        normalized = ensembler(chunk)
        raw = normalized * np.array(stats["std"]) + np.array(stats["mean"])
        if use_action_mask:
            raw[6] = normalized[6]  # Octo's convention: the masked gripper stays as predicted
        np.testing.assert_allclose(step.action[:3], raw[:3], rtol=1e-5, atol=1e-7)
        np.testing.assert_allclose(step.action[3:6], euler_to_axis_angle(*raw[3:6]), rtol=1e-5, atol=1e-7)
        assert step.action[6] == (1.0 if raw[6] > 0.5 else -1.0)


def test_google_robot_fractal_statistics_and_sticky_gripper() -> None:
    policy = _policy(robot="google_robot")
    assert policy.dataset_key == "fractal20220817_data"
    assert policy.info.camera == "overhead_camera" and policy.info.episode_steps_for("pick_up") == 80
    policy.reset("pick up the coke can")
    frame = Observation(image=load_frame("google_robot"))
    sticky, expected, got = StickyGripper(15), [], []
    for _ in range(6):
        got.append(policy.step(frame).action[6])
        expected.append(sticky(policy.last_raw_action[6]))
    assert got[0] == 0.0 and got == pytest.approx(expected)


def test_no_ensembling_takes_the_first_action_of_each_chunk() -> None:
    policy = _policy(ensemble=False)
    policy.reset("put the spoon on the towel")
    step = policy.step(Observation(image=load_frame("widowx")))
    assert step.action.shape == (7,)


def test_unknown_dataset_key_lists_the_known_ones() -> None:
    with pytest.raises(ConfigError, match="bridge_dataset, fractal20220817_data"):
        _policy(dataset_key="libero")


def test_lanczos_resize_tensorflow_and_pillow_agree() -> None:
    """SimplerEnv resizes with TensorFlow (lanczos3, antialias); without TF we use Pillow's Lanczos."""
    from PIL import Image

    frame = load_frame("widowx")
    ours = resize_lanczos(frame, 256)
    pil = np.asarray(Image.fromarray(frame).resize((256, 256), Image.Resampling.LANCZOS))
    assert ours.shape == (256, 256, 3) and ours.dtype == np.uint8
    diff = np.abs(ours.astype(int) - pil.astype(int))
    print(f"lanczos TF vs Pillow: mean |diff| {diff.mean():.3f}, max {diff.max()} (of 255)")
    assert diff.mean() < 2.0
