"""The scene from a tagged description: what the tagger marked, read by the value rules.

The span tagger (:mod:`ladev_lib.language.tagging`) decides *which* phrases
say what: the objects put in the scene, those only mentioned again or taken
back, the random fill and the stated total, the task's object, destination
and relation, positions, and the lighting and camera words that still hold
after the writer's corrections. This module reads the values out of those
phrases with the rule readers' value functions (catalog names, counts,
regions, amounts, directions) and assembles the same operations dict as
:func:`ladev_lib.language.scene.reader.read_description`.

    read_tagged("a bowl - no, a basket, and two plums; one plum goes in the basket", vocab)
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from ladev_lib.language.frames import read_instruction
from ladev_lib.language.scene.environment import merge_camera
from ladev_lib.language.scene.objects import (
    canonical_name,
    find_region,
    find_relation,
    singular,
)
from ladev_lib.language.scene.settings import read_camera_request, read_lighting_request
from ladev_lib.language.scene.words import (
    PAIRED_NOUNS,
    Vocabulary,
    normalize_text,
    protect_coordinates,
)
from ladev_lib.language.tagging.markup import RELATION_TAGS, Span

_OBJECT_TAGS = ("OBJ", "REF", "DROP", "SRC", "TGT")
_POSITION_TAGS = ("POS", "POS_NEXT", "POS_ALL")
_PRONOUN = re.compile(
    r"^(?:it|them|that|this|that one|this one|those|these|they|the one|one|same|latter|former|(?:any |each |either )?of "
    r"(?:them|those|these))$"
)
_PLURAL_PRONOUN = re.compile(r"^(?:them|those|these|they|(?:any |each |either )?of (?:them|those|these))$")
_PREPOSITION_BEFORE = re.compile(
    r"\b(?:with|near|next to|by|behind|beside|besides|on|onto|on top of|in|into|inside|at|to|of|from|than|around|"
    r"under|beneath|against|alongside|toward|towards|between|among|for|over|above|across|past|beyond)\s+"
    r"(?:(?:the|a|an|this|that|its|my|your|our|one of the|both)\s+)?$"
)
_DETERMINERS = re.compile(
    r"^(?:(?:the|a|an|one|some|any|another|that|this|those|these|its|my|our|your|said|same|both|each|"
    r"single|lone|one of the|one of|of the|other|\d+x?|x\d+)\s+)+"
)
_NUMBER = re.compile(r"(?<![\d.])(\d+)(?![\d.])")
_SENTENCE_END = re.compile(r"[.!?;\n]")
_WORDS = ("zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve")


_ADJECTIVE = re.compile(
    r"^(?:(?:small|large|big|little|tiny|light|dark|extra large|plain|regular|"
    r"green|yellow|red|blue|pink|purple|orange|white|black|brown|grey|gray|navy|lime green)\s*)+$"
)
_RELATION_WORDS = re.compile(
    r"\b(?:near|next to|beside|besides|by|close to|closer to|alongside|adjacent to|around|left of|right of|flanking|"
    r"surrounding|either side of|on either side of|"
    r"in front of|behind|against|nearby|touching|beneath|under|on top of|on|atop|in|inside|into|between|with)"
    r"(?:\s+(?:of|to))?\s*$"
)
_GROUP_NOUN = re.compile(r"\b(?:\d+|two|three|four|five|six|seven|several|some|few|pair of|couple of)\s+((?:[a-z]+\s+){0,2}[a-z]+s)\b")
_TASK_CUE = (
    r"\b(?:task|goal|aim|objective|job|test|robot|arm|gripper|manipulator|should|must|needs?|wants?|want|goes|go|"
    r"put|puts|place|places|move|moves|set|sets|drop|drops|pick|picks|lift|lifts|grab|grabs|bring|brings|stack|"
    r"lay|lays|slide|slides|carry|carries|take|takes|get|gets|end up|ends up|can it|could it|will|try|push|pushes|"
    r"nudge|nudges|shove|shoves|tuck|tucks|pop|pops|toss|tosses|nest|nests|drag|drags|transfer|transfers|deposit|"
    r"insert|inserts|load|loads|then|next|finally|afterwards|ends?|finish(?:es)?)\b|->|=>|\?"
)
_DROP_BEFORE = re.compile(
    r"(?i)\b(?:no|not|nope|without|minus|except|nor|neither|instead|rather|place of|remove|removing|removed|drop|dropped|"
    r"delete|scratch|scrap|leave|take|get rid|lose|skip|forget|ditch|cut|nix|exclude|excluding|omit|replace[sd]?|replacing|swap|"
    r"swapping|switch|exchange|substitute|don'?t|do not|no longer|never|sorry|actually|wait|correction|make (?:that|it)|"
    r"make (?:the|them|those)|i mean|but|strike|cross|kill|pull|toss|bin|trash|zero|del|rm|despawn|ignore|disregard|"
    r"meant|originally|old|draft|earlier|previous|used to|plan|hmm|er|um|oops|ugh|edit|use|using|better|only|this time)\b|"
    r"[-~!#\u2717\u2718\u00d7]\s*$|<-"
)
"""Words before a phrase (in its clause) that can take it back."""
_DROP_AFTER = re.compile(
    r"(?i)\b(?:no|not|nope|never|wait|sorry|actually|correction|make (?:that|it)|i mean|rather|instead|replaced?|replaces|"
    r"swap(?:ped)?|switch(?:ed)?|goes|go|gone|out|away|remove[ds]?|delete[ds]?|scratch(?:ed)?|scrap|skip|drop(?:ped)?|ditch|"
    r"forget|nix|cut|isn'?t|don'?t|won'?t|get rid|hmm|oops|changed?|mind|after all|anymore|any more|either|excluded|"
    r"omitted|struck|crossed|zero|none|false|off|ignore|ignored|disregard|old|meant|better|er|um|use|too|only)\b|~~|\)|->|"
    r"\u2192|=>|<-|#|\u2014"
)
"""Words between a phrase and the next object phrase that can take it back."""
_SUPPORT = (
    r"(?:(?:the|a|our|my|this|lab|robot|work|bare|empty|whole)\s+)*(?:table|table ?top|desk|desktop|counter|counter ?top|"
    r"worktop|work ?surface|workspace|work area|surface|workbench|bench ?top|floor|scene|setup|set-up|tray area)s?"
)
"""What the scene stands on: said as a subject or a place ("the tabletop has..."), never an object of it."""
_FUNCTION_WORDS = frozenset({
    "the", "a", "an", "to", "into", "onto", "on", "in", "near", "next", "with", "and", "then", "of", "inside", "beside",
    "by", "at", "from", "top", "it", "task", "obj", "object", "target", "dest",
})
_ORDINALS = frozenset({"first", "second", "third", "fourth", "fifth", "sixth", "seventh", "last", "next", "other"})
_NOT_ITEMS = frozenset({
    "lighting", "light", "lights", "camera", "cam", "setup", "table", "scene", "task", "objects", "object", "things",
    "thing", "items", "item", "robot", "arm", "gripper", "default", "normal", "same", "nothing", "none", "rest",
    "others", "random", "stuff", "everything", "anything", "something", "brightness", "view", "change", "changes",
})
_STOPWORDS = frozenset({"the", "a", "an", "of", "and", "or", "to", "in", "on", "at", "with", "some", "any"})


@dataclass
class _Mention:
    tag: str
    span: Span
    name: str | None = None
    """Catalog name (as the vocabulary spells it) or, for an unknown object, its phrase."""
    unknown: bool = False
    count: int = 1
    positions: list[dict[str, Any]] = field(default_factory=list)

    @property
    def position(self) -> dict[str, Any] | None:
        return self.positions[-1] if self.positions else None


@dataclass
class _Object:
    name: str
    unknown: bool = False
    position: dict[str, Any] | None = None
    mentions: list[_Mention] = field(default_factory=list)


def _norm(text: str, vocab: Vocabulary) -> str:
    return normalize_text(text, vocab).strip(" .,;:!?\"'()[]")


def _count(normal: str, default: int = 1) -> int:
    m = _NUMBER.search(normal)
    if m is None:
        return default
    n = int(m.group(1))
    return n if 0 < n <= 12 else default


def _names(phrase: str, vocab: Vocabulary) -> list[tuple[str, int]]:
    """(catalog name, count) for each catalog name in an object phrase ("two apples and a pear", "apple x2")."""
    normal = _counted(_norm(re.sub(r"[\"`]", " ", phrase), vocab))
    # "a lego brick (green)": a colour said in brackets after the name
    normal = re.sub(r"([a-z][a-z ]*?)\s*\(\s*(green|yellow|red|blue|pink|purple|orange|white|black|small|large|big)\s*\)",
                    r"\2 \1", normal)
    out: list[tuple[str, int]] = []
    at = 0
    found = list(vocab.name_pattern.finditer(normal))
    for k, m in enumerate(found):
        before = normal[at:m.start()]
        if out and not re.search(r"[,;/&+]|\b(?:and|or|plus|with|then)\b", before) and (
            _object_id(vocab, out[-1][0]) == _object_id(vocab, canonical_name(vocab, m.group(0)))
            or _object_id(vocab, out[-1][0]) is None
        ):
            out.pop()  # "cheez it cracker box": two names of one object side by side are that object
        after = re.match(r"\s*(?:\(\s*)?(?:x|×|\*|times\s*)\s*(\d{1,2})\b|\s*\(\s*(\d{1,2})\s*\)", normal[m.end():])
        if after is None and k == len(found) - 1:
            # "carrot,2", "tennis ball, qty: 2", "name: mug, count 3": a count that ends the phrase
            after = re.fullmatch(
                r"\s*[-,:;=|(]?\s*(?:(?:qty|count|quantity|num|number|n|amount)\s*[:=]?\s*|(?:say|like|about|around|maybe|"
                r"roughly|approximately)\s+)?(\d{1,2})\s*[;,]?\s*|(?!)(\d)",
                normal[m.end():],
            )
        if re.search(r"\bone of (?:the|those|these|them)?\s*$", before):
            n = 1
        elif after is not None:
            n = int(after.group(1) or after.group(2))
        elif re.fullmatch(r"\s*(\d{1,2})\s*(?:pcs|pc|pieces|units|ea|x|×)?\s*[,;:|x×*]?\s*", before):
            n = int(re.search(r"\d+", before).group(0))  # type: ignore[union-attr]  # "2,tennis ball", "2 pcs,peach"
        else:
            n = _count(before.split(",")[-1].split(" and ")[-1]) if _NUMBER.search(before) else 1
            said = m.group(0)
            if n == 1 and said not in vocab.canonical and said.endswith("s") and not re.search(
                r"\b(?:a|an|one|single|each|every|either)\s+(?:\w+\s+)?$", before
            ):
                n = 0  # "golf balls": more than one, how many unsaid
        name = canonical_name(vocab, m.group(0))
        post = re.match(r"\s+([a-z]+)\b", normal[m.end():])
        if post is not None and f"{post.group(1)} {name}" in vocab.canonical:
            name = vocab.canonical[f"{post.group(1)} {name}"]  # "apple red", "plate red": the adjective said after
        out.append((name, max(min(n, 12), 0)))
        at = m.end()
    return out


def _object_id(vocab: Vocabulary, name: str) -> str | None:
    """The catalog id of a name or display name the vocabulary knows ("7 up" and "7up", "seven up can")."""
    for form in (name, vocab.canonical.get(name, name), re.sub(r"(?<=\d) (?=[a-z])", "", name)):
        oid = vocab.name_ids.get(form) or next((c for c, d in vocab.ids.items() if d == form), None)
        if oid is not None:
            return oid
    return None


def _counted(normal: str) -> str:
    """Counts said with words for them as digits: "pair of peaches", "one pair of golf balls", "half a dozen eggs",
    "three or so"."""
    normal = re.sub(rf"\b(?:(?:a|one|1)\s+)?(?:pair|couple)\s+of\b(?!\s+(?:{PAIRED_NOUNS})\b)", "2", normal)
    normal = re.sub(r"\b([2-6])\s+(?:pairs|couples)\s+of\b", lambda m: str(2 * int(m.group(1))), normal)
    normal = re.sub(r"\bhalf (?:a )?dozen\b", "6", normal)
    normal = re.sub(r"\b(?:a|one|1)\s+dozen\b", "12", normal)
    return re.sub(r"\b(\d{1,2})\s*(?:or so|-ish|ish|or thereabouts)\b", r"\1", normal)


_GENERIC_NAMES = (
    (re.compile(r"^(?:(?:my|an?)\s+)?(?:i ?phone|cell ?phone|mobile(?: phone)?|phone|android(?: phone)?|smart ?phone)$"),
     "smartphone"),
    (re.compile(r"^(?:mac ?book|notebook computer|laptop computer)$"), "laptop"),
)
_ABBREVIATIONS = {
    "cn": "can", "bx": "box", "btl": "bottle", "bttl": "bottle", "lg": "large", "lrg": "large", "sm": "small",
    "sml": "small", "med": "medium", "blu": "blue", "grn": "green", "ylw": "yellow", "yel": "yellow", "rd": "red",
    "pnk": "pink", "prpl": "purple", "choc": "chocolate", "scrwdrvr": "screwdriver",
}
"""Shorthand people write in notes for words of catalog names."""


def _edits(a: str, b: str, limit: int) -> int:
    """Edits from ``a`` to ``b`` (insert, delete, replace, swap two neighbours), or ``limit + 1`` when more."""
    prev2: list[int] | None = None
    prev = list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        cur = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cur[j] = min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1]))
            if prev2 is not None and i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                cur[j] = min(cur[j], prev2[j - 2] + 1)
        if min(cur) > limit:
            return limit + 1
        prev2, prev = prev, cur
    return prev[-1]


_MEASURE = re.compile(r"^(?:pair|set|bunch|couple|piece|bundle|ring|kind|sort|type)s? of\s+(?=\w)")


def _unknown_name(bare: str) -> str:
    """How an object the catalog lacks is reported: its noun phrase without measure words ("a set of keys" ->
    "keys"), brand and short names as the generic thing ("iPhone", "phone" -> "smartphone")."""
    name = _MEASURE.sub("", bare.strip())
    for pattern, generic in _GENERIC_NAMES:
        if pattern.match(name):
            return generic
    return name


def _bare(phrase: str, vocab: Vocabulary) -> str:
    """An object phrase without its determiners and count ("a little toy car" -> "little toy car")."""
    normal = _norm(re.sub(r"\b(?:one|ones)\b", "qqoneqq", phrase, flags=re.IGNORECASE), vocab)
    normal = re.sub(r"\([^()]*\)", " ", normal)
    normal = re.sub(r"^(?:either|any|whichever|each)\s+", "", normal.strip())
    normal = _DETERMINERS.sub("", normal.strip())
    normal = re.sub(r"^(?:qqoneqq of (?:the |those |these )?)", "", normal)
    normal = re.sub(r"^qqoneqq\s+(?=\w)", "", normal)
    normal = re.sub(r"\s+", " ", normal).strip(" .,;:-")
    return normal.replace("qqoneqq", "one")


class _Assembly:
    def __init__(self, text: str, spans: list[Span], vocab: Vocabulary) -> None:
        self.text = text
        self.spans = sorted(spans, key=lambda s: s.start)
        self.vocab = vocab
        self.mentions: list[_Mention] = []
        self.objects: list[_Object] = []
        self._pronoun_refs: list[tuple[int, str]] = []
        """(where, what) for positions said relative to a pronoun inside their words ("to its left")."""
        self.removed: set[str] = set()
        """Names of objects a taken-back mention removed ("replace the towel with a plate")."""

    def retag(self) -> None:
        """What a phrase's own words say about its tag: "not a bowl" takes it back, "random filler up to five
        objects" and "just the two" state totals, "any two objects" are random ones, "random objects: two" counts."""
        out: list[Span] = []
        spans = self.spans
        skip: set[int] = set()
        for k, s in enumerate(spans):
            if k in skip:
                continue
            low = s.text.lower()
            before = self.text[max(0, s.start - 12):s.start].lower()
            tag = s.tag
            if tag == "DROP" and not self._drop_said(k, out):
                tag = "OBJ"
            if tag == "OBJ" and re.search(r"\b(?:not|no|without|minus|except)\s+$", before) and not re.search(
                r"\b(?:nothing|none|no other|no objects?|no items?|no things?|empty)\b[^.;:]*\bexcept\s+$",
                self.text[max(0, s.start - 80):s.start].lower(),
            ):
                tag = "DROP"  # "not a bowl", "without a sponge"; "nothing on the table except a ball" keeps the ball
            elif tag == "SRC" and re.search(
                r"\b(?:remove|drop|delete|scratch|leave out|take out|take away|get rid of|lose|skip|forget|ditch|nix)\s+$",
                before,
            ) and not any(t.tag in RELATION_TAGS and t.start > s.end and self._same_sentence(s.end, t.start) for t in spans) \
                    and not re.match(r"\s*(?:in|into|on|onto|inside|next to|near|beside|over)\b", self.text[s.end:s.end + 12].lower()):
                tag = "DROP"  # "Drop the peach." with no destination: taken out of the scene, no task
            elif tag in ("OBJ", "REF") and re.search(
                r"\b(?:remove|drop|delete|scratch|leave out|take out|take away|get rid of|lose|skip|forget|ditch|cut|nix)"
                r"\s+$", before
            ) and not self._kept_after(s):
                tag = "DROP"  # "actually, drop the pepsi can" (not "remove the banana... actually no, keep it")
            elif tag in ("OBJ", "REF") and re.match(
                r"\s*(?:[-\u2014\u2013,;:]|\.\s)?\s*(?:please\s+)?(?:remove|drop|delete|take out|lose|ditch|get rid of)\s+"
                r"(?:it|that one|that)\b", self.text[s.end:s.end + 40], re.IGNORECASE
            ):
                tag = "DROP"  # "Not the coffee can - remove it from the scene."
            elif tag in ("OBJ", "REF") and self._replaced(s, k):
                tag = "DROP"  # "replace the spoon with a knife", "a basket instead of the bowl", "not the knife after all"
            elif tag == "ANY" and re.search(r"\bup to\s+$", before):
                tag = "TOTAL"  # "fill the table up to six objects with random stuff"
            elif tag == "ANY" and re.search(
                r"\bup to\s+(?:\d|one|two|three|four|five|six|seven|eight|nine|ten)\b|\b(?:in total|total|in all|overall|"
                r"altogether)\b", low
            ) or tag == "ANY" and re.match(r"\s*(?:just |only )?(?:the|those|these)\s+(?:\d+|two|three|four|five|six|seven)\b"
                                          r"(?!\s+(?:others?|more|remaining|extra|random|rest))", low):
                tag = "TOTAL"
            elif tag == "TOTAL" and re.search(r"\b(?:any|random|other|more|extra|additional|arbitrary|fillers?|"
                                              r"distractors?|spare|decoys?|filler objects?)\b", low):
                tag = "ANY"
            elif tag in ("CAM", "LIGHT") and re.fullmatch(r"\(?\s*[-+]?[\d.]+\s*(?:cm|mm|m)?\s*,\s*[-+]?[\d.]+\s*(?:cm|mm|m)?\s*\)?", low) \
                    and re.search(r"(?:\bto|\bat|@)\s*\(?\s*$", before):
                # "ADD soup can to (5 cm, -10 cm)": where the object goes (brackets included)
                start = s.start - 1 if self.text[max(0, s.start - 1):s.start] == "(" else s.start
                end = s.end + 1 if self.text[s.end:s.end + 1] == ")" else s.end
                s = Span(s.tag, start, end, self.text[start:end])
                tag = "POS"
            if tag == "ANY" and not _NUMBER.search(_norm(s.text, self.vocab)) and k + 1 < len(spans):
                nxt = spans[k + 1]
                if nxt.tag == "TOTAL" and re.fullmatch(r"\s*[:=]\s*", self.text[s.end:nxt.start]):
                    out.append(Span("ANY", s.start, nxt.end, self.text[s.start:nxt.end]))  # "random objects: two"
                    skip.add(k + 1)
                    continue
            out.append(Span(tag, s.start, s.end, s.text) if tag != s.tag else s)
        # "a sponge near the plate; camera 2 cm up": an indefinite object placed by a relation, in a clause with no
        # word of doing or wanting, describes the scene (a position), it states no task
        for k, s in enumerate(out):
            if s.tag != "SRC" or not re.match(r"(?i)\s*(?:a|an|one)\s", s.text):
                continue
            lo = max(self.text.rfind(c, 0, s.start) for c in ".;\n") + 1  # a label before a colon counts ("Task: ...")
            hi = min([e for e in (self.text.find(c, s.end) for c in ".;\n") if e >= 0] or [len(self.text)])
            clause = self.text[lo:hi].lower()
            if re.search(_TASK_CUE, clause):
                continue
            moving = [t for t in out[k + 1:] if t.start < hi and t.tag in ("ON", "IN", "NEAR")]
            if moving and re.fullmatch(r"(?:into|onto|on to|in to|->|→|=>)", moving[0].text.lower().strip()):
                continue  # "one golf ball into the bowl": a direction of motion, a task said without its verb
            for j in range(k, len(out)):
                t = out[j]
                if t.start >= hi:
                    break
                new = {"SRC": "OBJ", "TGT": "REF", "NEAR": "POS", "ON": "POS", "IN": "POS"}.get(t.tag)
                if new is not None:
                    out[j] = Span(new, t.start, t.end, t.text)
        out = self._listed_items(out)
        out = self._corrected_lists(out)
        out = self._task_literal(out)
        out = self._landmarks_and_echoes(out)
        # "[cup] with [a handle]": two object phrases that together are one catalog name are that object
        joined: list[Span] = []
        for s in out:
            last = joined[-1] if joined else None
            if last is not None and last.tag == s.tag and s.tag in _OBJECT_TAGS and re.fullmatch(
                r"\s+(?:with|of)?\s*", self.text[last.end:s.start]
            ):
                whole = self.text[last.start:s.end]
                names = _names(whole, self.vocab)
                if len(names) == 1 and not _names(last.text, self.vocab) and names != _names(s.text, self.vocab):
                    joined[-1] = Span(s.tag, last.start, s.end, whole)
                    continue
            joined.append(s)
        self.spans = joined

    def _drop_said(self, k: int, decided: list[Span]) -> bool:
        """Whether a phrase tagged as taken back has words that take it back: near it (before it in its clause,
        "scratch the softball", "no stapler", "instead of the bowl"; or between it and the next object phrase, "a
        bowl -- no, a basket", "lemon <- ignore", "Red Bull -> Pepsi"), or at a later mention of the same object
        ("a softball ... Scratch the softball"), or at an earlier one taken back. An object that replaces another ("swap the bowl for [the basket]")
        is not taken back."""
        s = self.spans[k]
        objects = [t for t in self.spans if t.tag in _OBJECT_TAGS]
        earlier = [t for t in objects if t.end <= s.start]
        if earlier and re.fullmatch(r"\s+(?:out\s+)?(?:with|for|by|to|into)\s+", self.text[earlier[-1].end:s.start].lower()) \
                and re.search(r"\b(?:replace|swap(?:\s+out)?|switch(?:\s+out)?|exchange|trade|change)\s+$",
                              self.text[max(0, earlier[-1].start - 16):earlier[-1].start].lower()):
            return False
        lo = max([self.text.rfind(c, 0, s.start) for c in ".;\n!?"] + [s.start - 50, 0])
        if _DROP_BEFORE.search(self.text[lo:s.start]) or _DROP_BEFORE.search(s.text):
            return True
        later = [t for t in objects if t.start >= s.end]
        hi = min(later[0].start if later else len(self.text), s.end + 60)
        gap = self.text[s.end:hi]
        if _DROP_AFTER.search(gap) and not (later and hi == later[0].start and re.search(
                r"\b(?:swap|replace|remove|scratch|scrap|drop|delete|lose|ditch|skip|nix|cut|forget|leave out|take out|"
                r"get rid of|not|no|without|instead of|rather than)\s+(?:(?:the|a|an)\s+)?$", gap.lower())):
            return True  # "a plate. Oh wait, swap [the Red Bull]": the words are said of the next one
        def words(text: str) -> set[str]:
            return {w.rstrip("s") for w in re.findall(r"[a-z]+", text.lower()) if w not in _STOPWORDS and len(w) > 2}
        def same(a: str, b: str) -> bool:
            na, nb = {n for n, _ in _names(a, self.vocab)}, {n for n, _ in _names(b, self.vocab)}
            if na and nb:
                return bool(na & nb) or any(x in y or y in x for x in na for y in nb)  # "the Spam" / "a Spam can"
            return bool(words(a) & words(b))
        return any(same(s.text, t.text) for t in later) or any(t.tag == "DROP" and same(s.text, t.text) for t in decided)

    def _task_literal(self, spans: list[Span]) -> list[Span]:
        """A task written as the schema writes it, with its arguments after it: "TASK put_in plum lunchbox",
        "task,move_near,mustard bottle;spam can", "pick_up: carrot". The arguments are split at separators, or
        at the catalog's names ("put_in golf ball large blue cup"); a word no name covers is a name of its own."""
        found = list(re.finditer(r"\b(pick_up|move_near|put_on|put_in)\b", self.text))
        if len(found) != 1:
            return spans
        lit = found[0]
        need = 1 if lit.group(1) == "pick_up" else 2
        stops = ["\n", ")", "}", " --", "["]
        line = self.text[self.text.rfind("\n", 0, lit.start()) + 1:lit.start()]
        stops += [q for q in "\"'" if line.count(q) % 2]  # a task inside a quoted string ends with it
        line_end = min([e for e in (self.text.find(c, lit.end()) for c in stops) if e >= 0] or [len(self.text)])
        region = self.text[lit.end():line_end]
        args: list[tuple[int, int]] = []
        for m in re.finditer(r"[^,;:|'\"\[\]{}()<>=\u2192]+", region):
            piece = m.group(0)
            if re.fullmatch(r"\s*(?:-+|to|into|onto|on|in|near|and)?\s*", piece, re.IGNORECASE):
                continue
            a = lit.end() + m.start() + len(piece) - len(piece.lstrip())
            args.extend(self._names_in(a, lit.end() + m.start() + len(piece.rstrip())))
        args = [(a, b) for a, b in args if re.search(r"[A-Za-z]", self.text[a:b])][:need]
        if len(args) != need or any(t.tag in ("SRC", "TGT") and not args[0][0] <= t.start < args[-1][1] for t in spans):
            return spans  # fewer arguments than the task has, or the task's objects are said elsewhere (corrected)
        roles = [("SRC", *args[0])] + ([("TGT", *args[1])] if need == 2 else [])
        lo, hi = args[0][0], args[-1][1]
        kept = [t for t in spans if not (t.tag in _OBJECT_TAGS and t.start < hi and t.end > lo)
                and not (t.tag in RELATION_TAGS and t.start < lit.end() and t.end > lit.start())]
        tag = {"pick_up": "PICK", "move_near": "NEAR", "put_on": "ON", "put_in": "IN"}[lit.group(1)]
        kept.append(Span(tag, lit.start(), lit.end(), lit.group(0)))
        kept.extend(Span(role, a, b, self.text[a:b]) for role, a, b in roles)
        return sorted(kept, key=lambda t: t.start)

    def _landmarks_and_echoes(self, spans: list[Span]) -> list[Span]:
        """An object phrase that only names where another stands ("a red apple [near] [the plate], the plate",
        "spawn lemon at [near] [mug] / spawn mug"), or that says yes to one asked about ("maybe a knife? yes, [a
        knife] too"), is a mention of that object, not one more of it, when the object is put there elsewhere."""
        out = list(spans)
        objs = [k for k, t in enumerate(out) if t.tag == "OBJ"]
        names = {k: {n for n, _ in _names(out[k].text, self.vocab)} for k in objs}
        for k in objs:
            mine = names[k]
            if not mine or len(mine) > 1 or _count(_norm(out[k].text, self.vocab)) > 1:
                continue
            others = [j for j in objs if j != k and names[j] == mine]
            if not others:
                continue
            prev = out[k - 1] if k > 0 else None
            landmark = prev is not None and prev.tag in _POSITION_TAGS and re.fullmatch(
                r"[ ]*(?:of|to|from)?[ ]*", self.text[prev.end:out[k].start]) is not None and re.search(
                r"(?i)\b(?:near|next to|beside|by|behind|in front of|left of|right of|close to|between|on|in|under|against|"
                r"of|to)\s*$", prev.text
            ) is not None
            asked = [j for j in others if j < k and "?" in self.text[out[j].end:out[k].start]]
            echo = bool(asked) and re.search(r"(?i)\b(?:yes|yeah|yep|sure|right|ok|okay|indeed)\b\W*$",
                                             self.text[max(0, out[k].start - 20):out[k].start]) is not None
            if landmark or echo:
                t = out[k]
                out[k] = Span("REF", t.start, t.end, t.text)
                objs_left = [j for j in objs if out[j].tag == "OBJ" and names[j] == mine]
                if not objs_left:  # the last one said: keep it
                    out[k] = t
        return out

    def _names_in(self, a: int, b: int) -> list[tuple[int, int]]:
        """The words from ``a`` to ``b`` cut into the catalog's names, longest first ("golf ball large blue
        cup"); words side by side that no name covers are a name of their own ("lunchbox", "computer mouse")."""
        words = [(w.start() + a, w.end() + a) for w in re.finditer(r"\S+", self.text[a:b])]
        out: list[tuple[int, int]] = []
        k, unknown = 0, False
        while k < len(words):
            best = None
            for j in range(len(words) - 1, k - 1, -1):
                if self.vocab.name_pattern.fullmatch(_norm(self.text[words[k][0]:words[j][1]].lower(), self.vocab)):
                    best = j
                    break
            if best is not None:
                out.append((words[k][0], words[best][1]))
                k, unknown = best + 1, False
                continue
            if self.text[words[k][0]:words[k][1]].lower() in _FUNCTION_WORDS:
                unknown = False
            elif unknown:
                out[-1] = (out[-1][0], words[k][1])
            else:
                out.append(words[k])
                unknown = True
            k += 1
        return out

    def _kept_after(self, s: Span) -> bool:
        """Whether the words after a removal take it back: "remove the banana... actually no, keep it" (a "keep" or
        "leave" of something else, "leave the lighting at default", does not)."""
        after = self.text[s.end:s.end + 120].lower()
        if re.match(r"\W*(?:never mind|scratch that|no wait|actually no)\b", after):
            return True
        m = re.search(r"^[^.!?\n]*[.!?\n]?[^.!?\n]*\b(?:keep|leave)\s+(?:(it|them|that|it in|it there)\b|the\s+(\w+))", after)
        if m is None:
            return False
        return m.group(1) is not None or m.group(2) in set(re.findall(r"[a-z]+", s.text.lower()))

    def _replaced(self, s: Span, k: int) -> bool:
        """Whether an object phrase's own surroundings take it out of the scene: it is replaced ("replace the spoon
        with a knife", "swap the fork for a spoon", "substitute a mug for the cup", "the bowl, replaced by a
        basket"), a later one stands in its place ("a basket instead of the bowl", outside a sentence that states
        the task), or it is ruled out after all ("but not the knife after all")."""
        before = self.text[max(0, s.start - 30):s.start].lower()
        after = self.text[s.end:s.end + 40].lower()
        later = [t for t in self.spans[k + 1:] if t.tag in _OBJECT_TAGS]
        nxt = later[0] if later else None

        def then_object(pattern: str) -> bool:
            m = re.match(pattern, after)
            return m is not None and nxt is not None and nxt.start - s.end <= m.end() + 3
        if re.search(r"\b(?:replace|swap(?:\s+out)?|switch(?:\s+out)?|exchange|trade(?:\s+in)?|change)\s+$", before) and \
                then_object(r"\s*(?:(?:out\s+)?(?:with|for|by|into)|to)\s+"):
            return True
        if re.search(r"\bsubstitute\s+$", self.text[max(0, (nxt or s).start - 60):(nxt or s).start].lower()):
            return False
        prev = [t for t in self.spans[:k] if t.tag in ("OBJ", "REF")]
        if prev and re.search(r"\bsubstitute\s+$", self.text[max(0, prev[-1].start - 12):prev[-1].start].lower()) and \
                re.fullmatch(r"\s+for\s+", self.text[prev[-1].end:s.start].lower()):
            return True  # "substitute a mug for [the cup]"
        if then_object(r"\s*,?\s*(?:(?:is|gets|should be|will be)\s+)?(?:replaced|swapped(?:\s+out)?|switched|exchanged|"
                       r"substituted)\s+(?:with|for|by)\s+"):
            return True
        if re.search(r"\b(?:instead of|in place of|rather than)\s+(?:the\s+|a\s+|an\s+)?$", before):
            lo = max(self.text.rfind(c, 0, s.start) for c in ".;\n!?") + 1
            hi = min([e for e in (self.text.find(c, s.end) for c in ".;\n!?") if e >= 0] or [len(self.text)])
            return not any((t.tag in RELATION_TAGS or t.tag in ("SRC", "TGT")) and lo <= t.start < hi for t in self.spans)
        if re.search(r"\b(?:leave|keep|take|pull|cross|strike)\s+$", before) and re.match(r"\s*(?:out|off)\b", after):
            return True  # "leave the coffee can out, actually"
        if re.search(r"\b(?:don'?t|do not|no need to|never)\s+(?:include|add|use|need|want|put|place|bring|spawn)\s+"
                     r"(?:the\s+|a\s+|an\s+|any\s+)?$", before):
            return True  # "don't include the knife after all"
        return bool(re.search(r"\b(?:not|no)\s+(?:the\s+|a\s+|an\s+)?$", before)) and bool(
            re.match(r"\s*(?:,\s*)?(?:after all|any ?more)\b", after))

    def _corrected_lists(self, spans: list[Span]) -> list[Span]:
        """Objects a correction right after them replaces: "a bowl (no, make that a basket)", "a pear and a bowl --
        no wait, make that a pear and a basket" (as many as the correction names, counted back from it; all of
        them when it names as many as the list had)."""
        out = list(spans)
        joint = re.compile(r"\s*(?:,|;|&|\+)?\s*(?:(?:and|or|plus)\s+)?")
        place = r"(?:\s+(?:on|onto|to|in)\s+(?:the\s+)?(?:table|desk|counter|scene|workspace|surface|setup)|\s+there|\s+too)?"
        cue = re.compile(
            place + r"\W*(?:(?:no|nope|wait|sorry|actually|correction|rather|hmm|oh|scratch that|i mean|make (?:that|it)|"
            r"change (?:that|it) to|on second thought|or rather|let'?s say|well|instead)\W*)+", re.IGNORECASE)
        strong = re.compile(r"(?i)\b(?:no|nope|sorry|actually|correction|rather|scratch that|i mean|make (?:that|it)|"
                            r"change (?:that|it) to|on second thought|wait)\b")
        objs = [i for i, t in enumerate(out) if t.tag in ("OBJ", "DROP")]
        for a, b in zip(objs, objs[1:], strict=False):
            first, second = out[a], out[b]
            gap = self.text[first.end:second.start]
            if first.tag != "OBJ" or second.tag != "OBJ" or not cue.fullmatch(gap) or not strong.search(gap):
                continue
            if any(t.start >= first.end and t.end <= second.start for t in out):
                continue
            before = [a]
            while before[0] > 0 and out[before[0] - 1].tag == "OBJ" and joint.fullmatch(
                    self.text[out[before[0] - 1].end:out[before[0]].start]):
                before.insert(0, before[0] - 1)
            after = [b]
            while after[-1] + 1 < len(out) and out[after[-1] + 1].tag == "OBJ" and joint.fullmatch(
                    self.text[out[after[-1]].end:out[after[-1] + 1].start]):
                after.append(after[-1] + 1)
            if len(after) == len(before):
                dropped = before
            else:
                said = {n for i in after for n, _ in _names(out[i].text, self.vocab)}
                if said & {n for t in out[:a + 1] if t.tag == "OBJ" for n, _ in _names(t.text, self.vocab)}:
                    continue  # "one apple with a mug ... actually make it two apples": a new count, read where it is said
                dropped = before[-1:]
            for i in dropped:
                t = out[i]
                out[i] = Span("DROP", t.start, t.end, t.text)
        return out

    def _listed_items(self, spans: list[Span]) -> list[Span]:
        """An item of a list of tagged objects that the tagger left untagged ("a book, [a coffee can] and [a cup]",
        "[mug]; [fork]; calculator"): an object phrase too, when its head is an English noun."""
        from ladev_lib.language.wordnet import default_nouns

        nouns = default_nouns()
        if nouns is None:
            return spans
        # "a book", "an eraser"; a bare noun only in a list of bare nouns separated by ";" ("mug; fork; calculator")
        item = r"(?:an?\s+[A-Za-z][A-Za-z-]*(?:\s+[A-Za-z][A-Za-z-]*){0,2}|(?<=;)\s*[A-Za-z][A-Za-z-]*|(?<=; )[A-Za-z][A-Za-z-]*)"
        sep = r"(?:,|;|\band\b|,\s*and\b|\bplus\b)"
        objs = [s for s in spans if s.tag == "OBJ"]
        found: list[tuple[int, int]] = []
        for a, b in zip(objs, objs[1:], strict=False):
            gap = self.text[a.end:b.start]
            m = re.fullmatch(rf"\s*{sep}\s*({item})\s*{sep}\s*", gap)
            if m is not None:
                found.append((a.end + m.start(1), a.end + m.end(1)))
        if objs:
            first, last = objs[0], objs[-1]
            line_start = self.text.rfind("\n", 0, first.start) + 1
            lead = re.search(rf"[:=]\s*({item})\s*{sep}\s*$", self.text[line_start:first.start])
            if lead is not None:
                found.append((line_start + lead.start(1), line_start + lead.end(1)))
            line_end = self.text.find("\n", last.end)
            tail = re.match(rf"\s*[,;]\s*({item})\s*(?:[.;]?\s*$)", self.text[last.end:line_end if line_end >= 0 else len(self.text)])
            if tail is not None and objs[-2:-1] and re.fullmatch(r"\s*[,;]\s*", self.text[objs[-2].end:last.start]):
                found.append((last.end + tail.start(1), last.end + tail.end(1)))
        taken = [(s.start, s.end) for s in spans]
        added: list[Span] = []
        for start, end in found:
            words = self.text[start:end].lower().split()
            head = words[-1]
            if head != singular(head) and not re.fullmatch(PAIRED_NOUNS, head) or head in _ORDINALS:
                continue  # "two apples, [a red one] and [a plain one]": a plural introduces its members
            if any(start < e and s0 < end for s0, e in taken) or head in _NOT_ITEMS or not (
                nouns.senses(head) or nouns.senses(singular(head))
            ):
                continue
            added.append(Span("OBJ", start, end, self.text[start:end]))
        return sorted([*spans, *added], key=lambda s: s.start) if added else spans

    # -- mentions ---------------------------------------------------------------
    def _group_head(self, pos: int) -> str | None:
        """The noun of the plural group said just before ``pos`` ("three Lego bricks: a pink, a blue ...")."""
        window = self.text[max(0, pos - 160):pos].lower()
        found = list(_GROUP_NOUN.finditer(window))
        for m in reversed(found):
            head = singular(m.group(1).strip())
            if head.split()[-1] in ("object", "item", "thing", "degree", "centimeter", "centimetre", "percent", "time"):
                continue
            return head
        return None

    def _kind_words(self) -> frozenset[str]:
        """Words of catalog names that say what kind of thing it is ("cup", "brick", "duplo"), not how it looks."""
        if not hasattr(self, "_kinds"):
            words = {w for n in self.vocab.names for w in n.split() if not _ADJECTIVE.match(w) and len(w) > 2}
            self._kinds = frozenset(words - _STOPWORDS - {"wooden", "plastic", "colored", "coloured", "extra", "toy"})
        return self._kinds

    def _member_name(self, s: Span, words: str) -> str | None:
        """The catalog name of a group member said by its looks alone ("[a pink], [a blue] and [a yellow Duplo
        brick]", "Duplo in three colours ([blue], ...)", "the small cups - [orange], ..."): the kind word of the
        coordination's last member, else the nearest kind word before it in the sentence."""
        heads: list[str] = []
        at = s.end
        for t in self.spans:
            if t.start < s.end or t.tag not in ("OBJ", "SRC", "REF", "DROP"):
                continue
            if not re.fullmatch(r"\s*(?:,|and|or|&|/|,\s*and|,\s*or)\s*", self.text[at:t.start]):
                break
            bare = _bare(t.text, self.vocab)
            kind = " ".join(w for w in bare.split() if not _ADJECTIVE.match(w))
            if kind:
                heads.append(kind)
                break
            at = t.end
        kinds = self._kind_words()
        size = ""
        for stops in (".;\n!?", ".\n!?"):  # the clause, then the sentence ("the small cups - ...; the large ones - ...")
            lo = max(self.text.rfind(c, 0, s.start) for c in stops) + 1
            tokens = re.findall(r"[a-z]+", _norm(self.text[lo:s.start], self.vocab))
            for k in range(len(tokens) - 1, -1, -1):
                w = tokens[k]
                if w in ("ones", "kind", "kinds", "size", "sizes") and k and re.fullmatch(
                    r"small|smaller|large|larger|big|bigger|little|tiny|extra large", tokens[k - 1]
                ) and not size:
                    size = tokens[k - 1]  # "the large ones - blue, green and yellow"
                if w in kinds or singular(w) in kinds:
                    heads.append(w if w in kinds else singular(w))
                    if not size and k and re.fullmatch(r"small|large|big|little|tiny", tokens[k - 1]):
                        size = tokens[k - 1]  # "the small cups - orange, ..."
            if heads:
                break
        size = {"big": "large", "bigger": "large", "larger": "large", "little": "small", "smaller": "small",
                "tiny": "small"}.get(size, size)
        for head in heads:
            noun = head.split()[-1]
            for filled in ([f"{size} {words} {head}", f"{size} {words} {noun}"] if size else []) + [
                f"{words} {head}", f"{words} {noun}", f"{words}{noun}"  # "base" of "balls": the baseball
            ]:
                named = _names(filled, self.vocab)
                if len(named) == 1 and named[0][0] != words and set(words.split()) <= set(
                    f"{named[0][0]} {self._display(named[0][0]) or ''}".split()
                ):
                    return named[0][0]
        return None

    def _in_colour_list(self, s: Span) -> bool:
        """Whether a colour word that is also a thing ("orange") is one of a list of colours: another member said by
        its colour alone beside it, or a plural noun and a colon or dash just before the list ("cups - orange, ...")."""
        k = self.spans.index(s)
        for j in (k - 1, k + 1):
            if 0 <= j < len(self.spans) and self.spans[j].tag in ("OBJ", "DROP"):
                lo, hi = sorted((s, self.spans[j]), key=lambda t: t.start)
                if re.fullmatch(r"\s*(?:,|and|or|/|,\s*and)\s*", self.text[lo.end:hi.start]) and _ADJECTIVE.fullmatch(
                    re.sub(r"\bones?$", "", _bare(self.spans[j].text, self.vocab)).strip() or "-"
                ):
                    return True
        before = self.text[max(0, s.start - 40):s.start].lower()
        plural = re.search(r"([a-z]{3,}s)\s*(?:\(|[:\u2014\u2013-]+)\s*$", before)
        return plural is not None and (singular(plural.group(1)) in self._kind_words() or plural.group(1) in (
            "colours", "colors"))

    def _vocab_words(self) -> frozenset[str]:
        if not hasattr(self, "_vwords"):
            self._vwords = frozenset(w for n in self.vocab.names for w in re.findall(r"[a-z]+", n))
        return self._vwords

    def _spelled(self, phrase: str, fuzzy: bool = True) -> str | None:
        """The phrase with misspelt and abbreviated words of catalog names written out ("teh markr" -> "teh
        marker", "soup cn" -> "soup can", "lg yellow cup" -> "large yellow cup"), or None when nothing changed.
        A word is corrected only to the one catalog word nearest to it (one edit for short words, two for long
        ones, a swap of neighbours counting one), never when it is an English noun of its own."""
        from ladev_lib.language.wordnet import default_nouns

        nouns = default_nouns()
        vocab = self._vocab_words()
        changed = False
        out = []
        for token in re.split(r"(\W+)", phrase):
            low = token.lower()
            if not low.isalpha() or low in vocab or low in _STOPWORDS:
                out.append(token)
                continue
            fixed = _ABBREVIATIONS.get(low)
            if fixed is None and fuzzy and len(low) >= 4 and not (nouns is not None and (nouns.senses(low) or nouns.senses(singular(low)))):
                limit = 1 if len(low) <= 5 else 2
                near = [(d, w) for w in vocab if w[0] == low[0] and abs(len(w) - len(low)) <= limit
                        and (d := _edits(low, w, limit)) <= limit]
                if near:
                    best = min(d for d, _ in near)
                    words = {w for d, w in near if d == best}
                    fixed = words.pop() if len(words) == 1 else None
            if fixed is not None:
                changed = True
                out.append(fixed)
            else:
                out.append(token)
        return "".join(out) if changed else None

    def _each(self, s: Span) -> int | None:
        """"two of each: [a golf ball], [a marble]": how many of each listed object, when said before the list."""
        if s.tag != "OBJ" or _NUMBER.search(_norm(s.text, self.vocab)):
            return None
        lo = max(self.text.rfind(c, 0, s.start) for c in ".;!?\n") + 1  # the list in the clause of "of each"
        said = list(re.finditer(r"\b(\d+|two|three|four|five) of each(?: kind| colou?r| type| sort)?\b", _norm(
            self.text[lo:s.start], self.vocab)))
        if not said:
            return None
        m = said[-1]
        n = _count(m.group(1), 0) or {"two": 2, "three": 3, "four": 4, "five": 5}.get(m.group(1), 0)
        return n if n > 1 else None

    def _mention(self, s: Span) -> list[_Mention]:
        each = self._each(s)
        if each is not None:
            return [_Mention(m.tag, m.span, m.name, m.unknown, each, m.positions) for m in self._mention_once(s)]
        return self._mention_once(s)

    def _mention_once(self, s: Span) -> list[_Mention]:
        found = [(name, n or self._plural_count(s)) for name, n in _names(s.text, self.vocab)]
        if s.tag in _OBJECT_TAGS:
            spelled = self._spelled(s.text, fuzzy=not found)
            if spelled is not None and _names(spelled, self.vocab):
                s = Span(s.tag, s.start, s.end, spelled)  # the text as meant; offsets stay the writer's
                found = [(name, n or self._plural_count(s)) for name, n in _names(spelled, self.vocab)]
        bare0 = _bare(s.text, self.vocab)
        words0 = re.sub(r"\bones?$", "", bare0).strip()
        if found and re.search(r"\bones?$", bare0) and all(_ADJECTIVE.fullmatch(n) for n, _ in found):
            found = []  # "the large orange one": a colour, not the fruit
        if words0 and s.tag in ("OBJ", "DROP") and _ADJECTIVE.fullmatch(words0) and (
            not found or found[0][0] == words0 and self._in_colour_list(s)
        ):
            # "[orange], [green] and [yellow]" after "the small cups": colours of the group's kind, not the fruit
            member = self._member_name(s, words0)
            if member is not None:
                return [_Mention(s.tag, s, member, count=_count(_norm(s.text, self.vocab)) if s.tag == "OBJ" else 1)]
        if len(found) == 2 and s.tag == "OBJ" and re.match(r"(?i)\s*(?:the|that|this)\s+\S.*?\s+(?:an?|into an?|to an?)\s+\S",
                                                          s.text) and re.search(r"(?i)\bmake\s*$", self.text[:s.start]):
            # "make [the fork a spoon]": the first is replaced by the second
            return [_Mention("DROP", s, found[0][0]), _Mention("OBJ", s, found[1][0], count=found[1][1])]
        if len(found) > 1 and s.tag in ("OBJ", "DROP", "REF"):
            return [_Mention(s.tag, s, name, count=n) for name, n in found]  # "a fork and a spoon" as one phrase
        if found:
            return [_Mention(s.tag, s, found[0][0], count=found[0][1])]
        bare = _bare(s.text, self.vocab)
        normal = _norm(s.text, self.vocab)
        count = _count(normal) if s.tag == "OBJ" else 1
        words = re.sub(r"\bones?$", "", bare).strip()
        if s.tag == "OBJ" and re.fullmatch(r"(?:the )?(?:one|other|other one|another|another one|second|second one|"
                                           r"first|first one|last|last one|remaining one)", s.text.lower().strip(" .,")):
            # "two towels, [one] at the front, [the other] at the back": one of the group said before
            kind = self._group_noun(s.start) or self._member_name(s, "")
            if kind is not None:
                counted = [m for m in self.mentions if m.tag == "OBJ" and m.count > 1 and self._same(m.name, kind)
                           and self._same_sentence(m.span.end, s.start)]
                # "[two lemons], [one] on the left and one on the right": the group was counted, "one" places one of it
                return [_Mention("REF" if counted else s.tag, s, kind)]
        if s.tag in ("OBJ", "DROP") and bare and not _PRONOUN.match(bare) and not _ADJECTIVE.match(bare):
            kind = self._member_name(s, bare)  # "balls: [tennis] and [golf]"
            if kind is not None:
                return [_Mention(s.tag, s, kind, count=count)]
        if bare and (_ADJECTIVE.match(bare) or re.search(r"\bones?$", bare)) and not _PRONOUN.match(bare):
            if s.tag in ("SRC", "TGT", "REF") and words:
                # "the purple one" in a task: the one object described with those words
                said = set(words.split())
                fits = {m.name for m in self.mentions if m.tag != "DROP" and m.name and not m.unknown
                        and said <= set((self._display(m.name) or m.name).split()) | set(m.name.split())}
                if len(fits) == 1:
                    return [_Mention(s.tag, s, fits.pop())]
            # "a pink", "the yellow one": the head noun of the group or object said before
            head = self._group_head(s.start) or self._head_before(s.start)
            if head is not None:
                noun = head.split()[-1]
                for filled in (f"{words} {head}", f"{' '.join(head.split()[:-1])} {words} {noun}", f"{words} {noun}"):
                    named = _names(filled.strip(), self.vocab)
                    if named:
                        return [_Mention(s.tag, s, named[0][0], count=count)]
                return [_Mention(s.tag, s, f"{words} {head}".strip(), unknown=True, count=count)]
        if not bare or re.fullmatch(r"(?:\d+|of them|of those|of these|more|too)(?: of them| more)?", bare):
            # "no, just [two]", "[two of them]": as many of the object named before
            earlier = [x for x in self.mentions if x.span.end <= s.start and x.name]
            if earlier and s.tag == "OBJ" and re.search(r"\d", normal):
                return [_Mention(s.tag, s, earlier[-1].name, earlier[-1].unknown, count=count)]
            kind = self._member_name(s, "") if s.tag == "OBJ" else None
            if kind is not None:  # "double up on the bananas - [two of them]"
                return [_Mention(s.tag, s, kind, count=count)]
        if count > 1 and not re.search(rf"\b(?:{PAIRED_NOUNS})$", bare):
            bare = singular(bare)
        kind = self._catalog_kind(bare) if s.tag in ("OBJ", "REF", "DROP") and bare else None
        if kind is not None:
            return [_Mention(s.tag, s, kind, count=count)]
        if s.tag in ("OBJ", "REF") and re.fullmatch(_SUPPORT, bare):
            return []  # "the tabletop has a sugar box": where the scene stands, no object of it
        return [_Mention(s.tag, s, _unknown_name(bare) or None, unknown=True, count=count)]

    def _group_noun(self, pos: int) -> str | None:
        """The catalog object of a counted group said just before ``pos`` ("there are two orange, [one] ...")."""
        lo = max(self.text.rfind(c, 0, pos) for c in ".!?\n") + 1
        window = _norm(self.text[lo:pos], self.vocab)
        for m in reversed(list(re.finditer(r"\b(?:[2-9]|several|some)\s+((?:[a-z]+\s+){0,2}[a-z]+)", window))):
            named = _names(m.group(1), self.vocab)
            if len(named) == 1:
                return named[0][0]
        return None

    def _plural_count(self, s: Span) -> int:
        """How many a plural without a number stands for: as many as the phrase it replaces ("make the two
        tennis balls golf balls"), else two."""
        if s.tag != "OBJ":
            return 1
        dropped = [m for m in self.mentions if m.tag == "DROP" and m.span.end <= s.start]
        if dropped and re.search(r"[a-z]s\b", dropped[-1].span.text.lower()) and s.start - dropped[-1].span.end <= 40:
            counts = [m.count for m in self.mentions if m.name == dropped[-1].name and m.count > 1]
            if counts:
                return counts[0]
        return 2

    def _head_before(self, pos: int) -> str | None:
        earlier = [m for m in self.mentions if m.span.end <= pos and m.name and not _PRONOUN.match(m.name)]
        return earlier[-1].name.split()[-1] if earlier and earlier[-1].name else None

    def _catalog_kind(self, bare: str) -> str | None:
        """A phrase the catalog reads as one of its objects by head noun and modifiers ("yellow lego")."""
        frame = read_instruction(f"pick up the {bare}")
        obj = frame.object
        if frame.task != "pick_up" or obj is None or obj.object_id is None:
            return None
        name = self.vocab.ids.get(obj.object_id)
        head = singular(bare.split()[-1])
        said = [n for n, cid in self.vocab.name_ids.items() if cid == obj.object_id] + ([name] if name else [])
        if not any(singular(n.split()[-1]) == head for n in said):
            return None  # "wine glass" is not the windex bottle: a kind only by its own head noun
        return name

    def _a_thing(self, m: _Mention) -> bool:
        """Whether an unknown phrase names a thing at all: its head noun is an English noun (WordNet) or a word of
        a catalog name; "asdf qwerty" and "lorem ipsum" are no objects, "a laptop" is one the catalog lacks."""
        if not m.unknown or m.name is None or _PRONOUN.match(m.name):
            return True
        from ladev_lib.language.wordnet import default_nouns

        head = m.name.split()[-1]
        nouns = default_nouns()
        known = {w for n in self.vocab.names for w in n.split()}
        if head in known or singular(head) in known:
            return True
        if nouns is None or nouns.senses(head) or nouns.senses(singular(head)):
            return True
        # a compound of English words WordNet does not list ("smartphone", "lunchbox", "airpods")
        word = singular(head)
        return any(
            (nouns.senses(word[:k]) or len(word[:k]) == 1 and word[:k] in "ie") and nouns.senses(word[k:])
            for k in range(1, len(word) - 2)
        )

    def read_mentions(self) -> None:
        for s in self.spans:
            if s.tag in _OBJECT_TAGS:
                self.mentions.extend(
                    m for m in self._mention(s) if (m.name is None or m.name not in _STOPWORDS) and self._a_thing(m)
                )
        for m in self.mentions:  # pronouns named as objects ("near it") are their antecedents
            if m.name is not None and _PRONOUN.match(m.name) and m.tag in ("REF", "OBJ"):
                # "two bananas near it": not the objects being placed
                placed = [p for p in self.spans if p.tag in _POSITION_TAGS and 0 <= m.span.start - p.end <= 3]
                skip: set[Span] = set()
                if placed:
                    before = [x for x in self.mentions if x.span.end <= placed[0].start and x.tag != "DROP"]
                    if placed[0].tag == "POS_ALL":
                        skip = {x.span for x in self._group_before(placed[0], before)}
                    elif before:
                        skip = {before[-1].span} | ({before[-2].span} if self._pair(placed[0], before) else set())
                # "both balls start right of it": "it" is none of the balls
                heads = {singular(w) for x in self.mentions if x.span in skip and _bare(x.span.text, self.vocab)
                         for w in [_bare(x.span.text, self.vocab).split()[-1]] if w != singular(w) or x.count > 1}
                same_kind = {x.name for x in self.mentions if x.name and any(
                    len(h) >= 3 and singular(x.name.split()[-1]).endswith(h) for h in heads)}
                ante = self._resolve(m, skip=skip, exclude=same_kind)
                m.name, m.unknown = (ante.name, ante.unknown) if ante is not None else (None, True)
                if m.tag == "OBJ":
                    m.tag = "REF"

    def _oblique(self, m: _Mention) -> bool:
        """Whether a mention is said after a preposition ("next to [the mug]", "with [a fork] and [a spoon]"): a
        place or a companion, less likely what a later "it" means than the thing the clause is about."""
        if m.tag in ("TGT", "SRC"):
            return m.tag == "TGT"  # the task's object is what the text is about
        lo = max(self.text.rfind(c, 0, m.span.start) for c in ".;:!?\n(") + 1
        before = self.text[max(lo, m.span.start - 30):m.span.start].lower()
        if _PREPOSITION_BEFORE.search(before):
            return True
        if re.search(r"(?:,|\band|\bor)\s*(?:(?:the|a|an)\s+)?$", before):
            earlier = [x for x in self.mentions if x.span.end <= m.span.start and x.span != m.span]
            if earlier and m.span.start - earlier[-1].span.end <= 12 and earlier[-1].tag != "DROP":
                return self._oblique(earlier[-1])
        return False

    def _resolve(self, m: _Mention, skip: set[Span] | None = None, exclude: set[str] | None = None) -> _Mention | None:
        """What a pronoun stands for: a thing said before it (not one it is placed beside, not the other role of
        its task), a group for "them" / "one of them", the later or earlier of two for "the latter" / "the
        former"; among the rest, the latest said as the subject or object of its clause before one after a
        preposition."""
        word = _bare(m.span.text, self.vocab) if m.span.text else (m.name or "")
        cands = [
            x for x in self.mentions
            if x.span.end <= m.span.start and x.tag != "DROP" and x.name and not _PRONOUN.match(x.name)
            and x.span not in (skip or set()) and x.name not in (exclude or set())
            and not (x.span.text and _PRONOUN.match(_bare(x.span.text, self.vocab)) and x.name == m.name)
        ]
        if not cands:
            return None
        if word in ("latter", "former"):
            names: list[_Mention] = []
            for x in reversed(cands):
                if all(x.name != y.name for y in names):
                    names.append(x)
                if len(names) == 2:
                    break
            return names[0] if word == "latter" or len(names) < 2 else names[1]
        if _PLURAL_PRONOUN.match(word):
            many = [x for x in cands if x.count > 1]
            if many:
                return many[-1]
        if word == "it":
            cands = [x for x in cands if x.count == 1] or cands
        if self._placed_by(m):
            # "a lemon behind the mug and a pear in front of it", "knife left of it, a fork right of it": a
            # reference of a position stands for the reference of the position said before it in the sentence
            parallel = [x for x in cands if self._placed_by(x) and self._same_sentence(x.span.end, m.span.start)]
            if parallel:
                return parallel[-1]
        if m.tag == "TGT":
            # "put the plum in the cup. Actually put the strawberry in [it]": a destination stands for the
            # latest thing said after a preposition
            oblique = [x for x in cands if self._oblique(x)]
            if oblique:
                return oblique[-1]
        direct = [x for x in cands if not self._oblique(x)]
        return (direct or cands)[-1]

    def _placed_by(self, m: _Mention) -> bool:
        """Whether a mention is the reference of a position ("next to [it]")."""
        return any(p.tag in _POSITION_TAGS and 0 <= m.span.start - p.end <= 3 for p in self.spans)

    def _headers_and_restatements(self) -> None:
        """"two soda cans, a Sprite and a 7 Up": a counted plural that introduces as many listed objects is their
        header, not more objects; "towel: back" after a towel was listed: the same towel, placed."""
        obj = [m for m in self.mentions if m.tag == "OBJ"]
        for k, m in enumerate(obj):
            if m.count < 2 or not m.unknown and not (m.name and m.name.split()[-1] in ("can", "cube", "brick", "ball", "cup", "block")):
                continue
            nxt = [x for x in obj[k + 1:] if self._same_sentence(m.span.end, x.span.start)]
            gap = self.text[m.span.end:nxt[0].span.start] if nxt else ""
            if len(nxt) < m.count or not re.fullmatch(
                r"\s*(?:[,:(\u2014\u2013-]|including|namely|i\.e\.|that is)\s*(?:(?:a|an|one|the)\s+)?", gap
            ):
                continue
            members = nxt[: m.count]
            if any(x.count != 1 for x in members):
                continue  # "two Spam cans, two tuna cans": a list of counted objects, not a header and its members
            if re.fullmatch(r"\s*,\s*(?:(?:a|an|one|the)\s+)?", gap) and not all(self._member_of(x, m) for x in members):
                continue  # "two Coke cans, a Pepsi can": a comma joins a list unless what follows is of the plural's kind
            m.tag = "HEADER"
        seen: set[str] = set()
        previous: _Mention | None = None
        for m in self.mentions:
            last, previous = previous, m
            if m.tag != "OBJ" or m.name is None:
                continue
            if m.name in seen and last is not None and last.tag == "DROP" and re.fullmatch(
                r"\s*[,;:\u2014\u2013-]?\s*(?:but|just|only|rather|instead)?\s*", self.text[last.span.end:m.span.start]
            ):
                m.tag = "REF"  # "a lemon and a mug. Not a bowl, a mug.": the mug said again
                continue
            indefinite = re.match(r"\s*(?:a|an|another|one|two|three|four|five|\d+|more|extra|second)\b", m.span.text.lower())
            placed_before = any(x.name == m.name and x.positions for x in self.mentions if x.tag == "OBJ" and x is not m
                                and x.span.end <= m.span.start)
            if m.name in seen and m.positions and not indefinite and not placed_before:
                m.tag = "REF"  # "towel: back" after "a towel" was listed; "ADD marble LEFT / ADD marble RIGHT" are two
            seen.add(m.name)

    def _member_of(self, member: _Mention, header: _Mention) -> bool:
        """Whether ``member`` is one of the kind ``header`` names: a bare adjective of it ("a pink"), an object with
        its head noun ("a Sprite" for "soda cans": the sprite can) or of its category ("an apple" for "fruits")."""
        if _ADJECTIVE.match(_bare(member.span.text, self.vocab)) or re.search(r"\bones?\s*$", member.span.text.lower()):
            return True
        if not header.name or not member.name:
            return False
        head = singular(header.name.split()[-1])
        display = self._display(member.name) or member.name
        category = self._category(member.name) or ""
        return singular(display.split()[-1]) == head or singular(member.name.split()[-1]) == head or (
            bool(category) and singular(category.split()[-1]) == head
        )

    def _display(self, name: str) -> str | None:
        """The catalog's display name of a name the vocabulary knows ("sprite" -> "sprite can")."""
        oid = _object_id(self.vocab, name)
        return self.vocab.ids.get(oid) if oid is not None else None

    def _same_sentence(self, a: int, b: int) -> bool:
        lo, hi = min(a, b), max(a, b)
        return _SENTENCE_END.search(self.text[lo:hi]) is None

    # -- positions --------------------------------------------------------------
    def read_positions(self) -> None:
        spans = self.spans
        for k, s in enumerate(spans):
            if s.tag not in _POSITION_TAGS:
                continue
            nxt = spans[k + 1] if k + 1 < len(spans) else None
            position, ref_span = self._position(s, nxt)
            if position is None:
                continue
            before = [m for m in self.mentions if m.span.end <= s.start and m.tag != "DROP" and m.span != ref_span]
            after = [m for m in self.mentions if m.span.start >= s.end and m.tag != "DROP" and m.span != ref_span]
            if s.tag == "POS_NEXT" and after:
                targets = [m for m in after if m.span == after[0].span]
            elif s.tag == "POS_ALL" and before:
                targets = self._group_before(s, before)
            elif before and self._pair(s, before):
                targets = before[-2:]  # "; a marker and a fork at the front": both
            elif before:
                targets = [m for m in before if m.span == before[-1].span]
            elif after:
                targets = [m for m in after if m.span == after[0].span]
            else:
                continue
            for m in targets:
                m.positions.append(dict(position))

    def _relative_to_pronoun(self, s: Span) -> dict[str, Any] | None:
        """A position said relative to a pronoun inside its own words ("[to its left]", "[behind it]", "[left of
        it]"): that relation to what the pronoun stands for (not the object being placed)."""
        low = s.text.lower()
        if not re.search(r"\b(?:it|its|them|their)\b", low):
            return None
        before = [m for m in self.mentions if m.span.end <= s.start and m.tag != "DROP"]
        if not before:
            return None
        after = [m for m in self.mentions if m.span.start >= s.end and m.tag != "DROP"]
        if s.tag == "POS_NEXT" and after:
            skip = {after[0].span}  # "[to its left], a peach": the peach is placed, "its" is something else
        elif s.tag == "POS_ALL":
            skip = {x.span for x in self._group_before(s, before)}
        else:
            skip = {before[-1].span}
        word = re.search(r"\b(?:it|its|them|their)\b", low)
        assert word is not None
        probe = _Mention("REF", Span("REF", s.start + word.start(), s.start + word.end(), word.group(0)), word.group(0))
        # "a banana to its left, a pear to its right": the same "it" as the position before it in the sentence
        def near(a: int) -> bool:  # the same sentence, or the clause after a semicolon
            return not re.search(r"[.!?\n]", self.text[a:s.start])

        parallel = [(at, name) for at, name in self._pronoun_refs if near(at)]
        parallel += [(x.span.start, x.name) for x in before if x.name and self._placed_by(x)
                     and near(x.span.end) and x.span not in skip]
        ante_name = max(parallel)[1] if parallel else None
        if ante_name is None:
            ante = self._resolve(probe, skip=skip)
            ante_name = ante.name if ante is not None else None
        if ante_name is None:
            return None
        self._pronoun_refs.append((s.start, ante_name))
        relation = "near"
        for pattern, name in ((r"\bleft\b", "left_of"), (r"\bright\b", "right_of"), (r"\bin front\b|\bfront\b", "in_front_of"),
                              (r"\bbehind\b|\bback\b", "behind")):
            if re.search(pattern, low):
                relation = name
                break
        return {"relation": relation, "reference": ante_name}

    def _pair(self, s: Span, before: list[_Mention]) -> bool:
        """Whether a position follows a pair of objects that forms its own clause ("; a marker and a fork at the
        front", "with a plum and a pear up at the front") rather than the end of a longer list."""
        if len(before) < 2 or before[-1].span == before[-2].span:
            return False
        first, second = before[-2], before[-1]
        if not re.fullmatch(r"\s+and\s+", self.text[first.span.end:second.span.start]):
            return False
        if not re.fullmatch(r"\s*(?:(?:go|sit|stand|lie|are|both|all|placed|set|put|up|over|down)\s+)*", self.text[second.span.end:s.start]):
            return False
        lead = self.text[max(0, first.span.start - 12):first.span.start]
        return re.search(r"(?:^|[.;:\n]|\bwith|,\s*and|\bplus)\s*$", lead) is not None or first.span.start < 3

    def _group_before(self, s: Span, before: list[_Mention]) -> list[_Mention]:
        """The object phrases of the coordination just before ``s`` (back to a sentence end or a position)."""
        group: list[_Mention] = []
        limit = s.start
        for m in reversed(before):
            gap = self.text[m.span.end:limit]
            if _SENTENCE_END.search(gap) or ":" in gap or (group and any(
                p.tag in _POSITION_TAGS and m.span.end <= p.start < limit for p in self.spans
            )) or (group and re.search(r"(?i)\b(?:then|when|while|whereas|if|after|before|because|but|since|until|where|"
                                       r"which|so that)\b", gap)):
                break  # "a red plate, then a plum and a peach around it": the coordination is the plum and the peach
            group.append(m)
            limit = m.span.start
        return list(reversed(group))

    def _position(self, s: Span, nxt: Span | None) -> tuple[dict[str, Any] | None, Span | None]:
        said = self._relative_to_pronoun(s)
        if said is not None:
            return said, None
        protected, slots = protect_coordinates(normalize_text(s.text, self.vocab))
        for key in re.findall(r"@p\d+@", protected):
            x, y = slots[key][:2]
            return {"x": round(x, 4), "y": round(y, 4)}, None
        normal = _norm(s.text, self.vocab)
        letter = {"l": "left", "r": "right", "c": "center", "ctr": "center", "f": "front", "b": "back", "mid": "center"}
        if normal in letter:
            return {"region": letter[normal]}, None
        protected, slots = protect_coordinates(normal)
        for key in re.findall(r"@p\d+@", protected):
            x, y = slots[key][:2]
            return {"x": round(x, 4), "y": round(y, 4)}, None
        # a relation to the object phrase right after the relation words ("[near] [the bowl]")
        if (
            nxt is not None and nxt.tag in _OBJECT_TAGS and (nxt.start - s.end <= 3 and not re.search(
                r"[.;:\n]", self.text[s.end:nxt.start]
            ) or re.fullmatch(r"[\s\"'`]*(?:[:=]|the|a|an)?[\s\"'`]*", self.text[s.end:nxt.start]))  # {"near": "mug"}
            and _RELATION_WORDS.search(normal)
        ):
            ref = next((m for m in self.mentions if m.span == nxt), None)
            if ref is not None and ref.name is not None:
                relation = "near"
                for pattern, name in (
                    (r"\bleft of\b", "left_of"), (r"\bright of\b", "right_of"), (r"\bin front of\b", "in_front_of"),
                    (r"\bbehind\b", "behind"),
                ):
                    if re.search(pattern, normal):
                        relation = name
                        break
                return {"relation": relation, "reference": ref.name}, nxt
        rel = find_relation(self.vocab, normal)
        if rel is not None and rel[0].get("reference") in self.vocab.canonical.values():
            return rel[0], None
        region = find_region(normal)
        if region is not None:
            return {"region": region[0]}, None
        return None, None

    # -- objects ----------------------------------------------------------------
    def _same(self, a: str | None, b: str | None) -> bool:
        if a is None or b is None:
            return False
        if a == b or singular(a) == singular(b):
            return True
        oid = _object_id(self.vocab, a)
        return oid is not None and oid == _object_id(self.vocab, b)

    def _find(self, name: str | None) -> list[_Object]:
        return [o for o in self.objects if self._same(o.name, name)]

    def build_objects(self) -> None:
        for m in self.mentions:
            if m.name is None:
                continue
            if m.tag == "OBJ":
                before = self.text[max(0, m.span.start - 40):m.span.start].lower()
                if self._find(m.name) and re.search(
                    r"\b(?:correction|actually|instead|make (?:that|it)|i mean|sorry|no|rather|just|only)\b[^.;]*$", before
                ) and re.match(r"(?i)\s*(?:just\s+|only\s+)?(?:\d+|one|two|three|four|five|a|an|a single)\b", m.span.text) \
                        and not re.search(r"(?i)\b(?:second|another|extra|more|additional|spare|other|third)\b", m.span.text):
                    # "two lemons ... correction: just one lemon": the new count replaces the old one
                    for o in self._find(m.name):
                        self.objects.remove(o)
                for i in range(max(m.count, 1)):
                    # one position for the group is said of each; several are taken in turn
                    pos = m.positions[0] if len(m.positions) == 1 else (m.positions[i] if i < len(m.positions) else None)
                    self.objects.append(_Object(m.name, m.unknown, dict(pos) if pos else None, [m]))
            elif m.tag == "DROP":
                earlier = [o for o in self._find(m.name) if o.mentions and o.mentions[0].span.start < m.span.start]
                if earlier:
                    self.objects.remove(earlier[-1])
                    self.removed.add(m.name)

    def add_task_objects(self, task: dict[str, Any]) -> None:
        """The task's objects are the scene's: added when no phrase put them there; positions said of them kept."""
        for key, tag in (("source", "SRC"), ("target", "TGT")):
            name = task.get(key)
            if not isinstance(name, str) or not name:
                continue
            said = [m for m in self.mentions if m.tag == tag and m.positions]
            found = self._find(name)
            if found and all(o.mentions and re.search(
                r"(?i)\b(?:second|another|extra|additional|spare|other|2nd|decoy)\b", o.mentions[0].span.text
            ) for o in found) and any(x.tag == tag and not _PRONOUN.match(x.name or "it") for x in self.mentions):
                found = []  # "put the golf ball in the cup, with a spare golf ball beside it": two golf balls
            if not found:
                unknown = name not in self.vocab.canonical.values() and name not in self.vocab.name_ids
                position = said[-1].position if said else None
                self.objects.append(_Object(name, unknown, dict(position) if position else None))
            elif said and found[0].position is None:
                found[0].position = dict(said[-1].position or {})

    def task_slots(self, task: dict[str, Any]) -> int:
        """An instruction's objects the text leaves unsaid take the places the text keeps for them: a
        category phrase of their kind ("two fruits" holds the orange) or a random object ("4 random objects
        and a basket" holds the carrot). Returns how many random places were taken."""
        taken = 0
        for key in ("source", "target"):
            name = task.get(key)
            if not isinstance(name, str) or not name or self._find(name):
                continue
            kind = self._category(name)
            placeholder = next((o for o in self.objects if o.unknown and kind and singular(o.name) == kind), None)
            if placeholder is not None:
                self.objects.remove(placeholder)
            else:
                taken += 1
        return taken

    def _category(self, name: str) -> str | None:
        oid = self.vocab.name_ids.get(name) or next((c for c, d in self.vocab.ids.items() if d == name), None)
        return self.vocab.category_of.get(oid) if oid is not None else None

    def resolve_refs(self) -> None:
        """REF mentions: another mention of an object there; a position said of it goes to it."""
        for m in self.mentions:
            if m.tag != "REF" or m.name is None:
                continue
            group = self._group_of(m)
            if group:
                for o in group:  # "the cutlery on the right", "both lemons beside the towel"
                    if m.positions:
                        o.position = dict(m.positions[-1])
                continue
            same = self._find(m.name) or [
                o for o in self._by_head(m.name) if any(
                    x.span.start < m.span.start for x in [*o.mentions, *self.mentions] if x.tag != "DROP" and self._same(x.name, o.name)
                )
            ]  # "the plate" for a red plate said before; "Apple and a red apple" are two
            if same:
                free = [o for o in same if o.position is None] or same  # a later position corrects an earlier one
                for pos in m.positions:
                    if free:
                        free.pop(0).position = dict(pos)
            elif not m.unknown and not any(self._same(r, m.name) for r in self.removed):
                self.objects.append(_Object(m.name, False, dict(m.position) if m.position else None, [m]))
        for o in self.objects:  # "beside the cup": the scene's one cup
            ref = (o.position or {}).get("reference")
            if isinstance(ref, str):
                o.position["reference"] = self._in_scene(ref)  # type: ignore[index]

    def _group_of(self, m: _Mention) -> list[_Object]:
        """The objects a plural or collective mention stands for ("the cans", "both balls", "all cube", "the
        fruit", "the cutlery"): those of its head noun, category or kind, when there are at least two."""
        said = m.span.text.lower().strip()
        bare = re.sub(r"^(?:both|all|all the|all of the|the|these|those|the two|the three|the four|the other|"
                      r"the \d+|\d+)\s+", "", said)
        bare = re.sub(r"^(?:the|these|those)\s+", "", bare)
        words = re.findall(r"[a-z]+", bare)
        if not words or len(words) > 3:
            return []
        head = words[-1]
        plural = head != singular(head) or re.match(r"(?:both|all)\b", said) is not None
        collective = head in ("fruit", "cutlery", "silverware", "utensils", "produce", "tableware", "crockery", "food")
        if not plural and not collective:
            return []
        one = singular(head)
        from ladev_lib.language.wordnet import default_nouns

        nouns = default_nouns()
        out = []
        for o in self.objects:
            if o.unknown:
                continue
            display = self._display(o.name) or o.name
            category = self._category(o.name) or ""
            kinds = {singular(o.name.split()[-1]), singular(display.split()[-1]), category}
            if one in kinds or head in kinds or any(len(one) >= 3 and k.endswith(one) for k in kinds) or (nouns is not None and (nouns.is_a(display, one) or nouns.is_a(display, head))):
                if len(words) > 1 and not set(words[:-1]) <= set(f"{o.name} {display}".split()):
                    continue  # "the yellow cubes": only the yellow ones
                out.append(o)
        return out if len(out) >= 2 else []

    def _by_head(self, name: str | None) -> list[_Object]:
        """Objects a shorter name ends ("the plate" for the described "red plate", "the cup")."""
        if not name:
            return []
        head = singular(name.split()[-1])
        fits = [o for o in self.objects if singular(o.name.split()[-1]) == head and o.name.endswith(singular(name))]
        if len({o.name for o in fits}) == 1:
            return fits
        if len(name.split()) == 1 and len(head) >= 3:
            # "the ball" for the described racquetball: a compound whose last part is the word said
            fits = [o for o in self.objects if not o.unknown and (o.name.split()[-1].endswith(head) or (
                self._display(o.name) or "").split()[-1:] == [head])]
            if len({o.name for o in fits}) == 1:
                return fits
        # "the purple brick" for the described "purple lego brick": every word said is in one object's name
        said = set(singular(name).split()) - _STOPWORDS

        def words(o: _Object) -> set[str]:
            return set(singular(o.name).split()) | set((self._display(o.name) or "").split())

        own = _object_id(self.vocab, name)  # "the yellow lego brick" is not the small one described
        fits = [o for o in self.objects if head in {singular(w) for w in words(o)} and said <= words(o)
                and (own is None or own == _object_id(self.vocab, o.name))]
        if len({o.name for o in fits}) == 1:
            return fits
        return []

    # -- the task ---------------------------------------------------------------
    def task_type(self) -> str | None:
        rels = [(RELATION_TAGS[s.tag], s) for s in self.spans if s.tag in RELATION_TAGS]
        if not rels:
            return None
        placing = [r for r in rels if r[0] != "pick_up"]
        kind, said = placing[-1] if placing else rels[-1]
        if kind in ("put_on", "put_in") and re.fullmatch(r"\s*(?:->|→|=>|>|to|-->|—>)\s*", said.text):
            # "orange -> basket": an arrow says where, the destination says how (into a container, onto a top)
            tgt = self._phrase("TGT")
            name = self._task_phrase(tgt) if tgt is not None else None
            oid = self.vocab.name_ids.get(name or "") or next((c for c, d in self.vocab.ids.items() if d == name), None)
            if oid is not None:
                kind = "put_in" if oid in self.vocab.containers else "put_on"
        return kind

    def _phrase(self, tag: str) -> _Mention | None:
        found = [m for m in self.mentions if m.tag == tag]
        kept = [m for m in found if not re.search(
            r"\b(?:not|no|rather than|instead of|never|nor)\s+(?:\w+\s+)?$", self.text[max(0, m.span.start - 16):m.span.start].lower()
        )]
        found = kept or found  # "in the basket, not on the towel": the towel is no destination
        if not found:
            return None
        named = [m for m in found if m.name and not _PRONOUN.match(m.name)]
        return named[-1] if named else found[-1]

    def _antecedent(self, m: _Mention, exclude: _Mention | None = None) -> _Mention | None:
        names = {exclude.name} if exclude is not None and exclude.name and not _PRONOUN.match(exclude.name) else set()
        if names and self.objects:
            names |= {o.name for n in list(names) for o in self._find(n) or self._by_head(n)}
        return self._resolve(m, skip={exclude.span} if exclude is not None else None, exclude=names)

    def _task_phrase(self, m: _Mention | None, exclude: _Mention | None = None) -> str | None:
        """The name a task role is read from: pronouns filled in from the text before, and one of several objects
        told apart by where it stands or by its size ("the one at the back", "the big one", "its big sibling")."""
        if m is None:
            return None
        described = self._described(m, exclude)
        if described is not None:
            return described
        if not m.name or _PRONOUN.match(m.name):
            ante = self._antecedent(m, exclude)
            return ante.name if ante is not None else None
        return m.name

    def _described(self, m: _Mention, exclude: _Mention | None) -> str | None:
        """One object of the scene picked out by position or size words in a task phrase: "the one at the back",
        "the box at the front", "the back towel", "whichever bowl is on the right", "the one by the pitcher", "the
        thing in the middle", "the big one", "the bigger of the two", "its big sibling"."""
        low = _norm(m.span.text, self.vocab)
        other = {exclude.name} if exclude is not None and exclude.name else set()
        if exclude is not None and exclude.name:
            other |= {o.name for o in self._find(exclude.name) or self._by_head(exclude.name)}
        place = re.search(r"\b(?:left|right|front|back|rear|middle|center|centre|far|near|closest|nearest|farthest)\b", low)
        near = re.search(r"\b(?:by|near|next to|beside|closest to|nearest to)\s+(?:the\s+)?([a-z0-9' ]+)$", low)
        size = re.search(r"\b(big|bigger|biggest|large|larger|largest|small|smaller|smallest|little|tiny)\b", low)
        if place is None and near is None and size is None:
            return None
        words = re.sub(r"\b(?:the|a|an|one|ones|thing|object|item|whichever|which|that|is|its|of|two|2|sibling|"
                       r"twin|brother|sister|partner|on|at|in|to|by|near|next|beside|closest|nearest|farthest|camera|"
                       r"robot|side|left|right|front|back|rear|middle|center|centre|far|big|bigger|biggest|large|larger|"
                       r"largest|small|smaller|smallest|little|tiny|stands?|sits?|lies|placed)\b", " ", low)
        if near is not None:
            words = words.replace(near.group(1), " ")
        kind = [w for w in re.findall(r"[a-z]+", words) if len(w) > 2]
        pool = [o for o in self.objects if not o.unknown and o.name not in other]
        if kind:
            head = singular(kind[-1])
            pool = [o for o in pool if any(singular(w) == head or (len(head) >= 3 and w.endswith(head))
                                           for w in f"{o.name} {self._display(o.name) or ''}".split())]
        elif re.search(r"\b(?:sibling|twin|brother|sister|partner)\b", low) and exclude is not None and exclude.name:
            head = singular((self._display(exclude.name) or exclude.name).split()[-1])
            pool = [o for o in pool if singular((self._display(o.name) or o.name).split()[-1]) == head]
        if not pool or len({o.name for o in pool}) < 2 and not (place or near) and exclude is None:
            return None
        if near is not None:
            ref = near.group(1).strip()
            fits = [o for o in pool if (o.position or {}).get("reference") and self._same(
                str((o.position or {}).get("reference")), ref) or (o.position or {}).get("reference") in
                {x.name for x in self._find(ref) or self._by_head(ref)}]
            return fits[0].name if len({o.name for o in fits}) == 1 else None
        if place is not None:
            region = find_region(re.sub(r"\b(?:closest|nearest)\b(?: to the (?:camera|robot))?", "front",
                                        re.sub(r"\bfarthest\b(?: from the (?:camera|robot))?", "back", low)))
            if region is not None:
                want = region[0]
                fits = [o for o in pool if want in str((o.position or {}).get("region", "")).split("_")
                        or str((o.position or {}).get("region", "")) == want]
                if len({o.name for o in fits}) == 1:
                    return fits[0].name
            if size is None:
                return None
        assert size is not None
        large = size.group(1) in ("big", "bigger", "biggest", "large", "larger", "largest")

        def is_large(o: _Object) -> bool:
            said = f"{o.name} {self._display(o.name) or ''}"
            return re.search(r"\b(?:large|big|extra large)\b", said) is not None

        fits = [o for o in pool if is_large(o) == large]
        # "the small one ... the big one": one of two told apart, or the one left when the other role took its pair
        return fits[0].name if len({o.name for o in fits}) == 1 and (len({o.name for o in pool}) >= 2 or exclude) else None

    def task(self) -> dict[str, Any] | None:
        kind = self.task_type()
        src_m, tgt_m = self._phrase("SRC"), self._phrase("TGT")
        if kind is None:
            if src_m is None:
                return None
            kind = "pick_up" if tgt_m is None else "move_near"
            if tgt_m is not None and re.fullmatch(r"\s*(?:->|→|=>|-->|—>|>)\s*", self.text[src_m.span.end:tgt_m.span.start]):
                # "orange -> basket" with the arrow untagged: into a container, onto anything else
                oid = _object_id(self.vocab, self._task_phrase(tgt_m) or "")
                kind = "put_in" if oid is not None and oid in self.vocab.containers else "put_on"
        if kind is not None and kind != "pick_up" and tgt_m is None and src_m is not None:
            rel = [t for t in self.spans if t.tag in RELATION_TAGS and t.start >= src_m.span.end]
            said = re.match(r"\s+(it|that one|that|this one)\b", self.text[rel[0].end:rel[0].end + 14]) if rel else None
            if said is not None:  # "put the banana on it" with the pronoun left untagged
                a, b = rel[0].end + said.start(1), rel[0].end + said.end(1)
                tgt_m = _Mention("TGT", Span("TGT", a, b, said.group(1)), said.group(1))
        src = self._task_phrase(src_m, exclude=tgt_m if kind != "pick_up" else None)
        tgt = self._task_phrase(tgt_m, exclude=src_m) if kind != "pick_up" else None
        if kind is not None and kind != "pick_up" and src_m is None and tgt_m is not None:
            rel = [t for t in self.spans if t.tag in RELATION_TAGS and t.end <= tgt_m.span.start]
            lo = rel[-1].end if rel else max(self.text.rfind(c, 0, tgt_m.span.start) for c in ".;\n:") + 1
            between = list(self.vocab.name_pattern.finditer(_norm(self.text[lo:tgt_m.span.start], self.vocab)))
            if len(between) == 1 and self._task_phrase(tgt_m):
                # "move_near fork->[knife]": the object left untagged between the relation and the destination
                return self._ground_task(kind, canonical_name(self.vocab, between[0].group(0)), self._task_phrase(tgt_m))
            both = [canonical_name(self.vocab, m.group(0)) for m in self.vocab.name_pattern.finditer(
                _norm(tgt_m.span.text, self.vocab))]
            if len(both) == 2:  # "put_on;[apple;sponge]": the object and the destination in one phrase
                return self._ground_task(kind, both[0], both[1])
        if kind != "pick_up" and tgt_m is None and src_m is not None:
            # "put_in dice mug", "put_on;apple;sponge": the object and the destination in one phrase
            both = [canonical_name(self.vocab, m.group(0)) for m in self.vocab.name_pattern.finditer(
                _norm(src_m.span.text, self.vocab))]
            if len(both) == 2:
                src, tgt = both
        if src is None or (kind != "pick_up" and tgt is None):
            return None
        return self._ground_task(kind, src, tgt)

    def _ground_task(self, kind: str, src: str, tgt: str | None) -> dict[str, Any]:
        """Names as the scene has them: "the plate" is the scene's one (red) plate; unknown phrases stay."""
        out: dict[str, Any] = {"type": kind, "source": self._in_scene(src), "target": self._in_scene(tgt) if tgt else None}
        known = set(self.vocab.canonical.values())
        if out["source"] not in known or (tgt is not None and out["target"] not in known):
            grounded = self._ground_by_reader(kind, out["source"], out["target"])
            if grounded is not None:
                return grounded
        return out

    def _in_scene(self, name: str) -> str:
        found = self._find(name)
        if found:
            return name if any(o.name == name for o in found) else found[0].name
        by_head = self._by_head(name)
        if by_head:
            return by_head[0].name
        return name

    def _ground_by_reader(self, kind: str, src: str, tgt: str | None) -> dict[str, Any] | None:
        by_name = {**self.vocab.name_ids, **{n: cid for cid, n in self.vocab.ids.items()}}
        ids = [by_name[o.name] for o in self.objects if o.name in by_name]
        statement = {
            "pick_up": f"pick up the {src}", "move_near": f"move the {src} near the {tgt}",
            "put_on": f"put the {src} on the {tgt}", "put_in": f"put the {src} in the {tgt}",
        }[kind]
        frame = read_instruction(statement, scene_objects=ids or None)
        frame_in_scene = bool(ids)
        if frame.task != kind or frame.object is None:
            return None

        def name(phrase: Any, said: str | None) -> str | None:
            if phrase is None:
                return said
            oid = getattr(phrase, "object_id", None)
            if oid is None or said is None:
                return said
            head = singular(said.split()[-1])
            names = [n for n, cid in self.vocab.name_ids.items() if cid == oid] + [self.vocab.ids.get(oid, "")]
            if said in self.vocab.name_ids or any(singular(n.split()[-1]) == head for n in names if n):
                return self.vocab.ids.get(oid, said)
            if frame_in_scene and oid in ids:
                return self.vocab.ids.get(oid, said)  # "the vessel": the scene's one bowl
            return said  # "a wine glass" is not the windex bottle

        return {"type": kind, "source": name(frame.object, src),
                "target": name(frame.destination, tgt) if kind != "pick_up" else None}

    # -- counts -----------------------------------------------------------------
    def total(self) -> int | None:
        for s in reversed([s for s in self.spans if s.tag == "TOTAL"]):
            m = _NUMBER.search(_norm(s.text, self.vocab))
            if m is not None and 0 < int(m.group(1)) <= 20:
                return int(m.group(1))
        return None

    def total_after_removals(self, total: int) -> int:
        """A stated total that counted a list an object was later taken out of ("Three objects: strawberry, plate,
        softball. Scratch the softball."): the total of the list as it ends up."""
        said = [s for s in self.spans if s.tag == "TOTAL" and _NUMBER.search(_norm(s.text, self.vocab))]
        after = said[-1].end if said else 0
        drops = [m.span.start for m in self.mentions if m.tag == "DROP" and m.span.start >= after]
        if not drops:
            return total
        listed = sum(max(m.count, 1) for m in self.mentions if m.tag == "OBJ" and after <= m.span.start < drops[0])
        return len(self.objects) if listed == total else total

    def randoms(self) -> tuple[int, bool]:
        """(random objects with a count, whether some random fill has no count)."""
        n, fill = 0, False
        for s in self.spans:
            if s.tag != "ANY":
                continue
            normal = re.sub(r"\ba couple(?: of)?\b", "2", _counted(_norm(s.text, self.vocab)))
            m = _NUMBER.search(normal)
            if re.search(r"\b(?:no|nothing|none|not|without|zero)\b", normal):
                continue  # "nothing random"
            if m is not None and 0 < int(m.group(1)) <= 12:
                n += int(m.group(1)) - self._members(s)
            elif re.search(r"\b(?:rest|else|remaining|remainder|others|fill\w*|up)\b", normal) or re.search(
                r"\b(?:objects|things|items|ones|stuff|distractors|fillers|extras)\b", normal
            ):
                fill = True  # "the rest random", "random objects", "anything else"
            else:
                n += 1  # "a random fruit", "ADD random object"
        return max(n, 0), fill

    def _members(self, s: Span) -> int:
        """Named objects said to be among a random group ("three random objects, one of them a marker")."""
        after = [m for m in self.mentions if m.tag == "OBJ" and m.span.start > s.end
                 and not re.search(r"[.!?\n]", self.text[s.end:m.span.start])]  # "four random objects; make sure one is ..."
        count = 0
        at = s.end
        member = re.compile(
            r"\b(?:one|two|\d) of (?:them|which|those|these|those \w+|these \w+)\b|\bamong (?:them|which)\b|"
            r"\binclud(?:ing|es|e)\b|\bone being\b|\bof which\b|\bas long as\b|\bmake sure\b|"
            r"\b(?:one|another|the other)(?: of them| one)? (?:is|being|should be|must be|has to be|needs to be)\b"
        )
        inside = False
        for m in after:
            between = self.text[at:m.span.start].lower()
            tail = self.text[m.span.end:m.span.end + 40].lower()
            at = m.span.end
            also = re.match(r"\s*(?:too|as well|also)\b", tail) or re.search(
                r"\b(?:also|too|as well|in addition|additionally|plus|on top)\b", between
            )
            if also:
                break
            if member.search(between) or (inside and not also and re.fullmatch(
                r"\s*(?:,|and|,\s*and)?\s*(?:(?:one|another|the other)(?: of them)?(?: (?:is|being|must be|should be))?)?\s*",
                between,
            )) or re.match(
                r"\s*(?:is|are|being|must be|should be)\s+(?:among|one of|part of|included)", tail
            ):
                count += m.count
                inside = True
            else:
                break
        return count


