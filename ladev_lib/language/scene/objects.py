"""Object clauses: quantities, positions (relations, regions) and unknown object phrases."""

from __future__ import annotations

import re
from typing import Any

from ladev_lib.language.scene.words import (
    FILLERS,
    NON_OBJECT_NOUNS,
    SCENE_NOUNS,
    STOP_PREPOSITIONS,
    Vocabulary,
)


def canonical_name(vocab: Vocabulary, matched: str) -> str:
    """The catalog's spelling of a matched name (plurals and digit forms undone)."""
    canonical = vocab.canonical
    if matched in canonical:
        return canonical[matched]
    for suffix in ("es", "s"):
        if matched.endswith(suffix) and matched[: -len(suffix)] in canonical:
            return canonical[matched[: -len(suffix)]]
    for plural, single in (("ies", "y"), ("ves", "fe"), ("ves", "f")):  # "strawberries", "knives"
        if matched.endswith(plural) and matched[: -len(plural)] + single in canonical:
            return canonical[matched[: -len(plural)] + single]
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
            if relation == "near" and re.search(
                r"\b(?:throw|toss|put|add|bring|chuck|drop|pop|set|mix|stick|place|lay|join|come|came|fill)s?\s*$",
                text[: m.start()],
            ):
                continue  # "throw in a red bull can": a verb particle, not a place
            rest = text[m.end():]
            ref = _reference(vocab, rest, strict=(m.group(0).strip() in ("on", "in", "onto", "inside", "inside of", "on top of", "by")))
            if ref is None:
                continue
            name, used = ref
            new_text = text[: m.start()] + " " + rest[used:]
            return {"relation": relation, "reference": name}, new_text
    return None

def _reference(vocab: Vocabulary, rest: str, strict: bool) -> tuple[str, int] | None:
    if re.match(r"\s*(?:them|those|these|they|it|that|this|me|us|you)\b", rest):
        return None  # a pronoun: no object of its own ("a lamp behind them")
    if re.match(r"\s*(?:the\s+)?(?:front|back|far|near|left|right|rear)\s+(?:edge|side|end|corner)\b", rest):
        return None  # "near the front edge": a region of the table
    m = re.match(r"\s*(?:(?:the|a|an)\b)?\s*", rest)
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
    text = re.sub(r"\b(?:centrally|in the midst)\b", "center", text)
    text = re.sub(r"\brite\b", "right", text)
    text = re.sub(r"\bright(?=\s+(?:in|at|on|next|by|beside|near|there|here|now|behind|against)\b)", " ", text)
    horizontal: str | None = None
    vertical: str | None = None
    spans: list[tuple[int, int]] = []
    for m in re.finditer(r"\b(left|right)(?:\s*(?:hand|-hand))?\b", text):
        horizontal = m.group(1)
        spans.append(m.span())
    # From the viewer's side of the table: the far side is the back, the near side the front.
    for m in re.finditer(
        r"\b(away from the robot|far from the robot|near the robot|close to the robot|far side|far end|far edge|"
        r"near side|near edge|front edge|back edge|rear edge|far|front|back|rear|top|bottom|in front|at the back)\b",
        text,
    ):
        word = m.group(1)
        vertical = "back" if word in (
            "back", "rear", "bottom", "near the robot", "close to the robot", "at the back", "far side", "far end",
            "far edge", "back edge", "rear edge", "far", "top",
        ) else "front"
        spans.append(m.span())
    centre = re.search(r"\b(middle|center|centre|centered|centred|central)\b", text)
    if horizontal is None and vertical is None and centre is None:
        return None
    region: str
    if horizontal is not None and vertical is not None:
        region = f"{vertical}_{horizontal}"
    elif horizontal is not None or vertical is not None:
        region = horizontal or vertical or ""
    else:
        region = "center"
        assert centre is not None
        spans.append(centre.span())
    for a, b in sorted(spans, reverse=True):
        text = text[:a] + " " + text[b:]
    text = re.sub(r"\b(?:on|at|in|to|towards?|toward)\s+the\s+(?:side|corner|edge|part)?\b", " ", text)
    text = re.sub(r"\b(?:towards?|toward)(?:\s+the)?\s*$", " ", text)  # "both toward the left"
    return region, text

_JOINERS = {"and", "or", "plus", "also", "then"}


