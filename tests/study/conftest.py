"""Fixtures for study design and generation tests."""

from __future__ import annotations

import pytest

from ladev_lib.config import compose_config, section
from ladev_lib.study.design import StudyConfig


@pytest.fixture(scope="session")
def study_config(repo_root):
    """Compose a study option from conf/study."""

    def load(name: str, *overrides: str) -> StudyConfig:
        cfg = compose_config([f"study={name}", *overrides], repo_root / "conf")
        return section(cfg, "study", StudyConfig)

    return load


from tests.llm.conftest import params  # noqa: E402, F401
