"""The ``remote`` policy: a client of an openpi-compatible websocket policy server.

    policy = make_policy("remote", url="ws://gpu-box:8000", api_key_env="LADEV_POLICY_KEY")

It works against ``ladev serve-policy`` (which sends the policy's
:class:`PolicyInfo` and wire keys in its metadata) and against openpi's own
servers (pi0, pi0-FAST): set ``keys`` to what that server reads and returns,
and the PolicyInfo fields (``robots``, ``control_mode``, ...) in the config,
since an openpi server does not describe its action space. Action chunks
(openpi replies with shape (horizon, dim)) are executed open loop for
``replan_steps`` steps before asking again.

Failures raise :class:`RemotePolicyError` with what happened and where: no
server within ``wait_for_server_s``, a refused API key, an error the server
reported, a reply slower than ``step_timeout_s``, or a connection lost
mid-episode. The episode engine records these as ``error`` rows; the next
``reset`` reconnects. Dependencies: websockets, msgpack, numpy (and pydantic
for the config), nothing heavy.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import time
from collections import deque
from typing import Any

import numpy as np
from pydantic import BaseModel, ConfigDict, Field
from websockets.exceptions import ConnectionClosed, InvalidHandshake, InvalidStatus, InvalidURI
from websockets.protocol import State
from websockets.sync.client import ClientConnection, connect

from ladev_lib.arrays import Array
from ladev_lib.errors import ConfigError, LadevError
from ladev_lib.policies.base import EpisodeContext, Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.serving.codec import PayloadError, packb, str_keys, unpackb
from ladev_lib.serving.protocol import SERVER_KIND, WireKeys, get_path, info_from_wire, set_path


class RemotePolicyError(LadevError, RuntimeError):
    """The policy server could not be reached or did not answer properly."""


class ConnectionLostError(RemotePolicyError):
    """The connection closed while a request was in flight (the server died or stopped)."""


class RemotePolicyConfig(BaseModel):
    """Config of the ``remote`` policy (``conf/policy/remote.yaml``)."""

    model_config = ConfigDict(extra="forbid")

    url: str = "ws://127.0.0.1:8000"
    api_key_env: str | None = None
    """Environment variable holding the server's API key (keep keys out of configs)."""
    api_key: str | None = Field(default=None, repr=False)
    wait_for_server_s: float = Field(default=30.0, ge=0)
    """How long to keep retrying to connect (the server may still be loading a model)."""
    retry_interval_s: float = Field(default=1.0, gt=0)
    connect_timeout_s: float = Field(default=10.0, gt=0)
    step_timeout_s: float = Field(default=60.0, gt=0)
    """Longest wait for one reply."""
    keys: WireKeys | None = None
    """Wire keys; None: what a LADEV server announces, else openpi's defaults."""
    replan_steps: int | None = Field(default=None, ge=1)
    """Steps of each action chunk to execute before asking again; None: the whole chunk."""
    action_dim: int | None = Field(default=None, ge=1)
    """Keep only the first ``action_dim`` entries of each action (padded outputs)."""
    resize_to: tuple[int, int] | None = None
    """(width, height) to resize the image to before sending (openpi's resize with padding)."""
    send_state: bool = True
    # PolicyInfo fields; required for servers that do not announce them (openpi).
    name: str | None = None
    robots: tuple[str, ...] | None = None
    control_mode: str | None = None
    image_size: tuple[int, int] | None = None
    """(width, height) of the camera image to render (before ``resize_to``)."""
    control_freq_hz: float | None = None
    max_episode_steps: int | None = None
    camera: str | None = None