_MOTION_START = re.compile(
    r"(?i)\s*(?:and\s+|then\s+|while\s+|whilst\s+)?(?:tilt|pan|roll|yaw|pitch|rotate|turn|swing|raise|lower|lift|drop|"
    r"move|shift|slide|dolly|push|pull|nudge|zoom|bring)(?:ing|s|ed)?\b"
)


def _valued(text: str) -> bool:
    return re.search(r"\d|\b(?:one|two|three|four|five|six|seven|eight|nine|ten|half|quarter|third|fifth)\b", text.lower()) is not None


def _with_key(s: Span, text: str) -> str:
    """A span with the key it is the value of ("z_cm: [[1.5]]", "- yaw = [[+3]]"), when the line has one."""
    line_start = text.rfind("\n", 0, s.start) + 1
    prefix = text[line_start:s.start]
    stop = [m.end() for m in re.finditer(r"[.!?;,|]\s", prefix)]  # a key never reaches back across a sentence
    prefix = prefix[stop[-1]:] if stop else prefix
    m = re.search(r"([A-Za-z][\w ./-]{0,30})[\"']?\s*[:=]\s*[\"']?\s*$", prefix)
    cells = re.split(r"[;,\t|]", text[line_start:s.start])
    if m is None and not cells[-1].strip() and (len(cells) == 2 or len(cells) == 3 and not cells[0].strip()) and (
        re.fullmatch(r"\s*[A-Za-z][A-Za-z_.\- ]{0,28}\s*", cells[-2]) and len(cells[-2].split()) <= 3
    ):
        return f"{cells[-2].strip()}: {s.text}"  # "cam_dy_cm,1.5", "| cam yaw | -2 |": the row's own key
    if m is None and re.fullmatch(r"[^|\n][^\n]*[;,\t|]\s*", text[line_start:s.start]) and line_start > 0:
        # a CSV row under its header: the column's name is the key ("cam_pitch_deg;cam_dx_cm" / "...;-1;2")
        header = text[text.rfind("\n", 0, line_start - 1) + 1:line_start - 1]
        line_end = text.find("\n", s.end)
        row = text[line_start:line_end if line_end >= 0 else len(text)]
        sep = next((c for c in ";\t|," if header.count(c) >= 2 and header.count(c) == row.count(c)), None)
        if sep is not None:
            column = text[line_start:s.start].count(sep)
            names = header.split(sep)
            if column < len(names) and re.search(r"[a-z]", names[column].lower()):
                return f"{names[column].strip()}: {s.text}"
    if m is not None and re.search(r"\d", s.text.split()[0] if s.text.split() else "x") is not None:
        return f"{m.group(1)}: {s.text}"
    if m is not None:
        return f"{m.group(1)}: {s.text}"
    return s.text


