"""DVC stage ``paraphrase``: basic instructions -> validated paraphrases (instructions.parquet).

Reads params.yaml: study (seed, paraphrases_per_instruction, controls, control_factors), llm, paraphrase,
prompts.paraphrase, prompts.parse_instruction, catalog, paths. The work is
:mod:`ladev_lib.pipeline.paraphrase`. Run from the repository root:

    python stages/paraphrase.py [--params params.yaml]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: this checkout's ladev_lib

from ladev_lib.config import load_params  # noqa: E402
from ladev_lib.pipeline import run_stage  # noqa: E402
from ladev_lib.pipeline.paraphrase import run_paraphrase  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    return run_stage(lambda: run_paraphrase(load_params(args.params)).messages())


if __name__ == "__main__":
    raise SystemExit(main())
