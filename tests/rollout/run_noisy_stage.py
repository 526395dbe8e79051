"""Run the toy study's rollout stage with the noisy policy, in its own process.

    python -m tests.rollout.run_noisy_stage ROOT TRIALS

Two such processes on the same study must write the same episode table.
"""

from __future__ import annotations

import sys
from pathlib import Path

from ladev_lib.rollout.stage import rollout_stage
from tests.rollout.conftest import toy_config
from tests.rollout.doubles import make_noisy_policy, make_toy_sim


def main() -> int:
    root, trials = Path(sys.argv[1]), int(sys.argv[2])
    cfg = toy_config({"name": "serial"})
    cfg["study"]["trials_per_scene"] = trials
    result = rollout_stage(
        cfg, "toy", root=root, progress=False, sim_factory=make_toy_sim, policy_factory=make_noisy_policy
    )
    return result.exit_code


if __name__ == "__main__":
    raise SystemExit(main())
