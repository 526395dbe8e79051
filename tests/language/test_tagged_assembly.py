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
