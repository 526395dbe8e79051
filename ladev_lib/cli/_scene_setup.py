"""Shared set-up of ``ladev scene`` and ``ladev compile``: config -> a SceneCompiler."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ladev_lib.catalog import load_catalog
from ladev_lib.config import compose_config, section
from ladev_lib.llm.config import LLMConfig, make_client
from ladev_lib.llm.prompts import load_prompts
from ladev_lib.scenes.compiler import CompileConfig
from ladev_lib.scenes.spec import SceneBounds
from ladev_lib.scenes.text_to_scene import SceneCompiler


@dataclass
class SceneTools:
    config: dict[str, Any]
    compiler: SceneCompiler
    llm: LLMConfig
    robot: str


def scene_tools(overrides: list[str], config_dir: str | None, cache: bool = True) -> SceneTools:
    """Compose ``conf/`` with overrides and build the compiler the stages use."""
    cfg = compose_config(overrides, config_dir)
    llm = section(cfg, "llm", LLMConfig)
    compile_cfg = section(cfg, "compile", CompileConfig)
    bounds = SceneBounds.model_validate((cfg.get("study") or {}).get("bounds") or {})
    prompt = load_prompts(cfg, ["compile_scene"])["compile_scene"]
    catalog = load_catalog(cfg.get("catalog"))
    cache_dir = Path(cfg["paths"]["llm_cache_dir"]) / "cli" if cache else None
    client = make_client(llm, cache_dir)
    compiler = SceneCompiler(client, prompt, llm, catalog, bounds, compile_cfg)
    robot = str((cfg.get("robot") or {}).get("name") or "panda")
    return SceneTools(cfg, compiler, llm, robot)
