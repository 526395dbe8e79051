"""Grounding noun phrases on a scene (ids or names) or the catalog; validation on grounded frames."""

from __future__ import annotations

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.frames import NounPhrase, read_instruction
from ladev_lib.language.grounding import Grounder


@pytest.fixture(scope="module")
def grounder(minilm) -> Grounder:
    return Grounder(load_catalog(), minilm)


def np_(text: str, object_id: str | None = None) -> NounPhrase:
    words = text.split()
    return NounPhrase(text, words[-1], tuple(words[:-1]), object_id)


def test_scene_entries_are_ids_or_plain_names(grounder):
    scene = grounder.scene(["024_bowl", "plate", "wine rack", "black bowl"])
    assert [o.key for o in scene] == ["024_bowl", "plate", "wine rack", "black bowl"]
    assert scene[0].catalog_id == "024_bowl" and scene[2].catalog_id is None


def test_exact_head_and_ambiguous(grounder):
    scene = grounder.scene(["024_bowl", "plate"])
    assert grounder.ground(np_("dinner plate", "029_plate"), scene).object_id == "plate"
    assert grounder.ground(np_("mixing bowl"), scene).object_id == "024_bowl"
    two = grounder.scene(["mug", "cup", "sink"])
    g = grounder.ground(np_("cup"), two)
    assert g.object_id == "cup" and g.how == "exact"
    both = grounder.scene(["red folder", "blue folder"])
    amb = grounder.ground(np_("folder"), both)
    assert amb.object_id is None and amb.how == "ambiguous" and "ambiguous" in (amb.reason or "")
    assert grounder.ground(np_("red folder"), both).object_id == "red folder"


def test_a_phrase_not_in_the_scene_is_absent_not_guessed(grounder):
    g = grounder.ground(np_("stapler"), grounder.scene(["mug", "plate"]))
    assert g.object_id is None and g.how == "absent"


def test_a_catalog_object_never_grounds_on_a_different_catalog_object(grounder):
    """Embeddings put 'banana' near 'apple'; the catalog knows they are different objects."""
    fruit = grounder.scene(["apple", "eggplant"])
    g = grounder.ground(np_("banana", "011_banana"), fruit)
    assert g.object_id is None and g.how == "absent" and "011_banana" in (g.reason or "")
    # a phrase the catalog does not read as one object still grounds by embedding
    assert grounder.ground(np_("purple vegetable"), fruit).object_id == "eggplant"


def test_free_phrases_compare_by_head_and_modifiers(grounder):
    same, _, _, _ = grounder.compare(np_("wine bottle"), np_("wine bottle"))
    assert same
    assert grounder.compare(np_("rack"), np_("drying rack"))[0]  # less specific, not different
    assert not grounder.compare(np_("top drawer"), np_("bottom drawer"))[0]
    assert not grounder.compare(np_("black bowl"), np_("white bowl"))[0]
    assert not grounder.compare(np_("cream cheese"), np_("wine bottle"))[0]


@pytest.mark.parametrize(
    ("original", "candidate", "scene", "valid"),
    [
        ("put the bowl on the plate", "put the bowl on the dinner plate", ["024_bowl", "plate"], True),
        ("put the bowl on the plate", "put the bowl on the dinner plate", ["black bowl", "plate"], True),
        ("put the bowl on the plate", "put the bowl on the dinner plate", None, False),  # two plates in the catalog
        ("put the wine bottle on the rack", "set the bottle of wine onto the rack", None, True),
        ("put the wine bottle on the rack", "put the wine bottle on the shelf", None, False),
        ("put the wine bottle on the rack", "put the rack on the wine bottle", None, False),
        ("put the cream cheese in the bowl", "don't put the cream cheese in the bowl", None, False),
        ("put the mug in the sink", "put the cup in the sink", ["mug", "sink", "plate"], True),
        ("put the mug in the sink", "put the cup in the sink", ["mug", "cup", "sink"], False),
        ("pick up the black bowl next to the ramekin and place it on the plate",
         "grab the black bowl beside the ramekin and set it on the plate", None, True),
        ("pick up the black bowl next to the ramekin and place it on the plate",
         "pick up the black bowl on the ramekin and place it on the plate", None, False),
        # sizes and positions stated on both sides must agree, on objects the catalog does not know
        ("pick up the large kettle", "lift the big kettle", None, True),
        ("pick up the large kettle", "pick up the kettle", None, True),  # less specific, not different
        ("pick up the large kettle", "pick up the tiny kettle", None, False),
        ("pick up the left stapler", "grab the stapler on the left", None, True),
        ("pick up the left stapler", "grab the stapler on the right", None, False),
        ("pick up the stapler at the right end of the desk", "pick up the left stapler", None, False),
        ("put the mug in the front drawer", "put the mug in the drawer at the back", None, False),
        ("put the mug next to the left kettle", "put the mug next to the kettle on the left", None, True),
        # a scene settles what the catalog cannot: several catalog bottles, one bottle on this table
        ("pick up the bottle", "grab the bottle", ["bottle", "sponge"], True),
        ("pick up the bottle", "grab the sponge", ["bottle", "sponge"], False),
        # two bowls the catalog reads as its one bowl are two objects of the scene, told by size
        ("put the small bowl in the large bowl", "place the little bowl inside the big bowl",
         ["small bowl", "large bowl", "fork"], True),
        ("put the small bowl in the large bowl", "put the big bowl in the little bowl",
         ["small bowl", "large bowl", "fork"], False),
    ],
)
def test_validator_compares_grounded_frames(validator, original, candidate, scene, valid):
    (v,) = validator.validate_pairs([(original, candidate)], [frozenset(scene) if scene else None])
    assert v.valid == valid, v.reason
    assert v.expected_frame is not None and v.frame is not None and v.groundings
    if not valid:
        assert v.reason


def test_every_verdict_keeps_both_frames_and_groundings(validator):
    (v,) = validator.validate_pairs([("put the bowl on the plate", "put the bowl on the dinner plate")],
                                    [frozenset({"024_bowl", "plate"})])
    assert v.expected_frame == read_instruction("put the bowl on the plate", ["024_bowl", "plate"])
    assert any("dinner plate" in g and "-> plate" in g for g in v.groundings)
