"""The instruction parser: what it reads, and what it refuses to read as the same task."""

from __future__ import annotations

import pytest

from ladev_lib.language.frames import read_instruction
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.language.parser import InstructionParser, parse_instruction


@pytest.mark.parametrize(
    ("text", "roles"),
    [
        # the standard forms, also without articles (SimplerEnv's own instructions)
        ("pick up the coke can", ("pick_up", "coke_can", None)),
        ("pick coke can", ("pick_up", "coke_can", None)),
        ("move blue plastic bottle near pepsi can", ("move_near", "blue_plastic_bottle", "pepsi_can")),
        ("put eggplant into yellow basket", ("put_in", "eggplant", "basket")),
        # verb and relation synonyms, object synonyms
        ("grasp the can of coke", ("pick_up", "coke_can", None)),
        ("How about taking hold of the coca-cola can?", ("pick_up", "coke_can", None)),
        ("slide the apple right next to the dish sponge", ("move_near", "apple", "sponge")),
        ("toss the aubergine into the bin", ("put_in", "eggplant", "basket")),
        ("stack the green block on top of the yellow block", ("put_on", "green_cube", "yellow_cube")),
        ("drop the die into the cup with a handle", ("put_in", "062_dice", "025_mug")),
        ("put the rubik's cube in the bowl", ("put_in", "077_rubiks_cube", "024_bowl")),
        ("lift the seven up can", ("pick_up", "7up_can", None)),
        ("put the orange in the large orange cup", ("put_in", "orange", "065-g_cups")),
        # questions, polite requests, casual speech, context
        ("could you please set the carrot on the plate?", ("put_on", "carrot", "plate")),
        ("would you mind picking up the coke?", ("pick_up", "coke_can", None)),
        ("why don't you pick up the coke can?", ("pick_up", "coke_can", None)),
        ("don't forget to put the carrot on the plate", ("put_on", "carrot", "plate")),
        ("yo, grab that coke real quick", ("pick_up", "coke_can", None)),
        ("using your gripper, lift the cola can off the table", ("pick_up", "coke_can", None)),
        ("pick up the knife carefully, it's sharp", ("pick_up", "032_knife", None)),
        ("There's a coke can on the table. Pick it up.", ("pick_up", "coke_can", None)),
        ("pick up the coke can but don't squeeze it", ("pick_up", "coke_can", None)),
        ("pick up the coke can, not the pepsi can", ("pick_up", "coke_can", None)),
        # relative clauses, "a can of ...", partial names
        ("Please pick up the coke can that is on the table.", ("pick_up", "coke_can", None)),
        ("Place the carrot on the plate that's on the table.", ("put_on", "carrot", "plate")),
        ("Pick up that can of Coca-Cola.", ("pick_up", "coke_can", None)),
        ("grab the mustard", ("pick_up", "006_mustard_bottle", None)),
        # word order, passives, goals, topics
        ("on the plate, put the carrot", ("put_on", "carrot", "plate")),
        ("into the bowl goes the banana", ("put_in", "011_banana", "024_bowl")),
        ("the carrot should go on the plate", ("put_on", "carrot", "plate")),
        ("Could the golf ball be placed on top of the tuna can?", ("put_on", "058_golf_ball", "007_tuna_fish_can")),
        ("I want the mustard bottle next to the cracker box", ("move_near", "006_mustard_bottle", "003_cracker_box")),
        ("the banana on the table, lift it please", ("pick_up", "011_banana", None)),
        ("spoon on the towel, please", ("put_on", "spoon", "towel")),
        ("into the basket with the eggplant, please", ("put_in", "eggplant", "basket")),
        # one task said in two steps
        ("pick up the carrot and put it on the plate", ("put_on", "carrot", "plate")),
        ("grab the apple and set it down next to the sponge", ("move_near", "apple", "sponge")),
        ("move the apple so that it is near the sponge", ("move_near", "apple", "sponge")),
        ("using your gripper, move the banana until it is next to the mug", ("move_near", "011_banana", "025_mug")),
        ("put it on the plate after picking up the carrot", ("put_on", "carrot", "plate")),
        ("put the eggplant into the basket, and let go", ("put_in", "eggplant", "basket")),
        ("put the carrot on the plate and leave it there", ("put_on", "carrot", "plate")),
        ("put the carrot onto the plate, not into the basket", ("put_on", "carrot", "plate")),
    ],
)
def test_reads_faithful_forms(text, roles):
    parse = parse_instruction(text)
    assert parse.ok, parse.reason
    assert parse.roles == roles


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("don't pick up the coke can", "negated"),
        ("you should not pick up the yellow cube", "negated"),
        ("avoid picking up the blue plastic bottle", "negated"),
        ("nobody should pick up the coke can", "negated"),
        ("stop picking up the coke can", "negated"),
        ("the coke can should not be picked up", "negated"),
        ("pick up the coke can with the spoon", "mentions another object: spoon"),
        ("I don't want the carrot on the plate", "negated"),
        ("pick up the coke can and then put it down", "extra step"),
        ("put the eggplant in the basket and then take it out again", "extra step"),
        ("pick up the coke can and sing a song", "extra step: 'sing'"),
        ("pick up the coke can or push it", "alternative action"),
        ("put the carrot down", "without a destination"),
        ("move the apple", "without a destination"),
        ("put the eggplant inside", "no destination object"),
        ("put the carrot on the floor", "destination 'floor' is not an object"),
        # the table is a destination of its own (open vocabulary); the catalog does not name it
        ("put the carrot on the table", "'table' names no known object"),
        ("pick up the coke can and the pepsi can", "more than one object"),
        ("pick up the coke can or the pepsi can", "alternative objects"),
        ("move the green cube near the yellow cube and the sponge", "more than one destination"),
        ("pick up the coke can along with the pepsi can", "mentions another object: pepsi_can"),
        ("pick up the lego", "ambiguous"),
        ("pick up the coke cans", "plural"),
        ("pick up both coke cans", "quantity"),
        ("pick up the coke can twice", "more than once"),
        ("pick up the can", "ambiguous"),
        ("pick up the widget", "'widget' names no known object"),
        ("grab it", "refers to no object"),
        ("hand me the coke can", "hands the object to a person"),
        ("bring me the coke can", "hands the object to a person"),
        ("take the carrot off the plate", "takes the object away"),
        ("take the eggplant out of the basket", "takes the object away"),
        ("knock over the coke can", "not one of the tasks"),
        ("move the pepsi can behind the blue plastic bottle", "none of near / on / in"),
        ("open the drawer", "not one of the tasks"),
        ("peel the banana", "not one of the tasks"),
        ("admire the banana", "no task verb"),
        ("", "empty instruction"),
        ("!!!", "no words"),
    ],
)
def test_says_why_it_is_not_one_clear_task(text, reason):
    parse = parse_instruction(text)
    assert not parse.ok
    assert reason in (parse.reason or "")


