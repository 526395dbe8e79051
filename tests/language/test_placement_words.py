"""Placement words whose meaning depends on the verb and the noun: "to", "above", elided
objects, completed destinations, and synonyms for positions and parts.

Every rule that makes more paraphrases valid is tested beside the meaning changes that must
stay invalid (precision first). Structure only: the bag-of-words embedder with threshold 0.
"""

from __future__ import annotations

import pytest

from ladev_lib.language.frames import read_instruction
from ladev_lib.language.validator import ParaphraseValidator


@pytest.fixture()
def structure(bow_embedder):
    """Verdicts on structure alone (similarity threshold 0)."""
    return ParaphraseValidator(bow_embedder, threshold=0.0)


def _verdict(validator, original: str, candidate: str):
    [verdict] = validator.validate(original, [candidate])
    return verdict


# -- "to" after a carrying verb ----------------------------------------------------


@pytest.mark.parametrize(
    ("text", "task", "destination"),
    [
        ("move the mug to the tray", "put_on", "tray"),
        ("transfer the pear to the plate", "put_on", "plate"),
        ("carry the jar to the top shelf", "put_on", "top shelf"),
        ("bring the apple to the basket", "put_in", "basket"),
        ("take the ketchup to the basket", "put_in", "basket"),
        ("carry the book to the back compartment of the caddy", "put_in", "back compartment"),
        ("move the bowl to the microwave", "put_in", "microwave"),
        ("lift the bowl and move it to the plate", "put_on", "plate"),
    ],
)
def test_carrying_to_a_receptacle_or_surface_puts_it_there(text, task, destination):
    frame = read_instruction(text)
    assert frame.ok, frame.reason
    assert (frame.task, frame.destination.text) == (task, destination)


@pytest.mark.parametrize(
    "text",
    [
        "move the stapler to the laptop",  # not a receptacle
        "bring the sponge over to the apple",
        "shift the lamp over to the monitor",
        "move the mug over to the tray",  # "over to" moves it there, not onto it
        "slide the mug to the tray",  # sliding is not carrying
        "push the bowl towards the plate",
        "move the bowl next to the plate",
    ],
)
def test_to_stays_near_otherwise(text):
    frame = read_instruction(text)
    assert frame.ok and frame.task == "move_near", (text, frame.task, frame.reason)


@pytest.mark.parametrize(
    ("original", "candidate"),
    [
        ("put the mug on the tray", "move the mug to the tray"),
        ("put the apple in the basket", "bring the apple to the basket"),
        ("pick up the ketchup and place it in the basket", "take the ketchup to the basket"),
        ("put the bowl in the microwave", "move the bowl to the microwave"),
        ("move the stapler near the laptop", "move the stapler to the laptop"),
        ("pick up the black bowl next to the cookie box and place it on the plate",
         "move the black bowl near the cookie box to the plate"),
    ],
)
def test_carrying_to_keeps_the_meaning(structure, original, candidate):
    verdict = _verdict(structure, original, candidate)
    assert verdict.valid, verdict.reason


@pytest.mark.parametrize(
    ("original", "candidate", "why"),
    [
        # the project's convention: "to" a plate puts it on the plate, "near" does not
        ("move the bowl near the plate", "move the bowl to the plate", "task changed: move_near -> put_on"),
        ("put the bowl on the plate", "move the bowl near the plate", "task changed: put_on -> move_near"),
        ("put the bowl on the plate", "move the bowl over to the plate", "task changed"),
        ("put the bowl on top of the microwave", "move the bowl to the microwave", "task changed: put_on -> put_in"),
        ("put the apple in the basket", "bring the basket to the apple", "task changed"),  # the apple is no receptacle
        ("put the apple in the bowl", "move the apple to the plate", "task changed"),
        ("put the bowl on the plate", "move the bowl to the tray", "destination changed"),
        ("put the mug on the tray", "move the cup to the tray", ""),
        ("put the mug on the tray", "do not move the mug to the tray", "negated"),
        ("put the mug on the tray", "move the mug to the tray and wipe it", "extra step"),
        ("put the mug on the tray", "bring me the mug", "hands the object to a person"),
    ],
)
def test_carrying_to_meaning_changes_stay_invalid(structure, original, candidate, why):
    verdict = _verdict(structure, original, candidate)
    assert not verdict.valid
    assert why in verdict.reason


