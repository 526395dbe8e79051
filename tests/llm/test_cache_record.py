"""The LLM cache stores typed, versioned records; anything else is asked again."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from ladev_lib.llm.base import (
    LLM_CACHE_VERSION,
    ChatMessage,
    LLMCacheRecord,
    LLMRequest,
    LLMResponse,
)
from ladev_lib.llm.client import LLMClient
from ladev_lib.store import ContentStore


@dataclass
class Echo:
    """A backend that answers with the last message and counts its calls."""

    name: str = "echo"
    model: str = "echo-1"
    calls: list[str] = field(default_factory=list)

    def complete(self, request: LLMRequest) -> LLMResponse:
        self.calls.append(request.messages[-1].content)
        return LLMResponse(text=request.messages[-1].content.upper(), backend=self.name, model=self.model,
                           usage={"total_tokens": 3})

    def settings(self) -> dict[str, Any]:
        return {}


def _request(text: str) -> LLMRequest:
    return LLMRequest("paraphrase", (ChatMessage("user", text),))


def test_the_store_holds_a_versioned_record(tmp_path):
    backend = Echo()
    client = LLMClient(backend, cache=ContentStore(tmp_path))
    answer = client.complete(_request("pick up the cup"))
    raw = ContentStore(tmp_path).get(answer.call_id)
    record = LLMCacheRecord.model_validate(raw)
    assert record.schema_version == LLM_CACHE_VERSION == raw["schema_version"]
    assert (record.job, record.text, record.model, record.usage) == ("paraphrase", "PICK UP THE CUP", "echo-1",
                                                                     {"total_tokens": 3})
    again = LLMClient(backend, cache=ContentStore(tmp_path)).complete(_request("pick up the cup"))
    assert again.cached and again.text == "PICK UP THE CUP" and len(backend.calls) == 1


def test_an_untyped_or_foreign_entry_is_asked_again_and_rewritten(tmp_path):
    backend = Echo()
    client = LLMClient(backend, cache=ContentStore(tmp_path))
    key = client.call_key(_request("open the drawer"))
    store = ContentStore(tmp_path)
    # What an older LADEV wrote: a bare dict without a schema version.
    store.put(key, {"text": "stale", "backend": "echo", "model": "echo-1"})
    answer = client.complete(_request("open the drawer"))
    assert not answer.cached and answer.text == "OPEN THE DRAWER" and len(backend.calls) == 1
    assert store.get(key)["schema_version"] == LLM_CACHE_VERSION
    # A record from a future schema is not served either.
    store.put(key, {**store.get(key), "schema_version": LLM_CACHE_VERSION + 1})
    assert not client.complete(_request("open the drawer")).cached
    assert len(backend.calls) == 2