def unknown_phrase(text: str) -> str | None:
    """An object phrase that names nothing in the catalog, where a phrase introduces one."""
    text = re.sub(r"\([^()]*\)", " ", text)  # "my stapler (just clutter)": an aside
    words = re.findall(r"@n@|@\w+@|[a-z][a-z0-9]*|\d+(?:\.\d+)?", text)
    run: list[str] = []
    introduced = False
    content = [w for w in words if not w.startswith("@") and w not in FILLERS and not re.fullmatch(r"\d+(?:\.\d+)?", w)]
    if content and all(re.search(r"(?:ly|ed)$", w) for w in content):
        return None  # "loosely grouped", "neatly arranged": how, not what
    end = len(words)
    for i, w in enumerate(words):
        if w.startswith("@"):
            run = []
            continue
        if w in SCENE_NOUNS:
            nxt = words[i + 1] if i + 1 < len(words) else ""
            if not run and nxt.isalpha() and nxt not in FILLERS and nxt not in STOP_PREPOSITIONS and nxt not in SCENE_NOUNS:
                run.append(w)  # "a desk lamp": a scene noun as a modifier
                continue
            if run:
                end = i
                break
            continue
        if run and (w in STOP_PREPOSITIONS or w in ("that", "which", "who", "is", "are")):
            end = i
            break
        if w in FILLERS or w in ("my", "our") or re.fullmatch(r"\d+(?:\.\d+)?", w):
            if not run and w in ("the", "this", "that", "these", "those", "its", "their"):
                introduced = False  # "2 - the model confuses them": a determiner between
                continue
            if not run:
                # introduced as a new object: "a/an/my X", "2 X", "add X" (not "the X", a reference)
                if w in ("a", "an", "another", "add", "my", "our", "spawn") or re.fullmatch(r"\d+", w):
                    introduced = True
                continue
            end = i
            break
        run.append(w)
    if not run or len(run) > 3 or len("".join(run)) < 3 or run[-1] in NON_OBJECT_NOUNS:
        return None
    # the phrase must be all the clause names: nothing but fillers after it
    if any(w not in FILLERS and not w.startswith("@") and w not in STOP_PREPOSITIONS for w in words[end:]):
        return None
    # a bare item is a list entry ("pear, plum", "- softball"), not chat ("this time", "nothing fancy",
    # "no idea why"): nothing but a list joiner beside it
    others = [w for w in words if w not in run and not w.startswith("@")]
    bare_item = (
        len(content) == len(run) and len(words) <= len(run) + 1 and len(run) <= 2
        and all(w in _JOINERS for w in others)
    )
    if not introduced and not bare_item:
        return None
    if not introduced and re.search(r"[a-z]{3}(?<!s)s$", run[-1]):
        return None  # "something with tools": a kind of object, not one on the table
    return " ".join(run)


def singular(phrase: str) -> str:
    """The phrase with its last word in the singular ("soda cans" -> "soda can", "boxes" -> "box")."""
    words = phrase.split()
    w = words[-1]
    if re.search(r"(?:ch|sh|ss|x|z)es$", w):
        w = w[:-2]
    elif re.fullmatch(r"(?:pocket|steak|butter|bread|paring)?(?:kni|wi|li)ves", w):
        w = w[:-3] + "fe"  # knives, lives
    elif re.fullmatch(r"(?:book)?(?:shel|hal|wol|cal|sel|scar|loa|lea|thie|shea)ves", w):
        w = w[:-3] + "f"  # shelves, scarves, loaves, leaves, thieves
    elif w.endswith("ies") and len(w) > 4:
        w = w[:-3] + "y"
    elif w.endswith("s") and not w.endswith("ss"):
        w = w[:-1]
    return " ".join([*words[:-1], w])


