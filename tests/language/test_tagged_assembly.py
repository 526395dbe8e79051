"""The scene from tagged phrases (the assembly on hand-written tags, no model involved)."""

from __future__ import annotations

from typing import Any

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.scene.tagged import assemble
from ladev_lib.language.scene.words import Vocabulary
from ladev_lib.language.tagging.markup import parse_markup
from ladev_lib.scenes.text_to_scene import object_listing


@pytest.fixture(scope="module")
def vocab() -> Vocabulary:
    return Vocabulary.from_objects(object_listing(load_catalog(None)))


def read(annotated: str, vocab: Vocabulary, **kw: Any) -> dict[str, Any]:
    text, spans = parse_markup(annotated)
    return assemble(text, spans, vocab, **kw)


_VOCAB = Vocabulary.from_objects(object_listing(load_catalog(None)))
_NAME = {**{n: _VOCAB.ids[cid] for n, cid in _VOCAB.name_ids.items()}, **{d: d for d in _VOCAB.ids.values()}}


def name(said: str | None) -> str | None:
    """The catalog's display name of what the reader wrote (a synonym, a display name), or the words."""
    return _NAME.get(said, said) if said is not None else None


def objects(ops: dict[str, Any]) -> list[str | None]:
    return [name(op["object"]) for op in ops["operations"] if op["op"] == "add_object"]


def positions(ops: dict[str, Any]) -> dict[str, Any]:
    out = {}
    for op in ops["operations"]:
        if op["op"] == "add_object" and op["object"]:
            where = dict(op["position"]) if op.get("position") else None
            if where and "reference" in where:
                where["reference"] = name(where["reference"])
            out[name(op["object"])] = where
    return out


def task(ops: dict[str, Any]) -> dict[str, Any]:
    t = dict(ops["task"])
    return {**t, "source": name(t.get("source")), "target": name(t.get("target"))}


def test_objects_counts_and_the_task(vocab):
    ops = read("[[Two plums|OBJ]], [[a mug|OBJ]] and [[one Jell-O box|OBJ]]; put [[a plum|SRC]] [[in|IN]] [[the mug|TGT]].", vocab)
    assert objects(ops) == ["plum", "plum", "mug", "gelatin box"]  # the Jell-O box by its synonym
    assert task(ops) == {"type": "put_in", "source": "plum", "target": "mug"}


def test_a_taken_back_object_is_not_there_and_a_later_name_replaces_it(vocab):
    ops = read("[[a fork|OBJ]], [[a knife|OBJ]] and [[a bowl|OBJ]]. Actually leave out [[the knife|DROP]]. "
               "[[Lift|PICK]] [[the fork|SRC]].", vocab)
    assert objects(ops) == ["fork", "bowl"]


def test_the_task_objects_are_in_the_scene_even_when_only_the_task_names_them(vocab):
    ops = read("[[A lemon|OBJ]]. Move [[the banana|SRC]] [[next to|NEAR]] [[the lemon|TGT]].", vocab)
    assert sorted(objects(ops)) == ["banana", "lemon"]
    assert ops["task"]["type"] == "move_near"


def test_a_total_fills_up_with_random_objects(vocab):
    ops = read("[[Five things|TOTAL]]: [[a pear|OBJ]], [[a plate|OBJ]] and [[whatever else|ANY]]. "
               "Set [[the pear|SRC]] [[on|ON]] [[the plate|TGT]].", vocab)
    assert objects(ops).count(None) == 3 and len(objects(ops)) == 5


def test_named_members_of_a_random_group_are_part_of_it(vocab):
    ops = read("[[four random items|ANY]], one of them [[a padlock|OBJ]], and [[a basket|OBJ]] too. "
               "Drop [[the padlock|SRC]] [[into|IN]] [[the basket|TGT]].", vocab)
    assert objects(ops).count(None) == 3 and len(objects(ops)) == 5


def test_random_words_without_a_count(vocab):
    none = read("[[a spoon|OBJ]], [[no random extras|ANY]]. [[grab|PICK]] [[the spoon|SRC]]", vocab)
    assert objects(none) == ["spoon"]
    counted = read("[[Random objects|ANY]]: [[three|TOTAL]]. Named: [[a peach|OBJ]]. [[pick up|PICK]] [[the peach|SRC]]", vocab)
    assert objects(counted).count(None) == 3


def test_a_count_header_introduces_its_members(vocab):
    ops = read("Two blocks, [[a yellow one|OBJ]] and [[a green one|OBJ]]; stack [[the green one|SRC]] [[on|ON]] "
               "[[the yellow one|TGT]].", vocab)
    assert objects(ops) == ["yellow cube", "green cube"]
    assert task(ops) == {"type": "put_on", "source": "green cube", "target": "yellow cube"}
    tagged_header = read("[[three Duplo bricks|OBJ]]: [[a pink|OBJ]], [[a blue|OBJ]] and [[a yellow|OBJ]]. "
                         "[[lift|PICK]] [[the blue one|SRC]]", vocab)
    assert objects(tagged_header) == ["pink lego brick", "blue lego brick", "yellow lego brick"]


def test_positions_before_after_and_for_a_group(vocab):
    ops = read("[[A coffee can|OBJ]] [[at the back|POS]]; [[on the right|POS_NEXT]], [[a sponge|OBJ]]; "
               "[[a pear|OBJ]] and [[a plum|OBJ]] [[both in the middle|POS_ALL]]. [[pick up|PICK]] [[the pear|SRC]].", vocab)
    where = positions(ops)
    assert where["coffee can"] == {"region": "back"} and where["sponge"] == {"region": "right"}
    assert where["pear"] == where["plum"] == {"region": "center"}


def test_a_relation_to_another_object_and_a_pronoun_reference(vocab):
    ops = read("[[a bowl|OBJ]] [[in the centre|POS]] with [[a spoon|OBJ]] [[beside|POS]] [[it|REF]]. "
               "[[pick up|PICK]] [[the spoon|SRC]]", vocab)
    assert positions(ops)["spoon"] == {"relation": "near", "reference": "bowl"}


