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


# -- issue 11: readers for what people write (each case written for these tests) ---------------


def test_each_header_governs_only_the_text_after_it(vocab):
    # one line with both headers: the object part is not read as environment
    out = read_description(
        "Number and details of objects: a lemon, a plum and a peach, all sitting at the back of the table. "
        "Environmental setup: lights 10% brighter. Task: pick up the plum.", vocab,
    )
    assert all(_where(out, n) == {"region": "back"} for n in ("lemon", "plum", "peach")), out
    assert _light(out) == pytest.approx(0.1)


@pytest.mark.parametrize("text, objects", [
    # the group's noun, not a later plural ('4 degrees'), is what "one" stands for
    ("two cubes, a yellow one at the front and a green one at the back; camera tilted down 4 degrees",
     {"yellow cube": 1, "green cube": 1}),
    # "a green and a yellow one": both adjectives share the one noun
    ("Three objects: two cubes, a yellow and a green one, and a lemon.", {"yellow cube": 1, "green cube": 1, "lemon": 1}),
    # a group said "on the table" before its members
    ("So, three cups on the table: the red cup, the green cup and the yellow cup.",
     {"red cup": 1, "green cup": 1, "yellow cup": 1}),
])
def test_groups_spelled_out_by_their_members(vocab, text, objects):
    out = read_description(text, vocab)
    assert _named(out) == Counter(objects), out
    assert _randoms(out) == 0


@pytest.mark.parametrize("text", [
    "My arm always drops bananas, not sure why. This time: a banana and a bowl, nothing fancy.",
    "Sorry, no idea why it failed. Give me a banana and a bowl.",
    "A banana and a bowl (honestly, the model confuses them). Something with tools would be next.",
])
def test_chat_kinds_and_plural_mentions_are_not_objects(vocab, text):
    out = read_description(text, vocab)
    assert _named(out) == Counter({"banana": 1, "bowl": 1}), out
    assert _randoms(out) == 0


@pytest.mark.parametrize("text, where", [
    ("A mug on the right. A spoon and a fork go on the left.", {"spoon": "left", "fork": "left"}),
    ("a padlock and a dice, both near the front", {"padlock": "front", "dice": "front"}),
    ("A lemon at the back; a spoon and a fork at the front.", {"lemon": "back", "spoon": "front", "fork": "front"}),
    ("Two drinks, a coke can and a pepsi can, stand side by side on the left.", {"coke can": "left", "pepsi can": "left"}),
])
def test_a_position_said_of_coordinated_objects_is_said_of_each(vocab, text, where):
    out = read_description(text, vocab)
    for name, region in where.items():
        assert _where(out, name) == {"region": region}, (name, out)


def test_a_long_list_keeps_the_position_on_its_last_item(vocab):
    out = read_description("Objects: a coke can, an apple and a sponge on the right.", vocab)
    assert _where(out, "sponge") == {"region": "right"} and _where(out, "apple") is None


@pytest.mark.parametrize("text, task", [
    # about the robot, with "the pink one": only the scene says which objects
    ("two lego bricks, a pink one and a blue one, and the robot moves the pink brick near the blue one.",
     ("move_near", "pink lego brick", "blue lego brick")),
    # a task said without its verb
    ("A lemon and a large green cup, nothing else. Lemon into the cup.", ("put_in", "lemon", "large green cup")),
    # an inline tag makes a placement sentence the task
    ("A fork, a spoon and a towel. The spoon goes on the towel (that's the task), not the fork.",
     ("put_on", "spoon", "towel")),
    # a question about the arm, ending at "when"
    ("Can the robot pick up the small yellow lego brick when a pink lego brick lies next to it?",
     ("pick_up", "small yellow lego brick", None)),
    # "pick up bottle": the scene's one bottle
    ("objects: blue plastic bottle, apple; task: pick up bottle", ("pick_up", "blue plastic bottle", None)),
])
def test_tasks_that_need_the_scene_to_be_read(vocab, text, task):
    from ladev_lib.catalog import load_catalog
    from ladev_lib.scenes.resolve import ObjectResolver

    out = read_description(text, vocab)
    assert "error" not in out, out
    t = out["task"]
    resolver = ObjectResolver(load_catalog(None), 1.01)

    def oid(name: str | None) -> str | None:
        return None if name is None else resolver.resolve(name).obj.id  # type: ignore[union-attr]

    assert (t["type"], oid(t["source"]), oid(t.get("target"))) == (task[0], oid(task[1]), oid(task[2])), out


def test_a_statement_that_introduces_objects_stays_scene_text(vocab):
    out = read_description(
        "Could you set up a table with a coke can, a pepsi can and a plate? The robot should put the coke can on the plate.",
        vocab,
    )
    assert _named(out) == Counter({"coke can": 1, "pepsi can": 1, "plate": 1}), out


def test_one_more_example_is_not_a_random_object(vocab):
    out = read_description("We need one more example: a lemon and a bowl.", vocab)
    assert _randoms(out) == 0 and _named(out) == Counter({"lemon": 1, "bowl": 1})


def test_possessive_introduces_an_unknown_object(vocab):
    out = read_description("On the desk: my stapler (just clutter), a lemon and a bowl.", vocab)
    assert _named(out)["stapler"] == 1, out