def _joined(spans: list[Span], text: str) -> str:
    """The words of ``spans`` read in order; separate motions are joined with 'and'."""
    out = ""
    for s in spans:
        piece = _with_key(s, text).strip()
        if not out:
            out = piece
            continue
        both_valued = _valued(out.split(" and ")[-1]) and _valued(piece) and re.search(
            r"[a-z]{2,}", re.sub(r"\b(?:cm|mm|deg|degrees?|percent|centimet(?:er|re)s?|millimet(?:er|re)s?)\b", "", piece.lower())
        )
        # "lower the camera 3 cm" + "tilt it up a couple of degrees": a motion of its own after a complete one
        own_motion = _valued(out.split(" and ")[-1]) and _MOTION_START.match(piece) is not None
        out = f"{out} and {piece}" if both_valued or own_motion else f"{out} {piece}"
    return out


def _environment(spans: list[Span], text: str, vocab: Vocabulary) -> list[dict[str, Any]]:
    from ladev_lib.language.scene.reader import read_description

    ops: list[dict[str, Any]] = []
    # a value under the other setting's key ("[[lgt=-0.3|CAM]]", "[[cam: pan 2|LIGHT]]") is that setting's
    spans = [Span("LIGHT", s.start, s.end, s.text) if s.tag == "CAM" and _LIGHT_KEY.match(s.text)
             else Span("CAM", s.start, s.end, s.text) if s.tag == "LIGHT" and _CAM_KEY.match(s.text) else s for s in spans]
    light = _statement_of_bare_key([s for s in spans if s.tag == "LIGHT"], text, spans)
    cam = [s for s in spans if s.tag == "CAM"]
    if light and _taken_back(light[-1], text, "light"):
        light = []  # "slightly darker, actually no change"
    if cam and _taken_back(cam[-1], text, "camera"):
        cam = []
    if light:
        light = _with_gap_light_direction(light, text)
        said = _joined(light, text)
        op = read_lighting_request(said)
        if op is None:
            worded = said if re.search(r"\b(?:light|lights|lighting|brightness|lamps?|illumination)\b", said.lower()) \
                else f"lighting {said}"
            read = read_description(worded, vocab)
            ops.extend(op for op in read.get("operations", []) if op.get("op") == "set_lighting")
        elif op["intensity_delta"] != 0.0:
            ops.append(op)
    if cam:
        cam = _corrected_motions(_completed_values(cam, text), text)
        cam = _with_gap_directions(cam, text)
        said = _joined(cam, text)
        op = read_camera_request(said)
        if op is None:
            worded = said if re.search(r"\b(?:camera|cam|view|viewpoint)\b", said.lower()) else f"camera {said}"
            read = read_description(worded, vocab)
            moves = [op for op in read.get("operations", []) if op.get("op") == "move_camera"]
            ops.extend(merge_camera(moves) if len(moves) > 1 else moves)
        elif any(op["translation_m"]) or any(op["rotation_deg"]):
            ops.append(op)
    return ops


