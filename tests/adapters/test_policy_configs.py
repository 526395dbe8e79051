"""conf/policy entries of the paper's seven models and the remote policy (core install)."""

from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

import pytest

from ladev_lib.errors import MissingExtraError
from ladev_lib.policies import make_policy
from ladev_lib.policies.adapters.common import EMBODIMENTS, embodiment
from ladev_lib.policies.configured import parse_overrides, policy_config
from ladev_lib.policies.remote import RemotePolicyConfig

REPO = Path(__file__).resolve().parents[2]
PAPER_MODELS = {
    "rt1_1k": ("rt1", "rt_1_tf_trained_for_000001120"),
    "rt1_58k": ("rt1", "rt_1_tf_trained_for_000058240"),
    "rt1_400k": ("rt1", "rt_1_tf_trained_for_000400120"),
    "rt1_x": ("rt1", "rt_1_x_tf_trained_for_002272480_step"),
    "octo_small": ("octo", "octo-small"),
    "octo_base": ("octo", "octo-base"),
    "openvla_7b": ("openvla", "openvla-7b"),
}
ADAPTER_CLASSES = {"rt1": "RT1Policy", "octo": "OctoPolicy", "openvla": "OpenVLAPolicy"}


def _init_params(family: str) -> set[str]:
    """The adapter's constructor parameters, read without importing its ML stack."""
    source = (REPO / "ladev_lib/policies/adapters" / f"{family}.py").read_text()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ClassDef) and node.name == ADAPTER_CLASSES[family]:
            init = next(f for f in node.body if isinstance(f, ast.FunctionDef) and f.name == "__init__")
            return {a.arg for a in init.args.args + init.args.kwonlyargs} - {"self"}
    raise AssertionError(f"{ADAPTER_CLASSES[family]} not found")


@pytest.mark.parametrize("name", sorted(PAPER_MODELS))
def test_paper_model_config(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("LADEV_CHECKPOINTS", "/ckpts")
    family, checkpoint = PAPER_MODELS[name]
    registry_name, kwargs = policy_config(name, REPO / "conf")
    assert registry_name == family
    assert kwargs["checkpoint"] == f"/ckpts/{checkpoint}"
    assert set(kwargs) <= _init_params(family), set(kwargs) - _init_params(family)
    # The settings written in the config are SimplerEnv's, for both robots.
    for robot in ("google_robot", "widowx"):
        assert embodiment(robot, kwargs["embodiments"]) == EMBODIMENTS[robot]
    assert kwargs["robot"] == ("google_robot" if family == "rt1" else "widowx")
    # robot_by_task is the rollout's (one robot per task), never a model argument
    assert "robot_by_task" not in kwargs


def test_checkpoint_root_defaults_to_checkpoints(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("LADEV_CHECKPOINTS", raising=False)
    _, kwargs = policy_config("octo_base", REPO / "conf")
    assert kwargs["checkpoint"] == "checkpoints/octo-base"
    assert kwargs["text_encoder"] == "checkpoints/t5-base"


def test_overrides_switch_robot() -> None:
    _, kwargs = policy_config("rt1_x", REPO / "conf", parse_overrides(["robot=widowx", "device=/GPU:0"]))
    assert kwargs["robot"] == "widowx" and kwargs["device"] == "/GPU:0"
    assert embodiment(kwargs["robot"], kwargs["embodiments"]).camera == "3rd_view_camera"


def test_remote_config_validates() -> None:
    registry_name, kwargs = policy_config("remote", REPO / "conf")
    assert registry_name == "remote"
    assert RemotePolicyConfig.model_validate(kwargs).url == "ws://127.0.0.1:8000"


@pytest.mark.parametrize(
    ("family", "module"), [("rt1", "tensorflow"), ("octo", "jax"), ("openvla", "transformers")]
)
def test_missing_stack_names_the_extra(family: str, module: str) -> None:
    if importlib.util.find_spec(module) is not None:
        pytest.skip(f"{module} is installed in this environment")
    with pytest.raises(MissingExtraError, match=rf"ladev\[{family}\]"):
        make_policy(family, checkpoint="/nonexistent")


def test_unknown_policy_lists_options() -> None:
    from ladev_lib.errors import ConfigError

    with pytest.raises(ConfigError, match="rt1_x"):
        policy_config("rt2", REPO / "conf")


LEROBOT_MODELS = {"smolvla_libero": "smolvla", "pi0_libero": "pi0", "pi05_libero": "pi05"}


def _lerobot_init_params() -> set[str]:
    source = (REPO / "ladev_lib/policies/adapters/lerobot_policy.py").read_text()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ClassDef) and node.name == "LeRobotPolicy":
            init = next(f for f in node.body if isinstance(f, ast.FunctionDef) and f.name == "__init__")
            return {a.arg for a in init.args.args + init.args.kwonlyargs} - {"self"}
    raise AssertionError("LeRobotPolicy not found")


@pytest.mark.parametrize("name", sorted(LEROBOT_MODELS))
def test_lerobot_model_config(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    from ladev_lib.policies.adapters.lerobot_maps import (
        ACTION_LAYOUTS,
        GRIPPER_CONVENTIONS,
        LEROBOT_EMBODIMENTS,
        STATE_LAYOUTS,
    )

    monkeypatch.setenv("LADEV_CHECKPOINTS", "/ckpts")
    registry_name, kwargs = policy_config(name, REPO / "conf")
    assert registry_name == "lerobot" and kwargs["policy_type"] == LEROBOT_MODELS[name]
    assert kwargs["checkpoint"] == f"/ckpts/{name}"
    assert set(kwargs) <= _lerobot_init_params(), set(kwargs) - _lerobot_init_params()
    assert kwargs["state_layout"] in STATE_LAYOUTS and kwargs["action_layout"] in ACTION_LAYOUTS
    assert kwargs["gripper_convention"] in GRIPPER_CONVENTIONS
    # LIBERO's embodiment: LADEV's Panda with its end-effector delta controller at 20 Hz.
    emb = embodiment(kwargs["robot"], kwargs["embodiments"], table=LEROBOT_EMBODIMENTS)
    assert emb.robot == "panda" and emb.control_mode == "pd_ee_delta_pose" and emb.control_freq_hz == 20
    assert emb.image_size == (256, 256) and emb.episode_steps["pick_up"] == 120


def test_lerobot_missing_stack_names_the_extra() -> None:
    if importlib.util.find_spec("lerobot") is not None:
        pytest.skip("lerobot is installed in this environment")
    with pytest.raises(MissingExtraError, match=r"ladev\[lerobot\]"):
        make_policy("lerobot", checkpoint="/nonexistent")
