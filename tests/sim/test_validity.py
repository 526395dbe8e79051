"""The physical-validity check catches overlapping spawns, falling objects, unreachable
and invisible task objects, and lets a plain valid scene through."""

from __future__ import annotations

from typing import Any

import pytest

from ladev_lib.sim.validity import check_scene
from tests.sim.conftest import make_spec

pytestmark = pytest.mark.sim

PUT_ON = {"type": "put_on", "source": "green_cube", "target": "plate"}


def scene(cube_xy: tuple[float, float], plate_xy: tuple[float, float] = (0.05, -0.1), **extra: Any) -> Any:
    return make_spec(
        [
            {"name": "green_cube", "x": cube_xy[0], "y": cube_xy[1], "role": "source"},
            {"name": "plate", "x": plate_xy[0], "y": plate_xy[1], "role": "target"},
            {"name": "coke_can", "x": -0.08, "y": 0.1},
        ],
        PUT_ON,
        **extra,
    )


def test_valid_scene_passes(build: Any) -> None:
    v = check_scene(build(scene((0.05, 0.1))))
    assert v.valid, v.reasons
    assert v.checks == {
        "no_interpenetration": True,
        "at_rest": True,
        "reachable": True,
        "visible": True,
        "not_already_done": True,
    }
    assert v.details["visible_px"]["plate"] >= 20


def test_interpenetrating_spawn_is_caught(build: Any) -> None:
    v = check_scene(build(scene((-0.08, 0.11))))  # the cube inside the coke can
    assert not v.valid and not v.checks["no_interpenetration"]
    assert any("'coke_can' and 'green_cube' overlap" in r for r in v.reasons), v.reasons


def test_object_off_the_table_falls_and_is_caught(build: Any) -> None:
    u = build(scene((0.05, 0.1), plate_xy=(0.05, -1.4)))  # beyond the table's side edge
    v = check_scene(u)
    assert not v.checks["at_rest"]
    assert any("'plate' fell off the table" in r for r in v.reasons), v.reasons


def test_unreachable_target_is_caught(build: Any) -> None:
    v = check_scene(build(scene((0.05, 0.1), plate_xy=(0.45, -0.1))))
    assert not v.checks["reachable"] and v.checks["at_rest"]
    assert any(r.startswith("target 'plate' is") and "beyond its reach" in r for r in v.reasons), v.reasons


def test_object_outside_the_camera_view_is_caught(build: Any) -> None:
    v = check_scene(build(scene((0.05, 0.1), camera={"rotation_deg": [0.0, 0.0, 60.0]})))
    assert not v.checks["visible"]
    assert any("covers" in r and "policy camera" in r for r in v.reasons), v.reasons


def test_stacked_spawn_is_caught(build: Any) -> None:
    """Objects at the same x/y overlap at spawn (a spec cannot stack objects)."""
    v = check_scene(build(scene((0.05, -0.1))))  # the cube inside the plate
    assert not v.valid and not v.checks["no_interpenetration"], v.reasons
    # pushed out of the plate, the cube ends up resting on it: the task is already done
    assert not v.checks["not_already_done"]
    assert "the put_on task is already accomplished before the robot acts" in v.reasons