_GAP_DIRECTION = re.compile(
    r"(?i)\b(?:left|right|up|down|higher|lower|forward|forwards|closer|back|backward|backwards|further back|away|in|out|"
    r"clockwise|counter[- ]?clockwise|anti[- ]?clockwise)\b"
)


def _taken_back(last: Span, text: str, what: str) -> bool:
    """Whether the words after the last lighting / camera phrase take the change back ("slightly darker, actually
    no change", "camera 2 cm left... no, don't move it")."""
    after = text[last.end:last.end + 80]
    after = re.split(r"(?<!\.)[.!?](?!\.)\s+(?=[A-Z])|\n", after)[0].lower()  # up to the next sentence or line
    it = r"(?:it|them|the lights?|the lighting|the brightness|that)" if what == "light" else r"(?:it|the camera|the view|that)"
    # the words of the request may go on before the correction ("[[Dim]] the lights by a quarter; actually, never mind")
    return re.match(
        rf"(?:[^.!?\n]{{0,40}}?(?:[,;:\u2014\u2013-]|\.\.\.))?"
        rf"\W*(?:(?:actually|no|wait|hmm|sorry|on second thought|scratch that)\W+)+(?:,\s*)?(?:no change|unchanged|"
        rf"(?:leave|keep) {it}(?: (?:alone|as is|where it is|at default|default|unchanged))?|don'?t (?:move|change|touch) {it}|"
        rf"never ?mind|forget it|default|as (?:is|it is|before))\b",
        after,
    ) is not None