# -- "above" after a putting verb -----------------------------------------------------


def test_above_after_a_putting_verb_is_on(structure):
    frame = read_instruction("put the wine bottle above the cabinet")
    assert frame.ok and frame.task == "put_on" and frame.destination.text == "cabinet"
    assert _verdict(structure, "put the bowl on top of the cabinet", "place the bowl above the cabinet").valid


@pytest.mark.parametrize(
    "candidate",
    [
        "put the bowl under the cabinet",
        "put the bowl below the cabinet",
        "put the bowl beneath the cabinet",
        "put the bowl above the stove",
        "put the bowl inside the cabinet",
    ],
)
def test_above_is_not_any_other_relation(structure, candidate):
    assert not _verdict(structure, "put the bowl on top of the cabinet", candidate).valid


# -- "lift X from Y and move (it) to Z" -------------------------------------------------


def test_lift_from_and_move_to_carries_the_lifted_object():
    frame = read_instruction("lift bowl from ramekin and move to plate")
    assert frame.ok, frame.reason
    assert (frame.task, frame.object.text, frame.destination.text) == ("put_on", "bowl", "plate")
    [where] = frame.object.qualifiers
    assert where.relation == "from" and [p.text for p in where.landmarks] == ["ramekin"]


def test_move_without_an_object_is_still_the_robot_moving():
    frame = read_instruction("move to the ladle, grasp it and raise it")
    assert frame.ok and frame.task == "pick_up" and frame.object.text == "ladle"
    assert read_instruction("move to the plate").task is None  # no object: the robot moves


@pytest.mark.parametrize(
    ("candidate", "valid"),
    [
        ("lift bowl from ramekin and move to plate", True),
        ("lift the bowl from the ramekin and move it to the plate", True),
        ("lift the bowl from the stove and move to the plate", False),  # another bowl
        ("lift the bowl from the ramekin and move to the basket", False),  # another destination
        ("lift the bowl from the ramekin and move next to the plate", False),  # another relation
        ("lift the bowl from the ramekin", False),  # no destination
    ],
)
def test_lift_from_move_to_against_the_original(structure, candidate, valid):
    original = "pick up the black bowl on the ramekin and place it on the plate"
    verdict = _verdict(structure, original, candidate)
    assert verdict.valid is valid, verdict.reason


# -- a destination completed by a later clause -------------------------------------------


@pytest.mark.parametrize(
    ("text", "task"),
    [
        ("bring the wine bottle over to the rack and set it on top", "put_on"),
        ("carry the apple over to the basket and drop it inside", "put_in"),
    ],
)
def test_a_later_clause_can_say_how_the_object_ends_at_the_destination(text, task):
    frame = read_instruction(text)
    assert frame.ok and frame.task == task, frame.reason
    assert not frame.object.qualifiers  # "on top" describes no object


@pytest.mark.parametrize(
    "text",
    [
        "bring the wine bottle over to the rack and set it on the shelf",  # another destination
        "move the mug next to the tray and set it on top",  # "next to" is not a way to the tray
        "bring the mug over to the tray and set it down",  # no relation to complete it with
    ],
)
def test_a_later_clause_that_does_not_complete_the_destination_is_an_extra_step(text):
    assert not read_instruction(text).ok


# -- synonyms for positions and parts ---------------------------------------------------


@pytest.mark.parametrize(
    ("original", "candidate"),
    [
        ("pick up the book and place it in the back compartment of the caddy", "put book in rear compartment of caddy"),
        ("pick up the book and place it in the back compartment of the caddy", "set book into back slot of caddy"),
        ("put the eraser in the left compartment of the caddy", "place the eraser into the left slot of the caddy"),
        ("put the pen in the center compartment of the caddy", "drop the pen into the middle section of the caddy"),
        ("put the mug on the upper shelf", "place the mug on the top shelf"),
        ("put the jar on the lower rack", "set the jar down on the bottom rack"),
    ],
)
def test_position_and_part_synonyms_name_the_same_destination(structure, original, candidate):
    verdict = _verdict(structure, original, candidate)
    assert verdict.valid, verdict.reason


