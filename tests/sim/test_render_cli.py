"""``ladev render SPEC.json -o scene.png`` as a user runs it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from ladev_lib.cli import cli
from tests.sim.conftest import make_spec

pytestmark = pytest.mark.sim


def test_render_writes_policy_and_overview_side_by_side(tmp_path: Path) -> None:
    spec = make_spec(
        [
            {"name": "coke_can", "x": 0.05, "y": 0.1, "role": "source"},
            {"name": "plate", "x": -0.05, "y": -0.1, "role": "target"},
        ],
        {"type": "put_on", "source": "coke_can", "target": "plate"},
    )
    path = tmp_path / "spec.json"
    path.write_text(spec.to_json())
    out = tmp_path / "scene.png"
    result = CliRunner().invoke(cli, ["render", str(path), "-o", str(out), "--size", "160x120", "--check"])
    assert result.exit_code == 0, result.output
    assert "wrote" in result.output and "coke_can (" in result.output and "valid scene" in result.output
    img = np.asarray(Image.open(out))
    assert img.shape[0] == 384 and img.shape[1] > 512  # overview height; policy scaled beside it
    assert img[:, :100].std() > 10 and img[:, -100:].std() > 10  # both halves show a scene


def test_render_rejects_an_invalid_spec(tmp_path: Path) -> None:
    bad = json.loads(
        make_spec([{"name": "coke_can", "x": 0, "y": 0, "role": "source"}], {"type": "pick_up", "source": "coke_can"}).to_json()
    )
    bad["objects"][0]["id"] = "flux_capacitor"
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    result = CliRunner().invoke(cli, ["render", str(path)])
    assert result.exit_code != 0
    assert "unknown catalog object 'flux_capacitor'" in result.output
