"""Serve any LADEV policy over openpi's websocket protocol (see :mod:`.protocol`).

    server = PolicyServer(make_policy("rt1", ...), port=8000)
    server.run()                       # until SIGINT / SIGTERM

The model runs in its own environment or on a GPU machine; the rollout
reaches it through :class:`ladev_lib.policies.remote.RemotePolicy`, or any
openpi client. Inference runs on a worker thread, never on the event loop,
so ``/healthz`` and other connections stay responsive during a slow step.

Safety: it binds to loopback unless given another host, can require an API
key (``Authorization: Api-Key <key>``, compared in constant time), bounds
message sizes, and decodes requests with :func:`.codec.unpackb`, which
accepts only plain numeric arrays (never pickle, never object dtypes).

LADEV's VLA policies keep per-episode state (image history, sticky gripper),
so by default one client at a time is served; a second one is refused with
a text frame saying so (raise ``max_connections`` only for stateless policies).
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import http
import logging
import signal
import time
import traceback
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

import numpy as np
from websockets.asyncio.server import Server, ServerConnection, serve
from websockets.exceptions import ConnectionClosed
from websockets.frames import CloseCode
from websockets.http11 import Request, Response

import ladev_lib
from ladev_lib.policies.base import Observation, Policy
from ladev_lib.seeding import seed_episode
from ladev_lib.serving.codec import PayloadError, packb, str_keys, unpackb
from ladev_lib.serving.protocol import PROTOCOL, SERVER_KIND, WireKeys, get_path, info_to_wire

log = logging.getLogger(__name__)

DEFAULT_MAX_MESSAGE_BYTES = 64 * 1024 * 1024


class RequestError(ValueError):
    """A request that is well-formed msgpack but not a usable observation."""


@dataclass
class _Session:
    """Per-connection episode state."""

    prompt: str | None = None
    step: int = 0
    prev_total_ms: float | None = None


class PolicyServer:
    """A websocket server around one policy."""

    def __init__(
        self,
        policy: Policy,
        *,
        host: str = "127.0.0.1",
        port: int = 8000,
        api_key: str | None = None,
        keys: WireKeys | None = None,
        max_connections: int = 1,
        max_message_bytes: int = DEFAULT_MAX_MESSAGE_BYTES,
        metadata: dict[str, Any] | None = None,
    ) -> None:
        if max_connections < 1:
            raise ValueError("max_connections must be >= 1")
        self.policy = policy
        self.host = host
        self.port = port
        self.keys = keys or WireKeys()
        self.max_connections = max_connections
        self.max_message_bytes = max_message_bytes
        self._api_key = api_key or None
        self._active = 0
        # One worker: policies are not thread-safe and keep episode state.
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="ladev-policy")
        self.metadata: dict[str, Any] = {
            "protocol": PROTOCOL,
            "server": SERVER_KIND,
            "ladev_version": ladev_lib.__version__,
            "policy": info_to_wire(policy.info),
            "keys": self.keys.model_dump(),
            "requires_api_key": self._api_key is not None,
            **(metadata or {}),
        }

    # ------------------------------------------------------------------ HTTP

    def _process_request(self, connection: ServerConnection, request: Request) -> Response | None:
        if request.path == "/healthz":
            return connection.respond(http.HTTPStatus.OK, "OK\n")
        if self._api_key is not None:
            sent = request.headers.get("Authorization") or ""
            if not hmac.compare_digest(sent.encode(), f"Api-Key {self._api_key}".encode()):
                return connection.respond(
                    http.HTTPStatus.UNAUTHORIZED,
                    "missing or wrong API key: send the header 'Authorization: Api-Key <key>'\n",
                )
        return None

    # ------------------------------------------------------------------ websocket

    async def _handle(self, ws: ServerConnection) -> None:
        self._active += 1
        try:
            if self._active > self.max_connections:
                await self._fail(
                    ws,
                    f"server busy: it serves {self.max_connections} client(s) at a time "
                    "(its policy keeps per-episode state)",
                    CloseCode.TRY_AGAIN_LATER,
                )
                return
            await ws.send(packb(self.metadata))
            session = _Session()
            loop = asyncio.get_running_loop()
            async for message in ws:
                started = time.monotonic()
                try:
                    if isinstance(message, str):
                        raise PayloadError("expected a binary msgpack frame, got text")
                    request = str_keys(unpackb(message))
                    if not isinstance(request, dict):
                        raise PayloadError("a request must be a msgpack map")
                except PayloadError as exc:
                    await self._fail(ws, f"bad request: {exc}", CloseCode.UNSUPPORTED_DATA)
                    return
                try:
                    reply = await loop.run_in_executor(self._executor, self._infer, session, request)
                except Exception:  # noqa: BLE001 - reported to the client, as the protocol says
                    log.exception("policy failed on a request")
                    await self._fail(ws, traceback.format_exc(), CloseCode.INTERNAL_ERROR)
                    return
                timing = {"infer_ms": (time.monotonic() - started) * 1000.0}
                if session.prev_total_ms is not None:
                    timing["prev_total_ms"] = session.prev_total_ms
                reply["server_timing"] = timing
                await ws.send(packb(reply))
                session.prev_total_ms = (time.monotonic() - started) * 1000.0
        except ConnectionClosed:
            log.info("client %s went away", ws.remote_address)
        finally:
            self._active -= 1

    async def _fail(self, ws: ServerConnection, text: str, code: CloseCode) -> None:
        # A close reason may hold at most 123 bytes: the error's last line, cut.
        reason = text.strip().splitlines()[-1].encode()[:120].decode("utf-8", "ignore")
        with contextlib.suppress(ConnectionClosed):
            await ws.send(text)
            await ws.close(code=code, reason=reason)

    def _infer(self, session: _Session, request: dict[str, Any]) -> dict[str, Any]:
        keys = self.keys
        prompt = get_path(request, keys.prompt)
        if isinstance(prompt, bytes):
            prompt = prompt.decode("utf-8")
        if not isinstance(prompt, str):
            raise RequestError(f"the request needs the instruction as a string at {keys.prompt!r}")
        wants_reset = keys.reset is not None and bool(get_path(request, keys.reset))
        if wants_reset or session.prompt is None or prompt != session.prompt:
            seed = get_path(request, keys.seed) if keys.seed is not None else None
            if seed is not None:
                if isinstance(seed, bool) or not isinstance(seed, int | np.integer):
                    raise RequestError(f"{keys.seed!r} must be an integer, got {seed!r}")
                seed_episode(int(seed))
            self.policy.reset(prompt)
            session.prompt, session.step = prompt, 0
        image = get_path(request, keys.image)
        if image is not None and not (
            isinstance(image, np.ndarray) and image.ndim == 3 and image.dtype == np.uint8
        ):
            raise RequestError(f"{keys.image!r} must be an (H, W, 3) uint8 array")
        state = get_path(request, keys.state) if keys.state else None
        proprio = None if state is None else np.asarray(state)
        obs = Observation(image=image, proprio=proprio, step=session.step)
        step = self.policy.step(obs)
        session.step += 1
        reply: dict[str, Any] = {keys.action: np.asarray(step.action)}
        if keys.terminate is not None:
            reply[keys.terminate] = np.bool_(step.terminate)
        return reply

    # ------------------------------------------------------------------ running

    async def serve(self, on_ready: Callable[[Server], None] | None = None) -> None:
        """Serve until cancelled; ``on_ready`` gets the bound server (e.g. its port)."""
        async with serve(
            self._handle,
            self.host,
            self.port,
            process_request=self._process_request,
            compression=None,
            max_size=self.max_message_bytes,
        ) as server:
            for sock in server.sockets:
                log.info("serving %s on ws://%s:%s", self.policy.info.name, *sock.getsockname()[:2])
            if on_ready is not None:
                on_ready(server)
            await server.serve_forever()

    def run(self, on_ready: Callable[[Server], None] | None = None) -> None:
        """Serve until SIGINT or SIGTERM, then release the policy."""

        async def main() -> None:
            task = asyncio.current_task()
            assert task is not None
            loop = asyncio.get_running_loop()
            for sig in (signal.SIGINT, signal.SIGTERM):
                loop.add_signal_handler(sig, task.cancel)
            with contextlib.suppress(asyncio.CancelledError):
                await self.serve(on_ready)

        try:
            asyncio.run(main())
        finally:
            self._executor.shutdown(wait=False, cancel_futures=True)
            self.policy.close()
