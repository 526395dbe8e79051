"""The validator: both checks recorded per candidate, valid only when both hold."""

from __future__ import annotations

import pytest

from ladev_lib.language.parser import InstructionParse
from ladev_lib.language.validator import ParaphraseValidator, structure_mismatch


def test_issue_examples_that_no_threshold_separates(validator):
    verdicts = validator.validate_pairs([
        ("pick up the coke can", "pick up the pepsi can"),
        ("move the apple near the sponge", "move the sponge near the apple"),
        ("pick up the coke can", "could you lift the can of coke"),
        ("put the eggplant in the basket", "toss the aubergine into the bin"),
    ])
    pepsi, swap, coke, aubergine = verdicts
    # similarity alone gets these backwards: the swap scores higher than a true paraphrase
    assert swap.similarity > 0.95 > coke.similarity
    assert pepsi.similarity > coke.similarity
    assert not pepsi.valid and "object changed: coke_can -> pepsi_can" in pepsi.reason
    assert not swap.valid and "roles swapped" in swap.reason
    assert coke.valid and coke.reason is None
    # a catalog synonym lowers raw similarity a lot, not the canonical one
    assert aubergine.similarity < 0.5 < aubergine.canonical_similarity
    assert aubergine.valid


def test_each_check_recorded_and_both_required(bow_embedder):
    v = ParaphraseValidator(bow_embedder, threshold=0.99)
    [verdict] = v.validate("pick up the coke can", ["grab the coke can please"])
    assert verdict.same_structure and not verdict.similar and not verdict.valid
    assert verdict.reason.startswith("similarity")
    v = ParaphraseValidator(bow_embedder, threshold=0.0)
    [verdict] = v.validate("pick up the coke can", ["don't pick up the coke can"])
    assert verdict.similar and not verdict.same_structure and not verdict.valid
    assert "negated" in verdict.reason
    assert 0.0 <= verdict.similarity <= 1.0 + 1e-6


def test_embeds_each_distinct_text_once_and_canonical_forms_only_when_needed(bow_embedder):
    candidates = ["grab the coke can", "lift the can of coke", "grab the coke can"]
    v = ParaphraseValidator(bow_embedder, threshold=0.0)
    verdicts = v.validate("pick up the coke can", candidates)
    assert (bow_embedder.calls, bow_embedder.encoded) == (1, 3)  # original + 2 distinct candidates
    assert all(x.canonical_similarity is None for x in verdicts)  # all above the threshold
    v.validate("pick up the coke can", candidates)
    assert bow_embedder.calls == 1  # cached
    v = ParaphraseValidator(bow_embedder, threshold=1.0)
    verdicts = v.validate("pick up the coke can", candidates)
    # 3 texts again (fresh cache) + the one canonical form that differs: "lift the coke can"
    assert bow_embedder.encoded == 3 + 3 + 1
    assert verdicts[1].canonical_similarity > verdicts[1].similarity
    assert verdicts[1].reason.startswith("similarity")


def test_expected_roles_override_the_originals_reading(bow_embedder):
    v = ParaphraseValidator(bow_embedder, threshold=0.0)
    expected = InstructionParse("pick up the can", "pick_up", "coke_can", None)
    [verdict] = v.validate("pick up the can", ["grab the coke can"], expected=expected)
    assert verdict.valid
    # read alone, "the can" names no one catalog object, so not the coke can
    [verdict] = v.validate("pick up the can", ["grab the coke can"])
    assert not verdict.valid and "object changed" in verdict.reason


def test_scene_objects_reach_the_reader(bow_embedder):
    v = ParaphraseValidator(bow_embedder, threshold=0.0)
    [verdict] = v.validate("pick up the coke can", ["grab the can"], scene_objects=frozenset({"coke_can", "apple"}))
    assert verdict.valid, verdict.reason


@pytest.mark.parametrize(
    ("got", "reason"),
    [
        (("put_on", "carrot", "plate"), None),
        (("move_near", "carrot", "plate"), "task changed: put_on -> move_near"),
        (("put_on", "plate", "carrot"), "roles swapped"),
        (("put_on", "eggplant", "plate"), "object changed: carrot -> eggplant"),
        (("put_on", "carrot", "towel"), "destination changed: plate -> towel"),
    ],
)
def test_structure_mismatch_names_what_changed(got, reason):
    expected = InstructionParse("put the carrot on the plate", "put_on", "carrot", "plate")
    mismatch = structure_mismatch(expected, InstructionParse("x", *got))
    assert mismatch == reason if reason is None else reason in mismatch


def test_threshold_range_is_checked(bow_embedder):
    with pytest.raises(ValueError, match="threshold"):
        ParaphraseValidator(bow_embedder, threshold=1.5)


def test_bf16_similarities_stay_close_to_fp32(minilm):
    pairs = [("pick up the coke can", "could you lift the can of coke"),
             ("put the eggplant in the basket", "toss the aubergine into the bin"),
             ("move the apple near the sponge", "move the sponge near the apple")]
    fp32 = ParaphraseValidator(minilm, precision="fp32").similarities(pairs)
    bf16 = ParaphraseValidator(minilm, precision="bf16").similarities(pairs)
    assert abs(fp32 - bf16).max() < 0.01
    with pytest.raises(ValueError, match="precision"):
        ParaphraseValidator(minilm, precision="fp16")
