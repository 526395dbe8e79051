"""The offline backend's ``compile_scene`` job: a thin wrapper round the scene reader.

Inputs (the same the prompt in ``conf/prompts/default.yaml`` is rendered
from): ``description``, ``instruction`` (may be empty), ``task`` (may be
empty), ``objects`` (the catalog's list in the prompt). The answer is the JSON
a model is asked for, read by :func:`ladev_lib.language.scene.read_description`.
"""

from __future__ import annotations

import json

from ladev_lib.language.scene import RULE_MODULES as READER_MODULES
from ladev_lib.language.scene import Vocabulary, read_description
from ladev_lib.llm.base import OFFLINE_JOBS, LLMRequest

RULE_MODULES = (*READER_MODULES,)
"""Modules whose source is part of the offline rules' fingerprint."""


@OFFLINE_JOBS.register("compile_scene")
def compile_scene(request: LLMRequest) -> str:
    inputs = request.inputs
    vocab = Vocabulary.from_objects(inputs.get("objects") or [])
    ops = read_description(
        str(inputs.get("description") or ""),
        vocab,
        instruction=str(inputs.get("instruction") or "") or None,
        task=str(inputs.get("task") or "") or None,
    )
    return json.dumps(ops, ensure_ascii=False)
