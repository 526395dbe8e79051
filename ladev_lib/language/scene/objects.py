"""Object clauses: quantities, positions (relations, regions) and unknown object phrases."""

from __future__ import annotations

import re
from typing import Any

from ladev_lib.language.scene.words import FILLERS, SCENE_NOUNS, STOP_PREPOSITIONS, Vocabulary


def canonical_name(vocab: Vocabulary, matched: str) -> str:
    """The catalog's spelling of a matched name (plurals and digit forms undone)."""
    canonical = vocab.canonical
    if matched in canonical:
        return canonical[matched]
    for suffix in ("es", "s"):
        if matched.endswith(suffix) and matched[: -len(suffix)] in canonical:
            return canonical[matched[: -len(suffix)]]
    return matched

def quantity(before: str) -> int:
    """How many of the next-named object: '2 apples', '2 of them are apples'."""
    m = re.search(r"(?:^|\s)([1-9]\d?)\s+(?:[a-z]+\s+)?$", before)
    if m and not re.search(r"\bof\s+(?:them|which)\s*$", before):
        n = int(m.group(1))
        return n if n <= 12 else 1
    m = re.search(r"\b([1-9]\d?)\s+of\s+(?:them|which)\s+(?:are|being)\s+(?:[a-z]+\s+)?$", before)
    if m:
        return int(m.group(1))
    return 1

def find_relation(vocab: Vocabulary, text: str) -> tuple[dict[str, Any], str] | None:
    """A position relative to another object ('near the bowl'), and the text without it."""
    relations = [
        (r"\b(?:to the )?left of\b", "left_of"),
        (r"\b(?:to the )?right of\b", "right_of"),
        (r"\bin front of\b", "in_front_of"),
        (r"\bbehind\b", "behind"),
        (r"\b(?:right next to|next to|near to|near|beside|besides|close to|by|adjacent to|alongside|nearby)\b", "near"),
        (r"\b(?:on top of|on|onto|inside of|inside|in)\b(?=\s+(?:the|a|an)\s)", "near"),
    ]
    for pattern, relation in relations:
        for m in re.finditer(pattern, text):
            rest = text[m.end():]
            ref = _reference(vocab, rest, strict=(m.group(0).strip() in ("on", "in", "onto", "inside", "inside of", "on top of", "by")))
            if ref is None:
                continue
            name, used = ref
            new_text = text[: m.start()] + " " + rest[used:]
            return {"relation": relation, "reference": name}, new_text
    return None

def _reference(vocab: Vocabulary, rest: str, strict: bool) -> tuple[str, int] | None:
    m = re.match(r"\s*(?:the|a|an)?\s*", rest)
    start = m.end() if m else 0
    name = vocab.name_pattern.match(rest, start)
    if name is not None:
        return canonical_name(vocab, name.group(0)), name.end()
    cat = re.match(rf"({'|'.join(re.escape(c) for c in vocab.categories)})(?:e?s)?\b", rest[start:])
    if cat is not None:
        return cat.group(1), start + cat.end()
    if strict:
        return None
    words = re.match(r"((?:[a-z]+\s*){1,3})", rest[start:])
    if words is None:
        return None
    phrase_words = []
    for w in words.group(1).split():
        if w in STOP_PREPOSITIONS or w in ("robot", "edge", "center", "centre", "middle", "camera", "corner", "side"):
            break
        phrase_words.append(w)
    if not phrase_words or phrase_words[0] in FILLERS:
        return None
    phrase = " ".join(phrase_words)
    return phrase, start + rest[start:].index(phrase) + len(phrase)

def find_region(text: str) -> tuple[str, str] | None:
    horizontal = vertical = None
    spans: list[tuple[int, int]] = []
    for m in re.finditer(r"\b(left|right)(?:\s*(?:hand|-hand))?\b", text):
        horizontal = m.group(1)
        spans.append(m.span())
    for m in re.finditer(
        r"\b(front|back|rear|top|bottom|far|far side|far end|near side|near the robot|close to the robot|"
        r"away from the robot|in front|at the back)\b",
        text,
    ):
        word = m.group(1)
        vertical = "back" if word in ("back", "rear", "bottom", "near side", "near the robot", "close to the robot", "at the back") else "front"
        spans.append(m.span())
    centre = re.search(r"\b(middle|center|centre|centered|centred|central)\b", text)
    if horizontal is None and vertical is None and centre is None:
        return None
    if horizontal is None and vertical is None:
        region = "center"
        assert centre is not None
        spans.append(centre.span())
    elif horizontal and vertical:
        region = f"{vertical}_{horizontal}"
    else:
        region = horizontal or vertical  # type: ignore[assignment]
    for a, b in sorted(spans, reverse=True):
        text = text[:a] + " " + text[b:]
    text = re.sub(r"\b(?:on|at|in|to|towards?|toward)\s+the\s+(?:side|corner|edge|part)?\b", " ", text)
    return region, text

def unknown_phrase(text: str) -> str | None:
    """An object phrase that names nothing in the catalog, where a phrase introduces one."""
    words = re.findall(r"@n@|@\w+@|[a-z][a-z0-9]*|\d+(?:\.\d+)?", text)
    run: list[str] = []
    introduced = False
    previous = ""
    for w in words:
        if w.startswith("@"):
            run = []
            previous = w
            continue
        if w in SCENE_NOUNS:
            return None
        if run and (w in STOP_PREPOSITIONS or w in ("that", "which", "who", "is", "are")):
            break
        if w in FILLERS or re.fullmatch(r"\d+(?:\.\d+)?", w):
            if not run:
                if w in ("a", "an", "the", "another", "add", "is", "are", "some") or re.fullmatch(r"\d+", w):
                    introduced = True
                previous = w
                continue
            break
        if not run and not introduced and previous not in ("a", "an", "the"):
            introduced = False
        run.append(w)
    if not run or not introduced or len(run) > 4:
        return None
    return " ".join(run)
