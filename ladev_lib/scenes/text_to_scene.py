"""A scene description -> LLM operations -> a validated SceneSpec: the paper's single-scene flow.

    compiler = SceneCompiler(client, prompts["compile_scene"], llm_cfg, catalog)
    result = compiler.compile(SceneText("s1", "three objects, one a plastic bottle on the left",
                                        instruction="pick up the plastic bottle", seed=3))
    result.status, result.reason, result.spec, result.operations

The LLM (or the offline rules) reads the description with the catalog's list
of available objects and the operations schema in its prompt; its answer is
validated and repaired by the client; :func:`compile_operations` makes the
spec. Every failure, the LLM call's included, is a ``rejected`` result with a
reason.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

from ladev_lib.catalog import Catalog
from ladev_lib.errors import LLMCallError
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import PromptTemplate, build_request
from ladev_lib.scenes.compiler import CompileConfig, DesignExpectation, compile_operations
from ladev_lib.scenes.operations import SceneOperations, operations_json_schema
from ladev_lib.scenes.resolve import ObjectResolver
from ladev_lib.scenes.spec import SceneBounds, SceneSpec
from ladev_lib.tables import CompiledSceneRow, SceneDesignRow
from ladev_lib.vocabulary import Robot

JOB = "compile_scene"


@dataclass(frozen=True)
class SceneText:
    """One description to compile, with what is known about it."""

    scene_id: str
    description: str
    instruction: str | None = None
    task: str | None = None
    seed: int = 0
    object_set: str | None = None
    robot: Robot = "panda"
    expected: DesignExpectation | None = None


@dataclass
class CompiledScene:
    scene_id: str
    status: Literal["ok", "rejected"]
    reason: str | None = None
    operations: SceneOperations | None = None
    spec: SceneSpec | None = None
    notes: list[str] = field(default_factory=list)
    call_ids: list[str] = field(default_factory=list)
    calls: int = 0
    cached: int = 0
    instruction: str | None = None
    """The base instruction (given, or written from the spec's task)."""

    def row(self) -> CompiledSceneRow:
        return CompiledSceneRow(
            scene_id=self.scene_id,
            status=self.status,
            reason=self.reason,
            operations_json=self.operations.to_json() if self.operations is not None else None,
            spec_json=self.spec.to_json() if self.spec is not None else None,
            notes=self.notes,
            llm_call_ids=self.call_ids,
        )

    def as_dict(self) -> dict[str, Any]:
        """One line of ``ladev compile``'s output."""
        return {
            "id": self.scene_id,
            "status": self.status,
            "reason": self.reason,
            "instruction": self.instruction,
            "operations": json.loads(self.operations.to_json()) if self.operations is not None else None,
            "spec": json.loads(self.spec.to_json()) if self.spec is not None else None,
            "notes": self.notes,
            "llm_call_ids": self.call_ids,
        }


def object_listing(catalog: Catalog, sets: Sequence[str] | None = None) -> list[dict[str, Any]]:
    """The catalog (or some of its sets) as the prompts list it."""
    return [
        {
            "id": o.id,
            "name": o.display_name,
            "synonyms": list(o.synonyms),
            "category": o.category,
            "set": o.set,
            "graspable": o.graspable,
            "support": o.support,
            "container": o.container,
        }
        for o in catalog
        if sets is None or o.set in sets
    ]


class SceneCompiler:
    """Descriptions -> specs with one LLM call each (cached)."""

    def __init__(
        self,
        client: LLMClient,
        prompt: PromptTemplate,
        llm: LLMConfig,
        catalog: Catalog,
        bounds: SceneBounds | None = None,
        config: CompileConfig | None = None,
        resolver: ObjectResolver | None = None,
    ) -> None:
        self.client, self.prompt, self.llm, self.catalog = client, prompt, llm, catalog
        self.bounds = bounds or SceneBounds()
        self.config = config or CompileConfig()
        self.resolver = resolver or ObjectResolver(
            catalog, self.config.match_threshold, embedding_model=self.config.embedding_model
        )
        self._objects = object_listing(catalog)
        self._schema = operations_json_schema()
        self._schema_text = json.dumps(self._schema, separators=(",", ":"))

    def request(self, item: SceneText) -> Any:
        inputs = {
            "description": item.description,
            "instruction": item.instruction or "",
            "task": item.task or "",
            "objects": self._objects,
            "schema": self._schema_text,
        }
        if self.llm.backend == "offline":
            inputs["reader"] = self.config.reader  # which offline reader answers (a model reads for itself)
        # The answer depends on the text alone, not on the scene's seed: equal texts share a call.
        return build_request(JOB, self.prompt, inputs, self.llm, json_schema=self._schema, seed=self.llm.seed)

    def compile(self, item: SceneText) -> CompiledScene:
        try:
            result = self.client.complete_json(self.request(item), SceneOperations)
        except LLMCallError as exc:
            return CompiledScene(item.scene_id, "rejected", f"LLM call failed: {exc}")
        calls = sum(1 for r in result.responses if not r.cached)
        base = CompiledScene(
            item.scene_id, "rejected", call_ids=result.call_ids, calls=calls,
            cached=len(result.responses) - calls, instruction=item.instruction,
        )
        if result.value is None:
            base.reason = f"the LLM gave no valid operations: {result.reason}"
            return base
        ops = result.value
        base.operations = ops
        outcome = compile_operations(
            ops,
            self.catalog,
            seed=item.seed,
            bounds=self.bounds,
            config=self.config,
            resolver=self.resolver,
            object_set=item.object_set,
            default_task=item.task or "pick_up",
            robot=item.robot,
            scene_id=item.scene_id,
            expected=item.expected,
            approximate_coordinates=True,  # a description's coordinates are where a person roughly means
        )
        base.notes = outcome.notes
        if outcome.spec is None:
            base.reason = outcome.reason
            return base
        base.status = "ok"
        base.spec = outcome.spec
        if base.instruction is None:
            spec = outcome.spec
            target = spec.target
            base.instruction = basic_instruction(
                spec.task.type,
                self.catalog.get(spec.source.id).display_name,
                self.catalog.get(target.id).display_name if target is not None else None,
            )
        return base


def scene_text_of_row(row: SceneDesignRow) -> SceneText:
    """What the compile stage knows about a generated scene (its design is the expectation)."""
    return SceneText(
        scene_id=row.scene_id,
        description=row.description or "",
        instruction=row.base_instruction,
        task=row.task,
        seed=row.seed,
        object_set=row.object_set,
        robot=row.robot,
        expected=DesignExpectation(row.task, row.num_objects, row.object_set, row.environment),
    )
