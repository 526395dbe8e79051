"""Batch-style generation: scene descriptions and base instructions, n per LLM call.

    result = generate_descriptions(study, client, prompt, llm_cfg, catalog, robot="panda")
    write_table(result.rows, "data/scenes.parquet", SceneDesignRow)

Each batch asks for ``batch_size`` scenes of one (task, factor, level) cell
(see :class:`ladev_lib.study.design.Batch`). An answer is checked: one entry
per requested id, each instruction in the standard form of its task; the
client re-asks with the problem when it is not. A batch that still fails, or
whose call fails, becomes ``failed`` rows with the reason; the stage goes on.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ladev_lib.catalog import Catalog
from ladev_lib.errors import LLMCallError
from ladev_lib.language.scene import parse_instruction
from ladev_lib.llm.client import JsonResult, LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import PromptTemplate, build_request
from ladev_lib.scenes.text_to_scene import object_listing
from ladev_lib.study.design import Batch, DesignedScene, StudyConfig, plan_batches
from ladev_lib.tables import SceneDesignRow
from ladev_lib.vocabulary import Robot

JOB = "describe_scenes"


class DescribedScene(BaseModel):
    model_config = ConfigDict(extra="ignore")

    id: str
    description: str = Field(min_length=1)
    instruction: str = Field(min_length=1)


class DescribedBatch(BaseModel):
    model_config = ConfigDict(extra="ignore")

    scenes: list[DescribedScene]


def batch_model(items: Sequence[DesignedScene]) -> type[DescribedBatch]:
    """A model that also checks the ids and each instruction's task form."""
    tasks = {it.scene_id: it.task for it in items}

    class CheckedBatch(DescribedBatch):
        @model_validator(mode="after")
        def _matches_request(self) -> CheckedBatch:
            got = {s.id for s in self.scenes}
            missing = [i for i in tasks if i not in got]
            if missing:
                raise ValueError(f"no scene for id(s) {', '.join(missing)}; write one entry per id")
            for s in self.scenes:
                if s.id not in tasks:
                    continue
                parsed = parse_instruction(s.instruction)
                if parsed is None or parsed["type"] != tasks[s.id]:
                    raise ValueError(
                        f"scene {s.id}: instruction {s.instruction!r} is not a {tasks[s.id]} instruction "
                        "in the standard short form"
                    )
            return self

    return CheckedBatch


def batch_inputs(
    batch: Batch, study: StudyConfig, catalog: Catalog, catalog_path: str | None = None
) -> dict[str, Any]:
    """Template inputs for one batch: only its own items' fixed attributes (stable cache keys)."""
    sets = sorted({it.object_set for it in batch.items})
    inputs: dict[str, Any] = {
        "items": [
            {
                "id": it.scene_id,
                "task": it.task,
                "num_objects": it.num_objects,
                "total_objects": it.total_objects,
                "object_set": it.object_set,
                "environment": it.environment,
            }
            for it in batch.items
        ],
        "bounds": study.bounds.model_dump(mode="json"),
        "objects": object_listing(catalog, sets),
    }
    if catalog_path:
        inputs["catalog_path"] = catalog_path
    return inputs


@dataclass
class GenerationResult:
    rows: list[SceneDesignRow]
    calls: int = 0
    cached: int = 0
    failed_batches: list[str] = field(default_factory=list)


def _rows(
    batch: Batch,
    study: StudyConfig,
    robot: Robot,
    result: JsonResult[Any] | None,
    reason: str | None,
) -> list[SceneDesignRow]:
    answers: dict[str, DescribedScene] = {}
    if result is not None and result.value is not None:
        answers = {s.id: s for s in result.value.scenes}
    call_ids = result.call_ids if result is not None else []
    rows = []
    for it in batch.scenes:
        ans = answers.get(it.scene_id)
        rows.append(
            SceneDesignRow(
                scene_id=it.scene_id,
                study=study.name,
                task=it.task,
                factor=it.factor,
                level=it.level,
                num_objects=it.num_objects,
                object_set=it.object_set,
                environment=it.environment,
                robot=robot,
                seed=it.seed,
                description=ans.description if ans else None,
                base_instruction=ans.instruction if ans else None,
                status="ok" if ans else "failed",
                reason=None if ans else (reason or "no answer for this scene"),
                llm_call_ids=call_ids,
            )
        )
    return rows


def generate_descriptions(
    study: StudyConfig,
    client: LLMClient,
    prompt: PromptTemplate,
    llm: LLMConfig,
    catalog: Catalog,
    *,
    robot: Robot = "panda",
    catalog_path: str | None = None,
    on_batch: Callable[[int], None] | None = None,
) -> GenerationResult:
    """Every scene of the study with its description and base instruction (batch-style)."""
    batches = plan_batches(study)

    def run(batch: Batch) -> tuple[list[SceneDesignRow], int, int, str | None]:
        request = build_request(
            JOB, prompt, batch_inputs(batch, study, catalog, catalog_path), llm,
            json_schema=DescribedBatch.model_json_schema(), seed=study.seed,
        )
        try:
            result = client.complete_json(request, batch_model(batch.items))
        except LLMCallError as exc:
            return _rows(batch, study, robot, None, str(exc)), 0, 0, str(exc)
        calls = sum(1 for r in result.responses if not r.cached)
        cached = len(result.responses) - calls
        return _rows(batch, study, robot, result, result.reason), calls, cached, result.reason

    out = GenerationResult(rows=[])
    with ThreadPoolExecutor(max_workers=llm.concurrency) as pool:
        for batch, (rows, calls, cached, reason) in zip(batches, pool.map(run, batches), strict=True):
            out.rows.extend(rows)
            out.calls += calls
            out.cached += cached
            if reason:
                out.failed_batches.append(f"{batch.items[0].scene_id}..: {reason}")
            if on_batch is not None:
                on_batch(batch.used)
    return out
