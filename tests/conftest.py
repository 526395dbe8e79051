"""Shared fixtures and the rules for optional test layers.

- ``sim``: builds ManiSkill scenes; runs by default (CI renders with lavapipe).
- ``assets``: needs MS_ASSET_DIR; skipped when it is absent.
- ``manual``: real checkpoints, API keys or a GPU; skipped unless LADEV_MANUAL=1.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[1]

os.environ.setdefault("HF_HUB_OFFLINE", "1")
os.environ.setdefault("TOKENIZERS_PARALLELISM", "false")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    from ladev_lib.assets import asset_dir

    have_assets = asset_dir() is not None
    manual = os.environ.get("LADEV_MANUAL") == "1"
    for item in items:
        if "assets" in item.keywords and not have_assets:
            item.add_marker(pytest.mark.skip(reason="MS_ASSET_DIR not set or missing"))
        if "manual" in item.keywords and not manual:
            item.add_marker(pytest.mark.skip(reason="manual test; set LADEV_MANUAL=1"))


@pytest.fixture(scope="session")
def catalog():
    from ladev_lib.catalog import load_catalog

    return load_catalog()


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return REPO_ROOT
