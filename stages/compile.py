"""Stage ``compile``: scene descriptions -> validated scene specs (or rejections with reasons).

Reads ``params.yaml`` (study.bounds, llm, compile, prompts.compile_scene, catalog, paths)
and ``paths.scenes``; writes ``paths.compiled``. LLM calls are cached in
``paths.llm_cache_dir/compile``. A bad description is a ``rejected`` row, never a
crash. The physical-validity check runs at rollout: ``validity`` is ``not_checked`` here.
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's ladev_lib

from tqdm import tqdm  # noqa: E402

from ladev_lib.catalog import load_catalog  # noqa: E402
from ladev_lib.config import load_params, section  # noqa: E402
from ladev_lib.llm.config import LLMConfig, make_client  # noqa: E402
from ladev_lib.llm.prompts import load_prompts  # noqa: E402
from ladev_lib.scenes.compiler import CompileConfig  # noqa: E402
from ladev_lib.scenes.spec import SceneBounds  # noqa: E402
from ladev_lib.scenes.text_to_scene import CompiledScene, SceneCompiler, scene_text_of_row  # noqa: E402
from ladev_lib.tables import CompiledSceneRow, SceneDesignRow, read_table, rows_of, write_table  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    params = load_params(args.params)
    paths = params["paths"]
    bounds = SceneBounds.model_validate(params.get("study", {}).get("bounds") or {})
    config = section(params, "compile", CompileConfig)
    llm = section(params, "llm", LLMConfig)
    prompt = load_prompts(params, ["compile_scene"])["compile_scene"]
    catalog = load_catalog(params.get("catalog"))
    client = make_client(llm, Path(paths["llm_cache_dir"]) / "compile")
    compiler = SceneCompiler(client, prompt, llm, catalog, bounds, config)

    designs: list[SceneDesignRow] = rows_of(read_table(paths["scenes"], SceneDesignRow), SceneDesignRow)
    results: list[CompiledScene] = []
    with tqdm(total=len(designs), desc="compile", unit="scene") as bar, ThreadPoolExecutor(
        max_workers=llm.concurrency
    ) as pool:

        def one(design: SceneDesignRow) -> CompiledScene:
            if design.status != "ok" or not design.description:
                return CompiledScene(design.scene_id, "rejected", f"generation failed: {design.reason}")
            return compiler.compile(scene_text_of_row(design))

        for result in pool.map(one, designs):
            results.append(result)
            bar.update(1)
    write_table([r.row() for r in results], paths["compiled"], CompiledSceneRow)

    ok = sum(r.status == "ok" for r in results)
    calls = sum(r.calls for r in results)
    cached = sum(r.cached for r in results)
    print(
        f"compile: {len(results)} scenes ({ok} ok, {len(results) - ok} rejected); LLM calls: {calls} made, "
        f"{cached} cached ({llm.backend}:{client.backend.model}) -> {paths['compiled']}"
    )
    reasons = Counter((r.reason or "").split(":")[0] for r in results if r.status == "rejected")
    for reason, n in reasons.most_common(5):
        print(f"  rejected x{n}: {reason}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