def test_container_of_phrases_name_the_catalog_object(vocab):
    out = read_description("a lemon and a box of Jell-O gelatin", vocab)
    assert _named(out) == Counter({"lemon": 1, "gelatin box": 1}), out


@pytest.mark.parametrize("text, where", [
    # "next to it": the object described last
    ("The sugar box is on the left, and a lemon sits next to it.", ("lemon", {"relation": "near", "reference": "sugar box"})),
    # a relative clause places its own object
    ("The lemon lies beside a plate that sits in the middle.", ("plate", {"region": "center"})),
    # "the box": the one box described (or the task's), by its head noun
    ("A sugar box and a banana. Put the banana on the left and the box on the right.", ("sugar box", {"region": "right"})),
])
def test_positions_by_reference(vocab, text, where):
    out = read_description(text, vocab)
    assert _where(out, where[0]) == where[1], out


def test_the_tasks_object_is_placed_by_its_head_noun(vocab):
    out = read_description("The robot should put the tuna can on the plate. Put the can on the left.", vocab)
    assert out["task"]["source"] in ("tuna can", "starkist tuna can")
    assert any(op.get("position") == {"region": "left"} for op in out["operations"] if op["op"] == "add_object")


def test_swap_them_trades_places(vocab):
    out = read_description("A pear on the left and a plum on the right - actually, swap them.", vocab)
    assert _where(out, "pear") == {"region": "right"} and _where(out, "plum") == {"region": "left"}, out


def test_remove_by_one_word_of_the_name(vocab):
    out = read_description("A mustard bottle, a windex bottle and a lemon. No, remove the windex.", vocab)
    assert _named(out) == Counter({"mustard bottle": 1, "lemon": 1}), out


def test_a_category_word_before_another_noun_is_a_modifier(vocab):
    out = read_description("For a fruit test: a lemon and a plate.", vocab)
    assert _named(out) == Counter({"lemon": 1, "plate": 1}) and _randoms(out) == 0, out


def test_vocabulary_knows_every_id_and_category(vocab):
    assert vocab.ids["blue_plastic_bottle"] == "blue plastic bottle"
    assert {"fruit", "can", "cup"} <= vocab.categories
    assert vocab.name_ids["plastic bottle"] == "blue_plastic_bottle"


# -- forms added after the second blind held-out set (written for these tests) ---------------------


@pytest.mark.parametrize(
    "text, objects, task",
    [
        # a wish about named objects is the task; "I need a plate and a knife" only lists objects
        ("Today I need the peach in the bowl. Set out a peach, a bowl and a fork.",
         {"peach": 1, "bowl": 1, "fork": 1}, ("put_in", "peach", "bowl")),
        ("A banana, a marker and a plate on the table. We want the marker near the banana.",
         {"banana": 1, "marker": 1, "plate": 1}, ("move_near", "marker", "banana")),
        # a task written as a call
        ("+ pear\n+ plate\nTASK put_on(pear, plate)", {"pear": 1, "plate": 1}, ("put_on", "pear", "plate")),
        # a chatty lead-in before the command, and a back-reference after it
        ("just a lemon and a bowl. Ok, so put the lemon in the bowl, that is what the robot should do.",
         {"lemon": 1, "bowl": 1}, ("put_in", "lemon", "bowl")),
        # a corrected relation inside the task statement
        ("A fork, a spoon and a plate. Move the fork next to the spoon - no wait, next to the plate.",
         {"fork": 1, "spoon": 1, "plate": 1}, ("move_near", "fork", "plate")),
    ],
)
def test_more_ways_to_state_the_task(vocab, text, objects, task):
    test_the_stated_task_and_the_described_objects(vocab, text, objects, task)


def test_a_setting_said_with_a_placing_verb_is_no_task(vocab):
    out = read_description("a sugar box and a mug. Drop the brightness to 80 percent of default.", vocab, task="pick_up")
    assert out["task"] == {"type": "pick_up"}, out
    assert _light(out) == pytest.approx(-0.2)


@pytest.mark.parametrize(
    "text, named, randoms",
    [
        ("A pair of plums, a bowl and something else of your choice.", {"plum": 2, "bowl": 1}, 1),
        ("a marker\n+ random\n+ random", {"marker": 1}, 2),
        ("Put a mug at the back and add random objects so that there are four in all.", {"mug": 1}, 3),
        # a count that starts a list is not a group header
        ("Three pears, a mug and a sponge.", {"pear": 3, "mug": 1, "sponge": 1}, 0),
        # another kind of the same noun is not one of the group
        ("two golf balls, a tennis ball and a bowl", {"golf ball": 2, "tennis ball": 1, "bowl": 1}, 0),
        # adjectives sharing one "one"
        ("three cubes (a green, a yellow and a blue one)", {"green cube": 1, "yellow cube": 1, "blue cube": 1}, 0),
    ],
)
def test_counts_groups_and_free_choices(vocab, text, named, randoms):
    test_random_fill(vocab, text, named, randoms)


