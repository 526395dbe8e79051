"""Tenth round of reader rules: statements before a command (past forms, states, greetings, time
subjects, compound subjects, hedged amounts, interjections), verbless commands after them, end
states with a bare or a fronted subject, the table as a destination, relative clauses that describe
a phrase, conditions and the imperative "be" in polite forms, container nouns before "of", a more
specific word for a scene object's kind, and "put it down there" after carrying it somewhere.
Sentences in our own words."""

from __future__ import annotations

import pytest

from ladev_lib.language.frames import NounPhrase, read_instruction
from ladev_lib.language.grounding import Grounder
from ladev_lib.language.wordnet import default_nouns


def roles(text: str, scene: list[str] | None = None) -> tuple[str | None, str | None, str | None]:
    frame = read_instruction(text, scene)
    assert frame.ok, frame.reason
    return frame.roles


def reason(text: str) -> str:
    frame = read_instruction(text)
    assert not frame.ok
    return frame.reason or ""


# -- statements before the command are context ---------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        # a past form the lexicon lists as no verb, with "again" (what happened, not "do it again")
        ("My nephew left his crayons on the rug again, ugh. Anyway, pick up the stapler.", ("pick_up", "stapler", None)),
        # a regular past form after the subject
        ("My sister painted the fence yesterday, so put the brush in the bucket.", ("put_in", "brush", "bucket")),
        # an irregular past of a listed verb, and a hedged amount ("like twenty minutes" is a time)
        (
            "The bus was late, we waited for like twenty minutes. Anyway, put the pen in the cup.",
            ("put_in", "pen", "cup"),
        ),
        # a compound subject whose first noun is also a verb ("show")
        ("Show time is at eight, so move the lamp near the mirror.", ("move_near", "lamp", "mirror")),
        # a verb's base form after "is" is an adjective ("open"); so is a state in a participle
        ("It's a windy day and the window is open. Move the lamp near the sofa.", ("move_near", "lamp", "sofa")),
        ("The door is closed. Put the broom near the door.", ("move_near", "broom", "door")),
        # a greeting's addressee and a time noun as the subject; learner English "you put ..."
        (
            "Hi robot, tomorrow is a holiday for us, my aunt she arrive soon. So please, you put the cookies inside the jar.",
            ("put_in", "cookies", "jar"),
        ),
    ],
)
def test_statements_before_the_command_are_context(text, expected):
    assert roles(text) == expected


def test_a_verbless_command_after_context():
    # "chalk, in the box, please": a bare noun opening a verbless clause, then its destination
    assert roles("Rehearsal ran long today. Anyway: chalk, in the box, please.") == ("put_in", "chalk", "box")
    assert roles("Sponge, on the rack, thanks.") == ("put_on", "sponge", "rack")


def test_statements_that_still_ask_for_something():
    # a present statement with an additive word asks for more ("the pear is next")
    assert "mentions another object" in reason("The pear is next. Pick up the apple.")
    # an interjection is set off by commas only; a noun in its place stays a noun
    assert "more than one" in reason("Pick up the stapler, the ruler.")
    # the hedge "like" is no wish, but "would like" is
    assert roles("I would like the pen in the cup.") == ("put_in", "pen", "cup")


@pytest.mark.parametrize(
    ("original", "candidate", "valid"),
    [
        ("Put the pen in the drawer.", "My son left his pens everywhere again. Anyway, put the pen in the drawer.", True),
        ("Pick up the stapler.", "My nephew left his crayons on the rug. Pick up the crayons.", False),
        ("Move the lamp near the sofa.", "The window is open, so move the lamp near the window.", False),
    ],
)
def test_context_pairs(validator, original, candidate, valid):
    assert validator.validate(original, [candidate])[0].valid is valid


# -- end states: bare and fronted subjects, the table -------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Notebook goes in the drawer.", ("put_in", "notebook", "drawer")),
        ("Kettle should go on the stove.", ("put_on", "kettle", "stove")),
        # a fronted destination, then the subject and "goes"
        ("Onto the tray the teapot goes, please.", ("put_on", "teapot", "tray")),
        ("Into the bin the wrapper goes.", ("put_in", "wrapper", "bin")),
        # "at the start," opening a sentence says when; the table is a destination
        ("At the start, the kettle should be resting on the table.", ("put_on", "kettle", "table")),
        ("Raise the kettle onto the table.", ("put_on", "kettle", "table")),
    ],
)
def test_end_states_with_bare_or_fronted_subjects(text, expected):
    assert roles(text) == expected


