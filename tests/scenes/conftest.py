"""Fixtures for scene compilation tests."""

from __future__ import annotations

import pytest

from ladev_lib.scenes.resolve import ObjectResolver


@pytest.fixture(scope="session")
def exact_resolver(catalog) -> ObjectResolver:
    """Resolution without the embedding step (no model load)."""
    return ObjectResolver(catalog, threshold=1.01)


# The offline scene compiler and the composed config, shared with the LLM tests.
from tests.llm.conftest import offline_compiler, params  # noqa: E402, F401
