"""Decide whether a paraphrase keeps the original instruction's meaning.

Two checks, both recorded for every candidate:

1. **Similarity**: cosine similarity of sentence embeddings (all-MiniLM-L6-v2
   by default), as in the paper. Two figures are kept: ``similarity``
   between the sentences as written, and ``canonical_similarity`` between the
   sentences with every object name replaced by the object's display name.
   The threshold applies to the canonical one: a synonym the catalog already
   vouches for ("aubergine" for "eggplant", 0.42 as written) should not sink a
   candidate, while wording that drifts from the task still does.
2. **Structure**: the candidate is read back into (task, source, target) —
   by the offline parser, or by an LLM through the ``parse_instruction`` job —
   and must equal the original's.

A candidate is valid when both hold; otherwise ``reason`` says which failed.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.language.parser import InstructionParse, InstructionParser

DEFAULT_THRESHOLD = 0.5


class TextEmbedder(Protocol):
    """What the validator needs from an embedder (``ladev_lib.language.embeddings.Embedder``)."""

    def encode(self, texts: Sequence[str]) -> np.ndarray: ...


class StructureReader(Protocol):
    """Reads instructions into (task, source, target)."""

    name: str

    def read(
        self, texts: Sequence[str], scene_objects: Sequence[frozenset[str] | None]
    ) -> list[InstructionParse]: ...


class OfflineReader:
    """The grammar parser (``ladev_lib.language.parser``)."""

    name = "offline"

    def __init__(self, parser: InstructionParser) -> None:
        self.parser = parser

    def read(
        self, texts: Sequence[str], scene_objects: Sequence[frozenset[str] | None]
    ) -> list[InstructionParse]:
        return [self.parser.parse(t, s) for t, s in zip(texts, scene_objects)]


@dataclass(frozen=True)
class Verdict:
    """One candidate's checks and verdict."""

    original: str
    candidate: str
    similarity: float
    """Cosine similarity of the sentences as written."""
    canonical_similarity: float
    """Cosine similarity with object names replaced by display names (the gated figure)."""
    expected: InstructionParse
    parse: InstructionParse
    similar: bool
    same_structure: bool
    reason: str | None

    @property
    def valid(self) -> bool:
        return self.similar and self.same_structure


def structure_mismatch(expected: InstructionParse, got: InstructionParse) -> str | None:
    """Why ``got`` does not state the task ``expected`` states; None if it does."""
    if not expected.ok:
        return f"original not understood: {expected.reason}"
    if not got.ok:
        return f"candidate not understood: {got.reason}"
    if got.task != expected.task:
        return f"task changed: {expected.task} -> {got.task}"
    if (got.source, got.target) == (expected.target, expected.source) and got.source != got.target:
        return f"roles swapped: {got.source} is now moved to {got.target}"
    if got.source != expected.source:
        return f"object changed: {expected.source} -> {got.source}"
    if got.target != expected.target:
        return f"destination changed: {expected.target} -> {got.target}"
    return None


class ParaphraseValidator:
    """Similarity and structural round-trip checks, batched."""

    def __init__(
        self,
        embedder: TextEmbedder,
        threshold: float = DEFAULT_THRESHOLD,
        reader: StructureReader | None = None,
        catalog: Catalog | None = None,
    ) -> None:
        if not 0.0 <= threshold <= 1.0:
            raise ValueError(f"similarity threshold must be in [0, 1], got {threshold}")
        self.embedder = embedder
        self.threshold = threshold
        self.parser = InstructionParser(catalog or load_catalog())
        self.reader = reader or OfflineReader(self.parser)

    def similarities(self, pairs: Sequence[tuple[str, str]]) -> tuple[np.ndarray, np.ndarray]:
        """(as written, canonical) cosine similarity per pair; every distinct text embedded once."""
        canon = {t: self.parser.canonical_text(t) for pair in pairs for t in pair}
        texts = list(dict.fromkeys([*canon, *canon.values()]))
        vectors = self.embedder.encode(texts) if texts else np.zeros((0, 1), dtype=np.float32)
        row = {t: i for i, t in enumerate(texts)}

        def cosines(left: list[str], right: list[str]) -> np.ndarray:
            if not left:
                return np.zeros(0, dtype=np.float32)
            a = vectors[[row[t] for t in left]]
            b = vectors[[row[t] for t in right]]
            return np.asarray((a * b).sum(axis=1), dtype=np.float32)

        raw = cosines([o for o, _ in pairs], [c for _, c in pairs])
        canonical = cosines([canon[o] for o, _ in pairs], [canon[c] for _, c in pairs])
        return raw, canonical

    def validate_pairs(
        self,
        pairs: Sequence[tuple[str, str]],
        scene_objects: Sequence[frozenset[str] | None] | None = None,
        expected: Sequence[InstructionParse | None] | None = None,
    ) -> list[Verdict]:
        """Verdicts for (original, candidate) pairs.

        ``scene_objects`` (catalog ids per pair) lets names resolve against the
        scene; ``expected`` replaces the parse of the original (e.g. the scene
        spec's task) where given.
        """
        scenes = list(scene_objects) if scene_objects is not None else [None] * len(pairs)
        raw, canonical = self.similarities(pairs)
        originals = list(dict.fromkeys((o, s) for (o, _), s in zip(pairs, scenes)))
        parsed_originals = dict(
            zip(originals, self.reader.read([o for o, _ in originals], [s for _, s in originals]))
        )
        candidate_parses = self.reader.read([c for _, c in pairs], scenes)
        verdicts = []
        for i, ((orig, cand), scene) in enumerate(zip(pairs, scenes)):
            exp = (expected[i] if expected is not None else None) or parsed_originals[(orig, scene)]
            got = candidate_parses[i]
            mismatch = structure_mismatch(exp, got)
            similar = bool(canonical[i] >= self.threshold)
            reasons = []
            if not similar:
                reasons.append(f"similarity {canonical[i]:.2f} < {self.threshold:.2f}")
            if mismatch:
                reasons.append(mismatch)
            verdicts.append(
                Verdict(
                    original=orig,
                    candidate=cand,
                    similarity=float(raw[i]),
                    canonical_similarity=float(canonical[i]),
                    expected=exp,
                    parse=got,
                    similar=similar,
                    same_structure=mismatch is None,
                    reason="; ".join(reasons) or None,
                )
            )
        return verdicts

    def validate(
        self,
        original: str,
        candidates: Sequence[str],
        scene_objects: frozenset[str] | None = None,
        expected: InstructionParse | None = None,
    ) -> list[Verdict]:
        """Verdicts for several candidates of one original."""
        pairs = [(original, c) for c in candidates]
        return self.validate_pairs(
            pairs, [scene_objects] * len(pairs), [expected] * len(pairs) if expected else None
        )
