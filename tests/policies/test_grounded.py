"""``grounded`` retrieves the task the instruction asks for, and is fooled like a retriever is.

The cases below were measured with all-MiniLM-L6-v2 (the default model) and
are asserted both ways: right on unambiguous instructions, wrong where a
similar object is present. The printed similarities are in the test ids'
comments for the record.
"""

from __future__ import annotations

import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.embeddings import load_embedder
from ladev_lib.policies.grounded import TaskRetriever, afforded_tasks


@pytest.fixture(scope="module")
def retriever() -> TaskRetriever:
    return TaskRetriever(load_embedder())


def choose(retriever, ids, instruction):
    catalog = load_catalog()
    choice = retriever.choose(instruction, afforded_tasks([(i, catalog.get(i)) for i in ids]))
    c = choice.chosen
    return (c.task, c.source, c.target)


def test_affordances_respect_what_objects_can_do():
    catalog = load_catalog()
    tasks = afforded_tasks([(i, catalog.get(i)) for i in ("apple", "plate", "basket")])
    texts = {t.text for t in tasks}
    assert "put the apple on the plate" in texts and "put the apple in the basket" in texts
    assert "put the plate on the apple" not in texts  # the apple is no support
    assert "put the apple in the plate" not in texts  # the plate is no container
    assert all(t.target is None for t in tasks if t.task == "pick_up")
    assert {t.source for t in tasks if t.task == "pick_up"} <= {"apple", "plate", "basket"}


@pytest.mark.parametrize(
    ("objects", "instruction", "expected"),
    [
        # the basic form, with a look-alike on the table (1.000 vs 0.840)
        (["coke_can", "pepsi_can"], "pick up the coke can", ("pick_up", "coke_can", None)),
        # paraphrases (0.902, 0.967, 0.775, 0.810)
        (["coke_can", "pepsi_can"], "grab the can of coke", ("pick_up", "coke_can", None)),
        (["coke_can", "apple", "plate"], "place the apple onto the plate", ("put_on", "apple", "plate")),
        (["apple", "orange", "basket"], "drop the citrus fruit into the basket", ("put_in", "orange", "basket")),
        (["spoon", "towel", "sponge"], "place the spoon onto the cloth", ("put_on", "spoon", "towel")),
        # the move/put distinction (1.000 vs 0.881)
        (["coke_can", "apple", "plate"], "move the apple near the plate", ("move_near", "apple", "plate")),
    ],
)
def test_right_task_on_unambiguous_instructions(retriever, objects, instruction, expected):
    assert choose(retriever, objects, instruction) == expected


@pytest.mark.parametrize(
    ("instruction", "alone", "with_lookalike", "right", "fooled"),
    [
        # eggplant + apple -> eggplant (0.516); eggplant + carrot -> carrot (0.688 vs 0.516)
        ("pick up the purple vegetable", ["eggplant", "apple"], ["eggplant", "carrot"], "eggplant", "carrot"),
        # carrot + apple -> carrot (0.640); carrot + orange -> the orange (0.741)
        ("grab the orange vegetable", ["carrot", "apple"], ["carrot", "orange"], "carrot", "orange"),
        # fanta alone -> fanta (0.321); fanta + orange -> the orange (0.778)
        ("pick up the orange soda", ["fanta_can"], ["fanta_can", "orange"], "fanta_can", "orange"),
    ],
)
def test_fooled_where_a_similar_object_is_present(retriever, instruction, alone, with_lookalike, right, fooled):
    assert choose(retriever, alone, instruction)[1] == right
    assert choose(retriever, with_lookalike, instruction)[1] == fooled


def test_a_role_swap_is_read_as_the_afforded_task(retriever):
    # "put the plate on the carrot" is not afforded; the nearest afforded task swaps the roles back.
    assert choose(retriever, ["carrot", "plate", "sponge"], "put the plate on the carrot") == (
        "put_on", "carrot", "plate",
    )


def test_candidate_embeddings_are_cached(retriever):
    catalog = load_catalog()
    tasks = afforded_tasks([(i, catalog.get(i)) for i in ("apple", "plate")])
    retriever.choose("pick up the apple", tasks)
    cached = len(retriever._cache)
    retriever.choose("put the apple on the plate", tasks)
    assert len(retriever._cache) == cached


# -- the reader mode (the default) -------------------------------------------------


