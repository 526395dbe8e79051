"""The offline backend: honest name, deterministic answers, a rules fingerprint in the cache key."""

from __future__ import annotations

import inspect
import json

import pytest

from ladev_lib.errors import UnknownNameError
from ladev_lib.llm import OFFLINE_JOBS, ChatMessage, LLMRequest
from ladev_lib.llm import offline as offline_module
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig, make_backend
from ladev_lib.llm.offline import OfflineBackend, rules_fingerprint
from ladev_lib.scenes.operations import SceneOperations
from ladev_lib.store import ContentStore


class Counting:
    """Wraps a backend and counts the calls that reach it."""

    def __init__(self, inner):
        self.inner, self.name, self.model, self.calls = inner, inner.name, inner.model, 0

    def settings(self):
        return self.inner.settings()

    def complete(self, request):
        self.calls += 1
        return self.inner.complete(request)


def compile_request(description: str, instruction: str = "pick up the apple") -> LLMRequest:
    objects = [{"id": "apple", "name": "apple", "synonyms": [], "category": "fruit"},
               {"id": "plate", "name": "plate", "synonyms": ["dish"], "category": "plate"}]
    return LLMRequest(
        job="compile_scene",
        messages=(ChatMessage("user", f"{description} | {instruction}"),),
        inputs={"description": description, "instruction": instruction, "task": "", "objects": objects},
    )


def test_the_backend_says_it_is_rules_and_is_built_from_config():
    backend = make_backend(LLMConfig())
    assert isinstance(backend, OfflineBackend) and backend.name == "offline"
    assert "offline-rules" in backend.model
    assert "offline-rules" in OfflineBackend(model="gpt-4o").model  # never passes for a model
    settings = backend.settings()
    assert settings["rules_fingerprint"] == rules_fingerprint() and len(settings["rules_fingerprint"]) == 16
    assert {"describe_scenes", "compile_scene"} <= set(OFFLINE_JOBS.names())


def test_answers_are_deterministic_valid_operations():
    backend = OfflineBackend()
    a = backend.complete(compile_request("an apple on the left and a plate, lighting slightly darker"))
    b = backend.complete(compile_request("an apple on the left and a plate, lighting slightly darker"))
    assert a.text == b.text
    ops = SceneOperations.model_validate_json(a.text)
    assert [o.object for o in ops.objects] == ["apple", "plate"]
    assert ops.objects[0].position.region == "left" and ops.lighting[0].intensity_delta < 0


def test_unknown_job_lists_the_known_ones():
    with pytest.raises(UnknownNameError, match="compile_scene"):
        OfflineBackend().complete(LLMRequest(job="write_poem", messages=()))


def test_a_cache_hit_makes_zero_calls(tmp_path):
    counting = Counting(OfflineBackend())
    client = LLMClient(counting, cache=ContentStore(tmp_path))
    for _ in range(3):
        assert client.complete_json(compile_request("two objects"), SceneOperations).ok
    assert counting.calls == 1 and client.calls == 1 and client.cache_hits == 2
    fresh = Counting(OfflineBackend())
    assert LLMClient(fresh, cache=ContentStore(tmp_path)).complete(compile_request("two objects")).cached
    assert fresh.calls == 0


def test_changing_the_rules_changes_the_fingerprint_and_misses_the_cache(tmp_path, monkeypatch):
    client = LLMClient(OfflineBackend(), cache=ContentStore(tmp_path))
    key_before = client.call_key(compile_request("two objects"))
    before = rules_fingerprint()
    real_getsource = inspect.getsource

    def edited(module):
        text = real_getsource(module)
        return text + "\n# a changed rule\n" if module.__name__ == "ladev_lib.language.scene.environment" else text

    rules_fingerprint.cache_clear()
    monkeypatch.setattr(offline_module.inspect, "getsource", edited)
    try:
        after = rules_fingerprint()
        key_after = client.call_key(compile_request("two objects"))
    finally:
        rules_fingerprint.cache_clear()
    assert after != before and key_after != key_before


def test_describe_scenes_answers_every_item(catalog):
    items = [{"id": f"s{i}", "task": t, "num_objects": 2, "total_objects": 3, "object_set": "simpler",
              "environment": "default"} for i, t in enumerate(["move_near", "put_on", "put_in"])]
    request = LLMRequest(job="describe_scenes", messages=(ChatMessage("user", "3 scenes"),),
                         inputs={"items": items, "bounds": {}}, seed=0)
    answer = json.loads(OfflineBackend().complete(request).text)
    assert [s["id"] for s in answer["scenes"]] == ["s0", "s1", "s2"]
    assert [s["instruction"].split()[0] for s in answer["scenes"]] == ["move", "put", "put"]
    assert all(s["description"] for s in answer["scenes"])
