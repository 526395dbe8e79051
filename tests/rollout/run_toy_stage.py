"""Run the toy study's rollout stage in its own process (for the kill-and-resume test).

    python -m tests.rollout.run_toy_stage ROOT [local|serial]
"""

from __future__ import annotations

import sys
from pathlib import Path

from tests.rollout.conftest import run_toy, toy_config


def main() -> int:
    root, executor = Path(sys.argv[1]), sys.argv[2] if len(sys.argv) > 2 else "local"
    cfg = toy_config({"name": executor, "workers": 2} if executor == "local" else {"name": executor})
    return run_toy(root, cfg).exit_code


if __name__ == "__main__":
    raise SystemExit(main())
