"""The language jobs through the LLM layer: offline handlers, caching, the LLM reader."""

from __future__ import annotations

import json

import pytest

import ladev_lib.language.offline_jobs  # noqa: F401
from ladev_lib.config import compose_config
from ladev_lib.language.llm_jobs import (
    LLMReader,
    ParaphraseAnswer,
    paraphrase_request,
    parse_request,
    resolve_name,
)
from ladev_lib.language.parser import parse_instruction
from ladev_lib.llm.base import LLMRequest, LLMResponse
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.offline import rules_fingerprint
from ladev_lib.llm.prompts import load_prompts


@pytest.fixture(scope="module")
def prompts(repo_root):
    return load_prompts(compose_config([], repo_root / "conf"), ["paraphrase", "parse_instruction"])


class ScriptedBackend:
    """Answers every request with the next scripted text (a stand-in for a real model)."""

    name = "scripted"
    model = "scripted-1"

    def __init__(self, answers: list[str]) -> None:
        self.answers = list(answers)
        self.requests: list[LLMRequest] = []

    def settings(self) -> dict:
        return {}

    def complete(self, request: LLMRequest) -> LLMResponse:
        self.requests.append(request)
        return LLMResponse(self.answers.pop(0), self.name, self.model)


def test_offline_paraphrase_job_through_a_cached_client(prompts, tmp_path):
    llm = LLMConfig()
    client = make_client(llm, tmp_path / "cache")
    request = paraphrase_request(prompts["paraphrase"], llm, "put the carrot on the plate", 10)
    assert "put the carrot on the plate" in request.messages[-1].content  # inputs are in the messages
    first = client.complete_json(request, ParaphraseAnswer)
    assert first.ok and len(first.value.paraphrases) == 10
    again = client.complete_json(request, ParaphraseAnswer)
    assert again.value == first.value
    assert client.calls == 1 and client.cache_hits == 1


def test_offline_fingerprint_covers_the_language_rules():
    import ladev_lib.language.llm_jobs as jobs

    assert "ladev_lib.language.parser" in jobs.RULE_MODULES
    assert rules_fingerprint()  # computes over the registered language handlers without error


def test_offline_paraphrase_job_reports_an_instruction_it_cannot_read(prompts):
    llm = LLMConfig()
    client = make_client(llm, None)
    result = client.complete_json(paraphrase_request(prompts["paraphrase"], llm, "open the drawer", 5), ParaphraseAnswer)
    assert result.ok and result.value.paraphrases == []
    assert "cannot read" in result.value.problem


def test_llm_reader_on_the_offline_backend_agrees_with_the_parser(prompts, catalog):
    llm = LLMConfig()
    reader = LLMReader(make_client(llm, None), prompts["parse_instruction"], llm, catalog)
    texts = ["toss the aubergine into the bin", "move the sponge next to the apple",
             "pick up the coke can and then put it down", "grab the can"]
    scenes = [None, None, None, frozenset({"coke_can", "apple"})]
    for text, scene, got in zip(texts, scenes, reader.read(texts, scenes), strict=True):
        want = parse_instruction(text, scene)
        assert got.roles == (want.roles if want.ok else (None, None, None)), text
        assert got.ok == want.ok
    assert reader.call_ids


def test_llm_reader_resolves_names_a_model_writes_and_reports_bad_answers(prompts, catalog):
    llm = LLMConfig(backend="offline")
    answers = [
        json.dumps({"task": "put_in", "source": "the Aubergine", "target": "yellow basket", "problem": None}),
        json.dumps({"task": "pick_up", "source": "unicorn", "target": None, "problem": None}),
        json.dumps({"task": None, "source": None, "target": None, "problem": "negated"}),
        "no json here", "still none", "nothing",
    ]
    backend = ScriptedBackend(answers)
    reader = LLMReader(LLMClient(backend, repair_attempts=2), prompts["parse_instruction"], llm, catalog)
    ok, unknown, negated, garbage = reader.read(["a", "b", "c", "d"], [None] * 4)
    assert ok.roles == ("put_in", "eggplant", "basket") and ok.ok
    assert not unknown.ok and "unicorn" in unknown.reason
    assert not negated.ok and "negated" in negated.reason
    assert not garbage.ok and "no usable reading" in garbage.reason
    assert backend.requests[0].json_schema is not None


def test_parse_request_lists_scene_objects(prompts):
    request = parse_request(prompts["parse_instruction"], LLMConfig(), "grab the can", ["coke can", "apple"])
    assert "coke can, apple" in request.messages[-1].content
    assert request.inputs["objects"] == ["coke can", "apple"]


def test_resolve_name(catalog):
    assert resolve_name("the can of coke", catalog).object_id == "coke_can"
    assert resolve_name("Coca-Cola can", catalog).object_id == "coke_can"
    assert resolve_name("can", catalog).object_id is None
    assert resolve_name("can", catalog, frozenset({"pepsi_can", "apple"})).object_id == "pepsi_can"
