"""Fixtures for the policy-server tests: servers in a thread or in a subprocess."""

from __future__ import annotations

import asyncio
import os
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any

import pytest

from ladev_lib.policies.base import Policy
from ladev_lib.serving.server import PolicyServer

REPO_ROOT = Path(__file__).resolve().parents[2]


@contextmanager
def serve_in_thread(policy: Policy, **kwargs: Any) -> Iterator[tuple[str, PolicyServer]]:
    """A PolicyServer on a free loopback port, run by an event loop in a thread."""
    server = PolicyServer(policy, port=0, **kwargs)
    loop = asyncio.new_event_loop()
    ready = threading.Event()
    port: list[int] = []

    def on_ready(srv: Any) -> None:
        port.append(srv.sockets[0].getsockname()[1])
        ready.set()

    task_box: list[asyncio.Task[None]] = []

    def run() -> None:
        asyncio.set_event_loop(loop)
        task = loop.create_task(server.serve(on_ready))
        task_box.append(task)
        with suppress(asyncio.CancelledError):
            loop.run_until_complete(task)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    assert ready.wait(10), "server did not start"
    try:
        yield f"ws://127.0.0.1:{port[0]}", server
    finally:
        loop.call_soon_threadsafe(task_box[0].cancel)
        thread.join(10)
        loop.close()


@pytest.fixture
def threaded_server() -> Callable[..., Any]:
    return serve_in_thread


class ServerProcess:
    """``python -m tests.serving.run_server`` in a subprocess."""

    def __init__(self, tmp_path: Path, *args: str) -> None:
        self.port_file = tmp_path / f"port-{time.monotonic_ns()}"
        env = {**os.environ, "PYTHONPATH": f"{REPO_ROOT}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "tests.serving.run_server", str(self.port_file), *args],
            cwd=REPO_ROOT,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        deadline = time.monotonic() + 60
        while not self.port_file.exists():
            if self.proc.poll() is not None:
                raise RuntimeError(f"server exited: {self.proc.stderr.read().decode()}")  # type: ignore[union-attr]
            if time.monotonic() > deadline:
                self.kill()
                raise RuntimeError("server did not start within 60 s")
            time.sleep(0.05)
        self.port = int(self.port_file.read_text())
        self.url = f"ws://127.0.0.1:{self.port}"

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait(10)


@pytest.fixture
def server_process(tmp_path: Path) -> Iterator[Callable[..., ServerProcess]]:
    started: list[ServerProcess] = []

    def start(*args: str) -> ServerProcess:
        proc = ServerProcess(tmp_path, *args)
        started.append(proc)
        return proc

    yield start
    for proc in started:
        proc.kill()