def test_the_table_as_a_landmark_and_the_end_of_a_place():
    # a description's landmark, or a relative clause's, says where the object is
    assert roles("There's a mug on the table. Pick it up.") == ("pick_up", "mug", None)
    assert roles("pick up the mug that is on the table") == ("pick_up", "mug", None)
    # "at the end of the shelf" is a place, not a time
    assert "none of near / on / in" in reason("put the vase at the end of the shelf")


# -- relative clauses describe the phrase before ------------------------------------------------


def test_a_relative_clause_describes_the_phrase_before_it():
    # as "the mug next to the kettle" does
    assert roles("pick up the mug that is next to the kettle") == ("pick_up", "mug", None)
    frame = read_instruction("Put the spoon on the saucer that's on the shelf.")
    assert frame.roles == ("put_on", "spoon", "saucer")
    assert frame.destination is not None and frame.destination.qualifiers[0].landmarks[0].text == "shelf"


# -- politeness: conditions and the imperative "be" ----------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Please grab the ladle, if it's no bother.", ("pick_up", "ladle", None)),
        ("pick up the ladle if that is not a problem", ("pick_up", "ladle", None)),
        # the command inside the "if" clause is still the command
        ("I'd be grateful if you moved the lamp near the sofa.", ("move_near", "lamp", "sofa")),
        ("Be an angel and set the kettle on the stove.", ("put_on", "kettle", "stove")),
        ("Be quick and put the kettle on the stove.", ("put_on", "kettle", "stove")),
    ],
)
def test_conditions_and_the_imperative_be(text, expected):
    assert roles(text) == expected


def test_a_condition_does_not_hide_an_extra_step_or_a_negation():
    assert "extra step" in reason("Please pick up the ladle and, if it isn't too much trouble, wipe it.")
    assert "negated" in reason("Please don't pick up the ladle, if that's alright.")


# -- containers and kinds -------------------------------------------------------------------------


def test_a_container_noun_before_of_makes_one_phrase():
    assert roles("put the sack of potatoes in the cart") == ("put_in", "potatoes sack", "cart")
    assert roles("put the pouch of seeds on the shelf") == ("put_on", "seeds pouch", "shelf")


def test_putting_to_storage_furniture_is_in():
    assert roles("put the jam to the cupboard") == ("put_in", "jam", "cupboard")
    assert roles("place the mug to the tray") == ("put_on", "mug", "tray")
    # "to" anything else stays near
    assert roles("put the mug to the lamp") == ("move_near", "mug", "lamp")


@pytest.fixture(scope="module")
def grounder_wn():
    nouns = default_nouns()
    if nouns is None:
        pytest.skip("WordNet data not installed")
    return Grounder(nouns=nouns)


def np_(text: str) -> NounPhrase:
    words = text.split()
    return NounPhrase(text, words[-1], tuple(words[:-1]))


def test_a_more_specific_word_for_a_scene_objects_kind(grounder_wn):
    # a pouch is a bag; "coffee bag" is a bag WordNet does not know as a compound
    scene = grounder_wn.scene(["coffee bag", "mug", "kettle"])
    g = grounder_wn.ground(np_("beans pouch"), scene)
    assert (g.object_id, g.how) == ("coffee bag", "kind")
    # two bags: which one is not said
    two = grounder_wn.scene(["coffee bag", "flour bag", "mug"])
    assert grounder_wn.ground(np_("beans pouch"), two).how == "ambiguous"
    # a crate is no bag
    assert grounder_wn.ground(np_("beans crate"), scene).object_id is None
    # a catalog name stays its own object, whatever the head of a scene name's compound
    fruit = grounder_wn.scene(["fruit basket", "mug"])
    banana = NounPhrase("banana", "banana", (), "011_banana")
    assert grounder_wn.ground(banana, fruit).object_id is None


# -- "put it down there" after carrying it somewhere ------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("Pick up the vase, bring it over by the window, and put it down there.", ("move_near", "vase", "window")),
        ("Grab the kettle, carry it onto the stove and set it down there.", ("put_on", "kettle", "stove")),
    ],
)
def test_setting_it_down_there_is_the_same_placement(text, expected):
    assert roles(text) == expected


def test_setting_it_down_elsewhere_is_still_a_step():
    assert "extra step" in reason("Pick up the vase, bring it over by the window, and put it down on the sofa.")