def test_a_later_position_corrects_an_earlier_one(vocab):
    ops = read("[[a peach|OBJ]] [[on the left|POS]] and [[a lemon|OBJ]] [[on the right|POS]] - no, swap them: "
               "[[the peach|REF]] [[on the right|POS]], [[the lemon|REF]] [[on the left|POS]]. "
               "[[lift|PICK]] [[the lemon|SRC]]", vocab)
    assert positions(ops) == {"peach": {"region": "right"}, "lemon": {"region": "left"}}


def test_the_task_named_by_a_shorter_name_is_the_described_object(vocab):
    ops = read("[[a red plate|OBJ]] and [[a strawberry|OBJ]]; put [[the strawberry|SRC]] [[on|ON]] [[the plate|TGT]]", vocab)
    assert task(ops)["target"] == "red plate"
    assert objects(ops) == ["red plate", "strawberry"]


def test_a_cancelled_destination_is_no_destination(vocab):
    ops = read("[[a carrot|OBJ]], [[a basket|OBJ]], [[a towel|OBJ]]. Put [[the carrot|SRC]] [[in|IN]] [[the basket|TGT]], "
               "not on [[the towel|TGT]].", vocab)
    assert task(ops) == {"type": "put_in", "source": "carrot", "target": "basket"}


def test_an_object_the_catalog_lacks_is_kept_by_name_never_replaced(vocab):
    ops = read("[[a wine glass|OBJ]] and [[a pear|OBJ]]; drop [[the pear|SRC]] [[into|IN]] [[the wine glass|TGT]]", vocab)
    assert "wine glass" in objects(ops)
    assert task(ops)["target"] == "wine glass"


def test_lighting_and_camera_from_the_words_that_hold(vocab):
    ops = read("[[a mug|OBJ]]. [[Lights 40%|LIGHT]] brighter, wait, no, [[darker|LIGHT]]. "
               "[[Camera: pan right|CAM]] 6 degrees - sorry, [[3 degrees|CAM]], and [[lower it 5 mm|CAM]]. "
               "[[pick up|PICK]] [[the mug|SRC]]", vocab)
    light = [op for op in ops["operations"] if op["op"] == "set_lighting"]
    cam = [op for op in ops["operations"] if op["op"] == "move_camera"]
    assert light == [{"op": "set_lighting", "intensity_delta": -0.4}]
    assert len(cam) == 1
    assert cam[0]["rotation_deg"] == [0.0, 0.0, -3.0]  # pan right is negative yaw in the spec frame
    assert cam[0]["translation_m"] == pytest.approx([0.0, 0.0, -0.005])


def test_an_explicit_instruction_wins_over_the_text(vocab):
    ops = read("[[a plum|OBJ]] and [[a bowl|OBJ]]; [[pick up|PICK]] [[the plum|SRC]]", vocab,
               instruction="put the plum in the bowl")
    assert ops["task"]["type"] == "put_in"


def test_nothing_tagged_is_an_error_with_a_reason(vocab):
    ops = read("Good morning, hope the weekend went well.", vocab)
    assert "error" in ops


def test_a_pair_that_opens_its_clause_shares_its_position(vocab):
    ops = read("[[2|TOTAL]] cans and a lemon, wait: [[3|TOTAL]]. [[A lemon|OBJ]] [[on the left|POS]]; [[a Coke can|OBJ]] and "
               "[[a Fanta can|OBJ]] [[at the back|POS]]. [[lift|PICK]] [[the lemon|SRC]]", vocab)
    where = positions(ops)
    assert where["coke can"] == where["fanta can"] == {"region": "back"}
    longer = read("[[a fork|OBJ]], [[a mug|OBJ]] and [[a spoon|OBJ]] [[on the right|POS]]. [[lift|PICK]] [[the fork|SRC]]", vocab)
    assert positions(longer)["mug"] is None  # the last of a longer list only


def test_taking_back_words_before_an_object(vocab):
    ops = read("[[a plum|OBJ]], [[a peach|OBJ]] and [[a bowl|OBJ]]. Hmm, remove [[the peach|REF]]. "
               "Not [[a bowl|OBJ]] either - [[a basket|OBJ]]. Put [[the plum|SRC]] [[in|IN]] [[the basket|TGT]].", vocab)
    assert objects(ops) == ["plum", "basket"]


def test_an_object_said_again_after_a_correction_is_the_same_one(vocab):
    ops = read("[[A marker|OBJ]] and [[a mug|OBJ]]. Not [[a cup|DROP]], [[a mug|OBJ]]. Drop [[the marker|SRC]] "
               "[[into|IN]] [[the mug|TGT]].", vocab)
    assert objects(ops) == ["marker", "mug"]


def test_members_named_after_the_group(vocab):
    ops = read("[[Any three objects|TOTAL]], as long as [[a sponge|OBJ]] is among them. [[pick up|PICK]] [[the sponge|SRC]]",
               vocab)
    assert len(objects(ops)) == 3 and objects(ops).count(None) == 2
    listed = read("[[5 things of your choice|ANY]], which must include [[a plum|OBJ]] and [[a bowl|OBJ]]. Put [[the plum|SRC]] "
                  "[[in|IN]] [[the bowl|TGT]].", vocab)
    assert len(objects(listed)) == 5


def test_drop_without_a_destination_takes_the_object_out(vocab):
    ops = read("Put [[the lemon|SRC]] [[on|ON]] [[the towel|TGT]]. Objects: [[lemon|OBJ]], [[towel|OBJ]], [[pear|OBJ]]. "
               "Drop [[the pear|SRC]].", vocab)
    assert sorted(objects(ops)) == ["lemon", "towel"] and task(ops)["source"] == "lemon"


def test_a_replaced_object_named_again_in_a_corrected_task_stays_out(vocab):
    ops = read("[[a carrot|OBJ]] and [[a bowl|OBJ]]; swap [[the bowl|DROP]] for [[a basket|OBJ]]. Put [[the carrot|SRC]] "
               "[[in|IN]] [[the bowl|REF]] - I mean [[in|IN]] [[the basket|TGT]].", vocab)
    assert sorted(objects(ops)) == ["basket", "carrot"] and task(ops)["target"] == "basket"


