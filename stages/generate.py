"""DVC stage ``generate``: the study design -> scene descriptions and base instructions.

Reads ``params.yaml`` (study, llm, robot.name, prompts.describe_scenes, catalog, paths);
writes ``paths.scenes``. LLM calls are cached in ``paths.llm_cache_dir/generate``,
so a re-run or a grown study makes only the new calls. The work is
:mod:`ladev_lib.pipeline.generate`. Run from the repository root:

    python stages/generate.py [--params params.yaml]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: this checkout's ladev_lib

from ladev_lib.config import load_params  # noqa: E402
from ladev_lib.pipeline import run_stage  # noqa: E402
from ladev_lib.pipeline.generate import run_generate  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    return run_stage(lambda: run_generate(load_params(args.params)).messages())


if __name__ == "__main__":
    raise SystemExit(main())
