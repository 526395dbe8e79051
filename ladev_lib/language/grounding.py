"""Ground a noun phrase: which object of the scene (or of the catalog) it names.

    g = Grounder(catalog, embedder)
    g.ground(NounPhrase("dinner plate", "plate", ("dinner",), "029_plate"), g.scene(["024_bowl", "plate"]))
    -> Grounding(object_id="plate", how="head")      # the scene's one plate

Grounding is its own step after reading, tried in order:

1. **exact**: the phrase is a name (or synonym) of one scene object;
2. **head**: the phrase's head noun (or a group noun: "fruit", "container")
   fits exactly one scene object and its modifiers fit that object (colour,
   name words; size words fit anything);
2b. **kind**: when no head fits, what kind of thing each object is, from
   WordNet's noun hierarchy (:mod:`ladev_lib.language.wordnet`): "the tool"
   is the scene's one trowel, "the trash can" its one bin;
3. **embedding**: the phrase's sentence embedding is nearest one scene
   object's name, above ``min_similarity`` and by ``margin`` over the
   runner-up.

Two candidates within the margin (or two heads that fit) are *ambiguous*: a
reason, never a guess. Without a scene the catalog is the pool, and a phrase
the catalog does not name stays free text. Scene entries may be catalog ids
or plain names ("black bowl"); plain names are objects of their own.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Literal, Protocol

from ladev_lib.arrays import Array
from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.catalog.catalog import normalize_name
from ladev_lib.language import lexicon as lx
from ladev_lib.language.embeddings import rounded
from ladev_lib.language.frames import NounPhrase, Qualifier
from ladev_lib.language.mentions import NameIndex, name_index
from ladev_lib.language.wordnet import Nouns, default_nouns

DEFAULT_MARGIN = 0.05
"""Cosine margin the best scene object needs over the runner-up to be chosen by embedding."""
DEFAULT_MIN_SIMILARITY = 0.60
"""Lowest phrase-to-name cosine similarity that grounds by embedding."""
FREE_SAME_SIMILARITY = 0.80
"""Two phrases with different head nouns name the same thing at this similarity or above."""


class PhraseEmbedder(Protocol):
    def encode(self, texts: Sequence[str]) -> Array: ...


@dataclass(frozen=True)
class SceneObject:
    """One object of a scene: a catalog object, or a plain name the catalog does not know."""

    key: str
    """The catalog id, or the normalised plain name."""
    names: tuple[str, ...]
    """Normalised names (display name first)."""
    catalog_id: str | None = None


@dataclass(frozen=True)
class Grounding:
    """What a phrase names, and how that was decided."""

    phrase: NounPhrase
    object_id: str | None
    """A scene object's key (catalog id or plain name), a catalog id without a scene, or None."""
    how: str
    """exact | head | embedding | catalog | free | ambiguous | absent"""
    candidates: tuple[str, ...] = ()
    reason: str | None = None

    def describe(self) -> str:
        target = self.object_id or "-"
        text = f"'{self.phrase.text}' -> {target} ({self.how})"
        return f"{text}: {self.reason}" if self.reason else text


