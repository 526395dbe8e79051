from __future__ import annotations

from ladev_lib.language.embeddings import load_embedder


def test_packaged_minilm_loads_offline_and_ranks_sensibly():
    emb = load_embedder()
    assert emb.dimension == 384
    sims = emb.similarity(
        ["pick up the coke can", "pick up the coke can"],
        ["could you lift the can of coke", "open the top drawer"],
    )
    assert sims[0] > 0.6 > sims[1]
    assert load_embedder() is emb  # one load per process