_LIGHT_DIRECTION = re.compile(r"(?i)\b(?:brighter|darker|dimmer|lighter|up|down|increase|decrease|dim|brighten|darken)\b")


def _with_gap_light_direction(light: list[Span], text: str) -> list[Span]:
    """ "[[Lighting|LIGHT]] 40% brighter - no, [[make it 80%|LIGHT]]": a corrected amount keeps the direction said
    before it when no tagged word says one."""
    if any(_LIGHT_DIRECTION.search(s.text) for s in light):
        return light
    last = light[-1]
    after = re.match(r"\s*[(\[]?\s*(brighter|darker|dimmer|lighter|up|down)\b", text[last.end:last.end + 20], re.IGNORECASE)
    if after is not None:  # "light: [[0.5]] (brighter)"
        return [*light[:-1], Span(last.tag, last.start, last.end, f"{after.group(1)} {last.text}")]
    if len(light) < 2:
        # "Lighting: 40 % darker - no wait, [[25 %]]": the direction said earlier in the same statement
        lo = max(text.rfind(c, 0, last.start) for c in ".\n")
        said = [m for m in _LIGHT_DIRECTION.finditer(text[lo + 1:last.start]) if m.group(0).lower() not in ("up", "down")]
        if not said or not re.search(r"\b(?:no|wait|sorry|actually|make (?:that|it)|rather|correction|i mean)\b",
                                     text[lo + 1 + said[-1].end():last.start].lower()):
            return light
        return [Span(last.tag, last.start, last.end, f"{said[-1].group(0)} {last.text}")]
    found = _LIGHT_DIRECTION.search(text[light[0].end:last.start])
    if found is None:
        return light
    return [*light[:-1], Span(last.tag, last.start, last.end, f"{found.group(0)} {last.text}")]


