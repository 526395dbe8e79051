"""DVC stage ``rollout``: every planned episode of one policy -> ``episodes/<policy>.parquet``.

Reads params.yaml: ``policy.<NAME>`` (registry name and keyword arguments),
``sim``, ``robot``, ``executor``, ``rollout``, ``study.name``,
``study.trials_per_scene``, ``study.trial_factors`` and ``paths.*``.
Episodes already in the policy's store are not run again. Run from the
repository root:

    python stages/rollout.py --policy oracle [--params params.yaml] [--no-progress]

Exits 1 on a configuration error, or when more episodes ended in error than
``rollout.max_error_rate`` allows (the table is written either way).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

# Run as a script from the repository root: make ladev_lib importable without installing.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ladev_lib.config import load_params  # noqa: E402
from ladev_lib.errors import LadevError  # noqa: E402
from ladev_lib.rollout.stage import rollout_stage  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--policy", required=True, help="key of the policy section (policy.<NAME>)")
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar (logs, CI)")
    args = parser.parse_args(argv)
    try:
        result = rollout_stage(
            load_params(args.params), args.policy, root=Path.cwd(), progress=not args.no_progress
        )
    except LadevError as exc:
        print(f"rollout: {exc}", file=sys.stderr)
        return 1
    print(result.summary.format())
    print(f"rollout: wrote {result.table}" + (f" and {result.timings}" if result.timings else ""))
    if result.exit_code:
        print(
            f"rollout: error rate {100 * result.summary.error_rate:.1f}% is above the configured "
            f"{100 * result.max_error_rate:.1f}% (rollout.max_error_rate)",
            file=sys.stderr,
        )
    return result.exit_code


if __name__ == "__main__":
    raise SystemExit(main())
