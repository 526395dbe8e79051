"""Stage ``generate``: the study design -> scene descriptions and base instructions (``paths.scenes``).

Reads ``study``, ``llm``, ``robot.name``, ``prompts.describe_scenes``, ``catalog``
and ``paths``. LLM calls are cached in ``paths.llm_cache_dir/generate``, so a
re-run or a grown study makes only the new calls.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tqdm import tqdm

from ladev_lib.catalog import load_catalog
from ladev_lib.config import section
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.pipeline import StageMessages
from ladev_lib.study.design import StudyConfig, design_scenes, plan_batches
from ladev_lib.study.generation import generate_descriptions
from ladev_lib.tables import SceneDesignRow, write_table
from ladev_lib.vocabulary import as_robot


@dataclass(frozen=True)
class GenerateSummary:
    scenes: int
    ok: int
    batches: int
    batch_size: int
    calls: int
    cached: int
    backend: str
    model: str
    failed_batches: tuple[str, ...]


@dataclass(frozen=True)
class GenerateResult:
    table: Path
    rows: list[SceneDesignRow]
    summary: GenerateSummary

    def messages(self) -> StageMessages:
        s = self.summary
        head = (
            f"generate: {s.scenes} scenes ({s.ok} ok, {s.scenes - s.ok} failed) in "
            f"{s.batches} batches of {s.batch_size}; LLM calls: {s.calls} made, "
            f"{s.cached} cached ({s.backend}:{s.model}) -> {self.table}"
        )
        return StageMessages((head, *(f"  failed batch {line}" for line in s.failed_batches[:5])))


def run_generate(params: dict[str, Any], *, progress: bool = True) -> GenerateResult:
    """Describe every designed scene (cached LLM calls) and write ``paths.scenes``."""
    paths = params["paths"]
    study = section(params, "study", StudyConfig)
    llm = section(params, "llm", LLMConfig)
    prompt = load_prompts(params, ["describe_scenes"])["describe_scenes"]
    catalog_path = params.get("catalog")
    catalog = load_catalog(catalog_path)
    client = make_client(llm, Path(paths["llm_cache_dir"]) / "generate")

    total = len(design_scenes(study))
    with tqdm(total=total, desc="generate", unit="scene", disable=not progress) as bar:
        result = generate_descriptions(
            study, client, prompt, llm, catalog,
            robot=as_robot(str(params["robot"]["name"])), catalog_path=catalog_path, on_batch=bar.update,
        )
    write_table(result.rows, paths["scenes"], SceneDesignRow)

    summary = GenerateSummary(
        scenes=len(result.rows),
        ok=sum(r.status == "ok" for r in result.rows),
        batches=len(plan_batches(study)),
        batch_size=study.batch_size,
        calls=result.calls,
        cached=result.cached,
        backend=llm.backend,
        model=client.backend.model,
        failed_batches=tuple(result.failed_batches),
    )
    return GenerateResult(Path(paths["scenes"]), result.rows, summary)
