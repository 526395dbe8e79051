"""Lighting and camera values read from the words of a request (description frame in, spec frame out)."""

from __future__ import annotations

import pytest

from ladev_lib.language.scene.settings import read_camera_request, read_lighting_request
from ladev_lib.scenes.description_eval import camera_in_description_frame


def camera(text: str) -> tuple[list[float], dict[str, float]]:
    op = read_camera_request(text)
    assert op is not None, text
    return camera_in_description_frame(op["translation_m"], op["rotation_deg"])


@pytest.mark.parametrize(
    ("text", "translate", "rotate"),
    [
        ("camera shifted 3 cm to the left", [-3, 0, 0], {}),
        ("dolly in 25 mm", [0, 2.5, 0], {}),
        ("pull the camera back 4 cm and raise it 1 cm", [0, -4, 1], {}),
        ("come 2 centimetres closer to the table", [0, 2, 0], {}),
        ("tilt it down 2 degrees", [0, 0, 0], {"pitch": -2}),
        ("pan 4° to the right", [0, 0, 0], {"yaw": 4}),
        ("roll the view three degrees counter-clockwise", [0, 0, 0], {"roll": -3}),
        ("yaw: -2.5, z_cm: 1.5", [0, 0, 1.5], {"yaw": -2.5}),
        ("dx=0.5 droll=-3", [0.5, 0, 0], {"roll": -3}),
        ("-1 cm x, +2 cm z", [-1, 0, 2], {}),
        ("CAM pitch +4 z -1", [0, 0, -1], {"pitch": 4}),
        ("pan the camera 4 degrees left", [0, 0, 0], {"yaw": -4}),
        ("translate: {x: 0, y: 0, z: 1.5}", [0, 0, 1.5], {}),
        ("cam: pan L 3 deg", [0, 0, 0], {"yaw": -3}),
    ],
)
def test_camera_motions(text, translate, rotate):
    t, r = camera(text)
    assert t == pytest.approx(translate)
    assert {k: v for k, v in r.items() if abs(v) > 1e-9} == pytest.approx(rotate)


def test_camera_words_without_amounts_are_left_to_the_rule_reader():
    assert read_camera_request("move the camera a little higher") is None


@pytest.mark.parametrize(
    ("text", "delta"),
    [
        ("lighting 20% darker", -0.2),
        ("lights at 70% of normal", -0.3),
        ("150 percent of normal", 0.5),
        ("light = 0.9x", -0.1),
        ("scale 1.25", 0.25),
        ("brighter by a quarter", 0.25),
        ("dim it by a third", -0.3333),
        ("halve the brightness", -0.5),
        ("twice as bright", 1.0),
        ("brightness -10%", -0.1),
        ("LIGHT -0.2", -0.2),
        ("light more dark, 10 percent", -0.1),
        ("crank the lights up 50%", 0.5),
        ("darker for fifteen percent", -0.15),
    ],
)
def test_lighting_changes(text, delta):
    op = read_lighting_request(text)
    assert op is not None, text
    assert op["intensity_delta"] == pytest.approx(delta, abs=1e-4)


def test_lighting_words_without_amounts_are_left_to_the_rule_reader():
    assert read_lighting_request("slightly darker") is None


@pytest.mark.parametrize(
    ("text", "translate", "rotate"),
    [
        ("lower the camera by a centimeter", [0, 0, -1], {}),
        ("the camera backs off 4 cm", [0, -4, 0], {}),
        ("move it 25 mm toward the table and 10 mm up", [0, 2.5, 1], {}),
        ("roll -3 degrees (counter-clockwise)", [0, 0, 0], {"roll": -3}),
        ("yaw -2", [0, 0, 0], {"yaw": -2}),
    ],
)
def test_more_camera_wordings(text, translate, rotate):
    t, r = camera(text)
    assert t == pytest.approx(translate)
    assert {k: v for k, v in r.items() if abs(v) > 1e-9} == pytest.approx(rotate)


def test_vectors_keys_and_levels():
    t, _ = camera("translate_cm = 1, -3, 0")
    assert t == pytest.approx([1, -3, 0])
    _, r = camera("yaw;-4;pitch;2")
    assert r["yaw"] == pytest.approx(-4) and r["pitch"] == pytest.approx(2)
    op = read_lighting_request("dim it to a quarter of normal brightness")
    assert op is not None and op["intensity_delta"] == pytest.approx(-0.75)
