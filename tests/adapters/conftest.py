"""Fixtures for the VLA adapter tests: rendered observations (committed PNGs).

The PNGs are frames of each robot's SimplerEnv policy camera rendered by
ManiSkill3 (``fixtures/render_observations.py``), so adapter environments
without a simulator still test on a real rendered LADEV-style frame.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from ladev_lib.policies.base import Observation

FIXTURES = Path(__file__).resolve().parent / "fixtures"
FRAMES = {
    "google_robot": FIXTURES / "google_robot_overhead_640x512.png",
    "widowx": FIXTURES / "widowx_3rd_view_640x480.png",
}


def load_frame(robot: str) -> np.ndarray:
    return np.asarray(Image.open(FRAMES[robot]).convert("RGB"), dtype=np.uint8)


@pytest.fixture(params=["google_robot", "widowx"])
def robot(request: pytest.FixtureRequest) -> str:
    return str(request.param)


@pytest.fixture
def observation(robot: str) -> Observation:
    return Observation(image=load_frame(robot))