@pytest.mark.parametrize(
    "text, named",
    [
        ("a hammer, a wrench and a spatula, but not the wrench after all", {"hammer": 1, "spatula": 1}),
        # a replaced object keeps the count: four objects, one of them random
        ("Four objects: a plum, a pear and a fork - scratch the fork, make it a spoon - and the rest random.",
         {"plum": 1, "pear": 1, "spoon": 1}),
        # the correction re-counts the object it names; the others stay
        ("one lemon with a bowl and a knife... actually make it two lemons", {"lemon": 2, "bowl": 1, "knife": 1}),
    ],
)
def test_more_corrections(vocab, text, named):
    out = read_description(text, vocab, task="pick_up")
    assert _named(out) == Counter(named), out


def test_an_unknown_object_named_again_by_its_head_noun_is_one_object(vocab):
    out = read_description(
        "Put a game controller and a towel on the table, controller on the left. Place the controller on the towel.",
        vocab,
    )
    unknown = [op["object"] for op in out["operations"] if op["op"] == "add_object" and op.get("object") not in (None, "towel")]
    assert unknown == ["game controller"], out
    assert out["task"]["source"] == "game controller", out


# -- forms added after the third blind held-out set (written for these tests) ---------------------


@pytest.mark.parametrize(
    "text, objects, task",
    [
        ("A plum, a mug and a bowl. The plum goes in the bowl.", {"plum": 1, "mug": 1, "bowl": 1}, ("put_in", "plum", "bowl")),
        ("+ pear\n+ plate\npear -> on plate", {"pear": 1, "plate": 1}, ("put_on", "pear", "plate")),
        ("A fork and a towel... make that the sponge. Put the fork on it.", {"fork": 1, "sponge": 1}, ("put_on", "fork", "sponge")),
        ("Objects: marker, mug, bowl. Task: put the marker in the mug. Wait, no, in the bowl.",
         {"marker": 1, "mug": 1, "bowl": 1}, ("put_in", "marker", "bowl")),
    ],
)
def test_tasks_said_by_end_state_arrow_pronoun_or_corrected(vocab, text, objects, task):
    test_the_stated_task_and_the_described_objects(vocab, text, objects, task)


@pytest.mark.parametrize(
    "text, named, randoms",
    [
        ("two lego bricks (green, purple) and a towel", {"green lego brick": 1, "purple lego brick": 1, "towel": 1}, 0),
        ("the green lego brick and the pink one", {"green lego brick": 1, "pink lego brick": 1}, 0),
        ("a mug, a marker, a pair of scissors", {"mug": 1, "marker": 1, "pair of scissors": 1}, 0),
        ("* peach\n* 3x random", {"peach": 1}, 3),
        ("Four fruits (a pear, a plum, a peach and a lemon) plus one random object, five objects overall.",
         {"pear": 1, "plum": 1, "peach": 1, "lemon": 1}, 1),
        ("a sponge and a towel, neatly arranged", {"sponge": 1, "towel": 1}, 0),
    ],
)
def test_members_counts_and_manner_words(vocab, text, named, randoms):
    test_random_fill(vocab, text, named, randoms)


@pytest.mark.parametrize(
    "text, named",
    [
        ("a mug, a plum and a bowl; instead of the bowl use the basket", {"mug": 1, "plum": 1, "basket": 1}),
        ("a coke can and a pepsi can. No wait, swap the pepsi for a sprite can.", {"coke can": 1, "sprite can": 1}),
    ],
)
def test_one_object_for_another(vocab, text, named):
    out = read_description(text, vocab, task="pick_up")
    assert _named(out) == Counter(named), out


def test_a_correction_that_names_an_object_by_its_head_noun_replaces_only_that_object(vocab):
    out = read_description("a peach on a plate... make that the red plate", vocab, task="pick_up")
    assert _named(out) == Counter({"peach": 1}), out  # the red plate comes in as the peach's reference
    assert _where(out, "peach") == {"relation": "near", "reference": "red plate"}


@pytest.mark.parametrize(
    "text, delta",
    [
        ("a pear. Lighting 3/10 dimmer", -0.3),
        ("a pear. Lights 20% darker, actually make it 25%.", -0.25),
        ("a pear. dim everything by 40 percent and dolly in 2 cm", -0.4),
    ],
)
def test_lighting_fractions_corrected_amounts_and_camera_only_verbs(vocab, text, delta):
    out = read_description(text, vocab, task="pick_up")
    assert _light(out) == pytest.approx(delta), out


def test_a_lamp_with_an_article_is_an_object_not_the_lighting(vocab):
    out = read_description("a pear and a desk lamp behind them", vocab, task="pick_up")
    assert _named(out) == Counter({"pear": 1, "desk lamp": 1}), out
    assert _light(out) is None


# -- forms added after the fourth blind held-out set (written for these tests) ---------------------


def test_a_clause_after_the_task_statement_stays_scene_text(vocab):
    out = read_description(
        "We want to see whether it can move the marker next to the mug, with a pear sitting on the left.", vocab
    )
    assert _named(out) == Counter({"pear": 1}), out
    assert _where(out, "pear") == {"region": "left"}
    assert (out["task"]["type"], out["task"]["source"], out["task"]["target"]) == ("move_near", "marker", "mug")


