"""Every executor and policy option of conf/ composes and validates with the rollout models."""

from __future__ import annotations

import pytest

from ladev_lib.config import compose_config, section
from ladev_lib.errors import ConfigError
from ladev_lib.policies.config import PolicyConfig
from ladev_lib.rollout.config import (
    LocalExecutorConfig,
    RayExecutorConfig,
    RolloutConfig,
    SerialExecutorConfig,
    executor_config,
)


@pytest.mark.parametrize(
    ("option", "model"),
    [("local", LocalExecutorConfig), ("ray", RayExecutorConfig), ("serial", SerialExecutorConfig)],
)
def test_executor_options_compose(repo_root, option, model):
    cfg = compose_config([f"executor={option}"], repo_root / "conf")
    assert isinstance(executor_config(cfg), model)


def test_policy_options_compose_with_their_kwargs(repo_root):
    cfg = compose_config(["policy=[oracle,grounded,random,noop]"], repo_root / "conf")
    policies = {label: section(cfg["policy"], label, PolicyConfig) for label in cfg["policy"]}
    assert {label: p.name for label, p in policies.items()} == {
        "oracle": "oracle", "grounded": "grounded", "random": "random", "noop": "noop",
    }
    assert policies["grounded"].kwargs == {
        "embedding_model": "all-MiniLM-L6-v2", "max_attempts": 3, "mode": "reader",
    }
    assert policies["random"].kwargs == {"control_mode": "pd_ee_delta_pose"}


def test_rollout_section_defaults_and_errors(repo_root):
    cfg = compose_config([], repo_root / "conf")
    rollout = section(cfg, "rollout", RolloutConfig)
    assert (rollout.video, rollout.frames, rollout.max_error_rate) == ("none", True, 0.05)
    with pytest.raises(ConfigError, match="rollout.max_error_rate"):
        section({"rollout": {"max_error_rate": 2}}, "rollout", RolloutConfig)
    with pytest.raises(ConfigError, match="executor.address"):
        executor_config({"executor": {"name": "local", "address": "auto"}})
