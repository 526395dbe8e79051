"""Stage ``paraphrase``: basic instructions -> validated paraphrases (instructions.parquet).

Reads params.yaml: study.seed, study.paraphrases_per_instruction, study.controls,
study.control_factors, llm, paraphrase, prompts.paraphrase, prompts.parse_instruction,
paths. Control instructions (``study.controls``) are added as rows of kind ``control``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

# Run as a script from the repository root: make ladev_lib importable without installing.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tqdm import tqdm  # noqa: E402

import ladev_lib.language.offline_jobs  # noqa: E402, F401  (registers the offline language jobs)
from ladev_lib.catalog import load_catalog  # noqa: E402
from ladev_lib.config import load_params, section  # noqa: E402
from ladev_lib.language.config import ParaphraseConfig  # noqa: E402
from ladev_lib.language.pipeline import make_validator, paraphrase_scenes, scene_tasks  # noqa: E402
from ladev_lib.llm.config import LLMConfig, make_client  # noqa: E402
from ladev_lib.llm.prompts import load_prompts  # noqa: E402
from ladev_lib.study.controls import control_rows  # noqa: E402
from ladev_lib.study.design import StudyConfig  # noqa: E402
from ladev_lib.tables import (  # noqa: E402
    CompiledSceneRow,
    InstructionRow,
    SceneDesignRow,
    read_table,
    rows_of,
    write_table,
)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    params = load_params(args.params)
    paths = params["paths"]
    study = params["study"]
    cfg = section(params, "paraphrase", ParaphraseConfig)
    llm = section(params, "llm", LLMConfig)
    prompts = load_prompts(params, ["paraphrase", "parse_instruction"])
    catalog = load_catalog(params.get("catalog"))

    scenes = rows_of(read_table(paths["scenes"], SceneDesignRow), SceneDesignRow)
    compiled = rows_of(read_table(paths["compiled"], CompiledSceneRow), CompiledSceneRow)
    tasks, skipped = scene_tasks(scenes, compiled)

    client = make_client(llm, Path(paths["llm_cache_dir"]) / "paraphrase")
    validator = make_validator(
        cfg, llm, client=client, parse_prompt=prompts["parse_instruction"], catalog=catalog
    )
    outcome = paraphrase_scenes(
        tasks,
        client=client,
        prompt=prompts["paraphrase"],
        llm=llm,
        validator=validator,
        k=int(study["paraphrases_per_instruction"]),
        seed=int(study["seed"]),
        progress=lambda items, total, desc: tqdm(items, total=total, desc=desc),
    )
    controls = control_rows(scenes, compiled, section(params, "study", StudyConfig), catalog)
    write_table([*outcome.rows, *controls], paths["instructions"], InstructionRow)

    s = outcome.summary
    rate = f"{100 * s['valid_rate']:.1f}%" if s["valid_rate"] is not None else "n/a"
    print(
        f"paraphrase: {s['scenes']} scenes ({sum(skipped.values())} skipped: {skipped or 'none'}), "
        f"{s['candidates']} candidates, {s['valid']} valid ({rate}); "
        f"{s['selected_paraphrases']}/{s['instruction_scenes']} instruction-factor scenes got a paraphrase; "
        f"LLM calls {s['llm_calls']}, cached {s['llm_cache_hits']}; embeddings {cfg.embedding_model} "
        f"({validator.precision}); {len(controls)} control instructions -> {paths['instructions']}"
    )
    if s["rejections"]:
        print("  rejected: " + json.dumps(s["rejections"]))
    if s["instruction_scenes_without_valid_paraphrase"]:
        print(
            "  WARNING: no valid paraphrase for "
            + ", ".join(s["instruction_scenes_without_valid_paraphrase"]),
            file=sys.stderr,
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