class Grounder:
    """Grounds noun phrases against a scene's objects or the catalog."""

    def __init__(
        self,
        catalog: Catalog | None = None,
        embedder: PhraseEmbedder | None = None,
        margin: float = DEFAULT_MARGIN,
        min_similarity: float = DEFAULT_MIN_SIMILARITY,
        nouns: Nouns | None | Literal["default"] = "default",
    ) -> None:
        self.catalog = catalog or load_catalog()
        self._nouns = nouns
        self.index: NameIndex = name_index(self.catalog)
        self.embedder = embedder
        self.margin = margin
        self.min_similarity = min_similarity
        self._vectors: dict[str, Array] = {}

    @property
    def nouns(self) -> Nouns | None:
        """WordNet's nouns, for what kind of thing a plain name is ("trowel": a tool); None: not used.
        Read on first use (a grounding that never gets past names and head nouns does not load it)."""
        if self._nouns == "default":
            self._nouns = default_nouns()
        return self._nouns

    def _plural_names_one(self, a: str, b: str) -> bool:
        """Whether the plural of two head nouns names one thing and its singular nothing else: "scissors" /
        "scissor", "tongs" / "tong" (WordNet lists the plural as a noun of its own, the singular as no other
        noun); "glasses" / "glass" and "apples" / "apple" stay two numbers."""
        nouns = self.nouns
        plural = a if lx.looks_plural(a) else b
        one = b if plural == a else a
        if nouns is None or not nouns.listed(plural):
            return False
        mine, theirs = nouns.senses(one), nouns.senses(plural)
        return not mine or bool(theirs) and mine[0] == theirs[0]

    # -- scenes ------------------------------------------------------------------
    def scene(self, entries: Iterable[str]) -> tuple[SceneObject, ...]:
        """Scene objects from catalog ids or plain names (a name the catalog knows is its object)."""
        cleaned = [e.strip() for e in entries if e.strip()]
        known: dict[str, str | None] = {}
        for entry in cleaned:
            name = normalize_name(entry.replace("_", " "))
            known[entry] = entry if entry in self.catalog else self.index.names.get(tuple(name.split()))
        count: dict[str | None, int] = {}
        for cid in known.values():
            count[cid] = count.get(cid, 0) + 1
        out: list[SceneObject] = []
        for entry in cleaned:
            cid = known[entry]
            if cid is not None and (entry == cid or count[cid] == 1):
                out.append(self._catalog_object(cid))
            else:
                # a plain name; two names for one catalog object ("plate", "dish") stay two objects
                name = normalize_name(entry.replace("_", " "))
                out.append(SceneObject(name, (name,)))
        return tuple(out)

    def _catalog_object(self, object_id: str) -> SceneObject:
        obj = self.catalog.get(object_id)
        return SceneObject(object_id, tuple(normalize_name(n) for n in obj.names), object_id)

    # -- grounding ---------------------------------------------------------------
    def ground(self, phrase: NounPhrase, scene: Sequence[SceneObject] | None = None) -> Grounding:
        if scene:
            return self._in_scene(phrase, scene)
        if phrase.object_id is not None:
            return Grounding(phrase, phrase.object_id, "catalog")
        return Grounding(phrase, None, "free")

    def _in_scene(self, phrase: NounPhrase, scene: Sequence[SceneObject]) -> Grounding:
        # 1. exact name or synonym as written, then the catalog object the phrase names
        for exact in (
            [o.key for o in scene if phrase.text in o.names],
            [o.key for o in scene if phrase.object_id and o.key == phrase.object_id],
        ):
            if len(set(exact)) == 1:
                namesakes = [] if phrase.modifiers else self._namesakes(phrase, exact[0], scene)
                if namesakes:
                    return self._ambiguous(phrase, [exact[0], *namesakes])  # "the mug": the red one or the blue one
                return Grounding(phrase, exact[0], "exact")
            if len(exact) > 1:
                return self._ambiguous(phrase, exact)
        # 2. head noun and modifiers
        fits = [o.key for o in scene if self._head_fits(phrase, o, scene)]
        if len(fits) == 1:
            return Grounding(phrase, fits[0], "head")
        if len(fits) > 1:
            # an object with the phrase's own head noun before one that only belongs to its group: "the block"
            # is the toy block, not the toy box (a box is in the catalog's group of blocks)
            own = [k for k in fits if _singular(phrase.head) in {
                _singular(n.split()[-1]) for o in scene if o.key == k for n in o.names}]
            if len(own) == 1:
                return Grounding(phrase, own[0], "head")
            return self._ambiguous(phrase, fits)
        # 2b. what kind of thing each object is (WordNet), when no head noun fits
        kinds = [o.key for o in scene if self._head_fits(phrase, o, scene, kinds=True)]
        if len(kinds) == 1:
            return Grounding(phrase, kinds[0], "kind")
        if len(kinds) > 1:
            return self._ambiguous(phrase, kinds)
        # 3. embedding similarity with a margin, over the objects the phrase may name: a
        # phrase the catalog reads as one object ("banana") never names a different
        # catalog object ("apple"), however close their embeddings are
        pool = [o for o in scene if not _other_catalog_object(phrase, o)]
        if self.embedder is not None and pool:
            scored = sorted(
                ((self._similarity(phrase.text, o), o.key) for o in pool), reverse=True
            )
            best, key = scored[0]
            second = scored[1][0] if len(scored) > 1 else -1.0
            if best >= self.min_similarity:
                if best - second >= self.margin:
                    return Grounding(phrase, key, "embedding", reason=None)
                close = [k for s, k in scored if best - s < self.margin]
                return self._ambiguous(phrase, close)
        named = f" ({phrase.object_id})" if phrase.object_id else ""
        return Grounding(phrase, None, "absent", reason=f"'{phrase.text}'{named} is not in the scene")

    @staticmethod
    def _namesakes(phrase: NounPhrase, key: str, scene: Sequence[SceneObject]) -> list[str]:
        """Other scene objects whose names end in the phrase's one word ("blue mug" for "mug")."""
        head = _singular(phrase.head)
        return [o.key for o in scene if o.key != key and any(_singular(n.split()[-1]) == head for n in o.names)]

    def _ambiguous(self, phrase: NounPhrase, keys: Sequence[str]) -> Grounding:
        keys = tuple(dict.fromkeys(keys))
        return Grounding(
            phrase, None, "ambiguous", keys, f"'{phrase.text}' is ambiguous: {', '.join(keys)}"
        )

    def _head_fits(
        self, phrase: NounPhrase, obj: SceneObject, scene: Sequence[SceneObject], kinds: bool = False
    ) -> bool:
        head = _singular(phrase.head)
        heads = {_singular(n.split()[-1]) for n in obj.names}
        words = {w for n in obj.names for w in n.split()}
        by_group = False
        if obj.catalog_id is not None and head in lx.HYPERNYMS:
            by_group = obj.catalog_id in self.index._candidates(head)
        elif obj.catalog_id is None and head in lx.HYPERNYMS:
            # a plain name in the group when a catalog object with its head noun is ("screwdriver": a tool)
            group = self.index._candidates(head)
            by_group = any(group & self.index._candidates(h) for h in heads if h not in lx.GENERIC_HEADS)
        if kinds and obj.catalog_id is None and not by_group and head in lx.PLAIN_HYPERNYMS:
            by_group = bool(heads & lx.PLAIN_HYPERNYMS[head])
        if kinds and not by_group and head not in heads and self.nouns is not None:
            # what kind of thing a name is: "the trash can" is a bin; for a plain name also the other
            # way ("the tool" for a trowel), which the catalog's own groups give for its objects
            # (for a catalog object, a group noun the catalog defines is its own groups' business)
            general = obj.catalog_id is None or head not in lx.HYPERNYMS
            kind = self._kind_noun(phrase, self.nouns)
            by_group = any(
                self.nouns.is_a(phrase.text, n) or (general and self.nouns.is_a(n, kind)) for n in obj.names
            ) or (general and any(self.nouns.is_a(c, kind) for c in _contents(obj)))
            # a plain compound name WordNet does not know is a kind of its head noun ("kibble bag": a
            # bag), and a more specific word for that kind names it too ("the sack of dog food": a sack
            # is a bag); a catalog name stays its own object
            by_group = by_group or (
                obj.catalog_id is None
                and phrase.object_id is None
                and any(self.nouns.is_a(phrase.text, h) for h in _unknown_compound_heads(obj, self.nouns))
            )
        if head not in heads and not by_group and head not in lx.GENERIC_HEADS:
            if phrase.object_id is None or phrase.object_id == obj.catalog_id:
                return False
            # a catalog name outside the scene ("dinner plate"): its own head nouns count
            own = {_singular(normalize_name(n).split()[-1]) for n in self.catalog.get(phrase.object_id).names}
            if not own & heads:
                return False
        others = {w for o in scene if o.key != obj.key for n in o.names for w in n.split()}
        sizes = {lx.SIZE_CLASSES[w] for w in words if w in lx.SIZE_CLASSES}
        for word in phrase.modifiers:
            if word in lx.SIZE_CLASSES and sizes and lx.SIZE_CLASSES[word] not in sizes:
                return False  # "the little bowl" is not the scene's "large bowl"
            if word in words or word in lx.SIZE_WORDS:
                continue
            if obj.catalog_id is not None and word in _COLOURS:
                if not self.index.compatible(obj.catalog_id, [word]):
                    return False
                continue
            if word in _COLOURS or word in others:
                return False  # a colour the plain name does not state, or another object's word
        return True

    @staticmethod
    def _kind_noun(phrase: NounPhrase, nouns: Nouns) -> str:
        """The kind a phrase names, as WordNet may know it: the compound itself ("mixing bowl"),
        or, for one WordNet does not know, its head noun when every modifier only says what the
        thing is made of or holds, or its colour or size ("the glass vessel" is a vessel, the
        modifiers checked like any other's); a modifier of use ("the cooking vessel") makes a kind
        of its own, which WordNet cannot tell."""
        if nouns.senses(phrase.text) or not phrase.modifiers:
            return phrase.text
        if all(w in _COLOURS or w in lx.SIZE_WORDS or any(nouns.is_a(w, m) for m in _MATTER) for w in phrase.modifiers):
            return phrase.head
        return phrase.text

    def _similarity(self, text: str, obj: SceneObject) -> float:
        assert self.embedder is not None
        vectors = self._embed([text, *obj.names])
        return rounded(max(float(vectors[text] @ vectors[n]) for n in obj.names))

    def _embed(self, texts: Sequence[str]) -> dict[str, Array]:
        todo = [t for t in dict.fromkeys(texts) if t not in self._vectors]
        if todo:
            assert self.embedder is not None
            self._vectors.update(zip(todo, self.embedder.encode(todo), strict=True))
        return {t: self._vectors[t] for t in texts}

    # -- comparing two phrases ------------------------------------------------------
    def compare(
        self, a: NounPhrase, b: NounPhrase, scene: Sequence[SceneObject] | None = None
    ) -> tuple[bool, str | None, Grounding, Grounding]:
        """Whether two phrases name the same object, why not, and both groundings."""
        ga, gb = self.ground(a, scene), self.ground(b, scene)
        for g in (ga, gb):
            if g.how in ("ambiguous", "absent"):
                return False, g.reason, ga, gb
        colours_a = {_COLOUR_ALIASES.get(w, w) for w in a.modifiers if w in _COLOURS}
        colours_b = {_COLOUR_ALIASES.get(w, w) for w in b.modifiers if w in _COLOURS}
        if colours_a and colours_b and not colours_a & colours_b:
            return False, f"'{a.text}' -> '{b.text}' (another colour)", ga, gb
        sizes_a, sizes_b = _sizes(a), _sizes(b)
        if sizes_a and sizes_b and not sizes_a & sizes_b:
            return False, f"'{a.text}' -> '{b.text}' (another size)", ga, gb
        if _number_differs(a, b) and not self._plural_names_one(a.head, b.head):
            return False, f"'{a.text}' -> '{b.text}' (another number)", ga, gb
        sides_a, sides_b = _positions(a), _positions(b)
        if any(lx.OPPOSITE_POSITIONS[s] in sides_b for s in sides_a):
            return False, f"'{_described(a)}' -> '{_described(b)}' (another position)", ga, gb
        why = self._qualifiers_differ(a, b, scene)
        if why is not None:
            return False, why, ga, gb
        if ga.object_id is not None and gb.object_id is not None:
            if ga.object_id == gb.object_id:
                return True, None, ga, gb
            if not scene:
                return False, f"{ga.object_id} -> {gb.object_id} (different catalog objects; no scene given)", ga, gb
            return False, f"{ga.object_id} -> {gb.object_id}", ga, gb
        same = self._same_text(a, b, ga.object_id, gb.object_id)
        return same, None if same else f"'{a.text}' -> '{b.text}'", ga, gb

    def _qualifiers_differ(
        self, a: NounPhrase, b: NounPhrase, scene: Sequence[SceneObject] | None
    ) -> str | None:
        """Why two phrases' locating relations disagree ("next to the plate" vs "on the plate").

        A phrase without qualifiers is less specific, not different; where both
        locate the object, the first relation with landmarks must agree (a
        "from" fits "on" and "in") and every landmark of the shorter list must
        match one of the other's.
        """
        stated_a = [q for q in a.qualifiers if q.landmarks or q.places]
        stated_b = [q for q in b.qualifiers if q.landmarks or q.places]
        if not stated_a or not stated_b:
            return None
        qa = [_with_places(q) for q in stated_a]
        qb = [_with_places(q) for q in stated_b]
        ra, rb = qa[0].relation, qb[0].relation
        if ra != rb and not _same_location(ra, rb, stated_a[0], stated_b[0]):
            return f"'{a.text} {ra} ...' -> '{b.text} {rb} ...'"
        la = [p for q in qa for p in q.landmarks]
        lb = [p for q in qb for p in q.landmarks]
        short, long_ = (la, lb) if len(la) <= len(lb) else (lb, la)
        for p in short:
            if not any(self.compare(_bare(p), _bare(o), scene)[0] for o in long_):
                return f"landmark '{p.text}' not in '{' / '.join(o.text for o in long_)}'"
        return None

    def _fits_catalog(self, phrase: NounPhrase, object_id: str) -> bool:
        """A free phrase that describes a catalog object: its head and every modifier fit."""
        if object_id not in self.catalog:
            return False
        names = [normalize_name(n).split() for n in self.catalog.get(object_id).names]
        if not any(_singular(n[-1]) == _singular(phrase.head) for n in names):
            return False
        words = {w for n in names for w in n}
        unknown = [w for w in phrase.modifiers if w not in words and w not in _COLOURS and w not in lx.SIZE_WORDS]
        return not unknown and self.index.compatible(object_id, list(phrase.modifiers))

    def _same_text(self, a: NounPhrase, b: NounPhrase, id_a: str | None, id_b: str | None) -> bool:
        """Two phrases at least one of which is free: by head noun, else by embedding.

        A free phrase that fits several catalog objects ("the can", "the bottle") does not
        say which one, so it never equals one of them; two such phrases compare as text."""
        for free, grounded in ((a, id_b), (b, id_a)):
            if grounded is not None and len(free.candidates) > 1:
                return False
        if id_a is not None and self._fits_catalog(b, id_a) or id_b is not None and self._fits_catalog(a, id_b):
            return True
        if lx.position_word(_singular(a.head)) == lx.position_word(_singular(b.head)):
            ma, mb = _descriptive(a.modifiers), _descriptive(b.modifiers)
            return ma <= mb or mb <= ma
        colours_a = {_COLOUR_ALIASES.get(w, w) for w in a.modifiers if w in _COLOURS}
        colours_b = {_COLOUR_ALIASES.get(w, w) for w in b.modifiers if w in _COLOURS}
        if colours_a and colours_b and colours_a != colours_b:
            return False
        if self.nouns is not None and self.nouns.synonyms(a.text, b.text):
            return True  # one WordNet synset: "wastebin" and "trash can"
        if self.embedder is None:
            return a.text == b.text
        texts_a = [a.text] if id_a is None else [normalize_name(n) for n in self.catalog.get(id_a).names]
        texts_b = [b.text] if id_b is None else [normalize_name(n) for n in self.catalog.get(id_b).names]
        vectors = self._embed([*texts_a, *texts_b])
        best = rounded(max(float(vectors[x] @ vectors[y]) for x in texts_a for y in texts_b))
        return best >= FREE_SAME_SIMILARITY


