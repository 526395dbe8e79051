"""Object names as written ("plastic bottle", "a drill", "fruit") -> catalog objects.

In order: exact display name or synonym; a catalog name contained in the
mention as whole words, longest first ("the small coke can" -> coke can); a
category ("a fruit" -> a random fruit); the nearest name by sentence
embedding, when its cosine similarity reaches the threshold. Otherwise the
object is unavailable, as in the paper, and the caller decides what to do.

The embedder loads only when the first three steps fail (it costs seconds).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.catalog import Catalog, CatalogObject
from ladev_lib.catalog.catalog import normalize_name

MatchKind = Literal["exact", "contains", "category", "embedding", "unavailable"]
EmbedFn = Callable[[Sequence[str]], Array]
"""Texts -> unit-length embeddings, one row per text."""

_ARTICLES = re.compile(r"^(?:the|a|an|one|some|any)\s+")
_CATEGORY_ALIASES = {"food box": "food_box", "box of food": "food_box", "utensils": "utensil"}


@dataclass(frozen=True)
class Resolution:
    """What a mention resolved to."""

    mention: str
    kind: MatchKind
    obj: CatalogObject | None = None
    """The object (exact, contains, embedding)."""
    category: str | None = None
    """The category (kind 'category'): pick one of its objects."""
    score: float | None = None
    """Cosine similarity (embedding), or of the best candidate when unavailable."""
    nearest: str | None = None
    """Best candidate's name when unavailable."""

    @property
    def ok(self) -> bool:
        return self.kind != "unavailable"

    def describe(self) -> str:
        if self.kind == "embedding" and self.obj is not None:
            return f"{self.mention!r} -> {self.obj.display_name!r} (embedding similarity {self.score:.2f})"
        if self.kind == "category":
            return f"{self.mention!r} -> a random {self.category}"
        if self.kind == "unavailable":
            near = f" (nearest: {self.nearest!r}, similarity {self.score:.2f})" if self.nearest else ""
            return f"{self.mention!r} is not in the object catalog{near}"
        assert self.obj is not None
        return f"{self.mention!r} -> {self.obj.display_name!r}"


def _singular(word: str) -> str:
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "xes", "sses")):
        return word[:-2]
    if word.endswith("s") and not word.endswith("ss") and len(word) > 3:
        return word[:-1]
    return word


def clean_mention(text: str) -> str:
    """Normalised mention without a leading article: 'The Coke-Cans' -> 'coke cans'."""
    out = normalize_name(text)
    while True:
        stripped = _ARTICLES.sub("", out)
        if stripped == out:
            return out
        out = stripped


class ObjectResolver:
    """Resolves mentions against a catalog, preferring one object set on ties."""

    def __init__(
        self,
        catalog: Catalog,
        threshold: float = 0.75,
        embed: EmbedFn | None = None,
        embedding_model: str | None = None,
    ) -> None:
        self.catalog = catalog
        self.threshold = threshold
        self._embed = embed
        self._embedding_model = embedding_model
        self._names: list[tuple[str, CatalogObject]] = sorted(
            ((normalize_name(n), o) for o in catalog for n in o.names),
            key=lambda item: -len(item[0]),
        )
        self._categories = {o.category for o in catalog}
        self._name_vectors: Array | None = None

    # -- the lookup chain ----------------------------------------------------
    def resolve(self, mention: str) -> Resolution:
        text = clean_mention(mention)
        if not text:
            return Resolution(mention, "unavailable")
        obj = self.catalog.by_name(text) or self.catalog.by_name(_singular_phrase(text))
        if obj is None and text.replace(" ", "_") in self.catalog:
            obj = self.catalog.get(text.replace(" ", "_"))
        if obj is None and mention.strip() in self.catalog:
            obj = self.catalog.get(mention.strip())
        if obj is not None:
            return Resolution(mention, "exact", obj=obj)
        contained = self._contained(text)
        if contained is not None:
            return Resolution(mention, "contains", obj=contained)
        category = self._category(text)
        if category is not None:
            return Resolution(mention, "category", category=category)
        return self._nearest(mention, text)

    def _contained(self, text: str) -> CatalogObject | None:
        padded = f" {text} "
        singular = f" {_singular_phrase(text)} "
        for name, obj in self._names:
            if f" {name} " in padded or f" {name} " in singular:
                return obj
        return None

    def _category(self, text: str) -> str | None:
        words = _singular_phrase(text)
        for candidate in (words, words.replace(" ", "_"), _CATEGORY_ALIASES.get(words, "")):
            if candidate in self._categories:
                return candidate
        return None

    def _nearest(self, mention: str, text: str) -> Resolution:
        vectors = self._vectors()
        if vectors is None:
            return Resolution(mention, "unavailable")
        query = self._embedder()([text])[0]
        scores = vectors @ query
        best = int(np.argmax(scores))
        name, obj = self._names[best]
        score = float(scores[best])
        if score >= self.threshold:
            return Resolution(mention, "embedding", obj=obj, score=score)
        return Resolution(mention, "unavailable", score=score, nearest=name)

    # -- embeddings, loaded on first need ------------------------------------
    def _embedder(self) -> EmbedFn:
        if self._embed is None:
            from ladev_lib.language.embeddings import load_embedder

            self._embed = load_embedder(self._embedding_model).encode
        return self._embed

    def _vectors(self) -> Array | None:
        if self.threshold > 1.0:  # embedding matching switched off
            return None
        if self._name_vectors is None:
            self._name_vectors = self._embedder()([n for n, _ in self._names])
        return self._name_vectors


def _singular_phrase(text: str) -> str:
    words = text.split()
    return " ".join([*words[:-1], _singular(words[-1])]) if words else text
