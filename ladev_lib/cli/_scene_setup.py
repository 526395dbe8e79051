"""Shared set-up of ``ladev scene`` and ``ladev compile``: config -> the compiler the compile stage uses."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ladev_lib.config import compose_config
from ladev_lib.llm.config import LLMConfig
from ladev_lib.pipeline.compile import SceneCompilerSetup, scene_compiler
from ladev_lib.scenes.text_to_scene import SceneCompiler
from ladev_lib.vocabulary import Robot


@dataclass
class SceneTools:
    config: dict[str, Any]
    setup: SceneCompilerSetup

    @property
    def compiler(self) -> SceneCompiler:
        return self.setup.compiler

    @property
    def llm(self) -> LLMConfig:
        return self.setup.llm

    @property
    def robot(self) -> Robot:
        return self.setup.robot


def scene_tools(overrides: list[str], config_dir: str | None, cache: bool = True) -> SceneTools:
    """Compose ``conf/`` with overrides and build the compiler the stages use (LLM cache: ``llm_cache_dir/cli``)."""
    cfg = compose_config(overrides, config_dir)
    cache_dir = Path(cfg["paths"]["llm_cache_dir"]) / "cli" if cache else None
    return SceneTools(cfg, scene_compiler(cfg, cache_dir))
