"""Prompt templates from conf/, their few-shot examples, and the llm config."""

from __future__ import annotations

import json

import pytest

from ladev_lib.config import compose_config, section
from ladev_lib.errors import ConfigError
from ladev_lib.language.scene import Vocabulary, read_description
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import PromptTemplate, build_request, load_prompts, render_messages
from ladev_lib.scenes.operations import SceneOperations, operations_json_schema
from ladev_lib.scenes.text_to_scene import object_listing
from ladev_lib.study.generation import DescribedBatch


def test_compile_prompt_lists_the_catalog_and_the_schema(params, catalog):
    prompt = load_prompts(params, ["compile_scene"])["compile_scene"]
    inputs = {"description": "two objects", "instruction": "pick up the apple", "task": "",
              "objects": object_listing(catalog), "schema": json.dumps(operations_json_schema())}
    request = build_request("compile_scene", prompt, inputs, section(params, "llm", LLMConfig))
    system, *examples, user = request.messages
    assert system.role == "system" and "coke can (coca-cola can" in system.content
    assert "rubik's cube" in system.content and '"add_object"' in system.content
    assert len(examples) == 2 * len(prompt.examples) >= 6
    assert user.content == "Description: two objects\nBasic instruction: pick up the apple"
    assert request.temperature == 0.0 and request.inputs["description"] == "two objects"


def _task_ids(task, catalog):
    from ladev_lib.scenes.resolve import ObjectResolver

    if task is None:
        return None
    resolver = ObjectResolver(catalog, threshold=1.01)

    def oid(name):
        if name is None:
            return None
        res = resolver.resolve(name)
        return res.obj.id if res.obj is not None else name

    return (task.type, oid(task.source), oid(task.target))


def test_compile_examples_are_valid_and_agree_with_the_offline_rules(params, catalog):
    prompt = load_prompts(params, ["compile_scene"])["compile_scene"]
    vocab = Vocabulary.from_objects(object_listing(catalog))
    for example in prompt.examples:
        expected = SceneOperations.model_validate_json(example.assistant)
        lines = example.user.strip().splitlines()
        description = "\n".join(lines[:-1]).removeprefix("Description: ")
        last = lines[-1]
        instruction = last.removeprefix("Basic instruction: ") if last.startswith("Basic instruction: ") else None
        ours = SceneOperations.model_validate(read_description(description, vocab, instruction))
        assert len(ours.objects) == len(expected.objects), description
        # the same task on the same catalog objects ("plastic bottle" and "blue plastic bottle" are one)
        assert _task_ids(ours.task, catalog) == _task_ids(expected.task, catalog), description
        assert bool(ours.error) == bool(expected.error)
        assert [round(op.intensity_delta, 2) for op in ours.lighting] == [op.intensity_delta for op in expected.lighting]
        assert [(op.translation_m, op.rotation_deg) for op in ours.camera] == [
            (op.translation_m, op.rotation_deg) for op in expected.camera
        ]


def test_describe_prompt_renders_each_item_and_its_example_is_valid(params, catalog):
    prompt = load_prompts(params, ["describe_scenes"])["describe_scenes"]
    items = [{"id": "a-1", "task": "put_in", "num_objects": 2, "total_objects": 3, "object_set": "ycb",
              "environment": "camera"}]
    messages = render_messages(prompt, {"items": items, "bounds": params["study"]["bounds"],
                                        "objects": object_listing(catalog, ["ycb"])}, "describe_scenes")
    assert "id: a-1; task: put_in; total_objects: 3; object_set: ycb; environment: camera" in messages[-1].content
    system = messages[0].content
    assert "at most 5.0 cm" in system and "- banana [ycb; graspable]" in system and "[simpler" not in system
    for example in prompt.examples:
        assert DescribedBatch.model_validate_json(example.assistant).scenes


def test_template_errors_and_missing_prompts_say_what_to_fix():
    with pytest.raises(ConfigError, match="prompts.describe_scenes"):
        load_prompts({"prompts": {"describe_scenes": {}}}, ["describe_scenes"])
    bad = PromptTemplate(user="{{ nothing_here }}")
    with pytest.raises(ConfigError, match="nothing_here"):
        render_messages(bad, {}, "x")


@pytest.mark.parametrize("option", ["offline", "openai"])
def test_every_llm_option_composes_and_validates(repo_root, option):
    cfg = section(compose_config([f"llm={option}"], repo_root / "conf"), "llm", LLMConfig)
    assert cfg.backend == option and cfg.repair_attempts >= 1


def test_llm_config_rejects_typos():
    with pytest.raises(ConfigError, match="llm.temprature"):
        section({"llm": {"temprature": 0.2}}, "llm", LLMConfig)