class RemotePolicy(Policy):
    """A policy whose ``step`` is answered by a server over a websocket."""

    def __init__(self, **config: Any) -> None:
        self.config = RemotePolicyConfig.model_validate(config)
        self._api_key = self._resolve_api_key()
        self._ws: ClientConnection | None = None
        self._chunk: deque[Array] = deque()
        self._instruction: str | None = None
        self._new_episode = False
        self._seed: int | None = None
        self.server_metadata: dict[str, Any] = {}
        self._connect()
        self.keys = self.config.keys or self._announced_keys()
        self.info = self._build_info()

    # ------------------------------------------------------------------ set-up

    def _resolve_api_key(self) -> str | None:
        cfg = self.config
        if cfg.api_key:
            return cfg.api_key
        if cfg.api_key_env:
            key = os.environ.get(cfg.api_key_env)
            if not key:
                raise ConfigError(
                    f"remote policy: environment variable {cfg.api_key_env} (api_key_env) is not set"
                )
            return key
        return None

    def _connect(self) -> None:
        cfg = self.config
        headers = {"Authorization": f"Api-Key {self._api_key}"} if self._api_key else None
        deadline = time.monotonic() + cfg.wait_for_server_s
        last_error: BaseException | None = None
        while True:
            try:
                # Entered as a context manager: the one form every websockets >= 13 accepts
                # without deprecation warnings.
                ws = contextlib.ExitStack().enter_context(
                    connect(
                        cfg.url,
                        additional_headers=headers,
                        compression=None,
                        max_size=None,
                        open_timeout=cfg.connect_timeout_s,
                        close_timeout=1.0,
                    )
                )
                break
            except InvalidURI as exc:
                raise ConfigError(f"remote policy: invalid url {cfg.url!r}: {exc}") from exc
            except InvalidStatus as exc:
                status = exc.response.status_code
                body = exc.response.body.decode("utf-8", "replace").strip() if exc.response.body else ""
                if status == 401:
                    raise RemotePolicyError(
                        f"policy server at {cfg.url} refused the API key ({body}); "
                        "set api_key_env to the variable holding the server's key"
                    ) from exc
                raise RemotePolicyError(
                    f"policy server at {cfg.url} refused the connection: HTTP {status} {body}"
                ) from exc
            except InvalidHandshake as exc:
                raise RemotePolicyError(
                    f"{cfg.url} did not complete a websocket handshake ({exc}); "
                    "is it a policy server (ladev serve-policy / openpi)?"
                ) from exc
            except (OSError, TimeoutError) as exc:
                last_error = exc
                if time.monotonic() >= deadline:
                    raise RemotePolicyError(
                        f"no policy server reachable at {cfg.url} within "
                        f"{cfg.wait_for_server_s:g} s ({type(exc).__name__}: {exc}); "
                        "start one with: ladev serve-policy NAME --port PORT"
                    ) from last_error
                time.sleep(cfg.retry_interval_s)
        first = self._receive(ws, cfg.connect_timeout_s, "its metadata")
        if not isinstance(first, dict):
            ws.close()
            raise RemotePolicyError(f"policy server at {cfg.url} sent metadata that is not a map")
        self.server_metadata = first
        self._ws = ws

    def _announced_keys(self) -> WireKeys:
        keys = self.server_metadata.get("keys")
        if self.server_metadata.get("server") == SERVER_KIND and isinstance(keys, dict):
            return WireKeys.model_validate(keys)
        return WireKeys()

    def _build_info(self) -> PolicyInfo:
        cfg = self.config
        announced = self.server_metadata.get("policy")
        overrides: dict[str, Any] = {
            k: v
            for k, v in {
                "name": cfg.name,
                "robots": cfg.robots,
                "control_mode": cfg.control_mode,
                "image_size": cfg.image_size,
                "control_freq_hz": cfg.control_freq_hz,
                "max_episode_steps": cfg.max_episode_steps,
                "camera": cfg.camera,
            }.items()
            if v is not None
        }
        if cfg.robots is not None:
            overrides["robots"] = tuple(cfg.robots)
        if isinstance(announced, dict):
            return dataclasses.replace(info_from_wire(announced), **overrides)
        missing = [k for k in ("robots", "control_mode") if k not in overrides]
        if missing:
            raise ConfigError(
                f"policy server at {cfg.url} does not announce its policy (not a LADEV server); "
                f"set {', '.join(missing)} in the remote policy config"
            )
        overrides.setdefault("name", f"remote:{cfg.url}")
        return PolicyInfo(**overrides)

    # ------------------------------------------------------------------ I/O

    def _receive(self, ws: ClientConnection, timeout: float, what: str) -> Any:
        url = self.config.url
        try:
            frame = ws.recv(timeout=timeout)
        except TimeoutError as exc:
            # A late reply would be taken for the next one: drop the connection.
            ws.close()
            self._ws = None
            raise RemotePolicyError(
                f"policy server at {url} sent no {what} within {timeout:g} s (step_timeout_s)"
            ) from exc
        except ConnectionClosed as exc:
            self._ws = None
            raise ConnectionLostError(
                f"connection to the policy server at {url} was lost while waiting for {what} "
                f"(close code {exc.rcvd.code if exc.rcvd else 'none'}: the server died or "
                "was stopped)"
            ) from exc
        if isinstance(frame, str):
            ws.close()
            self._ws = None
            raise RemotePolicyError(f"policy server at {url} reported an error:\n{frame.strip()}")
        try:
            return str_keys(unpackb(frame))
        except PayloadError as exc:
            raise RemotePolicyError(f"policy server at {url} sent an invalid message: {exc}") from exc

    def _request(self, message: dict[str, Any]) -> dict[str, Any]:
        try:
            return self._send_and_receive(message)
        except ConnectionLostError:
            if not self._new_episode:
                raise
        # Lost before the episode's first reply: the server holds no state of this
        # episode yet, so reconnecting and asking again is safe.
        return self._send_and_receive(message)

    def _send_and_receive(self, message: dict[str, Any]) -> dict[str, Any]:
        if self._ws is None:
            self._connect()
        assert self._ws is not None
        try:
            self._ws.send(packb(message))
        except ConnectionClosed as exc:
            self._ws = None
            raise ConnectionLostError(
                f"connection to the policy server at {self.config.url} was lost mid-episode "
                "(the server died or was stopped)"
            ) from exc
        reply = self._receive(self._ws, self.config.step_timeout_s, "action")
        if not isinstance(reply, dict):
            raise RemotePolicyError(f"policy server at {self.config.url} replied with a non-map")
        return reply

    # ------------------------------------------------------------------ Policy

    def begin_episode(self, ctx: EpisodeContext) -> None:
        self._seed = ctx.seed

    def reset(self, instruction: str) -> None:
        self._instruction = instruction
        self._new_episode = True
        self._chunk.clear()
        if self._ws is not None and self._ws.protocol.state is not State.OPEN:
            self._ws = None  # the server went away between episodes
        if self._ws is None:
            self._connect()

    def _observation_message(self, obs: Observation) -> dict[str, Any]:
        assert self._instruction is not None
        keys = self.keys
        message: dict[str, Any] = {}
        set_path(message, keys.prompt, self._instruction)
        if obs.image is not None:
            set_path(message, keys.image, self._prepare_image(obs.image))
        if self.config.send_state and keys.state and obs.proprio is not None:
            set_path(message, keys.state, np.asarray(obs.proprio, dtype=np.float32))
        if keys.reset is not None and self._new_episode:
            set_path(message, keys.reset, True)
        if keys.seed is not None and self._new_episode and self._seed is not None:
            set_path(message, keys.seed, int(self._seed))
        return message

    def _prepare_image(self, image: Array) -> Array:
        if self.config.resize_to is None:
            return np.ascontiguousarray(image, dtype=np.uint8)
        return resize_with_pad(image, *self.config.resize_to)

    def step(self, obs: Observation) -> PolicyStep:
        if self._instruction is None:
            raise RuntimeError("call reset(instruction) before step()")
        if self._chunk:
            return PolicyStep(action=self._chunk.popleft())
        reply = self._request(self._observation_message(obs))
        self._new_episode = False
        raw = get_path(reply, self.keys.action)
        if raw is None:
            raise RemotePolicyError(
                f"the reply of {self.config.url} has no action at {self.keys.action!r} "
                f"(keys: {sorted(reply)}); set keys.action in the remote policy config"
            )
        actions = np.atleast_1d(np.asarray(raw, dtype=np.float64))
        if self.config.action_dim is not None:
            actions = actions[..., : self.config.action_dim]
        terminate = bool(get_path(reply, self.keys.terminate)) if self.keys.terminate else False
        if actions.ndim == 2:
            n = len(actions) if self.config.replan_steps is None else self.config.replan_steps
            self._chunk.extend(actions[1:n])
            return PolicyStep(action=actions[0], terminate=terminate)
        return PolicyStep(action=actions, terminate=terminate)

    def close(self) -> None:
        if self._ws is not None:
            self._ws.close()
            self._ws = None


def resize_with_pad(image: Array, width: int, height: int) -> Array:
    """Resize keeping the aspect ratio, pad with black to (height, width) (openpi's client does)."""
    from PIL import Image

    h, w = image.shape[:2]
    if (w, h) == (width, height):
        return np.ascontiguousarray(image, dtype=np.uint8)
    ratio = max(w / width, h / height)
    new_w, new_h = int(w / ratio), int(h / ratio)
    resized = np.asarray(Image.fromarray(image).resize((new_w, new_h), Image.Resampling.BILINEAR))
    out = np.zeros((height, width, 3), dtype=np.uint8)
    top, left = (height - new_h) // 2, (width - new_w) // 2
    out[top : top + new_h, left : left + new_w] = resized
    return out