def test_a_position_taken_back_keeps_its_object(vocab):
    ops = read("[[A peach|OBJ]] [[near|POS]] [[the mug|REF]] - no, on the right, not near [[the mug|DROP]]. "
               "[[The mug|REF]] [[goes at the back|POS]]. [[lift|PICK]] [[the peach|SRC]]", vocab)
    assert "mug" in objects(ops)


def test_object_and_destination_in_one_phrase(vocab):
    ops = read("ADD [[pear|OBJ]]\nADD [[bowl|OBJ]]\nTASK [[put_in|IN]] [[pear bowl|SRC]]", vocab)
    assert task(ops) == {"type": "put_in", "source": "pear", "target": "bowl"}


def test_an_arrow_takes_its_relation_from_the_destination(vocab):
    into = read("[[plum|OBJ]], [[basket|OBJ]]; task: [[plum|SRC]] [[->|ON]] [[basket|TGT]]", vocab)
    onto = read("[[plum|OBJ]], [[plate|OBJ]]; task: [[plum|SRC]] [[->|IN]] [[plate|TGT]]", vocab)
    assert task(into)["type"] == "put_in" and task(onto)["type"] == "put_on"


def test_a_corrected_count_replaces_the_first(vocab):
    ops = read("[[Three pears|OBJ]] and [[a mug|OBJ]]. Sorry, just [[two pears|OBJ]]. [[pick up|PICK]] [[a pear|SRC]]", vocab)
    assert objects(ops).count("pear") == 2


def test_remove_it_after_an_object_takes_it_out(vocab):
    ops = read("[[a mug|OBJ]], [[a fork|OBJ]], [[a lemon|OBJ]]. Not [[the fork|REF]], remove it. [[lift|PICK]] [[the lemon|SRC]]",
               vocab)
    assert sorted(objects(ops)) == ["lemon", "mug"]


def test_separate_motions_without_a_second_number_stay_apart(vocab):
    ops = read("[[a mug|OBJ]]. [[Lower the camera 2 cm|CAM]] and [[tilt it up a couple of degrees|CAM]]. "
               "[[pick up|PICK]] [[the mug|SRC]]", vocab)
    cam = [op for op in ops["operations"] if op["op"] == "move_camera"][0]
    assert cam["translation_m"] == pytest.approx([0.0, 0.0, -0.02]) and cam["rotation_deg"][1] == pytest.approx(-2.0)


# -- the assembly read against its own training rows' tags (benchmarks/eval_reader_parts.py): lists, groups,
# -- pronouns, spelling and names of things the catalog lacks, each in words of our own


def test_a_list_of_counted_objects_is_no_header_and_its_members(vocab):
    ops = read("[[Three golf balls|OBJ]], [[two dice|OBJ]] and [[a mug|OBJ]]; [[lift|PICK]] [[a die|SRC]].", vocab)
    assert sorted(o for o in objects(ops) if o) == ["dice", "dice", "golf ball", "golf ball", "golf ball", "mug"]
    header = read("[[two fizzy cans|OBJ]], [[a Fanta|OBJ]] and [[a Pepsi|OBJ]]; [[grab|PICK]] [[the Fanta|SRC]]", vocab)
    assert objects(header) == ["fanta can", "pepsi can"]  # members of the plural's kind: a header, no more objects


def test_plurals_the_catalog_spells_otherwise_and_counts_said_in_words(vocab):
    assert objects(read("[[2 knives|OBJ]] and [[three strawberries|OBJ]]; [[pick up|PICK]] [[a knife|SRC]]", vocab)) == [
        "knife", "knife", "strawberry", "strawberry", "strawberry"]
    for said, n in (("[[pair of lemons|OBJ]]", 2), ("[[plum x3|OBJ]]", 3), ("[[pear,2|OBJ]]", 2),
                    ("[[{item: peach, qty: 4}|OBJ]]", 4), ("[[some apples, four or so|OBJ]]", 4),
                    ("[[A few dice - five|OBJ]]", 5)):
        ops = read(f"{said} and [[a bowl|OBJ]]; [[pick up|PICK]] [[the bowl|SRC]]", vocab)
        assert len([o for o in objects(ops) if o != "bowl"]) == n, said


def test_a_plural_without_a_number_replaces_as_many_as_it_replaces(vocab):
    ops = read("[[Three lemons|DROP]] and [[a plate|OBJ]]... no, make [[the lemons|DROP]] [[peaches|OBJ]]. "
               "[[pick up|PICK]] [[a peach|SRC]]", vocab)
    assert objects(ops).count("peach") == 3 and "lemon" not in objects(ops)


def test_an_indefinite_object_moving_into_a_container_is_a_task_without_its_verb(vocab):
    ops = read("[[A mug|OBJ]] and [[two marbles|OBJ]]. [[One marble|SRC]] [[into|IN]] [[the mug|TGT]].", vocab)
    assert task(ops) == {"type": "put_in", "source": "marble", "target": "mug"}
    scene_only = read("[[a fork|SRC]] [[near|NEAR]] [[the plate|TGT]]; camera unchanged", vocab)
    assert "task" not in scene_only and positions(scene_only)["fork"] == {"relation": "near", "reference": "plate"}


def test_things_the_catalog_lacks_are_reported_by_the_name_of_the_thing(vocab):
    ops = read("[[a pair of headphones|OBJ]], [[a set of keys|OBJ]], [[my iPhone|OBJ]] and [[a lunchbox|OBJ]]; "
               "[[pick up|PICK]] [[the headphones|SRC]]", vocab)
    assert objects(ops) == ["headphones", "keys", "smartphone", "lunchbox"]
    assert task(ops)["source"] == "headphones"
    assert objects(read("[[zxqv plorp|OBJ]] and [[a lime|OBJ]]; [[lift|PICK]] [[the lime|SRC]]", vocab)) == ["lime"]