def test_key_value_snippets_with_braces_and_direction_keys(vocab):
    out = read_description(
        "{objects: [peach, plate], task: peach -> plate (put on), light: darker 0.2, camera: {up: 3 cm}}", vocab
    )
    assert _named(out) == Counter({"peach": 1, "plate": 1}), out
    assert _light(out) == pytest.approx(-0.2)
    translation, _ = _camera(out)
    assert translation == pytest.approx([0.0, 0.0, 0.03])


# -- forms added after the fifth blind held-out set (written for these tests) ---------------------


@pytest.mark.parametrize(
    "text, objects, task",
    [
        ("A plum, a pear and a bowl. The robot picks up the plum - sorry, the pear.", {"plum": 1, "pear": 1, "bowl": 1},
         ("pick_up", "pear", None)),
        ("peach, lemon, mug. Robot puts the peach in the mug - actually, use the lemon, not the peach.",
         {"peach": 1, "lemon": 1, "mug": 1}, ("put_in", "lemon", "mug")),
        ("A fork, a knife and a plate. Task: put the fork on the plate. Hmm, actually put the knife on it instead.",
         {"fork": 1, "knife": 1, "plate": 1}, ("put_on", "knife", "plate")),
        ("two fruits, an apple and a pear, and a bowl. Robot: put the pear in the bowl.",
         {"apple": 1, "pear": 1, "bowl": 1}, ("put_in", "pear", "bowl")),
        ("ok put a plum and a plate on the table then the robot puts the plum on the plate lights ten percent darker",
         {"plum": 1, "plate": 1}, ("put_on", "plum", "plate")),
    ],
)
def test_task_corrections_labels_and_dictation(vocab, text, objects, task):
    test_the_stated_task_and_the_described_objects(vocab, text, objects, task)


def test_numbered_lists_comparatives_and_unset_camera(vocab):
    out = read_description("1. pear\n2. mug\n3. task: pick up the pear\n4. lights 10% dimmer\n5. camera.rotate = none", vocab)
    assert _named(out) == Counter({"pear": 1, "mug": 1}), out
    assert _light(out) == pytest.approx(-0.1) and _camera(out) is None
    out = read_description("a pear. the light make more dark by 20 percent", vocab, task="pick_up")
    assert _light(out) == pytest.approx(-0.2)


@pytest.mark.parametrize(
    "text, named",
    [
        ("Objects: a plum, a towel and a fork. Don't include the fork after all.", {"plum": 1, "towel": 1}),
        ("a pear, a toy boat and one random object", {"pear": 1, "toy boat": 1}),
    ],
)
def test_take_backs_and_category_words_as_modifiers(vocab, text, named):
    out = read_description(text, vocab, task="pick_up")
    assert _named(out) == Counter(named), out


# -- forms added after the sixth blind held-out set (written for these tests) ---------------------


