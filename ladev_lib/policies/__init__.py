"""Policies by name: built-in baselines, VLA adapters and remote policies.

    from ladev_lib.policies import make_policy, POLICIES
    policy = make_policy("oracle")
    POLICIES.names()   # what is available

A policy family registers a factory ``(**config) -> Policy`` under its name.
Families with heavy dependencies are registered lazily with the extra to
install, so listing names never imports TensorFlow, JAX or a 7B model.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

from ladev_lib.errors import ConfigError
from ladev_lib.policies.base import (
    EpisodeContext,
    Observation,
    Policy,
    PolicyInfo,
    PolicyStep,
    PrivilegedState,
)
from ladev_lib.registry import Registry

PolicyFactory = Callable[..., Policy]

POLICIES: Registry[PolicyFactory] = Registry("policy")

# Built-in and optional families. Each target module defines the factory.
POLICIES.add_lazy("oracle", "ladev_lib.policies.oracle:OraclePolicy")
POLICIES.add_lazy("grounded", "ladev_lib.policies.grounded:GroundedPolicy")
POLICIES.add_lazy("random", "ladev_lib.policies.baselines:RandomPolicy")
POLICIES.add_lazy("noop", "ladev_lib.policies.baselines:NoopPolicy")
POLICIES.add_lazy("remote", "ladev_lib.policies.remote:RemotePolicy")
POLICIES.add_lazy("rt1", "ladev_lib.policies.adapters.rt1:RT1Policy", extra="rt1")
POLICIES.add_lazy("octo", "ladev_lib.policies.adapters.octo:OctoPolicy", extra="octo")
POLICIES.add_lazy("openvla", "ladev_lib.policies.adapters.openvla:OpenVLAPolicy", extra="openvla")
POLICIES.add_lazy("lerobot", "ladev_lib.policies.adapters.lerobot_policy:LeRobotPolicy", extra="lerobot")


def make_policy(name: str, /, **config: Any) -> Policy:
    """Construct the policy registered as ``name`` with its config.

    A config key the policy does not take is a ``ConfigError`` naming the keys it does.
    """
    factory = POLICIES.get(name)
    try:
        signature = inspect.signature(factory)
    except (TypeError, ValueError):  # a builtin or C factory: let it check its own arguments
        return factory(**config)
    params = signature.parameters.values()
    if not any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params):
        known = [p.name for p in params if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        unknown = sorted(set(config) - set(known))
        if unknown:
            raise ConfigError(
                f"policy {name!r} does not take {', '.join(map(repr, unknown))}; "
                f"its options are: {', '.join(known) or 'none'}"
            )
    return factory(**config)


__all__ = [
    "POLICIES",
    "EpisodeContext",
    "Observation",
    "Policy",
    "PolicyFactory",
    "PolicyInfo",
    "PolicyStep",
    "PrivilegedState",
    "make_policy",
]
