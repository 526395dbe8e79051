"""The offline paraphraser: k distinct, seeded sentences that keep the task."""

from __future__ import annotations

import pytest

from ladev_lib.language.instructions import basic_instruction
from ladev_lib.language.paraphrase import offline_paraphrases, sentence_key
from ladev_lib.language.parser import parse_instruction


def test_k_distinct_seeded_and_never_the_original(catalog):
    a = offline_paraphrases("put_on", "carrot", "plate", k=10, seed=0)
    assert len(a) == 10
    assert len({sentence_key(s) for s in a}) == 10
    assert sentence_key("put the carrot on the plate") not in {sentence_key(s) for s in a}
    assert offline_paraphrases("put_on", "carrot", "plate", k=10, seed=0) == a
    assert offline_paraphrases("put_on", "carrot", "plate", k=10, seed=1) != a
    assert offline_paraphrases("put_on", "carrot", "plate", k=0) == []


def test_varies_structure_and_names(catalog):
    sentences = offline_paraphrases("put_in", "eggplant", "basket", k=30, seed=3)
    assert any(s.endswith("?") for s in sentences)
    assert any("aubergine" in s.lower() or "purple eggplant" in s.lower() for s in sentences)
    assert any("bin" in s.lower().split() or "yellow basket" in s.lower() for s in sentences)
    assert len({s.split()[0].lower() for s in sentences}) >= 8  # many different openings


def test_unknown_task_is_a_clear_error():
    with pytest.raises(ValueError, match="unknown task"):
        offline_paraphrases("stack", "carrot", "plate", k=3)


def test_whole_catalog_paraphrases_pass_their_own_validator(all_catalog_cases, catalog, validator):
    """Every paraphrase for the four tasks over the catalog: distinct per set, and valid."""
    pairs = []
    for task, source, target in all_catalog_cases:
        original = basic_instruction(
            task, catalog.get(source).display_name, catalog.get(target).display_name if target else None
        )
        sentences = offline_paraphrases(task, source, target, k=10, seed=0)
        assert len(sentences) == 10, (task, source, target)
        assert len({sentence_key(s) for s in sentences}) == 10, sentences
        pairs += [(original, s) for s in sentences]
    tasks = {t for t, _, _ in all_catalog_cases}
    assert tasks == {"pick_up", "move_near", "put_on", "put_in"}
    assert len(all_catalog_cases) > 150
    verdicts = validator.validate_pairs(pairs)
    failures = [(v.original, v.candidate, v.reason) for v in verdicts if not v.valid]
    assert not failures, failures[:10]


def test_parser_reads_generator_output_in_a_scene(catalog):
    scene = ["carrot", "plate", "sponge", "coke_can"]
    for s in offline_paraphrases("put_on", "carrot", "plate", k=20, seed=5):
        assert parse_instruction(s, scene).roles == ("put_on", "carrot", "plate"), s
