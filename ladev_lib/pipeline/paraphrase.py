"""Stage ``paraphrase``: basic instructions -> validated paraphrases (``paths.instructions``).

Reads ``study`` (validated by ``StudyConfig``; the stage uses its ``seed``,
``paraphrases_per_instruction``, ``controls`` and ``control_factors``), ``llm``, ``paraphrase``, ``prompts.paraphrase``,
``prompts.parse_instruction``, ``catalog`` and ``paths``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tqdm import tqdm

import ladev_lib.language.offline_jobs  # noqa: F401  (registers the offline language jobs)
from ladev_lib.catalog import load_catalog
from ladev_lib.config import section
from ladev_lib.language.config import ParaphraseConfig
from ladev_lib.language.factory import make_validator
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.pipeline import StageMessages
from ladev_lib.pipeline.instructions import paraphrase_scenes, scene_tasks
from ladev_lib.study.controls import control_rows
from ladev_lib.study.design import StudyConfig
from ladev_lib.tables import (
    CompiledSceneRow,
    InstructionRow,
    SceneDesignRow,
    read_table,
    rows_of,
    write_table,
)


@dataclass(frozen=True)
class ParaphraseSummary:
    """``pipeline.instructions``'s counts, plus what the stage knows around them."""

    scenes: int
    skipped: dict[str, int]
    candidates: int
    valid: int
    valid_rate: float | None
    instruction_scenes: int
    selected_paraphrases: int
    instruction_scenes_without_valid_paraphrase: list[str]
    rejections: dict[str, int]
    llm_calls: int
    llm_cache_hits: int
    embedding_model: str
    precision: str
    controls: int = 0
    """Control instructions added (``study.controls``), rows of kind ``control``."""


@dataclass(frozen=True)
class ParaphraseResult:
    table: Path
    rows: list[InstructionRow]
    summary: ParaphraseSummary

    def messages(self) -> StageMessages:
        s = self.summary
        rate = f"{100 * s.valid_rate:.1f}%" if s.valid_rate is not None else "n/a"
        out = [
            f"paraphrase: {s.scenes} scenes ({sum(s.skipped.values())} skipped: {s.skipped or 'none'}), "
            f"{s.candidates} candidates, {s.valid} valid ({rate}); "
            f"{s.selected_paraphrases}/{s.instruction_scenes} instruction-factor scenes got a paraphrase; "
            f"LLM calls {s.llm_calls}, cached {s.llm_cache_hits}; embeddings {s.embedding_model} "
            f"({s.precision}); {s.controls} control instructions -> {self.table}"
        ]
        if s.rejections:
            out.append("  rejected: " + json.dumps(s.rejections))
        err: tuple[str, ...] = ()
        if s.instruction_scenes_without_valid_paraphrase:
            err = ("  WARNING: no valid paraphrase for " + ", ".join(s.instruction_scenes_without_valid_paraphrase),)
        return StageMessages(tuple(out), err)


def run_paraphrase(params: dict[str, Any]) -> ParaphraseResult:
    """Paraphrase and validate every compiled scene's instruction; write ``paths.instructions``."""
    paths = params["paths"]
    study = section(params, "study", StudyConfig)
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
        k=study.paraphrases_per_instruction,
        seed=study.seed,
        progress=lambda items, total, desc: tqdm(items, total=total, desc=desc),
    )
    controls = control_rows(scenes, compiled, study, catalog)
    rows = [*outcome.rows, *controls]
    write_table(rows, paths["instructions"], InstructionRow)

    s = outcome.summary
    summary = ParaphraseSummary(
        scenes=s["scenes"],
        skipped=dict(skipped),
        candidates=s["candidates"],
        valid=s["valid"],
        valid_rate=s["valid_rate"],
        instruction_scenes=s["instruction_scenes"],
        selected_paraphrases=s["selected_paraphrases"],
        instruction_scenes_without_valid_paraphrase=list(s["instruction_scenes_without_valid_paraphrase"]),
        rejections=dict(s["rejections"]),
        llm_calls=s["llm_calls"],
        llm_cache_hits=s["llm_cache_hits"],
        embedding_model=cfg.embedding_model,
        precision=str(validator.precision),
        controls=len(controls),
    )
    return ParaphraseResult(Path(paths["instructions"]), rows, summary)