def test_role_swaps_and_relation_changes_read_as_what_they_say():
    assert parse_instruction("move the sponge near the apple").roles == ("move_near", "sponge", "apple")
    assert parse_instruction("bring the sponge over to the apple").roles == ("move_near", "sponge", "apple")
    assert parse_instruction("put the plate on the carrot").roles == ("put_on", "plate", "carrot")
    assert parse_instruction("put the carrot near the plate").roles == ("move_near", "carrot", "plate")
    assert parse_instruction("put the eggplant on the basket").roles == ("put_on", "eggplant", "basket")


def test_similar_objects_stay_distinct():
    ids = {parse_instruction(f"pick up the {name}").source for name in
           ("coke can", "pepsi can", "orange", "navel orange", "orange cup", "sponge", "scrub sponge",
            "plate", "red plate", "spoon", "red spoon", "apple", "red apple")}
    assert len(ids) == 13


def test_scene_objects_resolve_head_nouns_and_colours():
    scene = ["coke_can", "apple", "sponge"]
    assert parse_instruction("pick up the can", scene).roles == ("pick_up", "coke_can", None)
    assert parse_instruction("move the can near the fruit", scene).roles == ("move_near", "coke_can", "apple")
    # "red apple" is the YCB apple's name; in a scene with only the (red) SimplerEnv apple it means that one
    assert parse_instruction("pick up the red apple", scene).source == "apple"
    assert parse_instruction("pick up the red apple").source == "013_apple"
    # a name that says another object is not bent to fit the scene
    assert parse_instruction("pick up the pepsi can", scene).source == "pepsi_can"
    cubes = ["green_cube", "yellow_cube"]
    assert parse_instruction("put the green one on the yellow one", cubes).roles == ("put_on", "green_cube", "yellow_cube")
    assert "ambiguous" in (parse_instruction("pick up the cube", cubes).reason or "")
    assert parse_instruction("pick up the green cube", ["yellow_cube"]).source == "green_cube"


def test_every_basic_instruction_of_the_catalog_reads_back(all_catalog_cases, catalog):
    for task, source, target in all_catalog_cases:
        text = basic_instruction(task, catalog.get(source).display_name,
                                 catalog.get(target).display_name if target else None)
        parse = parse_instruction(text)
        assert parse.ok and parse.roles == (task, source, target), (text, parse)


def test_canonical_text_replaces_only_names(catalog):
    parser = InstructionParser(catalog)
    assert parser.canonical_text("Could you lift the Can of Coke?") == "Could you lift the coke can?"
    assert parser.canonical_text("toss the aubergine into the bin") == "toss the eggplant into the basket"
    assert parser.canonical_text("pick up the coke can") == "pick up the coke can"


@pytest.mark.parametrize("said", [
    "put the ladle in the pot full stop",
    "okay robot put the ladle in the pot period thanks",
    "put the ladle in the pot comma thanks",
])
def test_punctuation_said_in_words(said):
    frame = read_instruction(said)
    assert frame.task == "put_in" and frame.reason is None


def test_a_punctuation_word_inside_a_name_stays_a_word():
    from ladev_lib.language.parser import _spoken_punctuation

    assert _spoken_punctuation("set the trial period timer on the tray") == "set the trial period timer on the tray"
