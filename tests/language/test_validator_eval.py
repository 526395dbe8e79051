"""LADEV's validator against similarity alone on the hand-labelled pairs."""

from __future__ import annotations

from collections import Counter

import pytest

from ladev_lib.language.evaluation import evaluate_validator, load_labelled_pairs
from ladev_lib.language.parser import parse_instruction


def test_labelled_set_is_large_and_covers_what_the_issue_lists(repo_root, catalog):
    pairs = load_labelled_pairs(repo_root / "tests/data/paraphrase_pairs.csv")
    assert len(pairs) >= 300
    categories = Counter(p.category for p in pairs if not p.same)
    for needed in ("similar_object_swap", "other_object_swap", "role_swap", "task_change",
                   "destination_change", "negation", "extra_step", "dropped_target"):
        assert categories[needed] >= 5, needed
    assert sum(p.same for p in pairs) >= 150
    originals = [parse_instruction(o) for o in {p.original for p in pairs}]
    assert {o.task for o in originals} == {"pick_up", "move_near", "put_on", "put_in"}
    sets = {catalog.get(o.source).set for o in originals}
    assert sets == {"simpler", "ycb"}


def test_ladev_validator_meets_targets_and_beats_similarity_alone(repo_root, validator):
    pairs = load_labelled_pairs(repo_root / "tests/data/paraphrase_pairs.csv")
    ev = evaluate_validator(pairs, validator)
    assert ev.ladev.precision >= 0.97, ev.errors()[:10]
    assert ev.ladev.recall >= 0.90, ev.errors()[:10]
    # the paper's check, even at the threshold that is best for this very set
    assert ev.similarity_best_f1.f1 <= ev.ladev.f1 - 0.2
    assert ev.similarity_at_recall.precision <= 0.8
    assert ev.similarity_best_f1.fp > 10 * max(ev.ladev.fp, 1)


@pytest.mark.parametrize(
    "name",
    [
        "paraphrase_pairs.csv",
        "paraphrase_pairs_holdout.csv",
        "paraphrase_pairs_open_vocab.csv",
        "paraphrase_pairs_open_vocab_holdout.csv",
        "paraphrase_pairs_open_vocab_holdout2.csv",
        "paraphrase_pairs_open_vocab_holdout3.csv",
    ],
)
def test_every_meaning_change_is_caught(repo_root, validator, name):
    """Object, role, task, destination, negation, extra step, partial: no 'different' pair is valid."""
    pairs = load_labelled_pairs(repo_root / "tests/data" / name)
    verdicts = validator.validate_pairs([(p.original, p.candidate) for p in pairs], [p.scene_objects for p in pairs])
    missed = [(p.category, p.original, p.candidate) for p, v in zip(pairs, verdicts, strict=True) if v.valid and not p.same]
    assert not missed
    assert all(v.reason for p, v in zip(pairs, verdicts, strict=True) if not p.same)