_CORRECTION_CUE = re.compile(
    r"(?i)\b(?:no|nope|sorry|actually|wait|rather|correction|i mean|make (?:that|it)|change (?:that|it) to|instead|"
    r"scratch that|on second thought|let'?s (?:say|do|go with)|go with)\b"
)
_DIRECTION_FAMILIES = (
    ("left", "right"),
    ("up", "down", "higher", "lower", "raise", "lift", "upward", "downward", "upwards", "downwards"),
    ("forward", "forwards", "closer", "back", "backward", "backwards", "away", "in", "out", "toward", "towards",
     "nearer", "further", "farther"),
    ("clockwise", "counterclockwise", "counter-clockwise", "anticlockwise", "anti-clockwise", "cw", "ccw"),
)
_AMOUNT = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:\s*(?:cm|mm|m|deg\w*|°|%|centimet\w*|millimet\w*))?(?![\w.])", re.IGNORECASE)


_MOTION_VERB = re.compile(
    r"(?i)\b(?:tilt|tip|dip|angle|pan|roll|yaw|pitch|rotate|turn|swing|raise|lower|lift|move|shift|slide|dolly|push|"
    r"pull|nudge|zoom|bring|translate)\w*\b"
)


_LIGHT_KEY = re.compile(r"(?i)\s*(?:lgt|light(?:ing|s)?|brightness|illumination|lux)\s*[:=]")
_CAM_KEY = re.compile(r"(?i)\s*(?:cam(?:era)?|view(?:point)?|pov)\s*[:=]")