_COLOURS = frozenset(lx.COLOR_WORDS) - {"light", "dark"}
_MATTER = ("material", "substance", "solid")
"""WordNet kinds of what a thing is made of or holds ("glass", "plastic", "water")."""
_COLOUR_ALIASES = {"violet": "purple", "gray": "grey"}


def _unknown_compound_heads(obj: SceneObject, nouns: Nouns) -> list[str]:
    """The head nouns of an object's compound names that WordNet does not know ("bag" of "kibble bag")."""
    return [n.split()[-1] for n in obj.names if len(n.split()) > 1 and not nouns.senses(n)]


def _contents(obj: SceneObject) -> list[str]:
    """What a packaged object holds: "milk" in "milk carton" (a drink, though a carton is not)."""
    out = []
    for n in obj.names:
        words = n.split()
        if len(words) > 1 and words[-1] in lx.CONTAINER_NOUNS:
            out.append(" ".join(words[:-1]))
    return out


def _other_catalog_object(phrase: NounPhrase, obj: SceneObject) -> bool:
    """The phrase is a catalog name and the scene object is a different catalog object."""
    return phrase.object_id is not None and obj.catalog_id is not None and obj.catalog_id != phrase.object_id


def _with_places(q: Qualifier) -> Qualifier:
    """Places as landmarks too ("from the table center")."""
    extra = tuple(NounPhrase(p, p.split()[-1], tuple(p.split()[:-1])) for p in q.places if p.split())
    return Qualifier(q.relation, (*q.landmarks, *extra))