_GROUP = re.compile(
    r"\b(?P<n>[2-9])\s+(?P<np>(?:[a-z]+\s+)?[a-z]+?)(?:es|s)\b"
    r"(?:\s+(?:on|at|in)\s+the\s+(?:table|scene|workspace|tabletop))?"  # "4 cups on the table: the ..."
    r"(?P<sep>\s*(?:,|:|-|\()\s*)"
    r"(?=(?:a|an|one|1|the)\s)"
)
_BACK_GROUP = re.compile(r"\b(?:those|these|the|both|all)\s+[2-9]\s+(?:[a-z]+\s+)?[a-z]{2,}?(?:es|s)\b")
_UNITS = {
    "degree", "deg", "cm", "mm", "centimeter", "centimetre", "millimeter", "millimetre", "percent", "second",
    "step", "time", "minute", "inch", "meter", "metre", "episode", "trial", "run",
}
ADJECTIVES = (
    r"green|yellow|red|blue|pink|purple|orange|white|black|brown|small|large|big|little|light blue|dark|other"
)
_GENERIC = {"object", "item", "thing", "prop", "piece", "distractor", "random object", "other object"}


def expand_groups(text: str, vocab: Vocabulary | None = None) -> str:
    """Plural groups spelled out item by item, as a person means them.

    "2 cubes, a green one and a yellow one" -> "a green cube and a yellow cube";
    "2 soda cans, a sprite and a 7up" -> "a sprite and a 7up" (the items are
    the group); "the green one" after "2 blocks" -> "the green block". Counts
    of generic nouns ("3 objects: ...") are totals and stay.
    """
    text = _bare_adjective_items(text)
    heads: list[tuple[int, str]] = []
    for m in re.finditer(r"\b([2-9])\s+((?:[a-z]+\s+)?[a-z]+(?:es|s))\b", text):
        np_ = singular(m.group(2).strip())
        if np_.split()[-1] in _UNITS or re.match(r"(?:more|other|random|extra)\b", np_):
            continue  # "3 degrees", "2 more objects": not a group of objects
        if np_ not in _GENERIC and np_.split()[-1] not in {w.split()[-1] for w in _GENERIC}:
            heads.append((m.end(), np_))

    def head_before(pos: int) -> str | None:
        found = [h for p, h in heads if p <= pos]
        return found[-1] if found else None

    def one(m: re.Match[str]) -> str:
        head = head_before(m.start()) or _named_head_before(text, m.start(), vocab)
        if head is None:
            return m.group(0)
        return f"{m.group(1)} {m.group(2)} {head}"

    def pair(m: re.Match[str]) -> str:
        head = head_before(m.start())
        if head is None:
            return m.group(0)
        return f"{m.group(1)} {m.group(2)} {head} and {m.group(3)} {m.group(4)} {head}"

    def listed(m: re.Match[str]) -> str:
        head = head_before(m.start())
        if head is None:
            return m.group(0)
        items = re.sub(rf"\b(a|an|one|1)\s+({ADJECTIVES})\b", rf"\1 \2 {head}", m.group(1))
        return f"{items}{m.group(2)} {m.group(3)} {head}"

    # "4 bricks (a green, a purple, a pink and a blue one)": every adjective shares the last "one"
    text = re.sub(
        rf"((?:\b(?:a|an|one|1)\s+(?:{ADJECTIVES})(?:\s*,\s*(?:and\s+)?|\s+and\s+))+)(a|an|one|1)\s+({ADJECTIVES})\s+(?:ones?|1)\b",
        listed, text,
    )
    # "2 cubes, a green and a yellow one": the first adjective shares the second's "one"
    text = re.sub(
        rf"\b(a|an|the|one|1)\s+({ADJECTIVES})\s+and\s+(a|an|the|one|1)\s+({ADJECTIVES})\s+(?:ones?|1)\b", pair, text
    )
    text = re.sub(rf"\b(a|an|the|one|1)\s+((?:[a-z]+\s+)?(?:{ADJECTIVES}))\s+(?:one|1)\b", one, text)
    # "those 2 blocks": the objects already named (by the task), not more of them
    text = _BACK_GROUP.sub(lambda m: " " + m.group(0).split(None, 1)[1] + "@", text)
    out = re.sub(r"\b[2-9]\s+(?:[a-z]+\s+)?[a-z]+@", " ", text)
    for m in list(_GROUP.finditer(text))[::-1]:
        np_ = m.group("np").strip()
        if np_ in _GENERIC or np_.split()[-1] in {w.split()[-1] for w in _GENERIC}:
            continue
        plural = text[m.start("np"):].split()[len(np_.split()) - 1]  # "cubes" (np is "cub" + "es")
        mods = tuple(w for w in np_.split()[:-1] if not re.fullmatch(rf"(?:{ADJECTIVES})", w))
        if not _members_follow(singular(re.sub(r"[^a-z]", "", plural)), text[m.end():], mods):
            continue
        if vocab is not None and not _one_object_named(vocab, np_, plural, text[m.end():]):
            continue  # "2 golf balls, a large blue cup": the golf balls are one catalog object, the cup is not one  # "2 lemons, a bowl and a sponge": a list that starts with a count, not a group
        out = out[: m.start()] + " " + out[m.end():]
    return out


