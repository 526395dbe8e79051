"""Amounts, directions, axes, levels, fractions and factors as people write them in lighting and camera requests."""

from __future__ import annotations

import pytest

from ladev_lib.language.scene.settings import read_camera_request, read_lighting_request
from ladev_lib.scenes.description_eval import camera_in_description_frame


def delta(text: str) -> float:
    op = read_lighting_request(text)
    assert op is not None, text
    return float(op["intensity_delta"])


def camera(text: str) -> tuple[list[float], dict[str, float]]:
    op = read_camera_request(text)
    assert op is not None, text
    t, r = camera_in_description_frame(op["translation_m"], op["rotation_deg"])
    return t, {k: v for k, v in r.items() if abs(v) > 1e-9}


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # a level is a change of level - 1
        ("brightness at 95 percent", -0.05),
        ("illumination 130%", 0.3),
        ("lamp power: 70%", -0.3),
        ("set the lamps to 115 %", 0.15),
        ("lights ninety-five percent", -0.05),
        ("light level = 105%", 0.05),
        ("room light 60 percent from default", -0.4),
        ("lights 0.7 of what they are normally", -0.3),
        ("bring it to 0.9 of before", -0.1),
        ("drop it to four fifths", -0.2),
        ("three-fifths as bright", -0.4),
        ("one-half as bright", -0.5),
        ("dim to 3/4 of the usual level", -0.25),
        # factors
        ("brightness 0.9x", -0.1),
        ("illumination ×1.15", 0.15),
        ("light × ¾", -0.25),
        ("light: 1.1", 0.1),
        ("--brightness 0.95", -0.05),
        ("two point five times brighter", 1.5),
        ("one and a half times the light", 0.5),
        # fractions and worded amounts with a direction
        ("a sixth dimmer", -1 / 6),
        ("cut the light by a twentieth", -0.05),
        ("lights up three-tenths", 0.3),
        ("⅕ darker", -0.2),
        ("raise brightness by 1/10", 0.1),
        ("take away a quarter of the light", -0.25),
        ("knock 15% off the lamps", -0.15),
        ("lights: minus 20 percent", -0.2),
        ("intensity negative 0.05", -0.05),
        ("12% lesser light", -0.12),
        # symbols and keys
        ("lamp ↓ 25%", -0.25),
        ("lamp ↑ 5%", 0.05),
        ("brightness_delta: 0.15", 0.15),
        ("change = -0.1", -0.1),
        # a percentage with a comparative after "to" is still a change
        ("bring the lights to 10% brighter", 0.1),
    ],
)
def test_lighting_values(text, expected):
    assert delta(text) == pytest.approx(expected, abs=1e-3)


def test_a_number_wins_over_a_worded_halving():
    assert delta("dim it - halve that: 12 percent") == pytest.approx(-0.12)


def test_a_bare_small_percentage_without_direction_is_left_to_the_rule_reader():
    assert read_lighting_request("lights 30%") is None


@pytest.mark.parametrize(
    ("text", "translate", "rotate"),
    [
        # symbols, keys, flags and columns naming an axis
        ("camera ↓ 2 cm, ↑ 1°", [0, 0, -2], {"pitch": 1}),
        ("Δx = +15 mm", [1.5, 0, 0], {}),
        ("cam dx=+2 dz=-1", [2, 0, -1], {}),
        ("--cam-dz 0.5 --cam-pitch -3", [0, 0, 0.5], {"pitch": -3}),
        ("cam.y: -10mm", [0, -1, 0], {}),
        ("camera elevation +2 cm", [0, 0, 2], {}),
        ("camera height: -0.5 cm", [0, 0, -0.5], {}),
        ("+2 cm camera height", [0, 0, 2], {}),
        ("raise_cm = 1", [0, 0, 1], {}),
        ("cam_y_cm\t3", [0, 3, 0], {}),
        ("dx 1 dy -2 yaw +1", [1, -2, 0], {"yaw": 1}),
        ("x should be -1.5", [-1.5, 0, 0], {}),
        # translation tuples and value-first axes
        ("translate 1, 0, -1", [1, 0, -1], {}),
        ("translation = (5 mm, -5 mm, 0)", [0.5, -0.5, 0], {}),
        ("xyz 0, 2, 0 cm", [0, 2, 0], {}),
        ("+3 cm x, -1 cm y", [3, -1, 0], {}),
        ("shifted -0.5 cm along x", [-0.5, 0, 0], {}),
        ("pitch +3 x -1", [-1, 0, 0], {"pitch": 3}),
        # worded amounts
        ("pan right two and a half degrees", [0, 0, 0], {"yaw": 2.5}),
        ("lower the camera a centimetre and a half", [0, 0, -1.5], {}),
        ("tilt it down a half degree", [0, 0, 0], {"pitch": -0.5}),
        ("roll three quarters of a degree clockwise", [0, 0, 0], {"roll": 0.75}),
        ("one point five centimetres to the left", [-1.5, 0, 0], {}),
        ("yaw minus 1.5", [0, 0, 0], {"yaw": -1.5}),
        # several motions in one phrase
        ("camera 3 cm up, 1 degree to the right", [0, 0, 3], {"yaw": 1}),
        ("down 1 cm left 2 cm", [-2, 0, -1], {}),
        ("left 1 cm forward 2 cm up 3 cm", [-1, 2, 3], {}),
        ("tipped 2° up, swung 1° right and backed away 4 mm", [0, -0.4, 0], {"pitch": 2, "yaw": 1}),
        ("a 3-degree tilt upward", [0, 0, 0], {"pitch": 3}),
        ("rotate 2 degrees about the optical axis", [0, 0, 0], {"roll": 2}),
        ("4 degrees in counter clockwise", [0, 0, 0], {"roll": -4}),
        ("tilt dn 1.5", [0, 0, 0], {"pitch": -1.5}),
        ("tilt U 2", [0, 0, 0], {"pitch": 2}),
        # directions people use
        ("1 cm further right", [1, 0, 0], {}),
        ("3 cm to the front", [0, 3, 0], {}),
        ("backed away 3 cm", [0, -3, 0], {}),
        ("2 cm more high", [0, 0, 2], {}),
        ("approach the table by 1 cm", [0, 1, 0], {}),
        ("go 2 cm right for the out-of-range check", [2, 0, 0], {}),
        ("For this one: up 4 cm", [0, 0, 4], {}),
    ],
)
def test_camera_values(text, translate, rotate):
    t, r = camera(text)
    assert t == pytest.approx(translate)
    assert r == pytest.approx(rotate)


