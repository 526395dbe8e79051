"""Fixtures for the LLM layer: composed config, an offline scene compiler, a local
OpenAI-compatible HTTP server."""

from __future__ import annotations

import contextlib
import json
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

import pytest

from ladev_lib.config import compose_config, section
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.scenes.compiler import CompileConfig
from ladev_lib.scenes.text_to_scene import SceneCompiler


@pytest.fixture(scope="session")
def params(repo_root) -> dict[str, Any]:
    return compose_config([], repo_root / "conf")


@pytest.fixture(scope="session")
def offline_compiler(params, catalog) -> SceneCompiler:
    llm = section(params, "llm", LLMConfig)
    prompt = load_prompts(params, ["compile_scene"])["compile_scene"]
    return SceneCompiler(make_client(llm, None), prompt, llm, catalog, config=section(params, "compile", CompileConfig))


# -- a tiny OpenAI-compatible server --------------------------------------------------


@dataclass
class Reply:
    """What the server does for one request: answer text, an HTTP error, or a delay first."""

    text: str | None = None
    status: int = 200
    error: str = ""
    delay_s: float = 0.0
    headers: dict[str, str] = field(default_factory=dict)


@dataclass
class FakeServer:
    url: str
    replies: list[Reply] = field(default_factory=list)
    requests: list[dict[str, Any]] = field(default_factory=list)
    auth_headers: list[str] = field(default_factory=list)
    reject_formats: set[str] = field(default_factory=set)
    """response_format types answered with 400, as servers without structured output do."""

    def script(self, *replies: Reply) -> None:
        self.replies.extend(replies)


def _completion(text: str, model: str) -> dict[str, Any]:
    return {
        "id": "chatcmpl-test",
        "object": "chat.completion",
        "created": int(time.time()),
        "model": model,
        "choices": [{"index": 0, "message": {"role": "assistant", "content": text}, "finish_reason": "stop"}],
        "usage": {"prompt_tokens": 11, "completion_tokens": 7, "total_tokens": 18},
    }


@pytest.fixture
def openai_server() -> Iterator[FakeServer]:
    state = FakeServer(url="")

    class Handler(BaseHTTPRequestHandler):
        def log_message(self, *args: Any) -> None:  # keep test output clean
            pass

        def _send(self, status: int, body: dict[str, Any], headers: dict[str, str] | None = None) -> None:
            data = json.dumps(body).encode()
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            for k, v in (headers or {}).items():
                self.send_header(k, v)
            self.end_headers()
            # The client may have given up already (timeout tests).
            with contextlib.suppress(BrokenPipeError, ConnectionResetError):
                self.wfile.write(data)

        def do_POST(self) -> None:  # noqa: N802 - http.server's name
            body = json.loads(self.rfile.read(int(self.headers.get("Content-Length", 0))) or b"{}")
            state.requests.append(body)
            state.auth_headers.append(self.headers.get("Authorization", ""))
            if not self.path.endswith("/chat/completions"):
                self._send(404, {"error": {"message": f"no route {self.path}"}})
                return
            fmt = (body.get("response_format") or {}).get("type")
            if fmt in state.reject_formats:
                self._send(400, {"error": {"message": f"response_format {fmt} is not supported", "type": "invalid_request_error"}})
                return
            reply = state.replies.pop(0) if state.replies else Reply(text="{}")
            if reply.delay_s:
                time.sleep(reply.delay_s)
            if reply.status != 200:
                self._send(reply.status, {"error": {"message": reply.error or f"status {reply.status}"}}, reply.headers)
                return
            self._send(200, _completion(reply.text or "", body.get("model", "?")))

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    server.daemon_threads = True
    thread = threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.05}, daemon=True)
    thread.start()
    state.url = f"http://127.0.0.1:{server.server_address[1]}/v1"
    try:
        yield state
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=5)
