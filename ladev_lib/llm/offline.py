"""The offline backend: deterministic rules, a grammar and templates. Not an LLM.

It answers the same jobs as a model (write scene descriptions, compile a
description into operations, paraphrase an instruction, ...) by dispatching
on ``request.job`` to a handler registered in :data:`OFFLINE_JOBS`; a handler
reads ``request.inputs`` and returns the answer text. No network, no keys,
the same answer for the same request.

Its ``settings()`` carry a fingerprint of the rules (a version plus a hash of
the code and data the handlers import, by ``ladev_lib.fingerprint``), so
changing a rule, the lexicon or the catalog invalidates the cached answers it
produced, and only those of the offline backend.
"""

from __future__ import annotations

import functools
import importlib
import inspect
from typing import TYPE_CHECKING, Any

from ladev_lib.fingerprint import fingerprint
from ladev_lib.llm.base import OFFLINE_JOBS, LLMRequest, LLMResponse

if TYPE_CHECKING:
    from ladev_lib.llm.config import LLMConfig

RULES_VERSION = "1"

HANDLER_MODULES: tuple[str, ...] = (
    "ladev_lib.scenes.offline_jobs",  # compile_scene (the scene reader)
    "ladev_lib.study.offline_jobs",  # describe_scenes (the scene writer)
    "ladev_lib.language.offline_jobs",  # paraphrase, parse_instruction (the language work)
)
"""Modules that register offline jobs when imported; they and everything they
import are fingerprinted. A listed module that is not part of this install is skipped (its jobs are then
unknown, and asking for one lists the known jobs)."""


def _import_handlers() -> list[str]:
    """Import the handler modules present; their names."""
    present = []
    for name in HANDLER_MODULES:
        try:
            importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name != name:
                raise  # the module is there but something it needs is not
            continue
        present.append(name)
    return present


@functools.lru_cache(maxsize=1)
def rules_fingerprint() -> str:
    """Hash of the code and data the offline rules depend on.

    The import closure of every handler module and job (``ladev_lib.fingerprint``, the
    mechanism episode ids use): the lexicon, the catalog and every module the rules
    import count, so editing any of them misses the cache.
    """
    names: set[str] = set(_import_handlers())
    for job in OFFLINE_JOBS.names():
        module = inspect.getmodule(OFFLINE_JOBS.get(job))
        if module is not None:
            names.add(module.__name__)
    return fingerprint(sorted(names), {"rules_version": RULES_VERSION})


class OfflineBackend:
    """Deterministic rules standing in for an LLM; the default backend."""

    name = "offline"

    def __init__(self, config: LLMConfig | None = None, model: str | None = None) -> None:
        chosen = model or (config.model if config is not None else None) or "offline-rules-v1"
        # The model name always says what this is.
        self.model = chosen if chosen.startswith("offline-rules") else f"offline-rules ({chosen})"
        _import_handlers()

    def settings(self) -> dict[str, Any]:
        return {"rules_version": RULES_VERSION, "rules_fingerprint": rules_fingerprint()}

    def complete(self, request: LLMRequest) -> LLMResponse:
        handler = OFFLINE_JOBS.get(request.job)
        text = handler(request)
        return LLMResponse(text=text, backend=self.name, model=self.model)
