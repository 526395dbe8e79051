"""Decide whether a paraphrase keeps the original instruction's meaning.

Two checks, both recorded for every candidate:

1. **Similarity**: cosine similarity of sentence embeddings (all-MiniLM-L6-v2
   by default) between the sentences as written, as in the paper. When that
   falls below the threshold, the sentences are compared once more with every
   object name replaced by the object's display name (``canonical_similarity``),
   and the better of the two must reach the threshold: a synonym the catalog
   vouches for ("aubergine" for "eggplant": 0.42 as written, 0.87 canonical)
   should not sink a candidate, while wording that drifts from the task still
   does. Only candidates that need it pay for the second embedding.
2. **Structure**: both sentences are read into frames (task, object,
   destination as noun phrases) — by the offline reader, or by an LLM through
   the ``parse_instruction`` job — each phrase is grounded (against the
   scene's objects when given: catalog ids or plain names; otherwise the
   catalog, unknown nouns staying free text), and the grounded frames must be
   equal (:mod:`ladev_lib.language.grounding`).

A candidate is valid when both hold; otherwise ``reason`` says which failed.
Every verdict keeps both frames and the grounding of each phrase.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ladev_lib.arrays import Array
from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.catalog.catalog import normalize_name
from ladev_lib.language.embeddings import SIMILARITY_DECIMALS
from ladev_lib.language.frames import Frame, NounPhrase
from ladev_lib.language.grounding import Grounder, Grounding, SceneObject
from ladev_lib.language.parser import InstructionParse, InstructionParser
from ladev_lib.language.tasks import needs_destination

DEFAULT_THRESHOLD = 0.45
"""A safety net for drift the structural check cannot see ("The history of the Roman empire
is long. Pick up the coke can.": 0.42). Faithful paraphrases in the labelled sets score
>= 0.65 (the better of as-written and canonical); the offline generator's lowest over the
whole catalog is about 0.51."""


class TextEmbedder(Protocol):
    """What the validator needs from an embedder (``ladev_lib.language.embeddings.Embedder``)."""

    def encode(self, texts: Sequence[str]) -> Array: ...


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
        return [self.parser.parse(t, s) for t, s in zip(texts, scene_objects, strict=True)]

    def read_frames(
        self, texts: Sequence[str], scene_objects: Sequence[frozenset[str] | None]
    ) -> list[Frame]:
        return [self.parser.read(t, s) for t, s in zip(texts, scene_objects, strict=True)]


def frame_of_parse(parse: InstructionParse, catalog: Catalog) -> Frame:
    """A catalog-id reading (an LLM's, or a scene spec's task) as a frame."""

    def phrase(object_id: str | None) -> NounPhrase | None:
        if object_id is None:
            return None
        words = normalize_name(catalog.get(object_id).display_name).split() if object_id in catalog else [object_id]
        return NounPhrase(" ".join(words), words[-1], tuple(words[:-1]), object_id)

    return Frame(parse.text, parse.task, phrase(parse.source), phrase(parse.target), reason=parse.reason)


def catalog_view(frame: Frame, groundings: Sequence[Grounding | None]) -> InstructionParse:
    """Roles as grounded ids (catalog ids or scene names), free text where nothing grounds."""
    ids: list[str | None] = []
    for phrase, g in zip((frame.object, frame.destination), groundings, strict=True):
        if phrase is None:
            ids.append(None)
        elif g is not None and g.object_id is not None:
            ids.append(g.object_id)
        else:
            ids.append(phrase.object_id or phrase.text)
    return InstructionParse(frame.text, frame.task, ids[0], ids[1], frame.reason, frame.notes)


@dataclass(frozen=True)
class Verdict:
    """One candidate's checks and verdict."""

    original: str
    candidate: str
    similarity: float
    """Cosine similarity of the sentences as written (the paper's measure)."""
    canonical_similarity: float | None
    """The same with object names replaced by display names; computed only when
    ``similarity`` is below the threshold (None otherwise)."""
    expected: InstructionParse
    """The original's roles as grounded ids (free text where nothing grounds)."""
    parse: InstructionParse
    """The candidate's roles as grounded ids."""
    similar: bool
    """max(similarity, canonical_similarity) >= threshold."""
    same_structure: bool
    reason: str | None
    expected_frame: Frame | None = None
    frame: Frame | None = None
    groundings: tuple[str, ...] = ()
    """How each phrase of both frames was grounded ("'dinner plate' -> plate (head)")."""

    @property
    def valid(self) -> bool:
        return self.similar and self.same_structure

    @property
    def best_similarity(self) -> float:
        return max(self.similarity, self.canonical_similarity or -1.0)


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


_DEFINITE = re.compile(
    r"negated|takes the object away|is not one of the tasks|without a destination|to a person|"
    r"relation '(?:to the |on the )?(?:behind|under|underneath|below|beneath|above|over|off|off of|out of|away from|"
    r"in front of|left of|right of|across|around|between|against|opposite|outside|beyond|past|toward|towards)' is none of"
)
"""Reasons of the parser that name what a sentence does instead of the task (a negation, another relation,
taking the object away, another action): it did read the sentence; the span tagger is not asked again."""


def frame_mismatch(
    expected: Frame, got: Frame, grounder: Grounder, scene: Sequence[SceneObject] | None
) -> tuple[str | None, list[Grounding | None], list[Grounding | None]]:
    """Why ``got`` does not ask for what ``expected`` asks for (None if it does), and the groundings."""
    g_exp: list[Grounding | None] = [None, None]
    g_got: list[Grounding | None] = [None, None]
    for groundings, frame in ((g_exp, expected), (g_got, got)):
        if frame.object is not None:
            groundings[0] = grounder.ground(frame.object, scene)
        if frame.destination is not None:
            groundings[1] = grounder.ground(frame.destination, _without(scene, groundings[0]))
    if not expected.ok:
        return f"original not understood: {expected.reason}", g_exp, g_got
    if not got.ok:
        return f"candidate not understood: {got.reason}", g_exp, g_got
    for which, (obj, dest) in (("original", g_exp), ("candidate", g_got)):
        if obj is not None and dest is not None and obj.object_id is not None and obj.object_id == dest.object_id:
            return f"{which} not understood: the same object is source and destination: {obj.object_id}", g_exp, g_got
    if got.task != expected.task:
        return f"task changed: {expected.task} -> {got.task}", g_exp, g_got
    if expected.object is None or got.object is None:
        return "no object to act on", g_exp, g_got
    same_obj, why_obj, g_obj, _ = grounder.compare(expected.object, got.object, scene)
    same_dest, why_dest = True, None
    if needs_destination(expected.task or ""):
        if expected.destination is None or got.destination is None:
            return "no destination", g_exp, g_got
        # where the object goes is another object than the one moved ("put the ladle in the container")
        rest = _without(scene, g_obj) if same_obj else scene
        same_dest, why_dest, _, _ = grounder.compare(expected.destination, got.destination, rest)
        if not same_obj and not same_dest:
            swapped = (
                grounder.compare(expected.object, got.destination, scene)[0]
                and grounder.compare(expected.destination, got.object, scene)[0]
            )
            if swapped:
                return f"roles swapped: '{got.object.text}' is now moved to '{got.destination.text}'", g_exp, g_got
    if not same_obj:
        return f"object changed: {why_obj}", g_exp, g_got
    if not same_dest:
        return f"destination changed: {why_dest}", g_exp, g_got
    return None, g_exp, g_got


def _without(scene: Sequence[SceneObject] | None, grounding: Grounding | None) -> Sequence[SceneObject] | None:
    """The scene less the object a phrase grounded on (a destination is never the object moved)."""
    if not scene or grounding is None or grounding.object_id is None:
        return scene
    return tuple(o for o in scene if o.key != grounding.object_id) or scene


def cpu_has_native_bf16() -> bool:
    """Whether this CPU computes bfloat16 natively (AVX512-BF16 or AMX); Linux only."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            flags = next((line for line in f if line.startswith("flags")), "")
    except OSError:
        return False
    return any(flag in flags.split() for flag in ("avx512_bf16", "amx_bf16"))


def resolve_precision(precision: str, device: str = "cpu") -> str:
    """ "auto" -> "fp32" on every machine: verdicts must not depend on the CPU.

    bf16 (about 1.6x faster where the CPU has it natively) moves similarities by up to
    0.002, enough to flip a verdict near the threshold between two machines; it is used
    only when asked for by name."""
    del device
    return "fp32" if precision == "auto" else precision


class ParaphraseValidator:
    """Similarity and structural round-trip checks, batched."""

    def __init__(
        self,
        embedder: TextEmbedder,
        threshold: float = DEFAULT_THRESHOLD,
        reader: StructureReader | None = None,
        catalog: Catalog | None = None,
        cache_size: int = 50_000,
        precision: str = "fp32",
        second_reading: bool = True,
        threads: int | None = None,
    ) -> None:
        if not 0.0 <= threshold <= 1.0:
            raise ValueError(f"similarity threshold must be in [0, 1], got {threshold}")
        self.embedder = embedder
        self.threshold = threshold
        self.catalog = catalog or load_catalog()
        self.parser = InstructionParser(self.catalog)
        self.reader = reader or OfflineReader(self.parser)
        self.grounder = Grounder(self.catalog, embedder)
        self.cache_size = cache_size
        if precision not in ("fp32", "bf16"):
            raise ValueError(f"precision must be fp32 or bf16, got {precision!r}")
        self.precision = precision
        self.second_reading = second_reading
        self.threads = threads
        """Torch threads while embedding (None: as the process has them)."""
        """Where the parser cannot read an original or a candidate, read it with the span tagger
        (:mod:`ladev_lib.language.tagged_frames`) and compare that frame."""
        """bf16: embed under CPU autocast to bfloat16 (about 1.6x faster on CPUs with native
        bf16; MiniLM cosine similarities move by 0.002 at most on the labelled pairs)."""
        self._vectors: dict[str, Array] = {}

    def embed(self, texts: Sequence[str]) -> dict[str, Array]:
        """Unit vectors for ``texts``: new distinct texts in one batch, the rest from the cache."""
        todo = [t for t in dict.fromkeys(texts) if t not in self._vectors]
        if todo:
            if len(self._vectors) + len(todo) > self.cache_size:
                self._vectors.clear()
            import torch

            before = torch.get_num_threads()
            if self.threads:
                torch.set_num_threads(self.threads)
            try:
                with torch.autocast("cpu", dtype=torch.bfloat16, enabled=self.precision == "bf16"):
                    vectors = self.embedder.encode(todo)
            finally:
                torch.set_num_threads(before)
            self._vectors.update(zip(todo, vectors, strict=True))
        return {t: self._vectors[t] for t in texts}

    def similarities(self, pairs: Sequence[tuple[str, str]]) -> Array:
        """Cosine similarity of each (original, candidate) as written."""
        vectors = self.embed([t for pair in pairs for t in pair])
        return np.array([float(vectors[o] @ vectors[c]) for o, c in pairs], dtype=np.float32)

    def canonical_similarities(self, pairs: Sequence[tuple[str, str]]) -> Array:
        """Cosine similarity of each pair with object names replaced by display names."""
        return self.similarities(
            [(self.parser.canonical_text(o), self.parser.canonical_text(c)) for o, c in pairs]
        )

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
        raw = np.round(self.similarities(pairs).astype(np.float64), SIMILARITY_DECIMALS)
        low = [i for i in range(len(pairs)) if raw[i] < self.threshold]
        canonical_raw = self.canonical_similarities([pairs[i] for i in low]).astype(np.float64)
        canonical: dict[int, float] = dict(
            zip(low, np.round(canonical_raw, SIMILARITY_DECIMALS).tolist(), strict=True)
        )
        given = list(expected) if expected is not None else [None] * len(pairs)
        grounded = {s: self.grounder.scene(sorted(s)) for s in dict.fromkeys(scenes) if s}
        # the reader reads in the scene's context even where no scene object is a catalog object
        # (plain names stay as they are: they never match a catalog id)
        ids = {s: frozenset(o.catalog_id or o.key for o in g) for s, g in grounded.items()}
        originals = list(
            dict.fromkeys((o, s) for (o, _), s, e in zip(pairs, scenes, given, strict=True) if e is None)
        )
        read_originals = self._frames([o for o, _ in originals], [ids.get(s) if s else None for _, s in originals])
        parsed_originals = dict(zip(originals, read_originals, strict=True))
        candidate_frames = self._frames([c for _, c in pairs], [ids.get(s) if s else None for s in scenes])
        verdicts = []
        for i, ((orig, cand), scene) in enumerate(zip(pairs, scenes, strict=True)):
            given_i = given[i]
            exp = frame_of_parse(given_i, self.catalog) if given_i is not None else parsed_originals[(orig, scene)]
            got = candidate_frames[i]
            if self.second_reading and (not exp.ok or not got.ok) and not (_DEFINITE.search(exp.reason or "")
                                                                          or _DEFINITE.search(got.reason or "")):
                exp, got = self._read_again(orig, cand, exp, got, ids.get(scene) if scene else None)
            scene_objs = grounded.get(scene) if scene else None
            mismatch, g_exp, g_got = frame_mismatch(exp, got, self.grounder, scene_objs)
            best = max(float(raw[i]), canonical.get(i, -1.0))
            similar = round(best, 4) >= self.threshold  # fp32 noise must not flip a verdict at the threshold
            reasons = []
            if not similar:
                reasons.append(
                    f"similarity {raw[i]:.2f} (canonical names {canonical[i]:.2f}) < {self.threshold:.2f}"
                )
            if mismatch:
                reasons.append(mismatch)
            verdicts.append(
                Verdict(
                    original=orig,
                    candidate=cand,
                    similarity=float(raw[i]),
                    canonical_similarity=canonical.get(i),
                    expected=catalog_view(exp, g_exp),
                    parse=catalog_view(got, g_got),
                    similar=similar,
                    same_structure=mismatch is None,
                    reason="; ".join(reasons) or None,
                    expected_frame=exp,
                    frame=got,
                    groundings=tuple(g.describe() for g in [*g_exp, *g_got] if g is not None),
                )
            )
        return verdicts

    def _read_again(
        self, original: str, candidate: str, exp: Frame, got: Frame, scene: frozenset[str] | None
    ) -> tuple[Frame, Frame]:
        """The frames with what the parser could not read read again by the span tagger (kept as they were
        when the tagger cannot read it either)."""
        from ladev_lib.language.tagged_frames import read_tagged_instruction
        from ladev_lib.language.tagging.model import weights_available

        if not weights_available():
            return exp, got
        if not exp.ok:
            again = read_tagged_instruction(original, scene, self.catalog)
            exp = again if again.ok else exp
        if not got.ok:
            again = read_tagged_instruction(candidate, scene, self.catalog)
            got = again if again.ok else got  # where neither reads it, the parser's reason says why
        return exp, got

    def _frames(self, texts: Sequence[str], scenes: Sequence[frozenset[str] | None]) -> list[Frame]:
        if isinstance(self.reader, OfflineReader):
            return self.reader.read_frames(texts, scenes)
        return [frame_of_parse(p, self.catalog) for p in self.reader.read(texts, scenes)]

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
