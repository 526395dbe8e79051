"""The LLM client: content-addressed caching, JSON parsing, validation and repair.

    client = LLMClient(backend, cache=ContentStore("data/cache/llm/compile"))
    result = client.complete_json(request, Operations)   # a pydantic model
    result.value, result.call_ids, result.reason

The cache key is a hash of the backend name, model, backend settings, job,
messages, schema and sampling settings; a key never contains an API key. A
cached answer costs no call: ``client.calls`` counts the calls that reached
the backend.
"""

from __future__ import annotations

import json
import re
import time
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

from pydantic import BaseModel, TypeAdapter, ValidationError

from ladev_lib.llm.base import ChatMessage, LLMBackend, LLMCacheRecord, LLMRequest, LLMResponse
from ladev_lib.store import ContentStore, content_key

T = TypeVar("T")

_FENCE = re.compile(r"```(?:json)?\s*(.*?)```", re.DOTALL)


def extract_json(text: str) -> Any:
    """The first JSON value in ``text``: fenced, bare, or embedded in prose."""
    fenced = _FENCE.search(text)
    candidates = [fenced.group(1)] if fenced else []
    candidates.append(text)
    decoder = json.JSONDecoder()
    for cand in candidates:
        cand = cand.strip()
        for i, ch in enumerate(cand):
            if ch in "[{":
                try:
                    value, _ = decoder.raw_decode(cand[i:])
                    return value
                except json.JSONDecodeError:
                    continue
    raise ValueError("no JSON object or array found in the answer")


@dataclass
class JsonResult(Generic[T]):
    """A validated answer, or the reason there is none."""

    value: T | None
    responses: list[LLMResponse] = field(default_factory=list)
    reason: str | None = None

    @property
    def ok(self) -> bool:
        return self.value is not None

    @property
    def call_ids(self) -> list[str]:
        return [r.call_id for r in self.responses]


class LLMClient:
    """A backend behind a cache, with JSON answers validated and repaired."""

    def __init__(
        self,
        backend: LLMBackend,
        cache: ContentStore | None = None,
        repair_attempts: int = 2,
    ) -> None:
        self.backend = backend
        self.cache = cache
        self.repair_attempts = repair_attempts
        self.calls = 0
        self.cache_hits = 0

    def call_key(self, request: LLMRequest) -> str:
        return content_key(
            "llm-call/v1",
            self.backend.name,
            self.backend.model,
            self.backend.settings(),
            request.job,
            [m.as_dict() for m in request.messages],
            dict(request.json_schema) if request.json_schema else None,
            request.temperature,
            request.max_tokens,
            request.seed,
            length=32,
        )

    def _cached(self, key: str) -> LLMCacheRecord | None:
        """The cached record under ``key``; None when absent or of another schema version."""
        assert self.cache is not None
        raw = self.cache.get(key)
        if raw is None:
            return None
        try:
            return LLMCacheRecord.model_validate(raw)
        except ValidationError:
            return None  # an older or foreign entry: ask again and overwrite it

    def complete(self, request: LLMRequest) -> LLMResponse:
        key = self.call_key(request)
        if self.cache is not None:
            hit = self._cached(key)
            if hit is not None:
                self.cache_hits += 1
                return LLMResponse(
                    text=hit.text,
                    backend=hit.backend,
                    model=hit.model,
                    call_id=key,
                    cached=True,
                    latency_s=0.0,
                    usage=hit.usage,
                )
        start = time.perf_counter()
        response = self.backend.complete(request)
        self.calls += 1
        latency = time.perf_counter() - start
        if self.cache is not None:
            record = LLMCacheRecord(
                job=request.job,
                text=response.text,
                backend=response.backend,
                model=response.model,
                usage=dict(response.usage),
                latency_s=latency,
            )
            self.cache.put(key, record.model_dump(mode="json"))
        return LLMResponse(
            text=response.text,
            backend=response.backend,
            model=response.model,
            call_id=key,
            cached=False,
            latency_s=latency,
            usage=response.usage,
        )

    def complete_json(self, request: LLMRequest, schema: type[T] | TypeAdapter[T]) -> JsonResult[T]:
        """Ask, parse, validate; on failure re-ask with the error, at most ``repair_attempts`` times."""
        adapter: TypeAdapter[Any] = schema if isinstance(schema, TypeAdapter) else TypeAdapter(schema)
        messages = request.messages
        responses: list[LLMResponse] = []
        error = "no answer"
        for _ in range(1 + self.repair_attempts):
            response = self.complete(request.with_messages(messages))
            responses.append(response)
            try:
                value = adapter.validate_python(extract_json(response.text))
                return JsonResult(value, responses)
            except (ValueError, ValidationError) as exc:
                error = _short_error(exc)
            messages = (
                *messages,
                ChatMessage("assistant", response.text),
                ChatMessage(
                    "user",
                    f"That answer is not valid: {error}. Reply again with only the JSON, "
                    "fixing this problem.",
                ),
            )
        return JsonResult(None, responses, f"invalid answer after {len(responses)} attempts: {error}")


def _short_error(exc: Exception) -> str:
    if isinstance(exc, ValidationError):
        parts = []
        for err in exc.errors()[:5]:
            loc = ".".join(str(p) for p in err["loc"]) or "(root)"
            parts.append(f"{loc}: {err['msg']}")
        return "; ".join(parts)
    return str(exc)


def model_json_schema(model: type[BaseModel]) -> dict[str, Any]:
    return model.model_json_schema()