def test_group_members_said_by_their_colour_take_the_group_kind(vocab):
    ops = read("Duplo in two colours ([[pink|OBJ]], [[purple|OBJ]]) and [[a bowl|OBJ]]. Put [[the pink one|SRC]] "
               "[[in|IN]] [[the bowl|TGT]].", vocab)
    assert objects(ops) == ["pink lego brick", "purple lego brick", "bowl"]
    assert task(ops)["source"] == "pink lego brick"
    cups = read("The little cups - [[orange|OBJ]] and [[green|OBJ]] - on the left; the big ones - [[blue|OBJ]] and "
                "[[yellow|OBJ]] - on the right. [[lift|PICK]] [[the orange cup|SRC]]", vocab)
    assert objects(cups) == ["orange cup", "green cup", "large blue cup", "large yellow cup"]
    fruit = read("[[an orange|OBJ]] and [[a plate|OBJ]]; [[grab|PICK]] [[the orange|SRC]]", vocab)
    assert objects(fruit) == ["orange", "plate"]  # an orange by itself is the fruit


def test_the_one_described_by_a_colour_or_size(vocab):
    ops = read("[[a green block|OBJ]], [[a yellow block|OBJ]], [[a mug|OBJ]]. Put [[the yellow block|REF]] on "
               "[[the mug|TGT]] - I mean [[the green one|SRC]].", vocab)
    assert task(ops)["source"] == "green cube"
    bricks = read("[[a purple Duplo brick|OBJ]], [[a blue Duplo brick|OBJ]]; move [[the purple brick|SRC]] "
                  "[[next to|NEAR]] [[the blue one|TGT]]", vocab)
    assert task(bricks) == {"type": "move_near", "source": "purple lego brick", "target": "blue lego brick"}


def test_what_a_pronoun_stands_for(vocab):
    near_group = read("[[A bowl|OBJ]] in the middle. [[A pear|OBJ]] and [[a plum|OBJ]] [[sit next to|POS_ALL]] "
                      "[[it|REF]]. Drop [[the plum|SRC]] [[in|IN]] [[the bowl|TGT]].", vocab)
    assert positions(near_group)["pear"] == {"relation": "near", "reference": "bowl"}
    subject = read("See [[the spoon|OBJ]] [[beside|POS]] [[the pitcher|OBJ]]? [[Lift|PICK]] [[it|SRC]].", vocab)
    assert task(subject)["source"] == "spoon"
    plural = read("[[Three plums|OBJ]] sit [[in front of|POS]] [[a mug|OBJ]]. [[Grab|PICK]] [[one of them|SRC]].", vocab)
    assert task(plural)["source"] == "plum"
    latter = read("[[A lemon|OBJ]] [[on the left|POS]], [[a peach|OBJ]] [[on the right|POS]]. [[Lift|PICK]] "
                  "[[the latter|SRC]].", vocab)
    assert task(latter)["source"] == "peach"
    parallel = read("[[A towel|OBJ]] in the middle: [[a knife|OBJ]] [[to its left|POS]], [[a fork|OBJ]] "
                    "[[to its right|POS]]. [[Pick up|PICK]] [[the fork|SRC]].", vocab)
    assert positions(parallel)["knife"] == {"relation": "left_of", "reference": "towel"}
    assert positions(parallel)["fork"] == {"relation": "right_of", "reference": "towel"}


def test_a_plural_or_collective_reference_places_every_member(vocab):
    ops = read("[[a bowl|OBJ]], [[a fork|OBJ]], [[a spoon|OBJ]] and [[a knife|OBJ]]. [[The cutlery|REF]] "
               "[[on the left|POS]]. [[lift|PICK]] [[the spoon|SRC]]", vocab)
    where = positions(ops)
    assert where["fork"] == where["spoon"] == where["knife"] == {"region": "left"} and where["bowl"] is None


def test_nothing_but_one_object_keeps_that_object(vocab):
    ops = read("Nothing on the table except [[one baseball|OBJ]]. [[lift|PICK]] [[it|SRC]].", vocab)
    assert objects(ops) == ["baseball"] and task(ops)["source"] == "baseball"


def test_misspelt_and_abbreviated_names(vocab):
    ops = read("[[pikc|PICK]] [[teh bannana|SRC]]; also [[a scisors|OBJ]], [[tuna cn|OBJ]], [[lg green cup|OBJ]]", vocab)
    assert objects(ops) == ["scissors", "tuna can", "large green cup", "banana"]
    assert task(ops)["source"] == "banana"


def test_members_named_inside_a_total(vocab):
    ops = read("[[Any six objects|TOTAL]] as long as one is [[a padlock|OBJ]] and one is [[a mug|OBJ]]. "
               "[[padlock|SRC]] [[into|IN]] [[the mug|TGT]].", vocab)
    assert len(objects(ops)) == 6
    chosen = read("[[five things in all|TOTAL]]: [[a pear|OBJ]], [[the other four are up to you|ANY]]. "
                  "[[lift|PICK]] [[the pear|SRC]]", vocab)
    assert len(objects(chosen)) == 5


def test_the_same_name_on_two_placed_lines_is_two_objects(vocab):
    ops = read("ADD [[plum|OBJ]] [[LEFT|POS]]\nADD [[plum|OBJ]] [[RIGHT|POS]]\nADD [[bowl|OBJ]]\n"
               "TASK [[put_in|IN]] [[plum|SRC]] [[bowl|TGT]]", vocab)
    assert objects(ops).count("plum") == 2
    restated = read("[[a towel|OBJ]], [[a lemon|OBJ]]; [[towel|OBJ]]: [[back|POS]]. [[lift|PICK]] [[the lemon|SRC]]", vocab)
    assert objects(restated) == ["towel", "lemon"] and positions(restated)["towel"] == {"region": "back"}


def test_a_camera_value_in_a_table_row_takes_its_column_name(vocab):
    ops = read("id;objects;cam_yaw_deg;cam_dz_cm\n7;[[mug|OBJ]];[[-2|CAM]];[[1.5|CAM]]\n", vocab)
    cam = next(op for op in ops["operations"] if op["op"] == "move_camera")
    assert cam["translation_m"][2] == pytest.approx(0.015) and cam["rotation_deg"][2] == pytest.approx(2.0)