def _bare(phrase: NounPhrase) -> NounPhrase:
    return NounPhrase(phrase.text, phrase.head, phrase.modifiers, phrase.object_id)


def _number_differs(a: NounPhrase, b: NounPhrase) -> bool:
    """One head noun, once singular and once plural: "the apple" is not "the apples" (a group)."""
    one_a, one_b = _singular(a.head), _singular(b.head)
    return one_a == one_b and (a.head == one_a) != (b.head == one_b) and (lx.looks_plural(a.head) or lx.looks_plural(b.head))


def _sizes(phrase: NounPhrase) -> frozenset[str]:
    """The sizes a phrase states ("big" and "large" are one)."""
    return frozenset(lx.SIZE_CLASSES[w] for w in phrase.modifiers if w in lx.SIZE_CLASSES)


def _positions(phrase: NounPhrase) -> frozenset[str]:
    """The positions a phrase places its object at, in its own words or in a relation that
    locates it ("the left notebook", "the notebook on the right", "at the back"); a landmark's
    own words ("next to the left plate") are the landmark's, not the object's."""
    words = list(phrase.modifiers)
    for q in phrase.qualifiers:
        words += q.relation.split()
        words += [w for place in q.places for w in place.split()]
        # a landmark that is a part of a place ("at the right end (of the desk)") places it too
        words += [w for p in q.landmarks if p.head in lx.POSITION_NOUNS for w in p.modifiers]
    return frozenset(p for p in (lx.position_word(w) for w in words) if p in lx.OPPOSITE_POSITIONS)


