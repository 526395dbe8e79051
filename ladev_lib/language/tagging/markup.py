"""The tag set and the inline markup annotated rows are written in.

An annotated description marks phrases as ``[[words|TAG]]``:

    "[[3 objects|TOTAL]]: [[a Coke can|OBJ]] [[on the left|POS]], [[an apple|OBJ]].
     [[Lights 30%|LIGHT]] brighter - wait, no, [[darker|LIGHT]]. [[Pick up|PICK]] [[the can|SRC]]."

:func:`parse_markup` gives the plain text and the character spans of the
tagged phrases. The tags (what each means is written for annotators in
``docs`` of the training data, and summarised here):

- objects: ``OBJ`` puts objects in the scene (with their count), ``ANY``
  random or unspecified ones, ``TOTAL`` the stated total, ``REF`` another
  mention of an object that is there anyway, ``DROP`` a mention of one that
  is not (taken back, replaced, ruled out);
- the task: ``SRC`` its object, ``TGT`` its destination, and the words that
  say which task it is: ``PICK``, ``NEAR``, ``ON``, ``IN``;
- positions: ``POS`` (said of the object phrase before it), ``POS_NEXT``
  (the one after), ``POS_ALL`` (every object phrase just before);
- ``LIGHT`` and ``CAM``: the words of the lighting and camera requests that
  still hold at the end, so that read in order they state them;
- in instructions, ``NEG`` (words that negate the task itself) and ``EXTRA``
  (another action or object asked for beyond the one task).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

TAGS: tuple[str, ...] = (
    "OBJ", "ANY", "TOTAL", "REF", "DROP", "SRC", "TGT", "PICK", "NEAR", "ON", "IN",
    "POS", "POS_NEXT", "POS_ALL", "LIGHT", "CAM", "NEG", "EXTRA",
)
"""Every tag, in a fixed order (the tagging head's label order depends on it)."""

OBJECT_TAGS = frozenset({"OBJ", "REF", "DROP", "SRC", "TGT"})
"""Tags of phrases that name an object."""
RELATION_TAGS = {"PICK": "pick_up", "NEAR": "move_near", "ON": "put_on", "IN": "put_in"}
"""Relation tags and the task each says."""

LABELS: tuple[str, ...] = ("O", *(f"{p}-{t}" for t in TAGS for p in ("B", "I")))
"""Token labels: outside, or the beginning / inside of a tagged phrase."""

_MARK = re.compile(r"\[\[([^\[\]|]+)\|([A-Z_]+)\]\]")


@dataclass(frozen=True)
class Span:
    """A tagged phrase: its tag and its character range in the plain text."""

    tag: str
    start: int
    end: int
    text: str


class MarkupError(ValueError):
    """An annotated text that cannot be read."""


def parse_markup(annotated: str) -> tuple[str, list[Span]]:
    """``[[words|TAG]]`` markup -> (plain text, spans in it)."""
    out: list[str] = []
    spans: list[Span] = []
    at = 0
    pos = 0
    for m in _MARK.finditer(annotated):
        out.append(annotated[at:m.start()])
        pos += m.start() - at
        words, tag = m.group(1), m.group(2)
        if tag not in TAGS:
            raise MarkupError(f"unknown tag {tag!r} in {m.group(0)!r}")
        lead = len(words) - len(words.lstrip())
        core = words.strip()
        spans.append(Span(tag, pos + lead, pos + lead + len(core), core))
        out.append(words)
        pos += len(words)
        at = m.end()
    out.append(annotated[at:])
    text = "".join(out)
    if "[[" in text or "]]" in text:
        raise MarkupError(f"broken markup in {annotated[:80]!r}")
    return text, spans


def to_markup(text: str, spans: list[Span]) -> str:
    """The inverse of :func:`parse_markup` (spans must not overlap)."""
    out: list[str] = []
    at = 0
    for s in sorted(spans, key=lambda s: s.start):
        out.append(text[at:s.start])
        out.append(f"[[{text[s.start:s.end]}|{s.tag}]]")
        at = s.end
    out.append(text[at:])
    return "".join(out)
