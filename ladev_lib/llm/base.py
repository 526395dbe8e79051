"""The LLM layer's interface: requests, responses, backends, offline jobs.

Every use of an LLM in LADEV is a *job* (write scene descriptions, compile a
description into operations, paraphrase an instruction, read an instruction
back into a task). A job's request carries both the rendered chat messages
(what a real model reads) and the template inputs they were rendered from
(what the deterministic offline backend reads). Backends are looked up by
name in :data:`BACKENDS`; the offline backend dispatches on the job name to a
handler in :data:`OFFLINE_JOBS`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol

from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.registry import Registry

Role = Literal["system", "user", "assistant"]


@dataclass(frozen=True)
class ChatMessage:
    role: Role
    content: str

    def as_dict(self) -> dict[str, str]:
        return {"role": self.role, "content": self.content}


@dataclass(frozen=True)
class LLMRequest:
    """One call: the job, the messages, and how to sample."""

    job: str
    messages: tuple[ChatMessage, ...]
    inputs: Mapping[str, Any] = field(default_factory=dict)
    """Template variables the messages were rendered from (the offline backend reads these)."""
    json_schema: Mapping[str, Any] | None = None
    """JSON Schema the answer must satisfy, for servers with structured output."""
    temperature: float = 0.0
    max_tokens: int | None = None
    seed: int | None = None

    def with_messages(self, messages: tuple[ChatMessage, ...]) -> LLMRequest:
        return LLMRequest(
            self.job, messages, self.inputs, self.json_schema, self.temperature, self.max_tokens, self.seed
        )


@dataclass(frozen=True)
class LLMResponse:
    """A backend's answer, with where it came from."""

    text: str
    backend: str
    model: str
    call_id: str = ""
    """Cache key of the call (set by the client)."""
    cached: bool = False
    latency_s: float = 0.0
    usage: Mapping[str, int] = field(default_factory=dict)


LLM_CACHE_VERSION: Literal[1] = 1


class LLMCacheRecord(BaseModel):
    """One cached answer, as stored under its call key (``LLMClient.call_key``).

    Versioned like every record LADEV persists (a ``schema_version`` field): a
    record of another version, or an untyped entry of an older LADEV, is not
    served; the call is made again and the record rewritten.
    """

    model_config = ConfigDict(frozen=True, extra="forbid")

    schema_version: Literal[1] = LLM_CACHE_VERSION
    job: str
    text: str
    backend: str
    model: str
    usage: dict[str, int] = Field(default_factory=dict)
    latency_s: float = Field(0.0, description="Seconds the original call took.")


class LLMBackend(Protocol):
    """Turns a request into text. Caching, parsing and repair live in the client."""

    name: str
    model: str

    def complete(self, request: LLMRequest) -> LLMResponse: ...

    def settings(self) -> dict[str, Any]:
        """Everything besides the request that changes the answer (part of the cache key).

        Never include secrets.
        """
        ...


BackendFactory = Callable[..., LLMBackend]
BACKENDS: Registry[BackendFactory] = Registry("LLM backend")
BACKENDS.add_lazy("offline", "ladev_lib.llm.offline:OfflineBackend")
BACKENDS.add_lazy("openai", "ladev_lib.llm.openai_backend:OpenAIBackend")

OfflineJob = Callable[[LLMRequest], str]
"""A deterministic handler: reads ``request.inputs`` and returns the answer text."""
OFFLINE_JOBS: Registry[OfflineJob] = Registry("offline LLM job")
