"""The ``llm:`` configuration section, and a client built from it.

    cfg = section(params, "llm", LLMConfig)
    client = make_client(cfg, cache_dir="data/cache/llm/compile")

The API key is read from the environment variable ``api_key_env`` names (or,
discouraged, from ``api_key``); it never reaches the cache or ``settings()``.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, SecretStr

from ladev_lib.errors import ConfigError
from ladev_lib.llm.base import BACKENDS, LLMBackend
from ladev_lib.llm.client import LLMClient
from ladev_lib.store import ContentStore

StructuredOutput = Literal["auto", "json_schema", "json_object", "none"]


class LLMConfig(BaseModel):
    """Which backend answers, and how it is asked."""

    model_config = ConfigDict(extra="forbid")

    backend: str = Field(default="offline", description="Registered backend name: offline | openai.")
    model: str = Field(default="offline-rules-v1", description="Model name sent to the server.")
    temperature: float = Field(default=0.0, ge=0.0, le=2.0)
    seed: int | None = Field(default=0, description="Sampling seed, where the server supports one.")
    max_tokens: int | None = Field(default=None, ge=1)
    base_url: str | None = Field(default=None, description="OpenAI-compatible endpoint; null: api.openai.com.")
    api_key_env: str = Field(default="OPENAI_API_KEY", description="Environment variable holding the key.")
    api_key: SecretStr | None = Field(
        default=None, description="The key itself (prefer api_key_env; never written to the cache)."
    )
    timeout_s: float = Field(default=60.0, gt=0)
    max_retries: int = Field(default=4, ge=0, le=20, description="Retries on 429, 5xx, timeouts.")
    backoff_s: float = Field(default=1.0, ge=0, description="First retry delay; doubles each retry.")
    backoff_max_s: float = Field(default=30.0, ge=0)
    structured_output: StructuredOutput = Field(
        default="auto",
        description="auto: JSON schema, falling back to JSON mode, then plain text, when the server refuses.",
    )
    repair_attempts: int = Field(default=2, ge=0, le=10, description="Re-asks after an invalid answer.")
    concurrency: int = Field(default=1, ge=1, le=64, description="Calls in flight at once in a stage.")

    def resolved_api_key(self) -> str | None:
        """The key from the config or the environment (None when neither has one)."""
        if self.api_key is not None:
            return self.api_key.get_secret_value()
        return os.environ.get(self.api_key_env) or None


def make_backend(config: LLMConfig) -> LLMBackend:
    """The configured backend (an unknown name lists the known ones)."""
    factory = BACKENDS.get(config.backend)
    try:
        return factory(config=config)
    except TypeError as exc:
        raise ConfigError(f"LLM backend {config.backend!r} cannot be built from the llm config: {exc}") from exc


def make_client(config: LLMConfig, cache_dir: str | Path | None) -> LLMClient:
    """A cached client for the configured backend (no cache when ``cache_dir`` is None)."""
    cache = ContentStore(cache_dir) if cache_dir is not None else None
    return LLMClient(make_backend(config), cache=cache, repair_attempts=config.repair_attempts)
