"""The offline backend's ``describe_scenes`` job: the study's scenes written as descriptions.

Inputs (the same the prompt in ``conf/prompts/default.yaml`` is rendered
from): ``items`` (id, task, num_objects, object_set, environment), ``bounds``;
optional ``catalog_path``. Each item's seed is derived from the request's seed
(the study seed) and the item id, the same seed the study design gives the
scene. The writing itself is :func:`ladev_lib.scenes.writer.write_scene`.
"""

from __future__ import annotations

import json
from typing import Any

from ladev_lib.catalog import load_catalog
from ladev_lib.llm.base import OFFLINE_JOBS, LLMRequest
from ladev_lib.scenes.spec import SceneBounds
from ladev_lib.scenes.writer import write_scene
from ladev_lib.seeding import derive_seed

RULE_MODULES = (
    "ladev_lib.scenes.writer",
    "ladev_lib.seeding",
    "ladev_lib.scenes.sampling",
    "ladev_lib.scenes.placement",
)
"""Modules whose source is part of the offline rules' fingerprint."""


@OFFLINE_JOBS.register("describe_scenes")
def describe_scenes(request: LLMRequest) -> str:
    inputs = request.inputs
    catalog = load_catalog(inputs.get("catalog_path"))
    bounds = SceneBounds.model_validate(inputs.get("bounds") or {})
    base = request.seed if request.seed is not None else 0
    scenes: list[dict[str, Any]] = []
    for item in inputs["items"]:
        written = write_scene(
            task=item["task"],
            num_objects=int(item["num_objects"]),
            object_set=item["object_set"],
            environment=item["environment"],
            seed=derive_seed(base, str(item["id"])),
            catalog=catalog,
            bounds=bounds,
        )
        scenes.append({"id": item["id"], "description": written.description, "instruction": written.instruction})
    return json.dumps({"scenes": scenes}, ensure_ascii=False)
