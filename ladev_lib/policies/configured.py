"""Policies by configured name: a ``conf/policy/<name>.yaml`` entry or a registry name.

``conf/policy/rt1_x.yaml`` holds ``rt1_x: {name: rt1, checkpoint: ..., robot: ...}``:
``name`` is the registry entry, the rest its keyword arguments (but ``robot_by_task``,
which tells the rollout which robot each task runs on; see :class:`PolicyConfig`). A name with no
file there is looked up in the registry directly (``random``, ``remote``).
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

import yaml

from ladev_lib.config import compose_config, find_config_dir, section
from ladev_lib.errors import ConfigError
from ladev_lib.policies import POLICIES, Policy, make_policy
from ladev_lib.policies.config import PolicyConfig


def parse_overrides(pairs: Iterable[str]) -> dict[str, Any]:
    """``["robot=widowx", "seed=3"]`` -> ``{"robot": "widowx", "seed": 3}`` (values as YAML)."""
    out: dict[str, Any] = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise ConfigError(f"override {pair!r} is not key=value")
        out[key.strip()] = yaml.safe_load(value)
    return out


def policy_config(
    name: str, config_dir: str | Path | None = None, overrides: dict[str, Any] | None = None
) -> tuple[str, dict[str, Any]]:
    """(registry name, keyword arguments) of the policy configured as ``name``."""
    kwargs: dict[str, Any]
    try:
        directory: Path | None = find_config_dir(config_dir)
    except ConfigError:
        directory = None
    if directory is not None and (directory / "policy" / f"{name}.yaml").exists():
        cfg = compose_config([f"policy=[{name}]"], directory)
        entry = section(cfg.get("policy") or {}, name, PolicyConfig)
        registry_name, kwargs = entry.name, entry.kwargs
    elif name in POLICIES:
        registry_name, kwargs = name, {}
    else:
        options = sorted(p.stem for p in (directory / "policy").glob("*.yaml")) if directory else []
        raise ConfigError(
            f"unknown policy {name!r}: not in conf/policy ({', '.join(options) or 'none'}) "
            f"nor registered ({', '.join(POLICIES.names())})"
        )
    extra = dict(overrides or {})
    # ``name`` is the registry entry in conf/policy, so an override of it picks another entry.
    chosen = extra.pop("name", registry_name)
    if not isinstance(chosen, str) or chosen not in POLICIES:
        raise ConfigError(f"name={chosen!r}: not a registered policy ({', '.join(POLICIES.names())})")
    kwargs.update(extra)
    return chosen, kwargs


def make_configured_policy(
    name: str, config_dir: str | Path | None = None, overrides: dict[str, Any] | None = None
) -> Policy:
    """Construct the policy configured as ``name`` (see :func:`policy_config`)."""
    registry_name, kwargs = policy_config(name, config_dir, overrides)
    return make_policy(registry_name, **kwargs)
