"""DVC stage ``aggregate``: episode rows -> tables, figures, HTML report, metrics.

Reads params.yaml: ``report`` (options), ``study.name`` (which study's episodes
to report) and ``paths.*`` (where things are). The work is
:mod:`ladev_lib.pipeline.aggregate`. Run from the repository root:

    python stages/aggregate.py [--params params.yaml]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: this checkout's ladev_lib

from ladev_lib.config import load_params  # noqa: E402
from ladev_lib.pipeline import run_stage  # noqa: E402
from ladev_lib.pipeline.aggregate import run_aggregate  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    return run_stage(lambda: run_aggregate(load_params(args.params)).messages())


if __name__ == "__main__":
    raise SystemExit(main())
