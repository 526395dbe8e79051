"""The scene-description reader, field by field, on descriptions in every style (written for these tests).

Each case is read by :func:`ladev_lib.language.scene.read_description` with
the project catalog's names; the operations it gives are checked field by
field: the named objects (a multiset), random fill, the task (stated anywhere
in the text), lighting, camera (spec frame: +x away from the robot, +y to its
left; yaw + pans left, pitch + tilts down, roll - is clockwise) and positions.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.scene import Vocabulary, read_description
from ladev_lib.language.scene.statements import find_task
from ladev_lib.scenes.text_to_scene import object_listing


@pytest.fixture(scope="module")
def vocab() -> Vocabulary:
    return Vocabulary.from_objects(object_listing(load_catalog(None)))


def _named(out: dict[str, Any]) -> Counter[str]:
    return Counter(op["object"] for op in out["operations"] if op["op"] == "add_object" and op.get("object"))


def _randoms(out: dict[str, Any]) -> int:
    return sum(1 for op in out["operations"] if op["op"] == "add_object" and not op.get("object"))


def _light(out: dict[str, Any]) -> float | None:
    ops = [op for op in out["operations"] if op["op"] == "set_lighting"]
    return ops[-1]["intensity_delta"] if ops else None


def _camera(out: dict[str, Any]) -> tuple[list[float], list[float]] | None:
    ops = [op for op in out["operations"] if op["op"] == "move_camera"]
    return (ops[0]["translation_m"], ops[0]["rotation_deg"]) if ops else None


def _where(out: dict[str, Any], name: str) -> dict[str, Any] | None:
    for op in out["operations"]:
        if op["op"] == "add_object" and op.get("object") == name:
            return op.get("position")
    return None


# -- the task, stated anywhere, is the scene's task; its objects are the scene's -------------

TASK_CASES = [
    # the paper's fixed structure, task line last or first
    ("Number and details of objects: 3 objects, a mug on the right, a fork and a lemon. Environmental setup: "
     "lights 10% dimmer, camera unchanged. Task: put the lemon in the mug.",
     {"mug": 1, "fork": 1, "lemon": 1}, ("put_in", "lemon", "mug")),
    ("Task: move the pear near the banana. Number and details of objects: 2 objects, a banana and a pear. "
     "Environmental setup: default.",
     {"banana": 1, "pear": 1}, ("move_near", "pear", "banana")),
    # free prose: the task in the middle, about the robot
    ("There is a bowl in the middle of the table and a strawberry beside it. I want the arm to drop the "
     "strawberry into the bowl. Leave the lights as they are.",
     {"bowl": 1, "strawberry": 1}, ("put_in", "strawberry", "bowl")),
    ("A sponge sits at the back. We'll check whether the robot can put the green cube on the sponge, "
     "and there is a green cube at the front.",
     {"sponge": 1, "green cube": 1}, ("put_on", "green cube", "sponge")),
    # terse list and key = value
    ("items: banana; plate; apple | goal = put banana on plate | light: default", {"banana": 1, "plate": 1, "apple": 1},
     ("put_on", "banana", "plate")),
    # command lines
    ("ADD lemon to (0.05, 0.02)\nADD bowl to (-0.05, -0.1)\nTASK put lemon in bowl",
     {"lemon": 1, "bowl": 1}, ("put_in", "lemon", "bowl")),
    # a bare command over definite nouns, after the scene
    ("A mustard bottle and a pear. Pick up the pear.", {"mustard bottle": 1, "pear": 1}, ("pick_up", "pear", None)),
    # an -ing statement inside a list sentence
    ("a quick one: spoon, mug, knife, with the robot placing the spoon in the mug.",
     {"spoon": 1, "mug": 1, "knife": 1}, ("put_in", "spoon", "mug")),
]


@pytest.mark.parametrize("text, objects, task", TASK_CASES)
def test_the_stated_task_and_the_described_objects(vocab, text, objects, task):
    out = read_description(text, vocab)
    assert "error" not in out, out
    assert _named(out) == Counter(objects), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task


def test_placement_commands_that_set_the_scene_are_not_the_task(vocab):
    out = read_description(
        "Put a carrot at the front, place the towel on the left side. The robot should pick up the carrot.", vocab
    )
    assert out["task"] == {"type": "pick_up", "source": "carrot", "target": None}
    assert _where(out, "carrot") == {"region": "front"} and _where(out, "towel") == {"region": "left"}


def test_an_explicit_instruction_wins_over_the_text(vocab):
    out = read_description("a lemon and a bowl. Task: pick up the lemon.", vocab, instruction="put the lemon in the bowl")
    assert out["task"] == {"type": "put_in", "source": "lemon", "target": "bowl"}
    assert _named(out) == Counter({"lemon": 1, "bowl": 1})  # the task line is not read as more objects


def test_with_neither_the_task_type_applies(vocab):
    out = read_description("a lemon and a bowl", vocab, task="pick_up")
    assert out["task"] == {"type": "pick_up"}


def test_find_task_takes_the_statement_out_of_the_object_text(vocab):
    found = find_task("Two apples and a basket; task: put an apple in the basket.", vocab.ids)
    assert found.task == {"type": "put_in", "source": "apple", "target": "basket"}
    assert "task" not in found.rest.lower()


# -- duplicates, plurals, numbers in words, random fill ----------------------------------------


def test_duplicates_of_the_task_object(vocab):
    out = read_description("three plums and a large green cup; put a plum in the large green cup", vocab)
    assert _named(out) == Counter({"plum": 3, "large green cup": 1})
    assert out["task"]["source"] == "plum"


def test_a_plural_spelled_out_item_by_item(vocab):
    out = read_description("two cubes, a yellow one at the back and a green one at the front", vocab)
    assert _named(out) == Counter({"yellow cube": 1, "green cube": 1})
    assert _where(out, "yellow cube") == {"region": "back"}


def test_a_group_named_item_by_item_is_not_extra(vocab):
    out = read_description("Three pieces of fruit - a peach, a plum and a lemon - next to a bowl.", vocab)
    assert _named(out)["peach"] == 1 and _named(out)["plum"] == 1 and _named(out)["lemon"] == 1
    assert _randoms(out) == 0


@pytest.mark.parametrize(
    "text, named, randoms",
    [
        ("five objects in total, among them a fork and a spoon", {"fork": 1, "spoon": 1}, 3),
        ("Four random objects, one of which is a tennis ball.", {"tennis ball": 1}, 3),
        ("any three objects plus a marker", {"marker": 1}, 3),
        ("a mug, and everything else random, four objects in all", {"mug": 1}, 3),
        ("random objects: 2. named objects: a padlock.", {"padlock": 1}, 2),
        ("a golf ball among two other balls", {"golf ball": 1}, 2),
    ],
)
def test_random_fill(vocab, text, named, randoms):
    out = read_description(text, vocab, task="pick_up")
    assert _named(out) == Counter(named), out
    assert _randoms(out) == randoms, out


# -- corrections and take-backs ------------------------------------------------------------------


@pytest.mark.parametrize(
    "text, named",
    [
        ("a knife - no, make that a fork - and a plate", {"fork": 1, "plate": 1}),
        ("A pear, a plum, and a bowl. Not a bowl, a mug.", {"pear": 1, "plum": 1, "mug": 1}),
        ("Three objects: a lemon, a peach and a banana. Actually, drop the banana.", {"lemon": 1, "peach": 1}),
        ("a hammer, a wrench and a marker; scratch the wrench, replace it with a spatula",
         {"hammer": 1, "marker": 1, "spatula": 1}),
    ],
)
def test_corrections_leave_what_the_writer_settled_on(vocab, text, named):
    out = read_description(text, vocab, task="pick_up")
    assert _named(out) == Counter(named), out
    assert _randoms(out) == 0, out


def test_the_last_statement_wins_in_the_environment(vocab):
    out = read_description("an apple. lights 30% brighter - wait, no, darker. camera: move it 2 cm to the left - "
                           "sorry, 4 cm.", vocab, task="pick_up")
    assert _light(out) == pytest.approx(-0.3)
    cam = _camera(out)
    assert cam is not None and cam[0] == pytest.approx([0.0, 0.04, 0.0])


# -- lighting ------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text, delta",
    [
        ("an apple; no lighting change", None),
        ("an apple; lighting: default", None),
        ("an apple; lights twelve percent brighter", 0.12),
        ("an apple; make the room a fifth darker", -0.2),
        ("an apple; lights at 70% of normal", -0.3),
        ("an apple; half as bright as usual", -0.5),
        ("an apple; light x1.2", 0.2),
        ("an apple; cut the light by three quarters", -0.75),
    ],
)
def test_lighting(vocab, text, delta):
    got = _light(read_description(text, vocab, task="pick_up"))
    assert got == (pytest.approx(delta) if delta is not None else None)


# -- camera (spec frame) -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text, translation, rotation",
    [
        ("a pear; camera moved 3 cm to the left", [0, 0.03, 0], [0, 0, 0]),
        ("a pear; pull the camera back 2 cm", [-0.02, 0, 0], [0, 0, 0]),
        ("a pear; camera 1.5 cm closer to the table", [0.015, 0, 0], [0, 0, 0]),
        ("a pear; raise the camera by 20 mm", [0, 0, 0.02], [0, 0, 0]),
        ("a pear; pan the camera two degrees to the right", [0, 0, 0], [0, 0, -2]),
        ("a pear; tilt the camera down 4 degrees", [0, 0, 0], [0, 4, 0]),
        ("a pear; roll the camera 3 degrees clockwise", [0, 0, 0], [-3, 0, 0]),
        # signed axis values are in the camera's own frame (x right, y forward; yaw + pans right, pitch + tilts up)
        ("a pear; cam: yaw +2 deg, pitch -1 deg", [0, 0, 0], [0, 1, -2]),
        ("a pear; cam x +2 cm", [0, -0.02, 0], [0, 0, 0]),
        ("a pear; camera: don't rotate it, but move it 3 cm closer", [0.03, 0, 0], [0, 0, 0]),
    ],
)
def test_camera(vocab, text, translation, rotation):
    cam = _camera(read_description(text, vocab, task="pick_up"))
    assert cam is not None
    assert cam[0] == pytest.approx(translation) and cam[1] == pytest.approx(rotation)


@pytest.mark.parametrize("text", ["a pear; don't move the camera", "a pear; camera: none", "a pear; CAMERA 0"])
def test_no_camera_change(vocab, text):
    assert _camera(read_description(text, vocab, task="pick_up")) is None


# -- positions ------------------------------------------------------------------------------------------


def test_positions_and_definite_mentions(vocab):
    out = read_description(
        "A fork, a knife and a plate. The fork goes on the left and the knife on the right; "
        "the plate sits in the middle, and a spoon on the far side.", vocab, task="pick_up")
    assert _named(out) == Counter({"fork": 1, "knife": 1, "plate": 1, "spoon": 1})
    assert _where(out, "fork") == {"region": "left"} and _where(out, "knife") == {"region": "right"}
    assert _where(out, "plate") == {"region": "center"} and _where(out, "spoon") == {"region": "back"}


# -- unavailable objects ----------------------------------------------------------------------------------


def test_unavailable_objects_are_read_by_name_not_substituted(vocab):
    out = read_description("objects: a teapot, an apple and a plate. Task: put the apple on the plate.", vocab)
    assert "teapot" in _named(out)
    out = read_description("a lemon and a bowl; the robot should put the lemon in the flower vase", vocab)
    assert out["task"]["target"] == "flower vase"


def test_chat_around_the_scene_is_not_read_as_objects(vocab):
    out = read_description(
        "Hey, long week. For the demo on Friday I need a tidy scene: an orange and a basket, "
        "and the robot should put the orange in the basket. Thanks!", vocab)
    assert _named(out) == Counter({"orange": 1, "basket": 1})