def _described(phrase: NounPhrase) -> str:
    places = " ".join(f"{q.relation} {' '.join(q.places)}".strip() for q in phrase.qualifiers if q.places)
    return f"{phrase.text} {places}".strip()


def _descriptive(modifiers: Iterable[str]) -> frozenset[str]:
    """Modifiers that tell objects apart, position words as one ("rear" is "back")."""
    return frozenset(lx.position_word(w) for w in modifiers if w not in lx.SIZE_WORDS)


_LOCATIVE = frozenset({"from", "on", "in", "at"})
"""Relation words that say where a thing is, interchangeable with "from" ("the bowl from the
stove" is the bowl on it) and with each other before a position ("in the middle of the table",
"at the center of the table")."""
_POSITIONS = frozenset(
    {"center", "middle", "centre", "edge", "corner", "side", "back", "rear", "front", "top", "bottom", "left", "right", "end"}
)


def _same_location(ra: str, rb: str, qa: Qualifier, qb: Qualifier) -> bool:
    """Two locating relations that place a thing alike."""
    if not {ra, rb} <= _LOCATIVE:
        return False
    return "from" in {ra, rb} or (_names_position(qa) and _names_position(qb))


def _names_position(q: Qualifier) -> bool:
    """A qualifier whose landmark is a position on something ("in *the middle*", "at *the center*")."""
    return not q.landmarks and bool(q.places) and all(
        lx.position_word(p.split()[-1]) in _POSITIONS for p in q.places if p.split()
    )


def _singular(word: str) -> str:
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "xes", "sses")):
        return word[:-2]
    if word.endswith("s") and not word.endswith("ss") and len(word) > 3:
        return word[:-1]
    return word
