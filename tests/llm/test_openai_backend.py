"""The ``openai`` backend against a local OpenAI-compatible HTTP server (see conftest)."""

from __future__ import annotations

from pathlib import Path

import pytest
from pydantic import BaseModel

from ladev_lib.errors import ConfigError, LLMCallError
from ladev_lib.llm import ChatMessage, LLMRequest
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig, make_backend
from ladev_lib.llm.openai_backend import OpenAIBackend
from ladev_lib.store import ContentStore
from tests.llm.conftest import FakeServer, Reply

KEY = "sk-test-DO-NOT-STORE-8f3a91"


class Count(BaseModel):
    count: int


def request(text: str = "How many objects? Answer in JSON.") -> LLMRequest:
    return LLMRequest(
        job="count_objects",
        messages=(ChatMessage("system", "Answer with JSON."), ChatMessage("user", text)),
        json_schema=Count.model_json_schema(),
        temperature=0.0,
        seed=7,
    )


@pytest.fixture
def config(openai_server: FakeServer, monkeypatch) -> LLMConfig:
    monkeypatch.setenv("LADEV_TEST_OPENAI_KEY", KEY)
    return LLMConfig(
        backend="openai", model="test-model", base_url=openai_server.url, api_key_env="LADEV_TEST_OPENAI_KEY",
        timeout_s=2.0, max_retries=2, backoff_s=0.01, backoff_max_s=0.05,
    )


def backend(config: LLMConfig, waits: list[float] | None = None) -> OpenAIBackend:
    return OpenAIBackend(config, sleep=(waits.append if waits is not None else lambda s: None))


def test_valid_json_answer_and_the_request_shape(openai_server, config, tmp_path):
    openai_server.script(Reply('{"count": 3}'))
    client = LLMClient(make_backend(config), cache=ContentStore(tmp_path))
    result = client.complete_json(request(), Count)
    assert result.ok and result.value == Count(count=3)
    assert len(openai_server.requests) == 1
    body = openai_server.requests[0]
    assert body["model"] == "test-model" and body["temperature"] == 0.0 and body["seed"] == 7
    assert [m["role"] for m in body["messages"]] == ["system", "user"]
    fmt = body["response_format"]
    assert fmt["type"] == "json_schema"
    assert fmt["json_schema"]["name"] == "count_objects" and fmt["json_schema"]["schema"] == Count.model_json_schema()
    assert openai_server.auth_headers == [f"Bearer {KEY}"]
    assert result.responses[0].usage["prompt_tokens"] == 11


def test_invalid_json_is_repaired_by_asking_again_with_the_error(openai_server, config):
    openai_server.script(Reply("Sure! The count is three."), Reply('```json\n{"count": 4}\n```'))
    result = LLMClient(make_backend(config)).complete_json(request(), Count)
    assert result.ok and result.value.count == 4 and len(result.call_ids) == 2
    second = openai_server.requests[1]["messages"]
    assert second[-2] == {"role": "assistant", "content": "Sure! The count is three."}
    assert "not valid" in second[-1]["content"] and "no JSON" in second[-1]["content"]


def test_repairs_are_bounded_and_the_reason_recorded(openai_server, config):
    openai_server.script(*[Reply('{"count": "many"}')] * 3)
    result = LLMClient(make_backend(config), repair_attempts=2).complete_json(request(), Count)
    assert not result.ok and "invalid answer after 3 attempts" in result.reason and "count" in result.reason
    assert len(openai_server.requests) == 3


def test_timeout_is_retried_then_reported(openai_server, config):
    cfg = config.model_copy(update={"timeout_s": 0.3, "max_retries": 1})
    openai_server.script(Reply('{"count": 1}', delay_s=1.0), Reply('{"count": 1}', delay_s=1.0))
    with pytest.raises(LLMCallError, match="after 2 attempt.*Timeout"):
        backend(cfg).complete(request())
    assert len(openai_server.requests) == 2


def test_timeout_then_success(openai_server, config):
    cfg = config.model_copy(update={"timeout_s": 0.3})
    openai_server.script(Reply('{"count": 1}', delay_s=1.0), Reply('{"count": 2}'))
    assert backend(cfg).complete(request()).text == '{"count": 2}'


def test_rate_limit_then_success_honours_retry_after(openai_server, config):
    waits: list[float] = []
    openai_server.script(Reply(status=429, error="slow down", headers={"Retry-After": "0.02"}), Reply('{"count": 5}'))
    response = backend(config, waits).complete(request())
    assert response.text == '{"count": 5}' and waits == [0.02] and len(openai_server.requests) == 2


