"""Prompt templates from ``conf/prompts/*.yaml``, rendered into requests.

A template per job: a system message, few-shot examples (user/assistant
pairs) and a user message, each a Jinja2 template over the job's inputs.

    prompts = load_prompts(params)                      # job -> PromptTemplate
    request = build_request("compile_scene", prompts["compile_scene"], inputs, llm_cfg,
                            json_schema=operations_json_schema())

The request carries the rendered messages (what a model reads and what the
cache key hashes) and the inputs (what the offline backend reads). Every
input a handler uses must therefore appear in the rendered messages, so that
a changed input changes the key.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from typing import Any

import jinja2
from pydantic import BaseModel, ConfigDict, Field

from ladev_lib.errors import ConfigError
from ladev_lib.llm.base import ChatMessage, LLMRequest
from ladev_lib.llm.config import LLMConfig


class FewShotExample(BaseModel):
    model_config = ConfigDict(extra="forbid")

    user: str
    assistant: str


class PromptTemplate(BaseModel):
    """One job's prompt. ``temperature`` / ``max_tokens`` override the llm config for this job."""

    model_config = ConfigDict(extra="forbid")

    system: str = ""
    examples: list[FewShotExample] = Field(default_factory=list)
    user: str
    temperature: float | None = Field(default=None, ge=0.0, le=2.0)
    max_tokens: int | None = Field(default=None, ge=1)


@functools.lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        undefined=jinja2.StrictUndefined, keep_trailing_newline=False, trim_blocks=True, lstrip_blocks=True
    )
    env.filters["tojson_compact"] = _tojson_compact
    return env


def _tojson_compact(value: Any) -> str:
    import json

    return json.dumps(value, ensure_ascii=False, separators=(",", ":"))


def load_prompts(cfg: Mapping[str, Any], jobs: list[str] | None = None) -> dict[str, PromptTemplate]:
    """The ``prompts`` section as templates (only ``jobs`` if given; empty slots are skipped)."""
    section = cfg.get("prompts") or {}
    out: dict[str, PromptTemplate] = {}
    for job, raw in section.items():
        if jobs is not None and job not in jobs:
            continue
        if not raw:
            continue
        try:
            out[job] = PromptTemplate.model_validate(raw)
        except ValueError as exc:
            raise ConfigError(f"invalid prompt template prompts.{job}: {exc}") from exc
    for job in jobs or []:
        if job not in out:
            raise ConfigError(f"prompts.{job} is empty or missing; see conf/prompts/default.yaml")
    return out


@functools.lru_cache(maxsize=256)
def _compiled(template: str) -> jinja2.Template:
    return _environment().from_string(template)


def render(template: str, inputs: Mapping[str, Any], where: str = "prompt") -> str:
    try:
        return _compiled(template).render(**inputs).strip()
    except jinja2.TemplateError as exc:
        raise ConfigError(f"cannot render {where}: {exc}") from exc


def render_messages(prompt: PromptTemplate, inputs: Mapping[str, Any], job: str = "") -> tuple[ChatMessage, ...]:
    messages: list[ChatMessage] = []
    if prompt.system:
        messages.append(ChatMessage("system", render(prompt.system, inputs, f"prompts.{job}.system")))
    for i, ex in enumerate(prompt.examples):
        messages.append(ChatMessage("user", render(ex.user, inputs, f"prompts.{job}.examples[{i}].user")))
        messages.append(ChatMessage("assistant", ex.assistant.strip()))
    messages.append(ChatMessage("user", render(prompt.user, inputs, f"prompts.{job}.user")))
    return tuple(messages)


def build_request(
    job: str,
    prompt: PromptTemplate,
    inputs: Mapping[str, Any],
    llm: LLMConfig,
    *,
    json_schema: Mapping[str, Any] | None = None,
    seed: int | None = None,
) -> LLMRequest:
    """A request for ``job``: rendered messages, the inputs, and the sampling settings."""
    return LLMRequest(
        job=job,
        messages=render_messages(prompt, inputs, job),
        inputs=dict(inputs),
        json_schema=json_schema,
        temperature=prompt.temperature if prompt.temperature is not None else llm.temperature,
        max_tokens=prompt.max_tokens if prompt.max_tokens is not None else llm.max_tokens,
        seed=seed if seed is not None else llm.seed,
    )
