"""The offline backend's ``compile_scene`` job: a thin wrapper round the scene reader.

Inputs (the same the prompt in ``conf/prompts/default.yaml`` is rendered
from): ``description``, ``instruction`` (may be empty), ``task`` (may be
empty), ``objects`` (the catalog's list in the prompt), and ``reader``
(``compile.reader``): ``tagged`` reads through the learned span tagger
(:func:`ladev_lib.language.scene.tagged.read_tagged`), ``rules`` through the
rule reader alone (:func:`ladev_lib.language.scene.read_description`). The
answer is the JSON a model is asked for.
"""

from __future__ import annotations

import json

from ladev_lib.language.scene import RULE_MODULES as READER_MODULES
from ladev_lib.language.scene import Vocabulary, read_description
from ladev_lib.language.scene.tagged import read_tagged
from ladev_lib.llm.base import OFFLINE_JOBS, LLMRequest

RULE_MODULES = (*READER_MODULES, "ladev_lib.language.scene.tagged")
"""Modules whose source is part of the offline rules' fingerprint."""


@OFFLINE_JOBS.register("compile_scene")
def compile_scene(request: LLMRequest) -> str:
    inputs = request.inputs
    vocab = Vocabulary.from_objects(inputs.get("objects") or [])
    read = read_tagged if str(inputs.get("reader") or "rules") == "tagged" else read_description
    ops = read(
        str(inputs.get("description") or ""),
        vocab,
        instruction=str(inputs.get("instruction") or "") or None,
        task=str(inputs.get("task") or "") or None,
    )
    return json.dumps(ops, ensure_ascii=False)