def test_server_errors_back_off_exponentially_then_give_up(openai_server, config):
    waits: list[float] = []
    openai_server.script(*[Reply(status=503, error="overloaded")] * 3)
    with pytest.raises(LLMCallError, match="after 3 attempt"):
        backend(config, waits).complete(request())
    assert waits == [0.01, 0.02]


def test_auto_structured_output_falls_back_and_remembers(openai_server, config):
    openai_server.reject_formats = {"json_schema"}
    openai_server.script(Reply('{"count": 1}'), Reply('{"count": 2}'))
    b = backend(config)
    assert b.complete(request()).text == '{"count": 1}'
    assert b.complete(request("again")).text == '{"count": 2}'
    kinds = [(r.get("response_format") or {}).get("type") for r in openai_server.requests]
    assert kinds == ["json_schema", "json_object", "json_object"]


def test_plain_text_when_the_server_has_no_json_modes(openai_server, config):
    openai_server.reject_formats = {"json_schema", "json_object"}
    openai_server.script(Reply('{"count": 1}'))
    assert backend(config).complete(request()).text == '{"count": 1}'
    assert "response_format" not in openai_server.requests[-1]


def test_explicit_modes_are_sent_as_configured(openai_server, config):
    openai_server.script(Reply("{}"), Reply("{}"))
    backend(config.model_copy(update={"structured_output": "json_object"})).complete(request())
    backend(config.model_copy(update={"structured_output": "none"})).complete(request())
    assert openai_server.requests[0]["response_format"] == {"type": "json_object"}
    assert "response_format" not in openai_server.requests[1]
    openai_server.reject_formats = {"json_schema"}
    with pytest.raises(LLMCallError, match="rejected the request"):
        backend(config.model_copy(update={"structured_output": "json_schema"})).complete(request())


def test_authentication_failure_is_a_config_error(openai_server, config):
    openai_server.script(Reply(status=401, error="invalid api key"))
    with pytest.raises(ConfigError, match="LADEV_TEST_OPENAI_KEY"):
        backend(config).complete(request())


def test_a_missing_key_names_the_variable(monkeypatch):
    monkeypatch.delenv("LADEV_TEST_OPENAI_KEY", raising=False)
    with pytest.raises(ConfigError, match=r"\$LADEV_TEST_OPENAI_KEY"):
        OpenAIBackend(LLMConfig(backend="openai", model="m", api_key_env="LADEV_TEST_OPENAI_KEY"))
    # A local server needs none.
    OpenAIBackend(LLMConfig(backend="openai", model="m", base_url="http://127.0.0.1:9/v1",
                            api_key_env="LADEV_TEST_OPENAI_KEY"))


def test_cache_hit_makes_no_call_and_the_cache_never_holds_the_key(openai_server, config, tmp_path):
    openai_server.script(Reply('{"count": 3}'))
    first = LLMClient(make_backend(config), cache=ContentStore(tmp_path / "cache"))
    assert first.complete_json(request(), Count).value.count == 3
    again = LLMClient(make_backend(config), cache=ContentStore(tmp_path / "cache"))  # a new process, say
    result = again.complete_json(request(), Count)
    assert result.value.count == 3 and result.responses[0].cached
    assert again.calls == 0 and again.cache_hits == 1 and len(openai_server.requests) == 1
    # The key reached the server, but no file of the cache and no cache key holds it.
    assert openai_server.auth_headers == [f"Bearer {KEY}"]
    assert KEY not in str(again.backend.settings()) and KEY not in again.call_key(request())
    ContentStore(tmp_path / "cache").close()
    files = [p for p in Path(tmp_path / "cache").rglob("*") if p.is_file()]
    assert files
    for p in files:
        assert KEY.encode() not in p.read_bytes(), p


def test_a_key_written_in_the_config_stays_secret(openai_server, tmp_path):
    cfg = LLMConfig(backend="openai", model="m", base_url=openai_server.url, api_key=KEY)
    assert KEY not in repr(cfg) and KEY not in str(cfg.model_dump())
    openai_server.script(Reply('{"count": 1}'))
    client = LLMClient(make_backend(cfg), cache=ContentStore(tmp_path))
    client.complete(request())
    assert openai_server.auth_headers == [f"Bearer {KEY}"]
    for p in tmp_path.rglob("*"):
        if p.is_file():
            assert KEY.encode() not in p.read_bytes()
