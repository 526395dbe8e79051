"""Fixtures for the simulator tests: one Panda env per test session, reused by reset.

Making an env and rendering its first frame costs seconds on software Vulkan, so the
tests share ``panda_env`` and rebuild scenes with ``reset(options={"spec": ...})``.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

os.environ.setdefault("LP_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")


def make_spec(objects: list[dict[str, Any]], task: dict[str, Any], **extra: Any) -> Any:
    """A SceneSpec from compact object dicts: name, id (defaults to name), x, y, role."""
    from ladev_lib.scenes.spec import SceneSpec

    objs = [{"id": o.get("id", o["name"]), **o} for o in objects]
    return SceneSpec.model_validate({"objects": objs, "task": task, **extra})


@pytest.fixture(scope="session")
def panda_env() -> Iterator[Any]:
    from ladev_lib.sim import SimConfig, make_env

    spec = make_spec(
        [{"name": "coke_can", "x": 0.0, "y": 0.0, "role": "source"}], {"type": "pick_up", "source": "coke_can"}
    )
    env = make_env(spec, SimConfig(image_size=(128, 128)))
    env.reset(seed=0)
    yield env
    env.close()


@pytest.fixture()
def build(panda_env: Any) -> Any:
    """``build(spec)`` -> the unwrapped env with that scene built and settled."""

    def _build(spec: Any, **options: Any) -> Any:
        panda_env.reset(seed=spec.seed, options={"spec": spec.model_dump(mode="json"), **options})
        return panda_env.unwrapped

    return _build


def settle(env: Any, seconds: float = 0.5) -> None:
    """Let physics run with the robot holding still (no new actions)."""
    for _ in range(max(1, round(seconds * env.unwrapped.control_freq))):
        env.step(None)


def image_difference(a: np.ndarray, b: np.ndarray) -> float:
    """Mean absolute pixel difference, 0..255."""
    return float(np.abs(a.astype(np.int16) - b.astype(np.int16)).mean())
