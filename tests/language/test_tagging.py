"""The span tagger: markup, token labels, constrained decoding, and the committed weights."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from ladev_lib.language.tagging.markup import (
    LABELS,
    TAGS,
    MarkupError,
    Span,
    parse_markup,
    to_markup,
)
from ladev_lib.language.tagging.model import WEIGHTS, _token_spans, decode, read_metadata
from ladev_lib.language.tagging.training import SpanScore, load_examples, token_labels

ROOT = Path(__file__).resolve().parents[2]


def test_markup_gives_the_plain_text_and_the_spans():
    text, spans = parse_markup("[[Two mugs|OBJ]] and [[a pear|OBJ]] [[at the back|POS]]; [[lift|PICK]] [[the pear|SRC]].")
    assert text == "Two mugs and a pear at the back; lift the pear."
    assert [(s.tag, text[s.start:s.end]) for s in spans] == [
        ("OBJ", "Two mugs"), ("OBJ", "a pear"), ("POS", "at the back"), ("PICK", "lift"), ("SRC", "the pear"),
    ]
    assert to_markup(text, spans) == "[[Two mugs|OBJ]] and [[a pear|OBJ]] [[at the back|POS]]; [[lift|PICK]] [[the pear|SRC]]."


@pytest.mark.parametrize("bad", ["[[a mug|THING]]", "[[a [[mug|OBJ]]|OBJ]]", "a mug|OBJ]] here [[x"])
def test_markup_that_cannot_be_read_says_so(bad):
    with pytest.raises(MarkupError):
        parse_markup(bad)


def test_tokens_get_begin_and_inside_labels():
    offsets = [(0, 0), (0, 3), (4, 7), (8, 10), (11, 14), (0, 0)]  # [CLS] put the mug in [SEP]
    spans = [Span("SRC", 4, 10, "the mug")]
    got = token_labels(offsets, spans)
    assert got[0] == -100 and got[-1] == -100
    assert [LABELS[i] for i in got[1:-1]] == ["O", "B-SRC", "I-SRC", "O"]


def _scores(rows: list[dict[str, float]]) -> np.ndarray:
    out = np.full((len(rows), len(LABELS)), -20.0)
    for i, row in enumerate(rows):
        for label, value in row.items():
            out[i, LABELS.index(label)] = value
    return out


def test_decoding_never_starts_a_phrase_inside():
    # the best label alone would be I-OBJ after O; the constrained path begins the phrase instead
    tokens = ["[CLS]", "a", "mug", "[SEP]"]
    offsets = [(0, 0), (0, 1), (2, 5), (0, 0)]
    scores = _scores([{"O": 0}, {"O": -1.0, "I-OBJ": -0.5, "B-OBJ": -0.9}, {"I-OBJ": -0.1}, {"O": 0}])
    labels = decode(scores, tokens, offsets)
    assert [LABELS[i] for i in labels[1:3]] == ["B-OBJ", "I-OBJ"]


def test_a_word_piece_keeps_its_word_label():
    tokens = ["[CLS]", "cheez", "##it", "[SEP]"]
    offsets = [(0, 0), (0, 5), (5, 7), (0, 0)]
    scores = _scores([{"O": 0}, {"B-OBJ": -0.1}, {"O": -0.05, "I-OBJ": -2.0}, {"O": 0}])
    labels = decode(scores, tokens, offsets)
    assert [LABELS[i] for i in labels[1:3]] == ["B-OBJ", "I-OBJ"]


def test_adjacent_pieces_of_one_object_phrase_become_one_phrase():
    text = "drop the pepsi can"
    offsets = [(0, 4), (5, 8), (9, 14), (15, 18)]
    labels = [LABELS.index(x) for x in ("O", "B-DROP", "B-REF", "B-DROP")]
    scores = _scores([{"O": 0}, {"B-DROP": -0.2, "B-REF": -2}, {"B-REF": -0.7, "B-DROP": -0.8}, {"B-DROP": -0.1}])
    spans = _token_spans(text, offsets, labels, ["drop", "the", "pepsi", "can"], scores)
    assert [(s.tag, s.text) for s in spans] == [("DROP", "the pepsi can")]
    # two objects with words between stay two
    spans = _token_spans("a mug and a cup", [(0, 1), (2, 5), (6, 9), (10, 11), (12, 15)],
                         [LABELS.index(x) for x in ("B-OBJ", "I-OBJ", "O", "B-OBJ", "I-OBJ")],
                         ["a", "mug", "and", "a", "cup"], _scores([{"B-OBJ": 0}] * 5))
    assert [s.text for s in spans] == ["a mug", "a cup"]


def test_span_scores_count_exact_spans():
    score = SpanScore()
    gold = [Span("OBJ", 0, 5, "a mug"), Span("POS", 6, 14, "on the left")]
    score.add(gold, [Span("OBJ", 0, 5, "a mug"), Span("POS", 9, 14, "left")])
    table = score.table()
    assert table["OBJ"]["f1"] == 1.0
    assert table["POS"]["precision"] == 0.0 and table["all"]["recall"] == 0.5


def test_the_training_rows_load_and_agree_with_their_guide():
    rows = sorted((ROOT / "training").glob("*/rows_*.jsonl"))
    examples, problems = load_examples(rows)
    assert not problems
    assert len(examples) >= 6000
    assert {s.tag for e in examples for s in e.spans} == set(TAGS)  # every tag is used
    for path in rows:
        row = json.loads(path.read_text(encoding="utf-8").splitlines()[0])
        assert {"id", "annotated"} <= set(row) and ({"expected"} <= set(row) or {"frame"} <= set(row))


def test_the_committed_weights_name_their_encoder_and_labels():
    meta = read_metadata(WEIGHTS)
    assert meta["labels"] == list(LABELS)
    assert meta["encoder"] == "all-MiniLM-L6-v2" and meta["encoder_digest"]
    assert meta["rows"] >= 5000


@pytest.fixture(scope="module")
def tagger():
    from ladev_lib.language.tagging.model import load_tagger

    return load_tagger()


def _tags(tagger, text: str) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for s in tagger.tag(text):
        out.setdefault(s.tag, []).append(s.text)
    return out


@pytest.mark.parametrize("text", [
    "A bowl - no, make that a basket - and a plum. The plum goes into the basket.",
    "Objects: a bowl, no wait, a basket, and a plum. Put the plum in the basket.",
])
def test_the_tagger_reads_a_correction(tagger, text):
    tags = _tags(tagger, text)
    assert "a basket" in tags.get("OBJ", []) and "a bowl" not in tags.get("OBJ", [])
    assert [t.lower() for t in tags.get("SRC", [])] == ["the plum"] and tags.get("TGT") == ["the basket"]
    assert tags.get("IN")


def test_the_tagger_keeps_only_the_lighting_that_holds(tagger):
    text = "Two apples and a mug. Make the lights 30% brighter. Hmm, no, darker. Pick up an apple."
    tags = _tags(tagger, text)
    said = " ".join(tags.get("LIGHT", []))
    assert said.strip().endswith("darker")  # the correction is marked as what holds
    # and the scene read from the marked words is the corrected one: darker by the 30% said first
    from ladev_lib.catalog import load_catalog
    from ladev_lib.language.scene.tagged import read_tagged
    from ladev_lib.language.scene.words import Vocabulary
    from ladev_lib.scenes.text_to_scene import object_listing

    ops = read_tagged(text, Vocabulary.from_objects(object_listing(load_catalog(None))))
    light = [op for op in ops["operations"] if op["op"] == "set_lighting"]
    assert light and light[0]["intensity_delta"] == pytest.approx(-0.3)


def test_long_texts_are_read_in_pieces(tagger):
    filler = "We talked about the demo for a while and nothing here is part of the scene. " * 40
    spans = tagger.tag(filler + "Put a carrot on the plate.")
    assert any(s.tag == "SRC" and s.text == "a carrot" for s in spans)


def test_a_phrase_ends_with_the_word_it_ends_in():
    from ladev_lib.language.tagging.model import _whole_words

    text = "light: {change: -0.3}, ball: rcquetball"
    spans = [Span("LIGHT", 16, 19, text[16:19]), Span("OBJ", 29, 33, text[29:33])]
    assert [s.text for s in _whole_words(text, spans)] == ["-0.3", "rcquetball"]


def test_weights_are_saved_as_half_floats_and_load_back_into_the_module(tmp_path):
    torch = pytest.importorskip("torch")
    from safetensors.torch import load_file

    from ladev_lib.language.tagging.model import save_weights

    class Tiny(torch.nn.Module):
        def __init__(self) -> None:
            super().__init__()
            self.head = torch.nn.Linear(3, 2)

        def trained_state(self) -> dict:
            return {n: t.detach().contiguous() for n, t in self.state_dict().items()}

    module = Tiny()
    path = tmp_path / "w.safetensors"
    save_weights(module, path, {"encoder": "x"})
    state = load_file(str(path))
    assert {t.dtype for t in state.values()} == {torch.float16}
    other = Tiny()
    other.load_state_dict(state)
    assert other.head.weight.dtype == torch.float32
    assert torch.allclose(other.head.weight, module.head.weight, rtol=1e-3, atol=1e-4)
    assert {t.dtype for t in load_file(str(WEIGHTS)).values()} == {torch.float16}  # the committed weights too