@pytest.mark.parametrize(
    ("original", "candidate"),
    [
        ("put the book in the rear compartment of the caddy", "put the book in the front compartment of the caddy"),
        ("put the book in the back compartment of the caddy", "put the book in the front slot of the caddy"),
        ("put the eraser in the left compartment of the caddy", "put the eraser in the right slot of the caddy"),
        ("put the pen in the center compartment of the caddy", "put the pen in the side section of the caddy"),
        ("put the mug on the upper shelf", "put the mug on the lower shelf"),
        ("put the mug on the top shelf", "put the mug on the bottom shelf"),
    ],
)
def test_other_positions_and_parts_stay_other_destinations(structure, original, candidate):
    verdict = _verdict(structure, original, candidate)
    assert not verdict.valid and "destination changed" in verdict.reason


def test_a_side_word_before_a_noun_describes_it():
    assert read_instruction("put the eraser in the right slot of the caddy").destination.text == "right slot"
    assert read_instruction("set book into back slot of caddy").destination.text == "back slot"
    assert read_instruction("put it back on the plate").destination.text == "plate"  # a particle


# -- where the object is: landmarks ---------------------------------------------------------


@pytest.mark.parametrize(
    ("candidate", "valid"),
    [
        ("pick up the black bowl in the middle of the table and place it on plate", True),
        ("move the black bowl at the center of table to the plate", True),
        ("lift the black bowl from the table centre and put it on the plate", True),
        ("pick up the black bowl at the edge of the table and place it on the plate", False),
        ("pick up the black bowl in the corner of the table and place it on the plate", False),
        ("pick up the black bowl on the stove and place it on the plate", False),
        ("pick up the black bowl next to the plate and place it on the plate", False),
    ],
)
def test_positions_on_the_table_as_landmarks(structure, candidate, valid):
    original = "pick up the black bowl from table center and place it on the plate"
    verdict = _verdict(structure, original, candidate)
    assert verdict.valid is valid, verdict.reason


# -- the LLM reader is told the same ------------------------------------------------------


def test_parse_prompt_says_what_to_means(repo_root):
    from ladev_lib.config import compose_config
    from ladev_lib.llm.prompts import load_prompts, render_messages

    prompt = load_prompts(compose_config([], repo_root / "conf"), ["parse_instruction"])["parse_instruction"]
    messages = render_messages(prompt, {"instruction": "move the mug to the tray", "objects": []})
    system = messages[0].content
    assert '"to" after a verb that carries the object' in system
    assert "any other object means move_near" in system and '"above" after a putting verb' in system
    shots = [(u.content, a.content) for u, a in zip(messages[1:-1:2], messages[2:-1:2], strict=True)]
    assert any("to the basket" in u and '"put_in"' in a for u, a in shots)
    assert any("over to the monitor" in u and '"move_near"' in a for u, a in shots)


def test_llm_reader_on_the_offline_backend_reads_to_like_the_parser(repo_root, catalog):
    import ladev_lib.language.offline_jobs  # noqa: F401
    from ladev_lib.config import compose_config
    from ladev_lib.language.llm_jobs import LLMReader
    from ladev_lib.language.parser import parse_instruction
    from ladev_lib.llm.config import LLMConfig, make_client
    from ladev_lib.llm.prompts import load_prompts

    prompt = load_prompts(compose_config([], repo_root / "conf"), ["parse_instruction"])["parse_instruction"]
    llm = LLMConfig()
    reader = LLMReader(make_client(llm, None), prompt, llm, catalog)
    texts = ["bring the apple to the basket", "move the eggplant to the plate", "bring the sponge over to the apple"]
    got = reader.read(texts, [None] * len(texts))
    assert [g.roles for g in got] == [
        ("put_in", "apple", "basket"), ("put_on", "eggplant", "plate"), ("move_near", "sponge", "apple")
    ]
    assert [g.roles for g in got] == [parse_instruction(t).roles for t in texts]