def _statement_of_bare_key(light: list[Span], text: str, spans: list[Span]) -> list[Span]:
    """ "[[Lights]] 45% brighter... hmm, too much, go with 25%": a lighting key tagged alone is read with the
    words of its statement, a correction in them read into the value it corrects."""
    if len(light) != 1 or re.search(r"\d", light[0].text) or _LIGHT_DIRECTION.search(light[0].text) or re.search(
            r"(?i)\b(?:half|double|twice|quarter|third|fifth|default|normal|unchanged)\b", light[0].text):
        return light
    s = light[0]
    end = re.search(r"[.!?](?:\s|$)(?!\.)|\n|;", text[s.end:])
    stop = s.end + end.start() if end is not None else len(text)
    words = text[s.start:stop]
    if re.match(r"\.\.", text[stop:stop + 2]) or text[stop - 2:stop + 1] == "...":
        stop2 = re.search(r"[.!?](?:\s|$)|\n|;", text[stop + 3:])
        words = text[s.start:stop + 3 + stop2.start()] if stop2 else text[s.start:]
    nxt = [t.start for t in spans if t.start >= s.end and t is not s]
    if nxt and s.start + len(words) > min(nxt):
        words = text[s.start:min(nxt)]  # up to the next tagged phrase ("lights dimmed, [[camera raised 5 cm]]")
    cue = _CORRECTION_CUE.search(words)
    if cue is not None:
        amount = _AMOUNT.search(words[cue.end():])
        new = _rewritten(words[:cue.start()].rstrip(" ,;.\u2014-"), amount.group(0)) if amount else None
        if new is not None:
            return [Span(s.tag, s.start, s.start + len(words), new)]
    said = _AMOUNT.search(words) or _LIGHT_DIRECTION.search(words[len(s.text):])
    return [Span(s.tag, s.start, s.start + len(words), words.rstrip(" ,;"))] if said else light


