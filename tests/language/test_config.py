"""The paraphrase: config section and the validator it builds."""

from __future__ import annotations

import pytest

from ladev_lib.config import compose_config, section
from ladev_lib.errors import ConfigError
from ladev_lib.language.config import ParaphraseConfig
from ladev_lib.language.factory import make_validator
from ladev_lib.language.llm_jobs import LLMReader
from ladev_lib.language.validator import OfflineReader
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.llm.prompts import load_prompts
from tests.language.test_llm_jobs import ScriptedBackend


def test_default_config_composes_and_validates(repo_root):
    cfg = section(compose_config([], repo_root / "conf"), "paraphrase", ParaphraseConfig)
    assert cfg.embedding_model == "all-MiniLM-L6-v2" and 0 < cfg.similarity_threshold < 1


def test_bad_values_name_the_key(repo_root):
    cfg = compose_config(["paraphrase.similarity_threshold=1.5"], repo_root / "conf")
    with pytest.raises(ConfigError, match="paraphrase.similarity_threshold"):
        section(cfg, "paraphrase", ParaphraseConfig)
    cfg = compose_config(["+paraphrase.treshold=0.5"], repo_root / "conf")
    with pytest.raises(ConfigError, match="paraphrase.treshold"):
        section(cfg, "paraphrase", ParaphraseConfig)


def test_reader_follows_the_backend(repo_root, minilm):
    prompts = load_prompts(compose_config([], repo_root / "conf"), ["parse_instruction"])
    client = LLMClient(ScriptedBackend([]))
    auto = ParaphraseConfig()
    offline = make_validator(auto, LLMConfig(backend="offline"), client=client,
                             parse_prompt=prompts["parse_instruction"])
    assert isinstance(offline.reader, OfflineReader)
    remote = make_validator(auto, LLMConfig(backend="openai", model="gpt-4o"), client=client,
                            parse_prompt=prompts["parse_instruction"])
    assert isinstance(remote.reader, LLMReader)
    forced = make_validator(ParaphraseConfig(reader="offline"), LLMConfig(backend="openai"), client=client,
                            parse_prompt=prompts["parse_instruction"])
    assert isinstance(forced.reader, OfflineReader)
    with pytest.raises(ConfigError, match="needs an LLM client"):
        make_validator(ParaphraseConfig(reader="llm"), LLMConfig())