_KIND_NOUNS = frozenset(
    {"can", "cube", "block", "brick", "ball", "fruit", "toy", "tool", "cup", "bottle", "box", "drink", "soda",
     "utensil", "vegetable", "veggie", "container", "kind", "type", "sort", "color", "colour"}
)
"""Group nouns whose items may be named without the noun ("2 soda cans, a sprite and a 7up")."""


def _named_head_before(text: str, pos: int, vocab: Vocabulary | None) -> str | None:
    """The noun of the object named last before ``pos``, without its adjectives: "the blue lego
    brick and the pink one" -> "lego brick"."""
    if vocab is None:
        return None
    said = [m for m in vocab.name_pattern.finditer(text, 0, pos)]
    if not said:
        return None
    name = canonical_name(vocab, said[-1].group(0))
    head = re.sub(rf"^(?:(?:{ADJECTIVES})\s+)+", "", name)
    return head or None


_ADJ_ITEM = rf"(?:(?:{ADJECTIVES})\s+)?(?:{ADJECTIVES})"


def _bare_adjective_items(text: str) -> str:
    """ "3 lego bricks (green, purple, small yellow)" -> "a green lego brick, a purple lego brick and
    a small yellow lego brick": items said by their adjectives alone, after a counted noun."""

    def spell(m: re.Match[str]) -> str:
        head = singular(m.group("noun"))
        items = [i.strip() for i in re.split(r"\s*,\s*(?:and\s+)?|\s+and\s+", m.group("items")) if i.strip()]
        if len(items) != int(m.group("n")):
            return m.group(0)
        said = [f"a {i} {head}" for i in items]
        return ", ".join(said[:-1]) + f" and {said[-1]}"

    return re.sub(
        rf"\b(?P<n>[2-9])\s+(?P<noun>(?:[a-z]+\s+)?[a-z]+s)\s*[(:]\s*"
        rf"(?P<items>{_ADJ_ITEM}(?:\s*,\s*(?:and\s+)?{_ADJ_ITEM}|\s+and\s+{_ADJ_ITEM})+)\s*\)?",
        spell, text,
    )


def _one_object_named(vocab: Vocabulary, np_: str, plural: str, after: str) -> bool:
    """When a group names one catalog object ("2 golf balls"), whether its first item is that object."""
    words = np_.split()
    group = " ".join([*words[:-1], singular(re.sub(r"[^a-z]", "", plural))])
    if group not in vocab.canonical:
        return True  # a kind ("2 soda cans", "4 fruits"): its items may be any objects of it
    first = re.split(r",|;|\)|\band\b|\.", after, maxsplit=1)[0]
    named = vocab.name_pattern.search(first)
    if named is None:
        return True  # "a green one", "the left one"
    return canonical_name(vocab, named.group(0)) == vocab.canonical[group]


def _members_follow(head: str, after: str, modifiers: tuple[str, ...] = ()) -> bool:
    """Whether what follows a count ("2 cubes, ...") spells out its members: the first item has
    the group's noun ``head``, is "one" or only adjectives, or the noun is a kind that items name
    alone. Not when the item is another kind of the same noun ("2 tennis balls, a golf ball")."""
    first = re.split(r",|;|\)|\band\b|\.", after, maxsplit=1)[0]
    words = [w for w in first.split() if w not in ("a", "an", "the", "one", "1")]
    kinds = [w for w in words[:-1] if not re.fullmatch(rf"(?:{ADJECTIVES})", w)]
    if modifiers and kinds and singular(words[-1]) == head and not set(modifiers) & set(kinds):
        return False
    if head in _KIND_NOUNS:
        return True
    if not words or words[-1] in ("ones", "1") or head in words or singular(words[-1]) == head:
        return True
    return all(re.fullmatch(rf"(?:{ADJECTIVES})", w) for w in words)
