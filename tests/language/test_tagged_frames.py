"""Instruction frames from tagged phrases, and the validator's second reading."""

from __future__ import annotations

import pytest

from ladev_lib.language.tagged_frames import NOTE, frame_from_spans
from ladev_lib.language.tagging.markup import parse_markup


def frame(annotated: str, scene=None):
    text, spans = parse_markup(annotated)
    return frame_from_spans(text, spans, scene)


def test_context_around_the_command_is_no_part_of_the_frame():
    f = frame("The concert went well tonight. Anyway: [[the rosin|SRC]], [[in|IN]] [[the violin case|TGT]], please.")
    assert f.ok and f.task == "put_in"
    assert f.object is not None and f.object.text == "rosin" and f.destination is not None
    assert f.destination.text == "violin case" and NOTE in f.notes


def test_a_step_by_step_version_reads_as_its_last_placement():
    f = frame("Grab [[the crayons|SRC]], carry them over to the box and drop them [[inside|IN]] [[it|TGT]].")
    # a pronoun destination with no named antecedent is a destination the parser cannot read
    assert f.task == "put_in"
    g = frame("Lift [[the lantern|SRC]], bring it over by [[the cooler|TGT]] and put it down [[next to|NEAR]] it.")
    assert g.ok and g.task == "move_near" and g.destination is not None and g.destination.text == "cooler"


def test_a_pronoun_object_takes_the_object_named_before():
    f = frame("There's [[a plum|OBJ]] by the sink; [[pick|PICK]] [[it|SRC]] up.")
    assert f.ok and f.task == "pick_up" and f.object is not None and f.object.text == "plum"


def test_negations_extra_steps_and_other_actions_are_reasons():
    neg = frame("[[don't|NEG]] [[pick up|PICK]] [[the remote|SRC]]")
    assert not neg.ok and neg.negated and "negated" in (neg.reason or "")
    extra = frame("[[rinse the beaker|EXTRA]], then put [[it|SRC]] [[on|ON]] [[the shelf|TGT]]")
    assert not extra.ok and extra.extra_steps == ("rinse the beaker",)
    other = frame("knock over [[the coke can|SRC]]")
    assert other.task == "other" and not other.ok


def test_a_missing_destination_is_named():
    f = frame("[[put|ON]] [[the cup|SRC]] down")
    assert not f.ok and f.dropped_roles == ("destination",)


def test_qualifiers_stay_with_their_object():
    f = frame("could you set [[the notebook on the left|SRC]] [[on|ON]] [[the tray|TGT]]")
    assert f.ok and f.object is not None and f.object.head == "notebook"
    assert any(q.relation for q in f.object.qualifiers) or "left" in f.object.modifiers + (f.object.text,)


@pytest.fixture(scope="module")
def validator():
    from ladev_lib.language.embeddings import load_embedder
    from ladev_lib.language.validator import ParaphraseValidator

    return ParaphraseValidator(load_embedder(), threshold=0.45, precision="fp32")


@pytest.mark.parametrize(
    ("original", "candidate", "same"),
    [
        ("put the rosin in the violin case",
         "The concert went really well tonight, everyone clapped for ages. Anyway: rosin, in the violin case, please.",
         True),
        ("put the mug in the sink", "My meeting starts at three - so please drop the mug into the sink.", True),
        ("put the mug in the sink", "My meeting starts at three - so please don't drop the mug into the sink.", False),
        ("put the mug in the sink", "My meeting starts at three - rinse the mug, then drop it into the sink.", False),
    ],
)
def test_the_second_reading_keeps_precision(validator, original, candidate, same):
    verdict = validator.validate(original, [candidate])[0]
    assert verdict.valid is same, verdict.reason


def test_an_object_joined_to_the_task_object_is_more_than_the_task():
    joined = frame("[[the apple|SRC]] + the pear, [[pick up|PICK]]")
    assert not joined.ok and joined.extra_steps
    both = frame("move both [[the bowl|SRC]] and the cup [[near|NEAR]] [[the plate|TGT]]")
    assert not both.ok
    steps = frame("grab [[the cup|SRC]] and put it [[on|ON]] [[the tray|TGT]]")
    assert steps.ok and steps.task == "put_on"


def test_embedding_threads_do_not_change_verdicts():
    from ladev_lib.language.embeddings import load_embedder
    from ladev_lib.language.validator import ParaphraseValidator

    pairs = [("put the mug in the sink", "could you drop the mug into the sink"),
             ("pick up the apple", "grab the pear"), ("move the pen near the cup", "slide the pen next to the cup")]
    one = ParaphraseValidator(load_embedder(), threshold=0.45, precision="fp32", threads=1).validate_pairs(pairs)
    two = ParaphraseValidator(load_embedder(), threshold=0.45, precision="fp32", threads=2).validate_pairs(pairs)
    assert [round(v.similarity, 4) for v in one] == [round(v.similarity, 4) for v in two]
    assert [v.valid for v in one] == [v.valid for v in two]