@pytest.mark.parametrize(
    ("text", "translate", "rotate"),
    [
        ("pan 3° right - sorry, left", [0, 0, 0], {"yaw": -3}),
        ("camera 2 cm lower, no, higher", [0, 0, 2], {}),
        ("camera 5 mm and closer", [0, 0.5, 0], {}),
        ("tilt 2 degrees, move up 1 cm and the tilt should be down", [0, 0, 1], {"pitch": -2}),
        ("turn 1° to the left. Correction: to the right", [0, 0, 0], {"yaw": 1}),
        ("yaw +2. On second thought: pitch -1", [0, 0, 0], {"pitch": -1}),
    ],
)
def test_camera_corrections_keep_the_amount_and_take_the_new_direction(text, translate, rotate):
    t, r = camera(text)
    assert t == pytest.approx(translate)
    assert r == pytest.approx(rotate)


def test_a_direction_without_an_amount_is_still_left_to_the_rule_reader():
    assert read_camera_request("tilt it up a little") is None


@pytest.mark.parametrize(
    ("said", "delta"),
    [("-25 % brightness", -0.25), ("lights to the half", -0.5), ("the lamp softened by about ten percent", -0.1),
     ("lighting at one hundred ten percent", 0.1)],
)
def test_signed_changes_levels_and_words_of_lowering(said, delta):
    op = read_lighting_request(said)
    assert op is not None and op["intensity_delta"] == pytest.approx(delta)


@pytest.mark.parametrize(
    ("said", "translation_m", "rotation_deg"),
    [("tilt to 4 degrees down", [0.0, 0.0, 0.0], [0.0, 4.0, 0.0]),
     ("the camera climbs of 3 cm", [0.0, 0.0, 0.03], [0.0, 0.0, 0.0]),
     ("camera advances of 1 cm", [0.01, 0.0, 0.0], [0.0, 0.0, 0.0]),
     ("raise it a full centimetre", [0.0, 0.0, 0.01], [0.0, 0.0, 0.0]),
     ("tz = 2", [0.0, 0.0, 0.02], [0.0, 0.0, 0.0])],
)
def test_camera_words_of_learners_and_keys(said, translation_m, rotation_deg):
    op = read_camera_request(said)
    assert op is not None
    assert op["translation_m"] == pytest.approx(translation_m) and op["rotation_deg"] == pytest.approx(rotation_deg)


@pytest.mark.parametrize(
    ("text", "translate", "rotate"),
    [
        # three numbers after a key of moving are x, y, z (a list, not decimal commas)
        ("camera: translate 2,1,-3 cm; pan 1", [2, 1, -3], {"yaw": 1}),
        ("cam_shift_cm = [1, -1, 0]", [1, -1, 0], {}),
        ("camera offset (mm): 10, 0, -20", [1, 0, -2], {}),
        # a decimal comma stays one number
        ("camera 2,5 cm up", [0, 0, 2.5], {}),
        # a translation key and its value with a space between
        ("CAM ty 1.5cm tz -1cm", [0, 1.5, -1], {}),
    ],
)
def test_camera_vectors_and_keys(text, translate, rotate):
    t, r = camera(text)
    assert t == pytest.approx(translate)
    assert r == pytest.approx(rotate)


def test_a_signed_decimal_comma_in_a_lighting_value():
    assert read_lighting_request("light: minus 0,2") == {"op": "set_lighting", "intensity_delta": pytest.approx(-0.2)}


@pytest.mark.parametrize(("said", "delta"), [
    ("lights at 15% below normal", -0.15),  # an amount below the baseline, not a level of 15 %
    ("lighting 20% above default", 0.2),
    ("lights at 70% of normal", -0.3),  # a level, as before
])
def test_an_amount_below_or_above_the_baseline(said, delta):
    assert read_lighting_request(said) == {"op": "set_lighting", "intensity_delta": pytest.approx(delta)}
