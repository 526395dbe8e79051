"""The configured paraphrase validator: embedding model, structure reader, precision.

    validator = make_validator(cfg, llm, client=client, parse_prompt=prompt, catalog=catalog)
"""

from __future__ import annotations

import os

from ladev_lib.catalog import Catalog
from ladev_lib.errors import ConfigError
from ladev_lib.language.config import ParaphraseConfig
from ladev_lib.language.embeddings import load_embedder
from ladev_lib.language.llm_jobs import LLMReader
from ladev_lib.language.validator import ParaphraseValidator, resolve_precision
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import PromptTemplate


def make_validator(
    cfg: ParaphraseConfig,
    llm: LLMConfig,
    *,
    client: LLMClient | None = None,
    parse_prompt: PromptTemplate | None = None,
    catalog: Catalog | None = None,
    threshold: float | None = None,
) -> ParaphraseValidator:
    """The configured validator: embedding model (loaded once per process) and structure reader."""
    embedder = load_embedder(cfg.embedding_model, cfg.device)
    embedder.batch_size = cfg.batch_size
    use_llm = cfg.reader == "llm" or (cfg.reader == "auto" and llm.backend != "offline")
    reader = None
    if use_llm:
        if client is None or parse_prompt is None:
            raise ConfigError("paraphrase.reader=llm needs an LLM client and prompts.parse_instruction")
        reader = LLMReader(client, parse_prompt, llm, catalog)
    return ParaphraseValidator(
        embedder,
        threshold=cfg.similarity_threshold if threshold is None else threshold,
        reader=reader,
        catalog=catalog,
        precision=resolve_precision(cfg.precision, cfg.device),
        second_reading=cfg.second_reading,
        threads=cfg.threads or os.cpu_count() or 1,
    )