@pytest.fixture(scope="module")
def reader():
    from ladev_lib.language.grounding import Grounder
    from ladev_lib.policies.grounded import TaskReader

    catalog = load_catalog()
    return TaskReader(catalog, Grounder(catalog, load_embedder()))


def read(reader, ids, instruction):
    catalog = load_catalog()
    reading = reader.read(instruction, [(i, catalog.get(i)) for i in ids])
    t = reading.task
    return (t.task, t.source, t.target) if t else reading.reason


@pytest.mark.parametrize(
    ("objects", "instruction", "expected"),
    [
        (["coke_can", "pepsi_can"], "grab the can of coke", ("pick_up", "coke_can", None)),
        (["carrot", "plate"], "put the carrot on the dinner plate", ("put_on", "carrot", "plate")),
        (["carrot", "orange", "basket"], "I'd like the carrot to end up in the basket", ("put_in", "carrot", "basket")),
        (["eggplant", "carrot"], "pick up the eggplant", ("pick_up", "eggplant", None)),
    ],
)
def test_reader_reads_the_task_on_the_table(reader, objects, instruction, expected):
    assert read(reader, objects, instruction) == expected


@pytest.mark.parametrize(
    ("objects", "instruction", "why"),
    [
        (["carrot", "plate"], "do nothing", "no task verb"),
        (["carrot", "plate"], "don't put the carrot on the plate", "negated"),
        (["apple", "orange", "basket"], "put the fruit in the basket", "ambiguous"),
        (["carrot", "plate"], "pick up the stapler", "not in the scene"),
        (["carrot", "plate", "sponge"], "put the plate on the carrot", "not afforded"),
    ],
)
def test_reader_says_why_it_holds_still(reader, objects, instruction, why):
    result = read(reader, objects, instruction)
    assert isinstance(result, str) and why in result



class _NoisyEmbedder:
    """Fixed unit vectors, one of them moved in its last bits (``jitter``), as another CPU's
    kernels or another batch would move it."""

    dimension = 3

    def __init__(self, vectors: dict[str, list[float]], moved: str, jitter: float) -> None:
        self.vectors, self.moved, self.jitter = vectors, moved, jitter

    def encode(self, texts):
        import numpy as np

        out = np.array([self.vectors[t] for t in texts], dtype=np.float64)
        for i, t in enumerate(texts):
            if t == self.moved:
                out[i, 0] += self.jitter
        return (out / np.linalg.norm(out, axis=1, keepdims=True)).astype(np.float32)


@pytest.mark.parametrize("jitter", [0.0, 1e-6, -1e-6])
def test_a_tie_is_broken_the_same_way_whatever_the_last_bits(jitter):
    from ladev_lib.policies.grounded import CandidateTask

    # the two tasks are equally near the instruction, up to the last bits of one of them
    vectors = {"fetch it": [1.0, 0.0, 0.0], "pick up the apple": [0.6, 0.8, 0.0], "pick up the pear": [0.6, -0.8, 0.0]}
    candidates = [
        CandidateTask("pick_up", "apple", None, "pick up the apple"),
        CandidateTask("pick_up", "pear", None, "pick up the pear"),
    ]
    choice = TaskRetriever(_NoisyEmbedder(vectors, "pick up the pear", jitter)).choose("fetch it", candidates)
    assert choice.chosen.source == "apple"  # the first in scene order, on every machine
    assert choice.score == pytest.approx(0.6, abs=1e-4)


def test_a_grounding_by_embedding_is_the_same_whatever_the_last_bits():
    from ladev_lib.language.frames import NounPhrase
    from ladev_lib.language.grounding import Grounder

    catalog = load_catalog()
    picks = set()
    for jitter in (0.0, 1e-6, -1e-6):
        vectors = {"the doohickey": [1.0, 0.0, 0.0], "gizmo": [0.8, 0.6, 0.0], "widget": [0.8, -0.6, 0.0]}
        # WordNet left out: it knows gizmos and widgets as one kind of gadget (the kind step would
        # call them ambiguous before the embedding step this test is about is reached)
        g = Grounder(catalog, _NoisyEmbedder(vectors, "gizmo", jitter), margin=0.0, min_similarity=0.5, nouns=None)
        picks.add(g.ground(NounPhrase("the doohickey", "doohickey", ()), g.scene(["gizmo", "widget"])).object_id)
    assert len(picks) == 1 and None not in picks