def test_one_and_the_other_of_a_counted_group(vocab):
    ops = read("There are two mugs, [[one|OBJ]] [[on the left|POS]] and [[the other|OBJ]] [[on the right|POS]], plus "
               "[[a lemon|OBJ]]. Drop [[the lemon|SRC]] [[into|IN]] [[the left mug|TGT]].", vocab)
    assert objects(ops) == ["mug", "mug", "lemon"]


def test_so_many_of_each_listed_kind(vocab):
    ops = read("Cans, two of each: [[Sprite|OBJ]] and [[Fanta|OBJ]]; and [[a plate|OBJ]]. [[lift|PICK]] "
               "[[a Sprite|SRC]]", vocab)
    assert sorted(objects(ops)) == ["fanta can", "fanta can", "plate", "sprite can", "sprite can"]
    kinds = read("Balls: [[tennis|OBJ]] and [[golf|OBJ]]; [[pick up|PICK]] [[the golf ball|SRC]]", vocab)
    assert objects(kinds) == ["tennis ball", "golf ball"]


def test_names_said_after_their_adjective_or_with_a_spaced_digit(vocab):
    ops = read("[[one plate red|OBJ]] and [[a 7 Up can|OBJ]]; put [[the 7 Up|SRC]] [[on|ON]] [[red plate|TGT]]", vocab)
    assert objects(ops) == ["red plate", "7up can"]
    assert task(ops) == {"type": "put_on", "source": "7up can", "target": "red plate"}


def test_removed_then_kept_stays(vocab):
    ops = read("[[a pear|OBJ]], [[a mug|OBJ]]. Remove [[the mug|REF]]... actually no, keep it. [[lift|PICK]] "
               "[[the pear|SRC]]", vocab)
    assert objects(ops) == ["pear", "mug"]


def test_one_of_several_picked_out_by_where_it_stands_or_its_size(vocab):
    back = read("Two mugs, [[one|OBJ]] [[at the front|POS]] and [[one|OBJ]] [[at the back|POS]], and [[a tennis ball|OBJ]]. "
                "Put [[the ball|SRC]] [[in|IN]] [[the one at the back|TGT]].", vocab)
    assert task(back) == {"type": "put_in", "source": "tennis ball", "target": "mug"}
    sized = read("[[The large blue cup|OBJ]] [[on the left|POS]]; [[the small blue one|OBJ]] [[on the right|POS]]. Move "
                 "[[the small one|SRC]] [[next to|NEAR]] [[the big one|TGT]].", vocab)
    assert task(sized) == {"type": "move_near", "source": "light blue cup", "target": "large blue cup"}
    former = read("[[A pear|OBJ]] and [[a plum|OBJ]], plus [[a bowl|OBJ]]. Drop [[the former|SRC]] [[into|IN]] "
                  "[[the bowl|TGT]].", vocab)
    assert task(former)["source"] == "pear"


def test_a_group_is_the_words_joined_as_one_list(vocab):
    ops = read("Lay out [[a red plate|OBJ]], then [[a lemon|OBJ]] and [[a plum|OBJ]] [[around it|POS_ALL]]. [[lift|PICK]] "
               "[[the plum|SRC]]", vocab)
    assert positions(ops)["lemon"] == positions(ops)["plum"] == {"relation": "near", "reference": "red plate"}
    assert positions(ops)["red plate"] is None


def test_an_untagged_item_of_a_tagged_list_is_an_object(vocab):
    ops = read("Objects: a stapler, [[a marker|OBJ]] and [[a padlock|OBJ]] ([[3|TOTAL]]). [[lift|PICK]] [[the marker|SRC]]",
               vocab)
    assert objects(ops) == ["stapler", "marker", "padlock"]
    data = read("OBJ: [[bowl|OBJ]]; [[spoon|OBJ]]; headphones\nTASK: [[spoon|SRC]] [[into|IN]] [[bowl|TGT]]", vocab)
    assert objects(data) == ["bowl", "spoon", "headphones"]
    header = read("two pears, [[a green one|OBJ]] and [[a plain one|OBJ]], and [[a bowl|OBJ]]. [[lift|PICK]] "
                  "[[the bowl|SRC]]", vocab)
    assert len(objects(header)) == 3  # a counted plural introduces its members, it is no item of its own


def test_an_untagged_arrow_and_a_destination_phrase_holding_both_names(vocab):
    arrow = read("[[lemon|OBJ]], [[bowl|OBJ]]. Task: [[lemon|SRC]] -> [[bowl|TGT]]", vocab)
    assert task(arrow)["type"] == "put_in"  # into a container
    onto = read("[[pear|OBJ]], [[plate|OBJ]]. Task: [[pear|SRC]] → [[plate|TGT]]", vocab)
    assert task(onto)["type"] == "put_on"
    both = read("[[apple|OBJ]]; [[sponge|OBJ]]\ntask;[[put_on|ON]];[[apple;sponge|TGT]]", vocab)
    assert task(both) == {"type": "put_on", "source": "apple", "target": "sponge"}


def test_a_camera_amount_takes_the_direction_left_between_its_words(vocab):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. [[Camera|CAM]] down 6 cm, sorry, [[2 cm|CAM]].", vocab)
    cam = next(op for op in ops["operations"] if op["op"] == "move_camera")
    assert cam["translation_m"] == pytest.approx([0.0, 0.0, -0.02])


def test_a_description_written_as_code_is_read_as_its_words():
    from ladev_lib.language.scene.tagged import plain_code

    said = "add('pear'); add('bowl', pos='left'); task('put_in', 'pear', 'bowl'); camera(yaw=2)"
    assert plain_code(said) == "add pear ; add bowl, pos left ; task put_in, pear, bowl ; camera yaw 2"
    prose = "Put the pear (the ripe one) in the bowl; camera yaw=2."
    assert plain_code(prose) == prose  # one call-like bracket is no code


def test_a_change_taken_back_after_its_words_is_no_change(vocab):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. Lighting: [[a bit brighter|LIGHT]], actually no change. "
               "[[Camera 2 cm left|CAM]]... no, don't move it.", vocab)
    assert not [op for op in ops["operations"] if op["op"] in ("set_lighting", "move_camera")]


