"""Shared set-up for the language commands: config, client, validator."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import click

import ladev_lib.language.offline_jobs  # noqa: F401  (registers the offline language jobs)
from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.config import compose_config, section
from ladev_lib.errors import LadevError
from ladev_lib.language.config import ParaphraseConfig
from ladev_lib.language.factory import make_validator
from ladev_lib.language.validator import ParaphraseValidator
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import PromptTemplate, load_prompts


@dataclass
class LanguageSetup:
    llm: LLMConfig
    paraphrase: ParaphraseConfig
    prompts: dict[str, PromptTemplate]
    client: LLMClient
    validator: ParaphraseValidator
    catalog: Catalog


def language_setup(
    overrides: tuple[str, ...],
    config_dir: str | None,
    cache_dir: str | None,
    threshold: float | None,
    reader: str | None = None,
) -> LanguageSetup:
    try:
        cfg = compose_config(list(overrides), config_dir)
        p_cfg = section(cfg, "paraphrase", ParaphraseConfig)
        if reader is not None:
            p_cfg = p_cfg.model_copy(update={"reader": reader})
        llm = section(cfg, "llm", LLMConfig)
        prompts = load_prompts(cfg, ["paraphrase", "parse_instruction"])
        catalog = load_catalog(cfg.get("catalog"))
        client = make_client(llm, Path(cache_dir) if cache_dir else None)
        validator = make_validator(
            p_cfg,
            llm,
            client=client,
            parse_prompt=prompts["parse_instruction"],
            catalog=catalog,
            threshold=threshold,
        )
    except LadevError as exc:
        raise click.ClickException(str(exc)) from exc
    return LanguageSetup(llm, p_cfg, prompts, client, validator, catalog)


def scene_objects(text: str | None, catalog: Catalog) -> frozenset[str] | None:
    """Catalog ids from "coke_can,apple" (commas, semicolons or spaces); None when empty."""
    if not text or not text.strip():
        return None
    ids = [t for t in text.replace(";", ",").replace(" ", ",").split(",") if t]
    for object_id in ids:
        if object_id not in catalog:
            try:
                catalog.get(object_id)
            except KeyError as exc:
                raise click.BadParameter(str(exc.args[0])) from None
    return frozenset(ids)


def reading(task: str | None, source: str | None, target: str | None) -> str:
    if task is None:
        return "-"
    return f"{task}({source}{', ' + target if target else ''})"
