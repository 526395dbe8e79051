"""Scenes compiled per second with the offline backend, and the cache hit rate of a repeated run.

    python benchmarks/bench_compile.py [--scenes 400]

Descriptions come from the offline writer over scenes spread across the
paper study (all tasks, factors and levels). Runs side by side in one
process: each offline reader with no cache (``compile.reader``: the tagged
reader, the default, and the rule reader), then the default with a cold cache
(every call made and stored) and the same cache again (every call a hit).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ladev_lib.catalog import load_catalog  # noqa: E402
from ladev_lib.config import compose_config, section  # noqa: E402
from ladev_lib.llm.config import LLMConfig, make_client  # noqa: E402
from ladev_lib.llm.prompts import load_prompts  # noqa: E402
from ladev_lib.scenes.compiler import CompileConfig, DesignExpectation  # noqa: E402
from ladev_lib.scenes.text_to_scene import SceneCompiler, SceneText  # noqa: E402
from ladev_lib.scenes.writer import write_scene  # noqa: E402
from ladev_lib.study.design import StudyConfig, design_scenes  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=400)
    args = parser.parse_args()

    root = Path(__file__).resolve().parents[1]
    cfg = compose_config(["study=paper"], root / "conf")
    study = section(cfg, "study", StudyConfig)
    llm = section(cfg, "llm", LLMConfig)
    compile_cfg = section(cfg, "compile", CompileConfig)
    prompt = load_prompts(cfg, ["compile_scene"])["compile_scene"]
    catalog = load_catalog(cfg.get("catalog"))

    design = design_scenes(study)
    step = max(1, len(design) // args.scenes)
    picked = design[::step][: args.scenes]
    t0 = time.perf_counter()
    items = []
    for s in picked:
        written = write_scene(s.task, s.num_objects, s.object_set, s.environment, s.seed, catalog, study.bounds)
        items.append(SceneText(s.scene_id, written.description, written.instruction, s.task, s.seed,
                               s.object_set, expected=DesignExpectation(s.task, s.num_objects, s.object_set,
                                                                        s.environment)))
    write_s = time.perf_counter() - t0

    def run(cache_dir: Path | None, reader: str | None = None) -> tuple[float, int, int, int]:
        client = make_client(llm, cache_dir)
        config = compile_cfg if reader is None else compile_cfg.model_copy(update={"reader": reader})
        compiler = SceneCompiler(client, prompt, llm, catalog, study.bounds, config)
        start = time.perf_counter()
        ok = sum(compiler.compile(item).status == "ok" for item in items)
        return time.perf_counter() - start, ok, client.calls, client.cache_hits

    with tempfile.TemporaryDirectory() as tmp:
        cache = Path(tmp) / "compile"
        run(None)  # load the tagger's weights and the embedding model once, outside the timings
        runs = {
            "tagged, no cache": run(None, "tagged"), "rules, no cache": run(None, "rules"),
            f"{compile_cfg.reader}, cold cache": run(cache), f"{compile_cfg.reader}, repeated": run(cache),
        }

    n = len(items)
    print(f"bench_compile: {n} scenes from the paper study (offline backend: {make_client(llm, None).backend.model})")
    print(f"  writing descriptions (offline writer): {n / write_s:8.1f} scenes/s")
    for name, (secs, ok, calls, hits) in runs.items():
        rate = hits / (calls + hits) if calls + hits else 0.0
        print(
            f"  compile, {name:<22}: {n / secs:8.1f} scenes/s  ({secs:6.2f} s, {ok}/{n} ok, "
            f"{calls} calls made, {hits} cache hits, hit rate {rate:.0%})"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