@pytest.mark.parametrize(
    "text, objects, task",
    [
        ("Task: put the plum in the bowl. The table has just those two things. Camera unchanged.",
         {"plum": 1, "bowl": 1}, ("put_in", "plum", "bowl")),
        ("I need scene with one pear and one mug. Pear must be put inside the mug by robot.",
         {"pear": 1, "mug": 1}, ("put_in", "pear", "mug")),
        ("objects: [marker, mug]\ntask: {type: put_in, object: marker, target: mug}",
         {"marker": 1, "mug": 1}, ("put_in", "marker", "mug")),
        ("a fork and a plate period the fork goes on the plate period", {"fork": 1, "plate": 1},
         ("put_on", "fork", "plate")),
        ("Plate, apple, orange. Task: put the apple on the plate. Wait — put the orange on the plate, not the apple.",
         {"plate": 1, "apple": 1, "orange": 1}, ("put_on", "orange", "plate")),
    ],
)
def test_only_these_passives_task_dicts_dictation_and_dashed_retractions(vocab, text, objects, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(objects), out
    assert _randoms(out) == 0, out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task


@pytest.mark.parametrize(
    "text, delta",
    [
        ("a pear. Light: double it.", 1.0),
        ("a pear. the lighting should be three quarters of what it is now", -0.25),
        ("a pear. Lights 40% brighter... hmm, that's too much, go with 20%.", 0.2),
    ],
)
def test_lighting_restated(vocab, text, delta):
    out = read_description(text, vocab, task="pick_up")
    assert _light(out) == pytest.approx(delta), out


# -- forms added after the seventh blind held-out set (written for these tests) -------------------


@pytest.mark.parametrize(
    "text, objects, task",
    [
        # dictated run-on text with fillers: the task clause starts at "and the robot", the setup goes on after it
        ("can you um set up a plum and uh a mug and the robot has to put the plum in the mug yeah and lights a bit "
         "darker and tilt the camera down like two degrees", {"plum": 1, "mug": 1}, ("put_in", "plum", "mug")),
        # grammar of a learner: "robot is put"
        ("Make table with lemon, banana and the bowl. Robot is put lemon in bowl.", {"lemon": 1, "banana": 1, "bowl": 1},
         ("put_in", "lemon", "bowl")),
        # a task without its verb, as a whole segment
        ("peach, mug, fork. peach in mug. lights -10%.", {"peach": 1, "mug": 1, "fork": 1}, ("put_in", "peach", "mug")),
        ("pear, towel, spoon | spoon next to pear", {"pear": 1, "towel": 1, "spoon": 1}, ("move_near", "spoon", "pear")),
        # a label's statement said as an end state; a heading word before the label
        ("Objects: a plum and a bowl. Task: by the end, the plum should be inside the bowl.", {"plum": 1, "bowl": 1},
         ("put_in", "plum", "bowl")),
        ("Objects: pear, mug, bowl. Task: put the pear in the mug. Update: the task is to put the pear in the bowl.",
         {"pear": 1, "mug": 1, "bowl": 1}, ("put_in", "pear", "bowl")),
        # "one of the Xs" as the subject of a passive; an end state once the robot is done
        ("Three things: two plums and a towel. One of the plums has to be placed on the towel.", {"plum": 2, "towel": 1},
         ("put_on", "plum", "towel")),
        ("A fork, a spoon and a mug. Once the robot is finished, the spoon rests right next to the mug.",
         {"fork": 1, "spoon": 1, "mug": 1}, ("move_near", "spoon", "mug")),
        # a statement after a colon; a command followed by an aside listing the objects
        ("Checking placement: the peach goes into the bowl. Also a fork on the left.",
         {"fork": 1}, ("put_in", "peach", "bowl")),
        ("Put the lemon on the towel (objects: lemon, towel, and a mug at the back).",
         {"lemon": 1, "towel": 1, "mug": 1}, ("put_on", "lemon", "towel")),
    ],
)
def test_dictation_learner_grammar_verbless_tasks_and_labelled_end_states(vocab, text, objects, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(objects), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task


def test_for_the_robot_to_pick_up_is_not_a_command_of_its_own(vocab):
    # "the robot to <verb>" said by a learner is a command; "for the robot to pick up" is a purpose
    out = read_description("Four objects of any kind, one of which is a pear for the robot to pick up.", vocab,
                           task="pick_up")
    assert "error" not in out and _named(out) == Counter({"pear": 1}) and _randoms(out) == 3, out


def test_a_scene_sentence_with_on_is_not_a_verbless_task(vocab):
    out = read_description("A peach and a bowl. Put the peach in the bowl. Also on the table are a mug on the left "
                           "and a towel.", vocab)
    assert (out["task"]["type"], out["task"]["source"], out["task"]["target"]) == ("put_in", "peach", "bowl")
    assert _named(out) == Counter({"peach": 1, "bowl": 1, "mug": 1, "towel": 1}), out
    out = read_description("a towel on the left, a fork. pick up the fork", vocab)
    assert out["task"]["type"] == "pick_up" and _where(out, "towel") == {"region": "left"}


@pytest.mark.parametrize(
    "text",
    [
        "objects:\n  - plum\n  - mug\ntask:\n  type: put_in\n  object: plum\n  target: mug\nlight: x0.8\ncamera:\n  yaw: 2\n  z: 10mm",
        "[objs] plum, mug [task] put_in plum mug [light] 0.8x [cam] +1cm z, 2 deg yaw",
        "obj: plum@left, mug; task=put_in plum->mug; lgt=-0.2; cam=(dx 0, dz 1cm, yaw 2)",
        "scene | plum, mug\ngoal | plum into mug\nlite | darker 0.2\nview | up 1 cm, pan R 2 deg",
    ],
)
def test_descriptions_written_as_data(vocab, text):
    out = read_description(text, vocab)
    assert _named(out) == Counter({"plum": 1, "mug": 1}), out
    assert (out["task"]["type"], out["task"]["source"], out["task"]["target"]) == ("put_in", "plum", "mug")
    assert _light(out) == pytest.approx(-0.2), out
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.0, 0.01]), out
    assert abs(camera[1][2]) == pytest.approx(2.0), out


def test_a_unit_factor_of_one_leaves_the_light_and_abbreviated_directions_are_read(vocab):
    out = read_description("plum; pick up plum; lights 1.0x; cam: tilt dn 2 deg, fwd 3 cm", vocab)
    assert _light(out) is None, out
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.03, 0.0, 0.0]) and camera[1][1] == pytest.approx(2.0)


@pytest.mark.parametrize(
    "text, named, where",
    [
        # a definite shorter name is the described object that has it as its end
        ("Just a fork, a mug and a red plate, the plate at the back. Pick up the fork.",
         {"fork": 1, "mug": 1, "red plate": 1}, ("red plate", {"region": "back"})),
        # "X (X in the middle)": where X is, not a second X
        ("Objects: a lemon and a mug (mug in the middle of the table). Task: put the lemon in the mug.",
         {"lemon": 1, "mug": 1}, ("mug", {"region": "center"})),
        # a restated list replaces the list it corrects; a corrected place
        ("Put a plum and a mug on the table - no wait, make that a plum and a bowl. Task: put the plum in the bowl.",
         {"plum": 1, "bowl": 1}, ("bowl", None)),
        ("Put a bowl and a fork on the table, with the bowl on the right... actually on the left. Pick up the fork.",
         {"bowl": 1, "fork": 1}, ("bowl", {"region": "left"})),
        ("The robot should pick up the pear. The other objects are a mug and a bowl, both toward the right.",
         {"mug": 1, "bowl": 1}, ("bowl", {"region": "right"})),
    ],
)
def test_references_asides_restated_lists_and_corrected_places(vocab, text, named, where):
    out = read_description(text, vocab)
    assert _named(out) == Counter(named), out
    assert _where(out, where[0]) == where[1], out


