from __future__ import annotations

import zlib

import numpy as np

from ladev_lib.scenes.resolve import ObjectResolver, clean_mention


def test_exact_names_synonyms_plurals_and_ids(exact_resolver):
    cases = {
        "Coke Can": "coke_can",
        "a can of coke": "coke_can",
        "the coca-cola can": "coke_can",
        "apples": "apple",  # ...but a plural is
        "011_banana": "011_banana",
        "rubik's cube": "077_rubiks_cube",
        "7-up can": "7up_can",
    }
    for mention, expected in cases.items():
        res = exact_resolver.resolve(mention)
        assert res.kind == "exact" and res.obj is not None and res.obj.id == expected, (mention, res)


def test_a_catalog_name_inside_a_longer_mention_wins_longest_first(exact_resolver):
    res = exact_resolver.resolve("the small shiny coke can")
    assert res.kind == "contains" and res.obj.id == "coke_can"
    res = exact_resolver.resolve("a cordless power drill from the garage")
    assert res.obj.id == "035_power_drill"
    assert exact_resolver.resolve("the large blue cup thing").obj.id == "065-h_cups"  # not 'blue cup'


def test_categories_resolve_to_a_category(exact_resolver):
    for mention, category in [("a fruit", "fruit"), ("some cups", "cup"), ("a toy", "toy")]:
        res = exact_resolver.resolve(mention)
        assert res.kind == "category" and res.category == category


def test_embedding_match_above_threshold_and_unavailable_below(catalog):
    # A stand-in embedding: words hashed into a bag of words, so that the test runs without a model.
    def embed(texts):
        out = np.zeros((len(texts), 1024), dtype=np.float32)
        for i, t in enumerate(texts):
            for w in clean_mention(t).split():
                out[i, zlib.crc32(w.encode()) % 1024] += 1.0
        norms = np.linalg.norm(out, axis=1, keepdims=True)
        return out / np.maximum(norms, 1e-9)

    resolver = ObjectResolver(catalog, threshold=0.6, embed=embed)
    res = resolver.resolve("bull red squeezy can")  # shares three words with 'red bull can', names none
    assert res.kind == "embedding" and res.obj.id == "redbull_can" and res.score >= 0.6
    res = resolver.resolve("purple elephant")
    assert res.kind == "unavailable" and not res.ok and "not in the object catalog" in res.describe()


def test_the_real_embedder_maps_near_names_and_refuses_far_ones(catalog):
    resolver = ObjectResolver(catalog, threshold=0.75)
    soda = resolver.resolve("soda can")
    assert soda.kind == "embedding" and soda.obj.category == "can"
    elephant = resolver.resolve("purple elephant")
    assert not elephant.ok and elephant.nearest and elephant.score < 0.75
