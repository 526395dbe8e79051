"""LLM backends by name, one interface, every call cached by content."""

from ladev_lib.llm.base import (
    BACKENDS,
    OFFLINE_JOBS,
    ChatMessage,
    LLMBackend,
    LLMRequest,
    LLMResponse,
)

__all__ = ["BACKENDS", "OFFLINE_JOBS", "ChatMessage", "LLMBackend", "LLMRequest", "LLMResponse"]
