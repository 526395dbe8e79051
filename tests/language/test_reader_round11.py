"""Eleventh round of reader rules, from the misses of paraphrase rounds 11-13 (sentences in our own
words): where an object is carried to, read from what WordNet says that thing is; "carry ... over
to"; a noun's "'s" before a participle; a plural that names one thing ("tongs"); the object with the
phrase's own head noun before a group's; "take X up from Y"; "elevate" and "clasp"."""

from __future__ import annotations

import pytest

from ladev_lib.language.frames import read_instruction
from ladev_lib.language.tokens import words_of
from ladev_lib.language.wordnet import default_nouns


def roles(text: str, scene: list[str] | None = None) -> tuple[str | None, str | None, str | None]:
    frame = read_instruction(text, scene)
    assert frame.ok, frame.reason
    return frame.roles


@pytest.fixture(scope="module", autouse=True)
def _wordnet() -> None:
    if default_nouns() is None:
        pytest.skip("WordNet data not installed")


@pytest.mark.parametrize(("text", "expected"), [
    # a container WordNet knows, and furniture one puts things on
    ("Transfer the swab to the flask.", ("put_in", "swab", "flask")),
    ("Bring the sock to the hamper.", ("put_in", "sock", "hamper")),
    ("Move the cushion to the bench.", ("put_on", "cushion", "bench")),
    ("Take the folder to the desk.", ("put_on", "folder", "desk")),
    # things that are neither stay near
    ("Move the mug to the lamp.", ("move_near", "mug", "lamp")),
    ("Bring the charger to the laptop.", ("move_near", "charger", "laptop")),
])
def test_carried_to_a_thing_by_what_it_is(text, expected):
    assert roles(text) == expected


def test_carrying_over_to_a_receptacle_puts_it_there_moving_over_to_stays_near():
    assert roles("Carry the pear over to the tray.") == ("put_on", "pear", "tray")
    assert roles("Transfer the swab over to the flask.") == ("put_in", "swab", "flask")
    assert roles("Move the pear over to the tray.") == ("move_near", "pear", "tray")


def test_a_nouns_s_before_a_participle_or_a_place_is_a_verb():
    assert words_of("the rag doll's been on the chair") == ["the", "rag", "doll", "has", "been", "on", "the", "chair"]
    assert words_of("the lamp's still on") == ["the", "lamp", "is", "still", "on"]
    assert roles("The rag doll's been on the floor for ages; set it on the shelf, would you?") == (
        "put_on", "rag doll", "shelf")


@pytest.mark.parametrize(("original", "candidate", "valid"), [
    # a plural that names one thing, said in the singular
    ("move the tongs near the pot", "tong, you move it near of the pot", True),
    ("pick up the goggles", "grab the goggle", True),
    # an ordinary plural stays another number, and "glasses" are not a glass
    ("pick up the cup", "pick up the cups", False),
    ("put the glass in the sink", "put the glasses in the sink", False),
])
def test_a_plural_that_names_one_thing(validator, original, candidate, valid):
    assert validator.validate(original, [candidate])[0].valid is valid


def test_the_object_with_the_phrases_own_head_noun(validator):
    scene = ["wooden block", "toy box", "teddy bear"]
    got = validator.validate("put the wooden block in the toy box", ["Into the toy box with the block."], scene_objects=frozenset(scene))
    assert got[0].valid, got[0].reason


@pytest.mark.parametrize(("text", "expected"), [
    ("Take the flask up from the bench.", ("pick_up", "flask", None)),
    ("Please elevate the flask.", ("pick_up", "flask", None)),
    ("Clasp the flask and lift it.", ("pick_up", "flask", None)),
])
def test_picking_up_in_other_words(text, expected):
    assert roles(text) == expected


def test_taking_it_from_somewhere_without_up_is_still_not_read_as_a_pick_up():
    assert read_instruction("take the flask from the bench").task != "pick_up"