def test_a_corrected_amount_keeps_the_direction_and_axis_said_before(vocab):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. [[Lights|LIGHT]] 30% darker - no, [[make it 10%|LIGHT]]. "
               "Camera: [[pan right 1 degree|CAM]] and roll 2 degrees clockwise; correction, [[roll counterclockwise|CAM]].",
               vocab)
    light = next(op for op in ops["operations"] if op["op"] == "set_lighting")
    cam = next(op for op in ops["operations"] if op["op"] == "move_camera")
    assert light["intensity_delta"] == pytest.approx(-0.1)
    assert cam["rotation_deg"] == pytest.approx([2.0, 0.0, -1.0])  # spec frame: roll, pitch, yaw


def test_make_one_object_another_in_one_phrase(vocab):
    ops = read("Objects: [[a bowl|OBJ]] and [[a knife|DROP]] - hmm, make [[the knife a fork|OBJ]]. [[lift|PICK]] "
               "[[the fork|SRC]]", vocab)
    assert objects(ops) == ["bowl", "fork"]


def test_the_object_left_untagged_before_its_destination_and_fillers_as_random(vocab):
    ops = read("obj: [[pear|OBJ]], [[mug|OBJ]]; task: [[move_near|NEAR]] pear->[[mug|TGT]]", vocab)
    assert task(ops) == {"type": "move_near", "source": "pear", "target": "mug"}
    fill = read("[[Two filler objects|TOTAL]] plus [[a bowl|OBJ]] and [[a plum|OBJ]]. Drop [[the plum|SRC]] [[in|IN]] "
                "[[the bowl|TGT]].", vocab)
    assert objects(fill).count(None) == 2 and len(objects(fill)) == 4


# -- what the words around a phrase say when the tagger's marks do not: replacements, removals, corrections of a
# -- motion, in words of our own (the marks are the kinds of mistakes the tagger makes on held-out text)


def camera(ops: dict[str, Any]) -> tuple[list[float], list[float]]:
    cam = [op for op in ops["operations"] if op["op"] == "move_camera"]
    return (cam[0]["translation_m"], cam[0]["rotation_deg"]) if cam else ([0.0] * 3, [0.0] * 3)


@pytest.mark.parametrize("annotated, kept", [
    # "replace X with Y", "swap X for Y", "substitute Y for X", "X replaced by Y": X goes, Y comes
    ("[[a pear|OBJ]], [[a mug|OBJ]] and [[a fork|OBJ]]. Please replace [[the fork|REF]] with [[a knife|OBJ]]. "
     "[[lift|PICK]] [[the pear|SRC]].", ["pear", "mug", "knife"]),
    ("[[a pear|OBJ]], [[a mug|OBJ]]. Oh, swap [[the mug|REF]] for [[a bowl|DROP]]. [[lift|PICK]] [[the pear|SRC]].",
     ["pear", "bowl"]),
    ("[[a pear|OBJ]], [[a mug|OBJ]]; substitute [[a bowl|OBJ]] for [[the mug|REF]]. [[lift|PICK]] [[the pear|SRC]].",
     ["pear", "bowl"]),
    # a later object in the place of one, outside the sentence of the task
    ("[[a lemon|OBJ]] and [[a plate|OBJ]]. Use [[a towel|OBJ]] instead of [[the plate|REF]]. [[lift|PICK]] "
     "[[the lemon|SRC]].", ["lemon", "towel"]),
    # ruled out after all, or not wanted
    ("[[a lemon|OBJ]], [[a plate|OBJ]] and [[a spoon|OBJ]], though not [[the spoon|REF]] after all. [[lift|PICK]] "
     "[[the lemon|SRC]].", ["lemon", "plate"]),
    ("[[a lemon|OBJ]], [[a plate|OBJ]], [[a spoon|OBJ]]. Do not include [[the spoon|REF]]. [[lift|PICK]] "
     "[[the lemon|SRC]].", ["lemon", "plate"]),
    # "remove X ... leave the lighting as it is": the "leave" is of something else
    ("[[a lemon|OBJ]], [[a plate|OBJ]], [[a spoon|OBJ]]. Remove [[the spoon|REF]]. Light: leave the lighting alone. "
     "[[lift|PICK]] [[the lemon|SRC]].", ["lemon", "plate"]),
])
def test_the_words_around_an_object_say_it_is_replaced_or_removed(vocab, annotated, kept):
    assert sorted(objects(read(annotated, vocab))) == sorted(kept)


def test_remove_then_keep_it_keeps_it(vocab):
    ops = read("[[a lemon|OBJ]], [[a spoon|OBJ]]. Remove [[the spoon|REF]]... no wait, keep it. [[lift|PICK]] "
               "[[the lemon|SRC]].", vocab)
    assert sorted(objects(ops)) == ["lemon", "spoon"]


@pytest.mark.parametrize("annotated, kept", [
    ("Set out [[a mug|OBJ]] (no, make that [[a bowl|OBJ]]) and [[a peach|OBJ]]. [[lift|PICK]] [[the peach|SRC]].",
     ["bowl", "peach"]),
    # as many as the correction names, counted back from it
    ("[[a peach|OBJ]] and [[a mug|OBJ]] on the table, sorry, I mean [[a peach|OBJ]] and [[a bowl|OBJ]]. "
     "[[lift|PICK]] [[the peach|SRC]].", ["peach", "bowl"]),
    ("[[a peach|OBJ]], [[a spoon|OBJ]], [[a mug|OBJ]] -- no, [[a bowl|OBJ]]. [[lift|PICK]] [[the peach|SRC]].",
     ["peach", "spoon", "bowl"]),
    # a new count of one said earlier replaces nothing else
    ("[[one peach|OBJ]] with [[a mug|OBJ]] and [[a spoon|OBJ]]... actually make it [[three peaches|OBJ]]. "
     "[[lift|PICK]] [[a peach|SRC]].", ["peach", "peach", "peach", "mug", "spoon"]),
])
def test_a_correction_right_after_objects_replaces_them(vocab, annotated, kept):
    assert sorted(objects(read(annotated, vocab))) == sorted(kept)


