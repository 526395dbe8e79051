"""Find the catalog objects an instruction names.

Names come from the catalog (display names and synonyms, unique across it),
matched longest-first on normalised tokens ("large orange cup" before
"orange"). A noun phrase without a full name ("the can", "the red one") is
resolved by its head noun and adjectives: against the scene's objects when
the scene is known, otherwise against the whole catalog, and left
unresolved (with the candidates) when more than one object fits.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from ladev_lib.catalog import Catalog, CatalogObject
from ladev_lib.catalog.catalog import normalize_name
from ladev_lib.language import lexicon as lx

# Reference colours for naming an object's stand-in colour (RGB in [0, 1]).
_PALETTE: dict[str, tuple[float, float, float]] = {
    "red": (0.75, 0.1, 0.1),
    "green": (0.15, 0.6, 0.2),
    "blue": (0.15, 0.3, 0.7),
    "yellow": (0.9, 0.8, 0.15),
    "orange": (0.95, 0.5, 0.1),
    "purple": (0.45, 0.15, 0.5),
    "pink": (0.95, 0.55, 0.7),
    "white": (0.92, 0.92, 0.92),
    "black": (0.1, 0.1, 0.1),
    "brown": (0.45, 0.3, 0.2),
    "grey": (0.5, 0.5, 0.5),
}
_COLOR_ALIASES = {"gray": "grey", "violet": "purple"}


@dataclass(frozen=True)
class ObjectRef:
    """A noun phrase that refers to an object, resolved or not."""

    text: str
    object_id: str | None = None
    problem: str | None = None
    """Why it is not resolved: ambiguous, plural, unknown."""
    note: str | None = None
    """How it was resolved when not by an exact name ("'the can' -> coke_can (scene)")."""
    candidates: tuple[str, ...] = ()
    """The catalog objects an ambiguous phrase fits."""


@dataclass(frozen=True)
class NameMatch:
    length: int
    object_id: str


@dataclass
class NameIndex:
    """Catalog names and head nouns, for matching on token lists."""

    catalog: Catalog
    names: dict[tuple[str, ...], str] = field(default_factory=dict)
    heads: dict[str, set[str]] = field(default_factory=dict)
    name_words: set[str] = field(default_factory=set)
    colors: dict[str, set[str]] = field(default_factory=dict)
    max_len: int = 1

    @classmethod
    def build(cls, catalog: Catalog) -> NameIndex:
        index = cls(catalog)
        for obj in catalog:
            for name in obj.names:
                words = tuple(normalize_name(name).split())
                index.names[words] = obj.id
                index.heads.setdefault(words[-1], set()).add(obj.id)
                index.name_words.update(words)
            index.colors[obj.id] = _colors_of(obj)
        index.max_len = max(len(k) for k in index.names)
        return index

    # -- exact names -----------------------------------------------------------
    def match_at(self, words: Sequence[str], i: int) -> NameMatch | None:
        """The longest catalog name starting at ``words[i]``."""
        for n in range(min(self.max_len, len(words) - i), 0, -1):
            obj_id = self.names.get(tuple(words[i : i + n]))
            if obj_id is not None:
                return NameMatch(n, obj_id)
        return None

    def display_name(self, object_id: str) -> str:
        return self.catalog.get(object_id).display_name

    def head_nouns(self, object_id: str) -> set[str]:
        """The last words of an object's names ("lid" for the skillet lid, also called "pan lid")."""
        if object_id not in self.catalog:
            return set()
        return {normalize_name(n).split()[-1] for n in self.catalog.get(object_id).names}

    # -- head nouns ------------------------------------------------------------
    def is_object_noun(self, word: str) -> bool:
        return (
            word in self.heads
            or word in lx.HYPERNYMS
            or word in lx.GENERIC_HEADS
            or self._singular(word) is not None
        )

    def _singular(self, word: str) -> str | None:
        for cut in ("es", "s"):
            if word.endswith(cut) and (word[: -len(cut)] in self.heads or word[: -len(cut)] in lx.HYPERNYMS):
                return word[: -len(cut)]
        return None

    def _candidates(self, head: str) -> set[str]:
        found = set(self.heads.get(head, ()))
        for selector in lx.HYPERNYMS.get(head, ()):
            found.update(o.id for o in self.catalog if _selects(o, selector))
        if head in lx.GENERIC_HEADS:
            found.update(self.catalog.ids())
        return found

    def compatible(self, object_id: str, modifiers: Sequence[str]) -> bool:
        """Every descriptive word fits the object: in one of its names, or its colour."""
        obj_words = {w for n in self.catalog.get(object_id).names for w in normalize_name(n).split()}
        for word in modifiers:
            if word in obj_words:
                continue
            colour = _COLOR_ALIASES.get(word, word)
            if colour in _PALETTE:
                if colour not in self.colors[object_id]:
                    return False
                continue
            if word in lx.SIZE_WORDS:
                continue  # "the little coke can": size words never pick another object
            if word in self.name_words:
                return False  # a word that names another object ("pepsi" for the coke can)
        return True

    def resolve_head(
        self, words: Sequence[str], scene: frozenset[str] | None, text: str
    ) -> ObjectRef | None:
        """Resolve a phrase without a full name by its last word; None if it names no object."""
        head = words[-1]
        modifiers = list(words[:-1])
        if head in lx.LOCATION_NOUNS and head not in self.heads:
            return None
        singular = self._singular(head) if head not in self.heads else None
        if singular is not None:
            return ObjectRef(text, problem=f"'{text}' is plural: more than one object")
        candidates = self._candidates(head)
        if not candidates:
            return self._by_identity_words(words, scene, text)
        return self._narrow(candidates, modifiers, scene, text)

    def _by_identity_words(
        self, words: Sequence[str], scene: frozenset[str] | None, text: str
    ) -> ObjectRef | None:
        """A phrase that is part of names ("the mustard", "coca cola"): the objects whose names
        hold all its words that are not colours or sizes."""
        identity = {w for w in words if w in self.name_words and w not in _PALETTE and w not in lx.SIZE_WORDS}
        if not identity:
            return None
        pool = {
            o.id
            for o in self.catalog
            if any(identity <= set(normalize_name(n).split()) for n in o.names)
        }
        if not pool:
            return None
        descriptive = [w for w in words if w not in identity]
        return self._narrow(pool, descriptive, scene, text)

    def _narrow(
        self, candidates: set[str], modifiers: Sequence[str], scene: frozenset[str] | None, text: str
    ) -> ObjectRef:
        pools = []
        if scene and not self._plain_namesake(scene, text, candidates):
            pools.append((candidates & scene, "scene"))
        pools.append((candidates, "catalog"))
        for pool, where in pools:
            fitting = sorted(o for o in pool if self.compatible(o, modifiers))
            if len(fitting) == 1:
                return ObjectRef(text, fitting[0], note=f"'{text}' -> {fitting[0]} (only fit in the {where})")
            if len(fitting) > 1:
                shown = ", ".join(self.display_name(o) for o in fitting[:4])
                more = f" and {len(fitting) - 4} more" if len(fitting) > 4 else ""
                return ObjectRef(text, problem=f"'{text}' is ambiguous: {shown}{more}", candidates=tuple(fitting))
        return ObjectRef(text, problem=f"'{text}' names no known object")

    def _plain_namesake(self, scene: frozenset[str], text: str, candidates: set[str]) -> bool:
        """A scene object given by a plain name with the phrase's head noun, or the head noun of
        one of its candidates ("blue cup" for "the cup", "screwdriver" for "the tool"): the
        catalog ids of the scene do not tell which object is meant; grounding does."""
        if not text.split():
            return False
        heads = {self._singular(text.split()[-1]) or text.split()[-1]}
        heads |= {normalize_name(n).split()[-1] for c in candidates for n in self.catalog.get(c).names}
        return any(
            s not in self.catalog and (self._singular(s.split()[-1]) or s.split()[-1]) in heads
            for s in scene if s.split()
        )

    def prefer_scene(
        self, object_id: str, words: Sequence[str], scene: frozenset[str] | None, text: str
    ) -> ObjectRef:
        """An exact name outside the scene that describes exactly one scene object.

        "the red apple" (the YCB apple's name) in a scene with only the
        SimplerEnv apple, which is red, means that apple; "the pepsi can" in a
        scene with only a coke can still means the pepsi can.
        """
        if not scene or object_id in scene:
            return ObjectRef(text, object_id)
        head = words[-1]
        pool = self._candidates(head) & scene
        fitting = [o for o in pool if self.compatible(o, words[:-1])]
        if len(fitting) == 1:
            return ObjectRef(text, fitting[0], note=f"'{text}' -> {fitting[0]} (scene object)")
        return ObjectRef(text, object_id)


def _selects(obj: CatalogObject, selector: str) -> bool:
    for cond in selector.split("&"):
        key, _, value = cond.partition(":")
        if str(getattr(obj, key)) != value:
            return False
    return True


def _colors_of(obj: CatalogObject) -> set[str]:
    """Colour words that fit the object: its names' colour words and its nearest palette colours."""
    found = {
        _COLOR_ALIASES.get(w, w)
        for n in obj.names
        for w in normalize_name(n).split()
        if _COLOR_ALIASES.get(w, w) in _PALETTE
    }
    r, g, b = obj.color
    ranked = sorted(_PALETTE, key=lambda c: sum((x - y) ** 2 for x, y in zip((r, g, b), _PALETTE[c], strict=True)))
    found.update(ranked[:2])
    return found


_INDEXES: dict[int, tuple[Catalog, NameIndex]] = {}


def name_index(catalog: Catalog) -> NameIndex:
    """The name index of a catalog, built once per catalog object."""
    hit = _INDEXES.get(id(catalog))
    if hit is None or hit[0] is not catalog:
        hit = (catalog, NameIndex.build(catalog))
        _INDEXES[id(catalog)] = hit
    return hit[1]
