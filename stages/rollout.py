"""DVC stage ``rollout``: every planned episode of one policy -> ``episodes/<policy>.parquet``.

Reads params.yaml: ``policy.<NAME>`` (registry name and keyword arguments),
``sim``, ``robot``, ``executor``, ``rollout``, ``study.name``,
``study.trials_per_scene``, ``study.trial_factors`` and ``paths.*``.
Episodes already in the policy's store are not run again. The work is
:mod:`ladev_lib.pipeline.rollout`. Run from the repository root:

    python stages/rollout.py --policy oracle [--params params.yaml] [--no-progress]

Exits 2 on a configuration error, 1 when more episodes ended in error than
``rollout.max_error_rate`` allows (the table is written either way).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: this checkout's ladev_lib

from ladev_lib.config import load_params  # noqa: E402
from ladev_lib.pipeline import run_stage  # noqa: E402
from ladev_lib.pipeline.rollout import run_rollout  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--policy", required=True, help="key of the policy section (policy.<NAME>)")
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar (logs, CI)")
    args = parser.parse_args(argv)
    return run_stage(lambda: run_rollout(load_params(args.params), args.policy, progress=not args.no_progress).messages())


if __name__ == "__main__":
    raise SystemExit(main())