@pytest.mark.parametrize(
    "text, task",
    [
        ("A mug, a lemon and a fork. What we need the robot to do is to move the lemon near the mug.",
         ("move_near", "lemon", "mug")),
        ("Objects: plum, peach, bowl. Task: put the plum in the bowl. Actually, make it the peach that goes in the bowl.",
         ("put_in", "peach", "bowl")),
    ],
)
def test_pseudo_clefts_and_cleft_corrections(vocab, text, task):
    out = read_description(text, vocab)
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task, out


def test_an_amount_corrected_in_the_next_sentence_keeps_its_unit(vocab):
    out = read_description("A plum. Raise the camera 2 cm. Hmm, make it 3. Pick up the plum.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.0, 0.03]), out
    out = read_description("A plum... actually make it two plums. Pick up a plum.", vocab)
    assert _named(out) == Counter({"plum": 2}), out


# -- forms added after the eighth blind held-out set (written for these tests) --------------------


@pytest.mark.parametrize(
    "text",
    [
        "cfg = {'objects': ['plum', 'mug'], 'task': ('put_in', 'plum', 'mug'), 'light_delta': -0.2, 'cam': {'z_cm': 1}}",
        "[scene]\nobjects = plum, mug\n[task]\ntype = put_in\nobject = plum\ntarget = mug\n[env]\nlight = -0.2\ncamera_z_cm = 1",
        "case,objects,task,lighting,camera\n3,\"plum|mug\",put_in(plum; mug),-20%,up 1 cm",
        '{"items": ["plum", "mug"], "goal": "plum into the mug", "lights": "-20%", "view": {"dz_mm": 10}}',
    ],
)
def test_configs_python_literals_ini_sections_and_csv_rows(vocab, text):
    out = read_description(text, vocab)
    assert _named(out) == Counter({"plum": 1, "mug": 1}), out
    assert (out["task"]["type"], out["task"]["source"], out["task"]["target"]) == ("put_in", "plum", "mug")
    assert _light(out) == pytest.approx(-0.2), out
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.0, 0.01]), out


