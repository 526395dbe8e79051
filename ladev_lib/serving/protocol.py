"""What travels between a policy server and its client (openpi's websocket protocol).

The protocol, as openpi defines it and LADEV speaks it:

1. The client opens a websocket (optionally sending ``Authorization: Api-Key
   <key>``). The server answers with one binary frame: its metadata, a
   msgpack map.
2. Each request is one binary frame, a msgpack map of numpy arrays and
   strings (the observation: images, state, prompt). Each reply is one binary
   frame, a map with the action (openpi: ``"actions"``, often a chunk of shape
   (horizon, dim)) and ``"server_timing"``.
3. A failure is reported as one *text* frame (the error and its traceback),
   after which the server closes the connection.
4. ``GET /healthz`` answers ``200 OK`` without opening a websocket.

Which keys hold the image, the state and the prompt differs between servers
(openpi's LIBERO policies read ``observation/image``, ALOHA ones a nested
``images`` map), so :class:`WireKeys` is configurable. A key containing "."
addresses a nested map (``images.cam_high``); "/" is an ordinary character
(openpi's flat ``observation/image``).
"""

from __future__ import annotations

from dataclasses import asdict
from typing import Any

from pydantic import BaseModel, ConfigDict

from ladev_lib.policies.base import PolicyInfo

PROTOCOL = "openpi-websocket"
SERVER_KIND = "ladev"


class WireKeys(BaseModel):
    """Where each piece of an observation and an action sits in a message."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    image: str = "observation/image"
    state: str | None = "observation/state"
    """Proprioception; None: not sent."""
    prompt: str = "prompt"
    reset: str | None = "reset"
    """Flag set on an episode's first request (LADEV's extension); None: never sent.
    LADEV's server also starts an episode on a connection's first request and
    when the prompt changes, so openpi clients work without it."""
    seed: str | None = "seed"
    """The episode's seed, on its first request (LADEV's extension); None: never sent.
    LADEV's server seeds its process's generators (Python, NumPy, torch, the C
    library, OMPL) from it before the policy starts the episode."""
    action: str = "actions"
    terminate: str | None = "terminate"
    """The policy's stop flag in replies; None: the server has none."""


def get_path(message: dict[str, Any], key: str) -> Any:
    """The value at ``key`` ("." nests), or None when absent."""
    node: Any = message
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def set_path(message: dict[str, Any], key: str, value: Any) -> None:
    """Put ``value`` at ``key`` ("." nests), creating maps on the way."""
    parts = key.split(".")
    node = message
    for part in parts[:-1]:
        node = node.setdefault(part, {})
    node[parts[-1]] = value


def info_to_wire(info: PolicyInfo) -> dict[str, Any]:
    """A :class:`PolicyInfo` as plain msgpack-able data."""
    data = asdict(info)
    data["robots"] = list(info.robots)
    data["image_size"] = list(info.image_size) if info.image_size is not None else None
    data["max_episode_steps_by_task"] = dict(info.max_episode_steps_by_task)
    return data


def info_from_wire(data: dict[str, Any]) -> PolicyInfo:
    """The inverse of :func:`info_to_wire`; unknown fields (newer servers) are ignored."""
    known = set(PolicyInfo.__dataclass_fields__)
    fields = {k: v for k, v in data.items() if k in known}
    if "robots" in fields:
        fields["robots"] = tuple(fields["robots"])
    if fields.get("image_size") is not None:
        fields["image_size"] = tuple(int(v) for v in fields["image_size"])
    return PolicyInfo(**fields)
