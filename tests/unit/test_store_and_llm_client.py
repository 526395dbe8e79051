from __future__ import annotations

import multiprocessing as mp

from pydantic import BaseModel

from ladev_lib.llm import ChatMessage, LLMRequest, LLMResponse
from ladev_lib.llm.client import LLMClient, extract_json
from ladev_lib.store import ContentStore, content_key


class ScriptedBackend:
    """Answers from a list, counting calls (a test double for a real server)."""

    name = "scripted"
    model = "m1"

    def __init__(self, answers: list[str]) -> None:
        self.answers = list(answers)
        self.received: list[LLMRequest] = []

    def settings(self) -> dict:
        return {}

    def complete(self, request: LLMRequest) -> LLMResponse:
        self.received.append(request)
        return LLMResponse(text=self.answers.pop(0), backend=self.name, model=self.model)


class Answer(BaseModel):
    count: int


def request(text: str = "how many?") -> LLMRequest:
    return LLMRequest(job="count", messages=(ChatMessage("user", text),))


def test_content_key_ignores_dict_order():
    assert content_key({"a": 1, "b": 2}) == content_key({"b": 2, "a": 1})
    assert content_key({"a": 1}) != content_key({"a": 2})


def test_store_round_trip_and_persistence(tmp_path):
    s = ContentStore(tmp_path)
    s.put("k", {"x": [1, 2]})
    assert s.get("k") == {"x": [1, 2]} and "k" in s and len(s) == 1
    assert ContentStore(tmp_path).get("k") == {"x": [1, 2]}
    assert s.get("missing") is None


def _writer(path: str, start: int) -> None:
    store = ContentStore(path)
    for i in range(start, start + 50):
        store.put(f"k{i}", i)


def test_store_accepts_writes_from_several_processes(tmp_path):
    procs = [mp.Process(target=_writer, args=(str(tmp_path), n * 50)) for n in range(3)]
    for p in procs:
        p.start()
    for p in procs:
        p.join()
    assert len(ContentStore(tmp_path)) == 150


def test_cache_hit_makes_no_call(tmp_path):
    backend = ScriptedBackend(['{"count": 3}'])
    client = LLMClient(backend, cache=ContentStore(tmp_path))
    first = client.complete(request())
    again = LLMClient(backend, cache=ContentStore(tmp_path)).complete(request())
    assert len(backend.received) == 1
    assert again.cached and not first.cached and again.call_id == first.call_id
    assert again.text == '{"count": 3}'


def test_invalid_json_is_repaired_with_the_error(tmp_path):
    backend = ScriptedBackend(["sure! {count: three}", '```json\n{"count": "x"}\n```', '{"count": 4}'])
    result = LLMClient(backend, cache=ContentStore(tmp_path)).complete_json(request(), Answer)
    assert result.ok and result.value == Answer(count=4)
    assert len(result.call_ids) == 3
    last_msgs = backend.received[-1].messages
    assert "count: Input should be a valid integer" in last_msgs[-1].content


def test_gives_up_with_a_reason(tmp_path):
    backend = ScriptedBackend(["nope"] * 3)
    result = LLMClient(backend, repair_attempts=2).complete_json(request(), Answer)
    assert not result.ok and "invalid answer after 3 attempts" in (result.reason or "")


def test_extract_json_from_prose():
    assert extract_json('Here you go: [{"a": 1}] hope it helps') == [{"a": 1}]