@pytest.mark.parametrize(
    "text, named, task",
    [
        # a passive about the camera is a setting, not the task
        ("The pear is to be put in the bowl by the arm. Objects: the pear and the bowl. The camera should be moved "
         "3 cm closer and the lights brought down a bit.", {"pear": 1, "bowl": 1}, ("put_in", "pear", "bowl")),
        ("Put a plum and a mug on the table. Actually, make that a bowl instead of the mug. Put the plum in the bowl.",
         {"plum": 1, "bowl": 1}, ("put_in", "plum", "bowl")),
        ("Objects: a fork, a Red Bull can and a mug. Wait, swap the Red Bull for a Pepsi. Pick up the Pepsi.",
         {"fork": 1, "mug": 1, "pepsi": 1}, ("pick_up", "pepsi can", None)),
        ("Only a navel orange and a mug; the orange should end up in the mug.", {"navel orange": 1, "mug": 1},
         ("put_in", "navel orange", "mug")),
        ("I want a plum on a towel - sorry, on a plate. So: plum, plate. The robot puts the plum on the plate.",
         {"plum": 1}, ("put_on", "plum", "plate")),
        ("Objects: a peach and a bowl which sits at the back side of the table. Put the peach in the bowl.",
         {"peach": 1, "bowl": 1}, ("put_in", "peach", "bowl")),
        ("pear + towel, pear onto towel. lights same", {"pear": 1, "towel": 1}, ("put_on", "pear", "towel")),
    ],
)
def test_settings_passives_replacements_brands_anaphora_and_restated_lists(vocab, text, named, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(named), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task, out


def test_a_fuller_name_said_after_the_task_is_not_its_antecedent(vocab):
    out = read_description("The robot should pick up the orange. The other objects are a navel orange and a bowl.", vocab)
    assert out["task"]["source"] == "orange", out


def test_only_these_n_overrides_a_total_and_defaults_reset_earlier_settings(vocab):
    out = read_description("Three objects total: plum, mug and one random thing. Actually, only these two. Pick up the plum.",
                           vocab)
    assert _randoms(out) == 0, out
    out = read_description("A plum. Pick up the plum. Lights 30% brighter. Actually, leave the lighting at default.", vocab)
    assert _light(out) is None, out


def test_corrected_directions_fractions_amount_clauses_and_table_sides(vocab):
    out = read_description("A plum. Pick up the plum. Shift the camera 2 cm to the left -- no, to the right.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, -0.02, 0.0]), out
    out = read_description("A plum. Pick up the plum. Light: up by one fifth. Pan the camera slightly left, 3 degrees.", vocab)
    assert _light(out) == pytest.approx(0.2), out
    camera = _camera(out)
    assert camera is not None and camera[1] == pytest.approx([0.0, 0.0, 3.0]), out
    out = read_description("A plum and a mug. The plum must be on the right of the table. Put the plum in the mug.", vocab)
    assert _where(out, "plum") == {"region": "right"}, out


# -- forms added after the ninth blind held-out set (written for these tests) ---------------------


@pytest.mark.parametrize(
    "text, named, task",
    [
        ("Items (3): plum, mug, fork.\nSetup: dim the lights by a fifth; pan the camera 2 degrees right.\n"
         "Task: put the plum in the mug.", {"plum": 1, "mug": 1, "fork": 1}, ("put_in", "plum", "mug")),
        ("Put a peach, a pear and a towel out. What I want to see at the end is the pear resting on the towel.",
         {"peach": 1, "pear": 1, "towel": 1}, ("put_on", "pear", "towel")),
        ("I need three plums and a bowl. Sorry, just one plum. Put the plum in the bowl.", {"plum": 1, "bowl": 1},
         ("put_in", "plum", "bowl")),
        ("Objects: an apple, a mug and a fork. Actually not the plain apple, use the red apple. Put the red apple "
         "in the mug.", {"red apple": 1, "mug": 1, "fork": 1}, ("put_in", "red apple", "mug")),
        ("Two plums, three dice and a bowl. Pick up a die.", {"plum": 2, "dice": 3, "bowl": 1}, ("pick_up", "die", None)),
    ],
)
def test_kept_keys_end_state_clefts_count_and_object_corrections(vocab, text, named, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(named), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task, out


def test_setup_lines_label_keys_and_clauses_after_a_command(vocab):
    out = read_description("Items (3): plum, mug, fork.\nSetup: dim the lights by a fifth; pan the camera 2 degrees right.\n"
                           "Task: put the plum in the mug.", vocab)
    assert _light(out) == pytest.approx(-0.2) and _camera(out) is not None, out
    out = read_description("id,objects,task,lighting\n12,plum|mug,pick_up(plum),n/a", vocab)
    assert _named(out) == Counter({"plum": 1, "mug": 1}) and _randoms(out) == 0, out
    out = read_description("A plum and a mug. Put the plum in the mug, and raise the camera 2 cm.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.0, 0.02]), out


def test_a_direction_corrected_in_the_next_sentence_and_camera_take_backs(vocab):
    out = read_description("Lights 20% brighter. Sorry, no, darker. A plum; pick up the plum.", vocab)
    assert _light(out) == pytest.approx(-0.2), out
    out = read_description("A plum; pick up the plum. Raise the camera 2 cm... never mind, don't move the camera.", vocab)
    assert _camera(out) is None, out
    out = read_description("A plum; pick up the plum. Camera: move 2 cm left; don't rotate it.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.02, 0.0]), out


@pytest.mark.parametrize(
    "text, placed, unplaced",
    [
        ("Put a mug on the left, and a plum and a pear on the right. Pick up the plum.", ["plum", "pear"], []),
        ("The bowl at the back, with a fork and a knife up at the front. Pick up the fork.", ["fork", "knife"], []),
        ("A mug, a plum and a pear on the right. Pick up the plum.", ["pear"], ["mug", "plum"]),
    ],
)
def test_a_position_after_a_pair_of_its_own_is_said_of_both(vocab, text, placed, unplaced):
    out = read_description(text, vocab)
    for name in placed:
        assert _where(out, name) is not None, (name, out)
    for name in unplaced:
        assert _where(out, name) is None, (name, out)


# -- forms added after the tenth blind held-out set (written for these tests) ---------------------


@pytest.mark.parametrize(
    "text, named, task",
    [
        ("I need scene with one pear and one bowl. The pear is near of the bowl. Robot must to put the pear in the bowl.",
         {"pear": 1, "bowl": 1}, ("put_in", "pear", "bowl")),
        ("Put a plum, a mug and a fork out. Really, the one thing the arm has to do is lift the fork off the table.",
         {"plum": 1, "mug": 1, "fork": 1}, ("pick_up", "fork", None)),
        ("plz: plum + mug. plum in mug.", {"plum": 1, "mug": 1}, ("put_in", "plum", "mug")),
        ("Objects: a plum, a pear, a bowl. First I thought the arm should pick up the plum, but new plan: put the pear "
         "in the bowl instead.", {"plum": 1, "pear": 1, "bowl": 1}, ("put_in", "pear", "bowl")),
    ],
)
def test_learner_prepositions_one_thing_clefts_and_replacing_commands(vocab, text, named, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(named), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task, out


@pytest.mark.parametrize(
    "text, delta",
    [
        ("A plum; pick up the plum. Lights up 40%. Hmm, that is a lot, make it 30%.", 0.3),
        ("A plum; pick up the plum. Darker by a third? No, by a quarter.", -0.25),
        ("A plum; pick up the plum. The room is lit 20% below the default.", -0.2),
    ],
)
def test_amounts_corrected_with_words_between_and_below_the_default(vocab, text, delta):
    out = read_description(text, vocab)
    assert _light(out) == pytest.approx(delta), out


def test_groups_placed_together_random_fillers_and_then_actually(vocab):
    out = read_description("Three cans, a coke can, a pepsi can and a fanta can, lined up at the front. Pick up the coke can.",
                           vocab)
    assert all(_where(out, n) == {"region": "front"} for n in ("coke can", "pepsi can", "fanta can")), out
    out = read_description("Five objects: three are random fillers; the other two are a plum and a mug. Pick up the plum.",
                           vocab)
    assert _named(out) == Counter({"plum": 1, "mug": 1}) and _randoms(out) == 3, out
    out = read_description("A plum; pick up the plum. Camera up 2 cm, then actually down 2 cm.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.0, -0.02]), out


def test_a_translation_vector_is_in_the_cameras_own_frame_like_its_axis_keys(vocab):
    # [x right, y forward, z up], as "x 2 cm" / "dy = 3" are read; the spec's frame is x forward, y left
    out = read_description("objects = [plum]\ntask = pick_up(plum)\ncamera.translate_cm = [1, 2, 3]", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.02, -0.01, 0.03]), out


# -- forms added after the eleventh blind held-out set (written for these tests) ------------------


@pytest.mark.parametrize(
    "text, named, task",
    [
        ("plum L, pear R, mug back. pick up plum.", {"plum": 1, "pear": 1, "mug": 1}, ("pick_up", "plum", None)),
        ("put_on: plum, towel\nobjects: plum, towel, fork", {"plum": 1, "towel": 1, "fork": 1}, ("put_on", "plum", "towel")),
        ("The plum gets put in the bowl. On the table: a plum, a bowl and a fork.", {"plum": 1, "bowl": 1, "fork": 1},
         ("put_in", "plum", "bowl")),
        ("The episode ends with the pear inside the mug. Also on the table: a fork.", {"fork": 1}, ("put_in", "pear", "mug")),
        ("A fork and a golf ball (golf ball at the back). Pick up the golf ball.", {"fork": 1, "golf ball": 1},
         ("pick_up", "golf ball", None)),
        ("Objects: green lego brick, pink lego brick, towel. Move the pink brick next to the towel - no, the green one.",
         {"green lego brick": 1, "pink lego brick": 1, "towel": 1}, ("move_near", "green lego brick", "towel")),
    ],
)
def test_side_letters_task_keys_get_passives_ends_with_and_one_corrections(vocab, text, named, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(named), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task, out


@pytest.mark.parametrize(
    "text, delta",
    [
        ("A plum; pick up the plum. Lights up thirty five percent.", 0.35),
        ("A plum; pick up the plum. Lighting, I'd say drop it by 10 percent.", -0.1),
        ("A plum; pick up the plum. 40% brighter - wait, no, darker. And 40% is too much, say 25%.", -0.25),
    ],
)
def test_compound_numbers_drop_and_corrections_in_a_row(vocab, text, delta):
    out = read_description(text, vocab)
    assert _light(out) == pytest.approx(delta), out


def test_a_motion_verb_that_introduces_axis_values_adds_no_default(vocab):
    out = read_description("A plum; pick up the plum. Rotate the camera: pitch +2, yaw -4.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[1] == pytest.approx([0.0, -2.0, 4.0]), out


# -- forms added after the twelfth blind held-out set (written for these tests) -------------------


@pytest.mark.parametrize(
    "text, named, task",
    [
        ("We want a plum, a bowl and a fork. What we actually want is the plum ending up in the bowl.",
         {"plum": 1, "bowl": 1, "fork": 1}, ("put_in", "plum", "bowl")),
        ("five things: three plums, a mug and a fork. one of the plums goes into the mug.", {"plum": 3, "mug": 1, "fork": 1},
         ("put_in", "plum", "mug")),
        ("Two pears and a towel. One pear should go on the towel.", {"pear": 2, "towel": 1}, ("put_on", "pear", "towel")),
        ("A mug and a pepsi can. The pepsi can should end up near the mug.", {"mug": 1, "pepsi can": 1},
         ("move_near", "pepsi can", "mug")),
    ],
)
def test_actual_wishes_one_of_the_goes_and_ends_up_near(vocab, text, named, task):
    out = read_description(text, vocab)
    assert _named(out) == Counter(named), out
    t = out["task"]
    assert (t["type"], t["source"], t.get("target")) == task, out


def test_restated_amounts_factors_halving_and_long_units(vocab):
    out = read_description("A plum; pick up the plum. Camera: move it 2 cm forward. Hmm, no, 4 cm forward.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.04, 0.0, 0.0]), out
    out = read_description("A plum; pick up the plum. Lights 1.5x, correction: 1.3x.", vocab)
    assert _light(out) == pytest.approx(0.3), out
    out = read_description("A plum; pick up the plum. Dim it by about a third? Let's just say 25%.", vocab)
    assert _light(out) == pytest.approx(-0.25), out
    out = read_description("A plum; pick up the plum. Lighting: halve the brightness. Camera: raise it by half a centimetre.",
                           vocab)
    assert _light(out) == pytest.approx(-0.5), out
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.0, 0.0, 0.005]), out
    out = read_description("A plum; pick up the plum. The camera go more close to the table 2 cm.", vocab)
    camera = _camera(out)
    assert camera is not None and camera[0] == pytest.approx([0.02, 0.0, 0.0]), out
