"""Run a PolicyServer around a ScriptedPolicy in this process (tests start it as a subprocess).

    python -m tests.serving.run_server PORT_FILE [--delay S] [--fail-at N] [--api-key K]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ladev_lib.serving.server import PolicyServer
from tests.serving.scripted import ScriptedPolicy


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("port_file", type=Path)
    parser.add_argument("--port", type=int, default=0)
    parser.add_argument("--delay", type=float, default=0.0)
    parser.add_argument("--fail-at", type=int, default=None)
    parser.add_argument("--api-key", default=None)
    args = parser.parse_args()
    policy = ScriptedPolicy(delay_s=args.delay, fail_at_step=args.fail_at)
    server = PolicyServer(policy, port=args.port, api_key=args.api_key)

    def ready(srv: object) -> None:
        port = srv.sockets[0].getsockname()[1]  # type: ignore[attr-defined]
        tmp = args.port_file.with_suffix(".tmp")
        tmp.write_text(str(port))
        tmp.rename(args.port_file)

    server.run(on_ready=ready)


if __name__ == "__main__":
    main()