def _completed_values(cam: list[Span], text: str) -> list[Span]:
    """A camera phrase that ends on an axis whose value the tagger left out ("[[roll -2, pitch]] +3"), and a
    phrase that ends on the "in" of "in one go", read with the words they should end with."""
    out = []
    for k, s in enumerate(cam):
        after = text[s.end:s.end + 24]
        bare_later = any(not re.search(r"[a-z]", re.sub(r"(?i)(?<=\d)\s*(?:cm|mm|deg\w*)\b", "", t.text.lower()))
                         for t in cam[k + 1:])
        if re.search(r"(?i)\b(?:yaw|pitch|roll|pan|tilt|d?[xyz]|t[xyz])\s*$", s.text) and not bare_later:
            m = re.match(r"\s*[:=]?\s*[-+]?\d+(?:\.\d+)?\s*(?:°|deg\w*|cm|mm)?", after, re.IGNORECASE)
            if m is not None and re.search(r"\d", m.group(0)):
                s = Span(s.tag, s.start, s.end + m.end(), text[s.start:s.end + m.end()])
        elif re.search(r"(?i)\s+in$", s.text) and re.match(r"(?i)\s+(?:one|a single|the same|a row)\b", after):
            s = Span(s.tag, s.start, s.end - 3, text[s.start:s.end - 3])
        out.append(s)
    return out


_AXIS_WORDS = (
    ("x", r"\b(?:left|right|sideways|x)\b"),
    ("z", r"\b(?:up|down|raise\w*|lower\w*|lift\w*|higher|upward\w*|downward\w*|z)\b"),
    ("y", r"\b(?:forward\w*|back\w*|closer|away|dolly|push|pull|toward\w*|nearer|y)\b"),
    ("yaw", r"\b(?:pan\w*|yaw\w*)\b"), ("pitch", r"\b(?:tilt\w*|pitch\w*|tip\w*)\b"), ("roll", r"\broll\w*\b"),
)


def _axis_of(words: str) -> str | None:
    """The one axis a motion's words move along ("lower 2 cm": z; "tilt down 3 degrees": pitch), or None."""
    low = words.lower()
    rotation = [a for a, p in _AXIS_WORDS[3:] if re.search(p, low)]
    if rotation:
        return rotation[0] if len(rotation) == 1 else None
    found = [a for a, p in _AXIS_WORDS[:3] if re.search(p, low)]
    return found[0] if len(found) == 1 else None


def _family(word: str) -> int | None:
    return next((i for i, f in enumerate(_DIRECTION_FAMILIES) if word.lower() in f), None)


def _rewritten(original: str, correction: str) -> str | None:
    """A motion said again with the words of its correction: its amount ("3 cm closer" + "6 cm" -> "6 cm closer"),
    its direction ("3 cm to the right" + "to the left" -> "3 cm to the left"), or both."""
    amounts = list(_AMOUNT.finditer(original))
    if len(amounts) > 1:
        return None  # several motions: which one the correction is of is not read here
    new = original
    said = _AMOUNT.search(correction)
    if said is not None:
        if not amounts:
            return None
        value = said.group(0)
        if not re.search(r"[a-z°%]", value, re.IGNORECASE):
            unit = re.search(r"[a-z°%].*$", amounts[0].group(0), re.IGNORECASE)
            value = f"{value} {unit.group(0)}" if unit else value
        new = new[:amounts[0].start()] + value + new[amounts[0].end():]
    for word in re.findall(r"[a-z]+(?:-[a-z]+)?", correction.lower()):
        fam = _family(word)
        if fam is None or word in ("in", "out") and said is not None:
            continue
        words = [m for m in re.finditer(r"[a-z]+(?:-[a-z]+)?", new.lower()) if _family(m.group(0)) is not None]
        same = [m for m in words if _family(m.group(0)) == fam] or words  # "3 cm up, I mean forward": another axis
        if same:
            m = same[-1]
            # the direction's own words go with it: "to the right", "closer to the table", "towards the table"
            lo = re.search(r"(?i)(?:\bto\s+the\s+)?$", new[:m.start()])
            hi = re.match(r"(?i)(?:\s+(?:to|from|toward|towards)?\s*the\s+(?:table|scene|robot|workspace))?", new[m.end():])
            start = m.start() - (len(lo.group(0)) if lo else 0)
            new = new[:start] + word + new[m.end() + (hi.end() if hi else 0):]
        else:
            new = f"{new} {word}"
    return None if new == original else new


def _corrected_motions(cam: list[Span], text: str) -> list[Span]:
    """ "[[Camera 3 cm]] closer to the table - no, make it [[6 cm]]", "[[Move the camera]] 3 cm to the right -- no,
    [[to the left]]", "Camera: 8 cm closer - no, make it [[4 cm]]": a corrected amount or direction read into the
    motion it corrects, with the words of that motion the tags left out."""
    out = list(cam)
    if out:
        first = out[0]
        lo = max(text.rfind(c, 0, first.start) for c in ".\n") + 1
        key = re.search(r"(?i)\b(?:camera|cam|view)\b", text[lo:first.start])
        if key is not None and not re.search(r"(?i)\b(?:camera|cam|view)\b", first.text) and _AMOUNT.search(first.text) \
                and not _MOTION_VERB.search(first.text) and _CORRECTION_CUE.search(text[lo + key.end():first.start]):
            out.insert(0, Span(first.tag, lo + key.start(), lo + key.end(), key.group(0)))  # the statement's key, untagged
    k = 1
    while k < len(out):
        prev, cur = out[k - 1], out[k]
        gap = text[prev.end:cur.start]
        cue = _CORRECTION_CUE.search(gap)
        if cue is None or re.search(r"[.!?\n]", gap[:cue.start()].replace("...", "")) and _AMOUNT.search(prev.text):
            k += 1
            continue
        end = min([e for e in (text.find(c, cur.end) for c in ".\n") if e >= 0] or [len(text)])
        if _MOTION_VERB.search(cur.text) and _AMOUNT.search(cur.text) and \
                _axis_of(cur.text) is not None and _axis_of(cur.text) == _axis_of(prev.text):
            del out[k - 1]  # "raise 2 cm, then - correction - lower 2 cm instead": the same axis said again, in full
            continue
        if _MOTION_VERB.search(cur.text) or not _AMOUNT.search(cur.text) and any(
                _AMOUNT.search(t.text) for t in out[k + 1:] if t.start < end):
            k += 1  # said again in full ("make that a tilt down of 2 degrees"), or its amount follows in its own words
            continue
        stop = re.search(r"[.!?](?:\s|$)|\n", gap[:cue.start()])
        original = text[prev.start:prev.end + (stop.start() if stop else cue.start())]
        original = re.sub(r"(?i)(?:[\s,;:.\u2014\u2013-]|\b(?:uh|um|er|erm|oh|well)\b)*$", "", original)
        new = _rewritten(original, cur.text)
        if new is None:
            k += 1
            continue
        out[k - 1:k + 1] = [Span(cur.tag, prev.start, cur.end, new)]
        if k < len(out) and re.fullmatch(r"[\s:=,;\u2014\u2013-]*", text[cur.end:out[k].start]) and \
                re.findall(r"[a-z0-9.]+", out[k].text.lower()) == re.findall(r"[a-z0-9.]+", new.lower()):
            del out[k]  # "pan right 3 degrees - sorry, left: pan left 3 degrees": the correction said in full again
    return out


def _with_gap_directions(cam: list[Span], text: str) -> list[Span]:
    """ "[[Camera|CAM]] back 10 cm, sorry, [[4 cm|CAM]]": an amount with no direction of its own takes the direction
    words left untagged between it and the camera words before it (the corrected amount is not taken)."""
    out = list(cam)
    for k in range(1, len(out)):
        prev, cur = out[k - 1], out[k]
        if _GAP_DIRECTION.search(cur.text) or _GAP_DIRECTION.search(prev.text) or not re.search(r"\d", cur.text):
            continue
        gap = text[prev.end:cur.start]
        found = _GAP_DIRECTION.search(gap)
        if found is not None and re.search(r"\d", gap[found.end():]):
            out[k] = Span(cur.tag, cur.start, cur.end, f"{found.group(0)} {cur.text}")
    for k in range(1, len(out)):
        prev, cur = out[k - 1], out[k]
        verb = re.match(r"(?i)\s*(roll|pan|tilt|yaw|pitch)\w*\b", cur.text)
        if verb is None or re.search(r"\d", cur.text):
            continue
        # "pan left 2 degrees and roll 3 degrees clockwise; correction - [[roll counterclockwise]]": the amount stays
        said = re.search(rf"(?i)\b{verb.group(1)}\w*\D{{0,20}}?(\d+(?:\.\d+)?)\s*(?:deg\w*|°)", text[prev.end:cur.start])
        if said is not None:
            out[k] = Span(cur.tag, cur.start, cur.end, f"{cur.text} {said.group(1)} degrees")
    return out


def assemble(
    text: str,
    spans: list[Span],
    vocab: Vocabulary,
    instruction: str | None = None,
    task: str | None = None,
) -> dict[str, Any]:
    """Tagged spans of ``text`` -> a SceneOperations-shaped dict (objects, task, lighting, camera)."""
    from ladev_lib.language.scene.reader import explicit_task

    a = _Assembly(text, spans, vocab)
    a.retag()
    a.read_mentions()
    a.read_positions()
    a._headers_and_restatements()
    a.build_objects()
    out: dict[str, Any] = {"schema_version": 1, "operations": []}
    low = text.lower()
    if re.search(r"\bycb\b|\bunseen objects?\b", low):
        out["object_set"] = "ycb"
    elif re.search(r"\bsimpler ?env\b|\bsimpler objects?\b|\bseen objects?\b|\bsimpler set\b", low):
        out["object_set"] = "simpler"
    stated = a.task()
    if instruction:
        out.update(explicit_task(instruction, vocab))
        if "error" in out:
            return out
    elif stated is not None:
        out["task"] = stated
    elif task:
        out["task"] = {"type": task}
    if text.strip() and not a.mentions and not any(s.tag in ("TOTAL", "ANY", "LIGHT", "CAM") for s in a.spans):
        out["error"] = "no object, object count, position, lighting or camera setting found in the description"
        return out
    if instruction or stated is None:
        # the text's own task phrases still name objects of the scene
        for m in a.mentions:
            if m.tag in ("SRC", "TGT") and m.name and not m.unknown and not _PRONOUN.match(m.name) and not a._find(m.name):
                a.objects.append(_Object(m.name, False, dict(m.position) if m.position else None, [m]))
    slots = a.task_slots(out.get("task") or {}) if instruction else 0
    a.add_task_objects(out.get("task") or {})
    a.resolve_refs()

    ops: list[dict[str, Any]] = []
    for obj in a.objects:
        op: dict[str, Any] = {"op": "add_object", "object": obj.name}
        if obj.position is not None:
            op["position"] = obj.position
        ops.append(op)
    counted, _fill = a.randoms()
    total = a.total()
    if total is not None and a.removed and len(a.objects) < total:
        total = a.total_after_removals(total)
    randoms = max(total - len(a.objects), 0) if total is not None else max(counted - slots, 0)
    ops.extend({"op": "add_object", "object": None} for _ in range(randoms))
    ops.extend(_environment(a.spans, text, vocab))
    out["operations"] = ops
    return out


def read_tagged(
    description: str,
    vocab: Vocabulary,
    instruction: str | None = None,
    task: str | None = None,
    weights: str | None = None,
) -> dict[str, Any]:
    """Description -> operations dict, through the span tagger (the committed weights by default)."""
    from ladev_lib.language.tagging.model import load_tagger

    text = plain_code(description or "")
    spans = load_tagger(weights).tag(text)
    return assemble(text, spans, vocab, instruction=instruction, task=task)


_CALL = re.compile(r"\b[A-Za-z_]\w*\(\s*(?:['\"]|[A-Za-z_]\w*\s*=)")


def plain_code(text: str) -> str:
    """A description written as code read as the words it says: ``add('pitcher', pos='back')`` ->
    ``add pitcher, pos back``; ``task('move_near', 'fork', 'mug')`` -> ``task move_near fork, mug``; a Python
    dict (``{'objects': ['mug'], 'task': ('pick_up', 'mug')}``) or one call with keywords likewise; prose and
    other text unchanged (the tagger reads such words; quotes, brackets and keyword signs only hide them)."""
    python_literal = re.search(r"'[^'\n]{1,40}'\s*:", text) is not None and len(re.findall(r"'[^'\n]*'", text)) >= 4
    one_call = len(_CALL.findall(text)) == 1 and len(re.findall(r"\b[A-Za-z_]\w*\s*=\s*(?!=)", text)) >= 2
    if len(_CALL.findall(text)) < 2 and not python_literal and not one_call:
        return text  # prose, JSON (the tagger reads its keys) and single calls stay as written
    out = re.sub(r"\b([A-Za-z_]\w*)\s*=\s*(?!=)", r"\1 ", text)  # pos='back' -> pos 'back'
    out = re.sub(r"(?<=[A-Za-z])\s*:\s*(?=[A-Za-z])", " ", out)  # 'near:mug' -> near mug
    out = re.sub(r"\b([A-Za-z_]\w*)\s*\(", r"\1 ", out)  # add( -> add
    out = re.sub(r"[\"'`\[\]{}()]", " ", out)
    out = re.sub(r"\s*,\s*", ", ", out)
    return re.sub(r"[ \t]+", " ", out).strip()


__all__ = ["assemble", "read_tagged"]
