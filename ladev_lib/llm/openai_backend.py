"""Any OpenAI-compatible chat endpoint through the official ``openai`` client.

GPT-4o (as in the paper), vLLM, Ollama, llama.cpp server: set ``model`` and
``base_url`` in ``conf/llm/openai.yaml``; the key comes from the environment
variable ``api_key_env`` names (local servers without keys need none).

- Structured output: with ``structured_output: auto`` a request that has a
  JSON schema asks for ``response_format: json_schema``; when the server
  refuses it (400/422), the backend falls back to ``json_object`` and then to
  plain text, and remembers the fallback. The client validates and repairs the
  answer in every case.
- Retries: 408/409/429, 5xx, timeouts and connection errors are retried
  ``max_retries`` times with exponential backoff (honouring ``Retry-After``);
  then :class:`LLMCallError`, which stages record as a failed row.
- Authentication or a wrong model name raise :class:`ConfigError` at once:
  every further call would fail the same way.
- The key is never part of ``settings()`` (the cache key) or the cache.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ladev_lib.errors import ConfigError, LLMCallError, MissingExtraError
from ladev_lib.llm.base import LLMRequest, LLMResponse

if TYPE_CHECKING:
    from ladev_lib.llm.config import LLMConfig

_MODES = ("json_schema", "json_object", "none")
_RETRY_STATUS = {408, 409, 429}

__all__ = ["LLMCallError", "OpenAIBackend"]


def _schema_name(job: str) -> str:
    return re.sub(r"[^a-zA-Z0-9_-]", "_", job)[:64] or "answer"


class OpenAIBackend:
    """Chat completions against an OpenAI-compatible server."""

    name = "openai"

    def __init__(
        self,
        config: LLMConfig,
        *,
        sleep: Callable[[float], None] = time.sleep,
    ) -> None:
        try:
            import openai
        except ImportError as exc:  # pragma: no cover - openai is a core dependency
            raise MissingExtraError("LLM backend 'openai'", "openai", exc) from exc
        self._openai = openai
        self.config = config
        self.model = config.model
        self._sleep = sleep
        key = config.resolved_api_key()
        if key is None:
            if config.base_url is None:
                raise ConfigError(
                    f"the openai backend needs an API key: set ${config.api_key_env} "
                    "(or point llm.base_url at a local server that needs none)"
                )
            key = "no-key"  # local servers (vLLM, Ollama, llama.cpp) ignore it
        self._client = openai.OpenAI(
            api_key=key, base_url=config.base_url, timeout=config.timeout_s, max_retries=0
        )
        # Where 'auto' starts: moves down the list when the server refuses a format.
        self._auto_level = 0

    def settings(self) -> dict[str, Any]:
        # Everything besides the request that changes the answer. No key, ever.
        return {
            "base_url": self.config.base_url,
            "structured_output": self.config.structured_output,
        }

    # -- one call --------------------------------------------------------------
    def complete(self, request: LLMRequest) -> LLMResponse:
        modes = self._modes(request)
        last: Exception | None = None
        for level, mode in modes:
            try:
                return self._call_with_retries(request, mode)
            except (self._openai.BadRequestError, self._openai.UnprocessableEntityError) as exc:
                last = exc
                if mode == "none" or self.config.structured_output != "auto":
                    raise LLMCallError(f"the server rejected the request: {_message(exc)}") from exc
                # The server refused this response_format: use the next one from now on.
                self._auto_level = max(self._auto_level, level + 1)
        raise LLMCallError(f"the server rejected every response format: {last}")

    def _modes(self, request: LLMRequest) -> list[tuple[int, str]]:
        if request.json_schema is None:
            return [(2, "none")]
        chosen = self.config.structured_output
        if chosen == "auto":
            return [(i, _MODES[i]) for i in range(self._auto_level, len(_MODES))]
        return [(_MODES.index(chosen), chosen)]

    def _arguments(self, request: LLMRequest, mode: str) -> dict[str, Any]:
        args: dict[str, Any] = {
            "model": self.model,
            "messages": [m.as_dict() for m in request.messages],
            "temperature": request.temperature,
        }
        if request.max_tokens is not None:
            args["max_tokens"] = request.max_tokens
        if request.seed is not None:
            args["seed"] = request.seed
        if mode == "json_schema" and request.json_schema is not None:
            args["response_format"] = {
                "type": "json_schema",
                "json_schema": {
                    "name": _schema_name(request.job),
                    "schema": dict(request.json_schema),
                    "strict": False,
                },
            }
        elif mode == "json_object":
            args["response_format"] = {"type": "json_object"}
        return args

    def _call_with_retries(self, request: LLMRequest, mode: str) -> LLMResponse:
        oa = self._openai
        delay = self.config.backoff_s
        args = self._arguments(request, mode)
        for attempt in range(self.config.max_retries + 1):
            wait: float | None = None
            try:
                completion = self._client.chat.completions.create(**args)
            except (oa.AuthenticationError, oa.PermissionDeniedError, oa.NotFoundError) as exc:
                raise ConfigError(
                    f"the LLM server refused the call ({_message(exc)}); check llm.model, "
                    f"llm.base_url and ${self.config.api_key_env}"
                ) from exc
            except (oa.APITimeoutError, oa.APIConnectionError) as exc:
                error: Exception = exc
            except oa.APIStatusError as exc:
                if exc.status_code not in _RETRY_STATUS and exc.status_code < 500:
                    raise
                error = exc
                wait = _retry_after(exc)
            else:
                return _response(completion, self.name, self.model, mode)
            if attempt == self.config.max_retries:
                raise LLMCallError(
                    f"LLM call failed after {attempt + 1} attempt(s): {type(error).__name__}: {_message(error)}"
                ) from error
            self._sleep(min(wait if wait is not None else delay, self.config.backoff_max_s))
            delay *= 2
        raise AssertionError("unreachable")  # pragma: no cover


def _response(completion: Any, backend: str, model: str, mode: str) -> LLMResponse:
    choice = completion.choices[0] if completion.choices else None
    text = (choice.message.content if choice is not None else None) or ""
    usage: dict[str, int] = {}
    if completion.usage is not None:
        usage = {
            "prompt_tokens": int(completion.usage.prompt_tokens or 0),
            "completion_tokens": int(completion.usage.completion_tokens or 0),
        }
    usage["structured_output_" + mode] = 1
    return LLMResponse(text=text, backend=backend, model=str(completion.model or model), usage=usage)


def _retry_after(exc: Any) -> float | None:
    response = getattr(exc, "response", None)
    value = response.headers.get("retry-after") if response is not None else None
    try:
        return float(value) if value is not None else None
    except ValueError:
        return None


def _message(exc: BaseException) -> str:
    text = str(getattr(exc, "message", "") or exc)
    return text if len(text) < 300 else text[:297] + "..."