@pytest.mark.parametrize("annotated, kept", [
    # a mark of taking back with no word that takes it back is an object of the scene
    ("[[a banana|DROP]], [[a mug|OBJ]] and [[a spoon|OBJ]]. [[lift|PICK]] [[the banana|SRC]].", ["banana", "mug", "spoon"]),
    # the "no" after it is said of the next one
    ("[[a banana|OBJ]], [[a mug|DROP]]. No, remove [[the spoon|DROP]]... [[lift|PICK]] [[the banana|SRC]].",
     ["banana", "mug"]),
    # a later mention that takes it back, and one after that
    ("[[a banana|DROP]], [[a mug|OBJ]]. Leave out [[the banana|DROP]], it rolls; [[the banana|DROP]] was a bad idea. "
     "[[lift|PICK]] [[the mug|SRC]].", ["mug"]),
])
def test_a_taken_back_mark_needs_words_that_take_it_back(vocab, annotated, kept):
    assert sorted(o for o in objects(read(annotated, vocab)) if o) == sorted(kept)


def test_a_total_that_counted_a_list_follows_a_removal_from_it(vocab):
    ops = read("[[Four objects|TOTAL]]: [[a lemon|OBJ]], [[a mug|OBJ]], [[a fork|OBJ]], [[a towel|OBJ]]. Drop "
               "[[the fork|DROP]]. [[lift|PICK]] [[the lemon|SRC]].", vocab)
    assert objects(ops) == ["lemon", "mug", "towel"]  # no random object in the fork's place
    more = read("[[Five objects|TOTAL]]: [[a lemon|OBJ]], [[a mug|OBJ]], [[a fork|OBJ]]. Drop [[the fork|DROP]]. "
                "[[lift|PICK]] [[the lemon|SRC]].", vocab)
    assert objects(more) == ["lemon", "mug", None, None, None]  # the total did not count the list: it holds


@pytest.mark.parametrize("annotated, translation, rotation", [
    # the amount corrected, the direction said once in untagged words
    ("[[Camera 2 cm|CAM]] towards the table -- no, make it [[4 cm|CAM]].", [0.04, 0.0, 0.0], None),
    ("Camera: 7 cm back -- sorry, that is too far, make it [[3 cm|CAM]].", [-0.03, 0.0, 0.0], None),
    ("[[Shift the camera|CAM]] 2 cm up. Actually, make it [[3|CAM]].", [0.0, 0.0, 0.03], None),
    # the direction corrected, the amount said once
    ("[[Move the camera|CAM]] 2 cm to the left -- no, [[to the right|CAM]].", [0.0, -0.02, 0.0], None),
    ("[[Camera left|CAM]] 3 cm, then actually [[right 3 cm|CAM]].", [0.0, -0.03, 0.0], None),
    ("[[Pitch the camera up|CAM]] 4 degrees, no, [[down 4 degrees|CAM]].", None, [0.0, 4.0, 0.0]),  # down: +pitch here
    ("[[move the camera 2 cm|CAM]] down, I mean [[backward|CAM]].", [-0.02, 0.0, 0.0], None),
    # said again in full after the correction: once
    ("Camera: [[yaw|CAM]] left 2 degrees -- sorry, [[right|CAM]]: [[yaw right 2 degrees|CAM]].", None, [0.0, 0.0, -2.0]),
    # a complete new motion replaces nothing
    ("[[Camera up 2 cm|CAM]]; no, also [[tilt it down 3 degrees|CAM]].", [0.0, 0.0, 0.02], [0.0, 3.0, 0.0]),
    # an axis whose value was left untagged, and "in one go"
    ("[[Camera: yaw 2, roll|CAM]] -3, nothing else.", None, [3.0, 0.0, -2.0]),
    ("Camera: [[forward 2 cm and up 1 cm in|CAM]] one go.", [0.02, 0.0, 0.01], None),
])
def test_a_corrected_camera_motion_is_read_with_its_own_words(vocab, annotated, translation, rotation):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. " + annotated, vocab)
    t, r = camera(ops)
    assert t == pytest.approx(translation or [0.0] * 3)
    assert r == pytest.approx(rotation or [0.0] * 3)


def test_a_corrected_lighting_amount_keeps_the_direction_said_before_it(vocab):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. Lights: 30 % dimmer -- no wait, [[10 %|LIGHT]].", vocab)
    assert [op for op in ops["operations"] if op["op"] == "set_lighting"] == [{"op": "set_lighting", "intensity_delta": -0.1}]


def test_a_lighting_request_taken_back_later_in_its_sentence(vocab):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. [[Brighten|LIGHT]] it by a fifth; actually, never mind, "
               "keep the lighting at default.", vocab)
    assert not [op for op in ops["operations"] if op["op"] == "set_lighting"]


@pytest.mark.parametrize("annotated, expected, kept", [
    # a task written as the schema writes it: its arguments are the task's objects, wherever the tags fell
    ("ADD [[pear|OBJ]]\nADD [[shoebox|OBJ]]\nTASK [[put_in|IN]] [[pear shoebox|TGT]]",
     {"type": "put_in", "source": "pear", "target": "shoebox"}, ["pear", "shoebox"]),
    ("item,qty\n[[mug,1|OBJ]]\n[[lemon,1|OBJ]]\ntask,[[move_near|NEAR]],[[lemon;mug|REF]]",
     {"type": "move_near", "source": "lemon", "target": "mug"}, ["mug", "lemon"]),
    ("spawn [[golf ball|OBJ]]\nspawn [[large blue cup|OBJ]]\ngoal: [[put_in|IN]] golf ball large blue cup",
     {"type": "put_in", "source": "golf ball", "target": "large blue cup"}, ["golf ball", "large blue cup"]),
    # an argument no catalog name covers is one name, however many words
    ("[[pick_up|PICK]],[[stuffed toy|SRC]]\n[[towel|OBJ]]", {"type": "pick_up", "source": "stuffed toy", "target": None},
     ["stuffed toy", "towel"]),
])
def test_a_task_written_as_the_schema_writes_it(vocab, annotated, expected, kept):
    ops = read(annotated, vocab)
    assert task(ops) == expected
    assert sorted(o for o in objects(ops) if o) == sorted(kept)


