"""Instruction frames through the span tagger: the second reading the validator turns to.

The instruction parser (:func:`ladev_lib.language.frames.read_instruction`)
reads what it has rules for; a sentence around the command ("The concert went
well. Anyway: rosin, in the violin case, please."), an end state, a
step-by-step version it does not know is "not understood". The span tagger
marks the task's object and destination, the words that say which task, a
negation of the task (``NEG``) and anything asked beyond it (``EXTRA``);
each marked phrase is then read alone by the parser ("pick up <phrase>"), so
that its noun-phrase analysis (head, modifiers, qualifiers such as "on the
left") and its grounding are the parser's own.

    read_tagged_instruction("It's raining again. Anyway, the mug goes in the sink, thanks!")
    -> Frame(task="put_in", object=NounPhrase("mug"), destination=NounPhrase("sink"), ...)
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from ladev_lib.catalog import Catalog
from ladev_lib.language.frames import Frame, read_instruction
from ladev_lib.language.tagging.markup import RELATION_TAGS, Span

_PRONOUN = re.compile(r"^(?:it|them|that|this|that one|this one|those|these|they)$", re.IGNORECASE)
_OBJECT_TAGS = ("OBJ", "REF", "SRC", "TGT")
NOTE = "read by the span tagger"


def _phrase(spans: list[Span], tag: str) -> Span | None:
    found = [s for s in spans if s.tag == tag]
    named = [s for s in found if not _PRONOUN.match(s.text.strip())]
    return (named or found)[-1] if found else None


def _antecedent(spans: list[Span], at: Span) -> str | None:
    """The object a pronoun stands for: the last object phrase before it, or the object of an extra step
    before it ("rinse the beaker, then put it on the shelf")."""
    for s in reversed([s for s in spans if s.end <= at.start]):
        if s.tag in _OBJECT_TAGS and not _PRONOUN.match(s.text.strip()):
            return s.text
        if s.tag == "EXTRA":
            m = re.search(r"\b(?:the|a|an|your|my)\s+([\w' -]+)$", s.text.strip())
            if m is not None:
                return m.group(0)
    return None


_COORDINATED_AFTER = re.compile(
    r"^\s*(?:\+|&|,?\s*(?:and|or|plus|as well as|together with|along with))\s+"
    r"(?:(?:the|a|an|your|my|this|that|those|these|its|one|two|another)\b|[^\W\d_]+\s*(?:[,.;]|$))", re.IGNORECASE
)
_COORDINATED_BEFORE = re.compile(r"\b(?:both|either|all of)\s*$", re.IGNORECASE)


def _coordinated(text: str, spans: list[Span]) -> tuple[str, ...]:
    """Another object joined to the task's object or destination ("the bowl and the cup", "pen + notebook",
    "both the bowl and ..."): the instruction asks for more than one object in that role."""
    found: list[str] = []
    for s in spans:
        if s.tag not in ("SRC", "TGT"):
            continue
        after = text[s.end:]
        verb_next = re.match(r"^\s*,?\s*(?:and|or)\s+(?:then\s+)?[a-z]+\s+(?:it|them|the|this|that)\b", after, re.IGNORECASE)
        if (_COORDINATED_AFTER.match(after) and not verb_next) or _COORDINATED_BEFORE.search(text[: s.start]):
            found.append(f"another object beside {s.text.strip()!r}")
    return tuple(found)


def _noun_phrase(phrase: str, scene_objects: Iterable[str] | None, catalog: Catalog | None) -> Frame:
    """A phrase read alone, with its modifiers and qualifiers ("the notebook on the left")."""
    return read_instruction(f"pick up {phrase.strip()}", scene_objects, catalog)


def frame_from_spans(
    text: str, spans: list[Span], scene_objects: Iterable[str] | None = None, catalog: Catalog | None = None
) -> Frame:
    """The frame the tagged phrases of one instruction state."""
    scene = list(scene_objects) if scene_objects is not None else None
    relations = [RELATION_TAGS[s.tag] for s in spans if s.tag in RELATION_TAGS]
    placing = [r for r in relations if r != "pick_up"]
    negations = tuple(s.text for s in spans if s.tag == "NEG")
    extras = tuple(s.text for s in spans if s.tag == "EXTRA") + _coordinated(text, spans)
    if negations:
        changed: str | None = f"negated: {', '.join(repr(n) for n in negations)}"
    elif extras:
        changed = f"asks for more than the task: {', '.join(repr(e) for e in extras)}"
    else:
        changed = None
    src, tgt = _phrase(spans, "SRC"), _phrase(spans, "TGT")

    def done(task: str | None, reason: str | None, **kw: object) -> Frame:
        return Frame(text, task, negated=bool(negations), extra_steps=extras, reason=changed or reason,
                     notes=(NOTE,), **kw)  # type: ignore[arg-type]

    if not relations and src is None:
        return done(None, "no task read")
    if not relations:
        # an object acted on with no word of the four tasks: another action ("knock over the can")
        return done("other", f"'{text.strip()}' is none of the four tasks")
    kind = placing[-1] if placing else "pick_up"
    src_text = src.text if src is not None else None
    if src is not None and _PRONOUN.match(src.text.strip()):
        src_text = _antecedent(spans, src)
    if src_text is None:
        return done(kind, "no object to act on named")
    tgt_text = tgt.text if tgt is not None else None
    if tgt is not None and _PRONOUN.match(tgt.text.strip()):
        tgt_text = _antecedent(spans, tgt)
    if kind != "pick_up" and tgt_text is None:
        return done(kind, "no destination named", dropped_roles=("destination",))
    obj = _noun_phrase(src_text, scene, catalog)
    dest = _noun_phrase(tgt_text, scene, catalog) if kind != "pick_up" and tgt_text is not None else None
    reason = changed or obj.reason or (dest.reason if dest is not None else None)
    if obj.object is None or (dest is not None and dest.object is None):
        reason = reason or "an object phrase could not be read"
    return Frame(
        text=text, task=kind, object=obj.object, destination=dest.object if dest is not None else None,
        negated=bool(negations), extra_steps=extras, reason=reason,
        notes=(*obj.notes, *(dest.notes if dest is not None else ()), NOTE),
    )


def read_tagged_instruction(
    text: str, scene_objects: Iterable[str] | None = None, catalog: Catalog | None = None
) -> Frame:
    """One instruction read through the span tagger (the packaged weights)."""
    from ladev_lib.language.tagging.model import load_tagger

    return frame_from_spans(text, load_tagger().tag(text), scene_objects, catalog)


__all__ = ["NOTE", "frame_from_spans", "read_tagged_instruction"]
