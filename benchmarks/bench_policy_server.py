"""What serving a policy over the websocket costs per step, side by side with a direct call.

    PYTHONPATH=. python benchmarks/bench_policy_server.py [--steps 200]

A policy that answers instantly is called directly and through a loopback
PolicyServer + RemotePolicy, with camera images of the sizes LADEV's VLA
embodiments use. Prints the per-step latency of each and the overhead.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import threading
import time
from typing import Any

import numpy as np

from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep
from ladev_lib.policies.remote import RemotePolicy
from ladev_lib.serving.server import PolicyServer


class InstantPolicy(Policy):
    info = PolicyInfo(name="instant", robots=("widowx",), control_mode="none")

    def reset(self, instruction: str) -> None:
        pass

    def step(self, obs: Observation) -> PolicyStep:
        return PolicyStep(action=np.zeros(7))


def serve_in_thread(policy: Policy) -> tuple[str, Any]:
    server = PolicyServer(policy, port=0)
    loop = asyncio.new_event_loop()
    ready = threading.Event()
    port: list[int] = []

    def on_ready(srv: Any) -> None:
        port.append(srv.sockets[0].getsockname()[1])
        ready.set()

    task = loop.create_task(server.serve(on_ready))

    def run() -> None:
        with contextlib.suppress(asyncio.CancelledError):
            loop.run_until_complete(task)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    ready.wait(10)

    def stop() -> None:
        loop.call_soon_threadsafe(task.cancel)
        thread.join(10)

    return f"ws://127.0.0.1:{port[0]}", stop


def per_step_ms(policy: Policy, obs: Observation, steps: int) -> float:
    policy.reset("put the carrot on the plate")
    policy.step(obs)  # warm-up
    start = time.perf_counter()
    for _ in range(steps):
        policy.step(obs)
    return (time.perf_counter() - start) / steps * 1000


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args()
    url, stop = serve_in_thread(InstantPolicy())
    remote = RemotePolicy(url=url, wait_for_server_s=5)
    direct = InstantPolicy()
    print(f"{'image (w x h)':>14} {'direct ms':>10} {'remote ms':>10} {'overhead ms':>12}")
    try:
        for w, h in ((256, 256), (640, 480), (640, 512)):
            obs = Observation(image=np.random.default_rng(0).integers(0, 255, (h, w, 3), dtype=np.uint8))
            d = per_step_ms(direct, obs, args.steps)
            r = per_step_ms(remote, obs, args.steps)
            print(f"{f'{w} x {h}':>14} {d:10.3f} {r:10.3f} {r - d:12.3f}")
    finally:
        remote.close()
        stop()


if __name__ == "__main__":
    main()
