"""Stage ``generate``: the study design -> scene descriptions and base instructions.

Reads ``params.yaml`` (study, llm, robot.name, prompts.describe_scenes, catalog, paths);
writes ``paths.scenes``. LLM calls are cached in ``paths.llm_cache_dir/generate``,
so a re-run or a grown study makes only the new calls.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's ladev_lib

from tqdm import tqdm  # noqa: E402

from ladev_lib.catalog import load_catalog  # noqa: E402
from ladev_lib.config import load_params, section  # noqa: E402
from ladev_lib.llm.config import LLMConfig, make_client  # noqa: E402
from ladev_lib.llm.prompts import load_prompts  # noqa: E402
from ladev_lib.study.design import StudyConfig, design_scenes, plan_batches  # noqa: E402
from ladev_lib.study.generation import generate_descriptions  # noqa: E402
from ladev_lib.tables import SceneDesignRow, write_table  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    params = load_params(args.params)
    paths = params["paths"]
    study = section(params, "study", StudyConfig)
    llm = section(params, "llm", LLMConfig)
    prompt = load_prompts(params, ["describe_scenes"])["describe_scenes"]
    catalog_path = params.get("catalog")
    catalog = load_catalog(catalog_path)
    client = make_client(llm, Path(paths["llm_cache_dir"]) / "generate")

    total = len(design_scenes(study))
    with tqdm(total=total, desc="generate", unit="scene") as bar:
        result = generate_descriptions(
            study, client, prompt, llm, catalog,
            robot=str(params["robot"]["name"]), catalog_path=catalog_path, on_batch=bar.update,
        )
    write_table(result.rows, paths["scenes"], SceneDesignRow)

    ok = sum(r.status == "ok" for r in result.rows)
    print(
        f"generate: {len(result.rows)} scenes ({ok} ok, {len(result.rows) - ok} failed) in "
        f"{len(plan_batches(study))} batches of {study.batch_size}; LLM calls: {result.calls} made, "
        f"{result.cached} cached ({llm.backend}:{client.backend.model}) -> {paths['scenes']}"
    )
    for line in result.failed_batches[:5]:
        print(f"  failed batch {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
