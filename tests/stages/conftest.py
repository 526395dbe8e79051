"""A temporary copy of the repository to run stages (and dvc) in."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.repo_copy import copy_repo


@pytest.fixture
def repo_copy(repo_root: Path, tmp_path: Path) -> Path:
    """Tracked and untracked-but-not-ignored files of this checkout, in a fresh git repo."""
    return copy_repo(repo_root, tmp_path / "repo")