def test_a_task_literal_does_not_override_a_task_corrected_elsewhere(vocab):
    ops = read("change the destination: it says [[bowl|REF]], I want [[the basket|TGT]].\nobjects: [[apple|OBJ]], "
               "[[bowl|OBJ]], [[basket|OBJ]]\ntask: [[put_in|IN]] [[apple|SRC]] [[bowl|REF]]", vocab)
    assert task(ops) == {"type": "put_in", "source": "apple", "target": "basket"}


def test_a_python_dict_and_a_call_with_keywords_are_read_as_their_words():
    from ladev_lib.language.scene.tagged import plain_code

    said = plain_code("cfg = {'objects': ['pear', 'mug', 'mug'], 'task': ('put_in', 'pear', 'mug'), 'light': None}")
    assert "'" not in said and "pear, mug, mug" in said and "put_in, pear, mug" in said
    call = plain_code("build(objects=['lemon', 'bowl'], task=('put_in', 'lemon', 'bowl'), cam_z=2)")
    assert "objects lemon, bowl" in call and "cam_z 2" in call
    assert plain_code('{"objects": ["pear"], "task": "pick_up pear"}') == '{"objects": ["pear"], "task": "pick_up pear"}'


def light_of(ops: dict[str, Any]) -> list[dict[str, Any]]:
    return [op for op in ops["operations"] if op["op"] == "set_lighting"]


def test_a_corrected_task_whose_destination_is_a_pronoun(vocab):
    ops = read("[[a pear|OBJ]], [[a lemon|OBJ]] and [[a bowl|OBJ]]. Put [[the pear|REF]] in [[the bowl|REF]]. No wait, put "
               "[[the lemon|SRC]] [[in|IN]] [[it|TGT]] instead.", vocab)
    assert task(ops) == {"type": "put_in", "source": "lemon", "target": "bowl"}


def test_an_untagged_pronoun_after_the_relation_is_the_destination(vocab):
    ops = read("[[a peach|OBJ]] and [[a towel|OBJ]]. Set [[the peach|SRC]] [[on|ON]] it.", vocab)
    assert task(ops) == {"type": "put_on", "source": "peach", "target": "towel"}


def test_a_value_under_the_other_settings_key(vocab):
    ops = read("obj: [[mug|OBJ]]; task: [[pick_up|PICK]] [[mug|SRC]]; [[light=-0.2|CAM]]; [[cam: up 1 cm|LIGHT]]", vocab)
    assert light_of(ops) == [{"op": "set_lighting", "intensity_delta": pytest.approx(-0.2)}]
    assert camera(ops)[0] == pytest.approx([0.0, 0.0, 0.01])


@pytest.mark.parametrize("said, delta", [
    ("[[Lighting|LIGHT]] 40% darker... ugh, too dark, go with 10%.", -0.1),
    ("[[Lights|LIGHT]] up by 20 percent.", 0.2),
    # the statement ends at the next tagged phrase
    ("[[lights|LIGHT]] a bit dimmer, [[camera raised 4 cm|CAM]].", None),
])
def test_a_lighting_key_tagged_alone_is_read_with_its_statement(vocab, said, delta):
    ops = read("[[a mug|OBJ]]. [[lift|PICK]] [[the mug|SRC]]. " + said, vocab)
    got = light_of(ops)
    if delta is None:
        assert len(got) == 1 and got[0]["intensity_delta"] < 0
    else:
        assert got == [{"op": "set_lighting", "intensity_delta": pytest.approx(delta)}]


def test_the_surface_the_scene_stands_on_is_no_object(vocab):
    ops = read("[[The tabletop|OBJ]] holds [[a mug|OBJ]] and [[a lemon|OBJ]]; [[lift|PICK]] [[the lemon|SRC]].", vocab)
    assert sorted(objects(ops)) == ["lemon", "mug"] and "unavailable" not in ops


@pytest.mark.parametrize("annotated, kept", [
    # a landmark of a position, the object put there elsewhere
    ("Objects: [[a pear|OBJ]] [[next to|POS]] [[the bowl|OBJ]], [[the bowl|OBJ]], [[a fork|OBJ]]. [[lift|PICK]] "
     "[[the pear|SRC]].", ["pear", "bowl", "fork"]),
    ("add [[lemon|OBJ]] at [[near|POS]] [[plate|OBJ]]\nadd [[plate|OBJ]]\n[[pick_up|PICK]] [[lemon|SRC]]",
     ["lemon", "plate"]),
    # a yes to an object asked about
    ("we need [[a bowl|OBJ]] and maybe [[a spoon|OBJ]]? yeah, [[a spoon|OBJ]] as well. [[lift|PICK]] [[the spoon|SRC]].",
     ["bowl", "spoon"]),
    # rows of a table: each row is an object of its own
    ("item\tplace\n[[pear|OBJ]]\t[[left|POS]]\n[[pear|OBJ]]\t[[right|POS]]\ntask\t[[pick_up|PICK]] [[a pear|SRC]]",
     ["pear", "pear"]),
])
def test_a_landmark_or_an_echo_is_no_second_object(vocab, annotated, kept):
    assert sorted(o for o in objects(read(annotated, vocab)) if o) == sorted(kept)


def test_leave_it_out_and_a_motion_of_the_same_axis_said_again_after_a_correction(vocab):
    ops = read("[[a pear|OBJ]], [[a mug|OBJ]] and [[a fork|OBJ]]; leave [[the fork|REF]] out. [[lift|PICK]] "
               "[[the pear|SRC]]. Camera: [[raise|CAM]] 3 cm, then, correction, [[lower 1 cm|CAM]] instead.", vocab)
    assert sorted(objects(ops)) == ["mug", "pear"]
    assert camera(ops)[0] == pytest.approx([0.0, 0.0, -0.01])
    # another axis after the correction is a motion of its own
    both = read("[[a pear|OBJ]]. [[lift|PICK]] [[the pear|SRC]]. [[Raise the camera 1 cm|CAM]]; no wait, and "
                "[[pan it left 2 degrees|CAM]].", vocab)
    t, r = camera(both)
    assert t == pytest.approx([0.0, 0.0, 0.01]) and r[2] == pytest.approx(2.0)
