"""Batch-style generation with the offline backend; stable caching as the study grows."""

from __future__ import annotations

from collections import Counter

import pytest

from ladev_lib.language.scene import Vocabulary, read_description
from ladev_lib.llm import LLMResponse
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.scenes.compiler import DesignExpectation, compile_operations
from ladev_lib.scenes.operations import SceneOperations
from ladev_lib.scenes.resolve import ObjectResolver
from ladev_lib.scenes.text_to_scene import object_listing
from ladev_lib.scenes.writer import STYLES, write_scene
from ladev_lib.study.design import design_scenes
from ladev_lib.study.generation import generate_descriptions


@pytest.fixture(scope="module")
def prompt(params):
    return load_prompts(params, ["describe_scenes"])["describe_scenes"]


def run(study, prompt, catalog, cache_dir):
    llm = LLMConfig()
    client = make_client(llm, cache_dir)
    return generate_descriptions(study, client, prompt, llm, catalog, robot="panda")


def test_every_scene_gets_a_description_and_a_standard_instruction(study_config, prompt, catalog, tmp_path):
    study = study_config("smoke")
    result = run(study, prompt, catalog, tmp_path)
    assert [r.scene_id for r in result.rows] == [s.scene_id for s in design_scenes(study)]
    assert all(r.status == "ok" and r.description and r.base_instruction for r in result.rows)
    assert result.calls == 36 and result.cached == 0  # one call per (task, factor, level) batch
    for r in result.rows:
        verb = {"pick_up": "pick up the ", "move_near": "move the ", "put_on": "put the ", "put_in": "put the "}
        assert r.base_instruction.startswith(verb[r.task]) and len(r.llm_call_ids) == 1


def test_growing_the_study_makes_only_the_new_calls(study_config, prompt, catalog, tmp_path):
    first = run(study_config("smoke"), prompt, catalog, tmp_path)
    again = run(study_config("smoke"), prompt, catalog, tmp_path)
    assert (again.calls, again.cached) == (0, 36) and again.rows == first.rows
    # 1 -> 2 scenes per level: the batches were full already, so no new call.
    two = run(study_config("smoke", "study.factors.num_objects.scenes_per_level=2"), prompt, catalog, tmp_path)
    assert (two.calls, two.cached) == (0, 36) and len(two.rows) == 48
    # 2 -> 10 per level (batch size 8): one new batch per (task, level) of that factor: 4 x 3.
    ten = run(study_config("smoke", "study.factors.num_objects.scenes_per_level=10"), prompt, catalog, tmp_path)
    assert (ten.calls, ten.cached) == (12, 36)
    old = {r.scene_id: r for r in two.rows}
    assert all(old[r.scene_id] == r for r in ten.rows if r.scene_id in old)


def test_a_bad_answer_becomes_failed_rows_with_the_reason(study_config, prompt, catalog):
    class Broken:
        name, model = "broken", "b1"

        def settings(self):
            return {}

        def complete(self, request):
            return LLMResponse(text='{"scenes": []}', backend=self.name, model=self.model)

    study = study_config("smoke")
    result = generate_descriptions(study, LLMClient(Broken(), repair_attempts=1), prompt, LLMConfig(), catalog)
    assert len(result.rows) == 36 and all(r.status == "failed" for r in result.rows)
    assert "no scene for id(s)" in result.rows[0].reason and result.calls == 72  # asked twice per batch
    assert len(result.rows[0].llm_call_ids) == 2


def test_written_descriptions_vary_in_style_and_compile_back_to_their_design(catalog):
    vocab = Vocabulary.from_objects(object_listing(catalog))
    resolver = ObjectResolver(catalog, threshold=1.01)
    styles = Counter()
    for seed in range(200):
        task = ["pick_up", "move_near", "put_on", "put_in"][seed % 4]
        env = ["default", "lighting", "camera"][seed % 3]
        object_set = ["simpler", "ycb"][(seed // 3) % 2]
        n = 1 + seed % 5
        written = write_scene(task, n, object_set, env, seed, catalog)
        styles[written.style] += 1
        ops = SceneOperations.model_validate(read_description(written.description, vocab, written.instruction))
        out = compile_operations(ops, catalog, seed=seed, resolver=resolver, object_set=object_set,
                                 expected=DesignExpectation(task, n, object_set, env))
        assert out.ok, (written.description, out.reason)
    assert set(styles) == set(STYLES) and min(styles.values()) >= 20
