"""Configuration: Hydra groups in ``conf/`` composed into one plain dict.

Two ways in, one result:

- Stage scripts read ``params.yaml``, the composed configuration DVC tracks
  (``dvc exp run -S ...`` recomposes it from ``conf/``).
- The ``ladev`` command line composes ``conf/`` directly with overrides
  (``ladev scene "..." llm=openai``).

Each section is validated by the pydantic model of the subpackage that owns
it (``StudyConfig``, ``LLMConfig``, ...) through :func:`section`, so a typo
or an out-of-range value fails fast with the key's path.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, TypeVar

import yaml
from pydantic import BaseModel, ValidationError

from ladev_lib.errors import ConfigError

M = TypeVar("M", bound=BaseModel)

PACKAGE_ROOT = Path(__file__).resolve().parent


def find_config_dir(explicit: str | Path | None = None) -> Path:
    """The ``conf/`` directory: explicit, $LADEV_CONFIG_DIR, ./conf, or the checkout's."""
    candidates = [
        Path(explicit) if explicit else None,
        Path(os.environ["LADEV_CONFIG_DIR"]) if os.environ.get("LADEV_CONFIG_DIR") else None,
        Path.cwd() / "conf",
        PACKAGE_ROOT.parent / "conf",
    ]
    for c in candidates:
        if c is not None and (c / "config.yaml").exists():
            return c.resolve()
    raise ConfigError(
        "no LADEV config directory found (looked for conf/config.yaml in --config-dir, "
        "$LADEV_CONFIG_DIR, the current directory and the LADEV checkout)"
    )


def compose_config(
    overrides: list[str] | None = None,
    config_dir: str | Path | None = None,
    config_name: str = "config",
) -> dict[str, Any]:
    """Compose ``conf/`` with Hydra overrides into a plain, resolved dict."""
    from hydra import compose, initialize_config_dir
    from hydra.errors import HydraException
    from omegaconf import OmegaConf

    directory = find_config_dir(config_dir)
    try:
        with initialize_config_dir(config_dir=str(directory), version_base="1.3"):
            cfg = compose(config_name=config_name, overrides=list(overrides or []))
    except HydraException as exc:
        raise ConfigError(f"cannot compose {directory}/{config_name}.yaml: {exc}") from exc
    data = OmegaConf.to_container(cfg, resolve=True)
    assert isinstance(data, dict)
    return {str(k): v for k, v in data.items()}


def load_params(path: str | Path = "params.yaml") -> dict[str, Any]:
    """Read the composed configuration DVC tracks."""
    p = Path(path)
    if not p.exists():
        raise ConfigError(f"{p} not found; run from the repository root or pass its path")
    with open(p, encoding="utf-8") as f:
        data = yaml.safe_load(f) or {}
    if not isinstance(data, dict):
        raise ConfigError(f"{p}: expected a mapping at the top level")
    return data


def section(cfg: dict[str, Any], key: str, model: type[M]) -> M:
    """Validate ``cfg[key]`` with ``model``; errors name the config path."""
    raw = cfg.get(key, {})
    try:
        return model.model_validate(raw if raw is not None else {})
    except ValidationError as exc:
        lines = []
        for err in exc.errors():
            loc = ".".join(str(p) for p in (key, *err["loc"]))
            lines.append(f"  {loc}: {err['msg']}")
        raise ConfigError(f"invalid configuration in '{key}':\n" + "\n".join(lines)) from exc
