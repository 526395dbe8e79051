"""Words, numbers, units, the catalog vocabulary and sentence segmentation."""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

# -- numbers -----------------------------------------------------------------------

_NUMBER_WORDS = {
    "zero": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7,
    "eight": 8, "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "thirteen": 13,
    "fourteen": 14, "fifteen": 15, "sixteen": 16, "seventeen": 17, "eighteen": 18,
    "nineteen": 19, "twenty": 20,
}
_NUMBER_PHRASES = [
    (r"\bhalf a dozen\b", "6"), (r"\ba dozen\b", "12"), (r"\ba couple of\b", "2"),
    (r"\ba single\b", "1"), (r"\bsingle\b", "1"), (r"\bjust 1\b", "1"),
    (r"\bboth\b", "2"),
]
NUM = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)"

SCENE_NOUNS = {
    "table", "scene", "workspace", "tabletop", "desk", "surface", "counter", "setup", "set",
    "environment", "layout", "arrangement", "configuration", "world", "bench", "area",
}
FILLERS = {
    "a", "an", "the", "some", "any", "there", "is", "are", "be", "being", "was", "were", "with",
    "anyway", "anyways", "also", "so", "okay", "ok", "well", "fun", "basically", "honestly",
    "and", "or", "plus", "too", "as", "of", "them", "which", "these", "those", "that",
    "this", "it", "its", "has", "have", "having", "contains", "contain", "containing", "holds", "hold",
    "holding", "includes", "include", "including", "included", "featuring", "features", "feature",
    "consisting", "consists", "made", "up", "let", "lets", "create", "make", "generate", "build",
    "add", "place", "placed", "put", "set", "puts", "located", "lying", "sitting", "standing",
    "resting", "positioned", "upright", "somewhere", "anywhere", "on", "in", "at", "to", "from", "for",
    "into", "onto", "by", "we", "i", "want", "need", "please", "should", "would", "like", "just",
    "only", "exactly", "total", "totally", "details", "detail", "number", "objects", "object", "items",
    "item", "things", "thing", "random", "randomly", "other", "others", "another", "more", "additional",
    "extra", "else", "chosen", "selected", "picked", "arbitrary", "whatever", "different", "various",
    "assorted", "distractor", "distractors", "distractor objects", "each", "every", "all", "both",
    "here", "then", "next", "following", "follows", "below", "rest", "remaining", "same",
    "cluttered", "messy", "tidy", "simple", "clean", "empty", "busy", "small", "large", "typical",
    "usual", "normal", "default", "standard", "new", "nice", "nicely", "arranged", "scattered",
    "spread", "visible", "clearly", "one", "ones", "side", "corner", "edge", "part", "region",
    "position", "positions", "pose", "poses", "location", "spot", "middle", "center", "centre",
    "left", "right", "front", "back", "top", "bottom", "far", "near", "close", "robot", "robots",
    "gripper", "arm", "it's", "theres", "there's", "scene's", "they", "their", "no",
    "not", "nothing", "none", "specific", "specified", "unspecified", "given", "mentioned",
    "besides", "beside", "apart", "except", "alongside", "together", "respectively", "whose",
    "where", "who", "what", "while", "but", "such", "e.g", "eg", "ie", "etc",
    "sim", "simulation", "simulated", "test", "tabletop", "task", "instruction",
    "obj", "objs", "env", "cam", "named", "fixed", "stuff", "choice", "your", "something", "anything",
    "everything", "selection", "mix", "bunch", "couple", "variety", "assortment",
    "lay", "out", "arrange", "give", "show", "use", "keep", "leave", "fill", "start", "scatter", "get", "see", "try", "hey", "hi", "hello", "thanks", "cheers", "yes", "yeah", "sure",
    "haha", "lol", "sigh", "hmm", "um", "uh", "oh", "ah", "thank", "wait", "oops", "sorry", "typo", "pls", "plz", "thx", "change",
    "replace", "replaced", "swap", "swapped", "instead", "actually", "scratch", "drop", "remove",
}
NON_OBJECT_NOUNS = frozenset({
    "example", "examples", "time", "times", "question", "questions", "version", "versions", "variant", "variants",
    "test", "tests", "idea", "ideas", "try", "tries", "attempt", "attempts", "run", "runs", "trial", "trials",
    "episode", "episodes", "step", "steps", "demo", "demos", "experiment", "experiments", "scene", "scenes",
})
"""Nouns a count or an article introduces in chat ("one more example"), never objects."""
STOP_PREPOSITIONS = {
    "on", "in", "at", "to", "from", "with", "of", "for", "over", "under", "near", "beside", "next",
    "behind", "between", "inside", "onto", "into", "by", "toward", "towards", "around", "left",
    "right", "front", "back",
}

HEADERS = re.compile(
    r"(?:^|(?<=[.;!?])\s*)\s*(number and details of objects|details of objects|objects and details|"
    r"object configuration|objects|items|props|spawn|environmental setup|environment setup|environment|setup|scene)"
    r"\s*:(?!\s*\d)",
)
_COORD2 = re.compile(
    rf"[\(\[]\s*(?:x\s*=\s*)?({NUM})\s*(cm|mm|m)?\s*[,;]\s*(?:y\s*=\s*)?({NUM})\s*(cm|mm|m)?\s*[\)\]]"
    rf"|\bx\s*[=:]\s*({NUM})\s*(cm|mm|m)?\s*,?\s*(?:and\s+)?y\s*[=:]\s*({NUM})\s*(cm|mm|m)?"
)
_COORD3 = re.compile(rf"[\(\[]\s*({NUM})\s*,\s*({NUM})\s*,\s*({NUM})\s*[\)\]]")
COUNT_TOTAL = re.compile(
    r"(?:\b(?:number of objects|num_objects|n_objects|objects|object count|count|items|total)\s*(?:is\s*)?[:=]\s*(\d+)\b)"
    r"|(?:\b(?:a total of|total of|in total|altogether)\s*(\d+)\b)"
    r"|(?:\b(\d+)\s+(?:(?:objects?|items?|things?)\s+)?(?:in all|in total|total|altogether|overall)\b)"
    r"|(?:\b(\d+)\s+(?:(?:different|distinct|total|items?|objects?|things?|props?|pieces?|random|other|more|additional|extra|"
    r"distractors?|small|household|kitchen|everyday|assorted|various|ycb|simplerenv|simpler)\s+){0,3}?"
    r"(?:objects?|objs?|items?|things?|props?|pieces?|distractors?)\b)"
)
KEYED_COUNT = re.compile(
    r"\b(?:number of objects|num_objects|n_objects|objects|object count|items|total)\s*(?:is\s*)?[:=]\s*(\d+)"
    r"\s*(?=$|[;,.)\n])"  # "objects: 7" but not "objects: 7-up can"
)
RANDOM_QUALIFIER = re.compile(r"\b(?:random|other|more|additional|extra|distractors?|arbitrary|unspecified|further)\b")


def unit_scale(unit: str | None, values: Iterable[float]) -> float:
    if unit in ("cm",):
        return 0.01
    if unit in ("mm",):
        return 0.001
    if unit in ("m",):
        return 1.0
    # No unit: metres unless the numbers only make sense as centimetres.
    return 0.01 if any(abs(v) > 1.0 for v in values) else 1.0


def length_scale(unit: str) -> float:
    unit = unit.lower()
    if unit.startswith("mm") or unit.startswith("millimet"):
        return 0.001
    if unit.startswith("cm") or unit.startswith("centimet"):
        return 0.01
    if unit.startswith("inch"):
        return 0.0254
    return 1.0


# -- vocabulary ----------------------------------------------------------------------


@dataclass
class Vocabulary:
    """The names the grammar recognises, longest first, from the prompt's object list."""

    names: list[str]
    """Names as they appear in normalised text (number words as digits), longest first."""
    canonical: dict[str, str]
    """Normalised form -> the name as the catalog writes it."""
    ids: dict[str, str]
    """catalog id -> display name (ids may appear verbatim in text)."""
    categories: set[str]
    name_ids: dict[str, str] = field(default_factory=dict)
    """Name or synonym as the catalog writes it (normalised) -> catalog id."""
    category_of: dict[str, str] = field(default_factory=dict)
    """catalog id -> its category ("fruit", "can")."""
    containers: frozenset[str] = frozenset()
    """catalog ids of objects that hold things inside (a basket, a bowl)."""

    @classmethod
    def from_objects(cls, objects: Iterable[Mapping[str, Any]]) -> Vocabulary:
        names: set[str] = set()
        ids: dict[str, str] = {}
        categories: set[str] = set()
        name_ids: dict[str, str] = {}
        category_of: dict[str, str] = {}
        containers: set[str] = set()
        for o in objects:
            if o.get("container"):
                containers.add(str(o["id"]).lower())
            display = _norm_name(str(o["name"]))
            names.add(display)
            name_ids.setdefault(display, str(o["id"]).lower())
            for s in o.get("synonyms", ()) or ():
                names.add(_norm_name(str(s)))
                name_ids.setdefault(_norm_name(str(s)), str(o["id"]).lower())
            ids[str(o["id"]).lower()] = display
            if o.get("category"):
                categories.add(str(o["category"]).replace("_", " "))
                category_of[str(o["id"]).lower()] = str(o["category"]).replace("_", " ")
        for n in list(names):
            spaced = re.sub(r"(?<=\d)(?=[a-z])", " ", n)
            if spaced != n:
                names.add(spaced)
        canonical = {_digits(n): n for n in names}
        for form, name in list(canonical.items()):
            if SPLIT_WORDS.search(form):
                canonical[form.replace(" ", "~")] = name
        return cls(
            sorted(canonical, key=lambda n: (-len(n), n)), canonical, ids, categories, name_ids, category_of,
            frozenset(containers),
        )

    @property
    def name_pattern(self) -> re.Pattern[str]:
        if not hasattr(self, "_pattern"):
            irregular = sorted({form for n in self.names for form in irregular_plurals(n)}, key=lambda n: (-len(n), n))
            alts = "|".join(re.escape(n) for n in [*irregular, *self.names])
            self._pattern = re.compile(rf"(?<![a-z0-9])(?:{alts})(?:e?s)?(?![a-z0-9])")
        return self._pattern

    @property
    def category_pattern(self) -> re.Pattern[str]:
        if not hasattr(self, "_cpattern"):
            alts = "|".join(re.escape(c) for c in sorted(self.categories, key=len, reverse=True))
            self._cpattern = re.compile(
                rf"(?<![a-z0-9])(?:(?:a|an|some|another|random|any|1|2|3|4|5|6)\s+(?:\w+\s+)?)"
                rf"(?P<cat>{alts})(?:e?s)?(?![a-z0-9])"
            )
        return self._cpattern


PAIRED_NOUNS = (
    "scissors|pliers|tongs|tweezers|glasses|sunglasses|eyeglasses|spectacles|goggles|binoculars|headphones|earphones|"
    "earbuds|shears|pincers|snips|cutters|clippers|jeans|trousers|pants|shorts|socks|gloves|shoes|chopsticks"
)
"""Nouns that "a pair of" makes one thing of ("a pair of scissors" is one object, not two scissors)."""


def irregular_plurals(name: str) -> list[str]:
    """Plurals of a name that its own letters plus "s" / "es" do not spell: "strawberries", "knives"."""
    out = []
    if re.search(r"[^aeiou]y$", name):
        out.append(name[:-1] + "ies")
    if name.endswith("fe"):
        out.append(name[:-2] + "ves")
    elif name.endswith("f") and not name.endswith("ff"):
        out.append(name[:-1] + "ves")
    return out


_TENS = {"twenty": 20, "thirty": 30, "forty": 40, "fifty": 50, "sixty": 60, "seventy": 70, "eighty": 80, "ninety": 90}


def _digits(text: str) -> str:
    for pattern, digit in _NUMBER_PHRASES:
        text = re.sub(pattern, digit, text)
    # "one hundred twenty percent", "a hundred and ten": hundreds
    small = "|".join(k for k, v in _NUMBER_WORDS.items() if 1 <= v <= 19)
    text = re.sub(
        rf"\b(?:a|one) hundred(?:(?: and)? ({'|'.join(_TENS)})(?:[ -]({small}))?|(?: and)? ({small}))?\b",
        lambda m: str(100 + (_TENS[m.group(1)] if m.group(1) else 0) + (_NUMBER_WORDS[m.group(2)] if m.group(2) else 0)
                      + (_NUMBER_WORDS[m.group(3)] if m.group(3) else 0)),
        text,
    )
    # "twenty five percent", "thirty-five", "forty": tens and units as one number
    units = "|".join(k for k, v in _NUMBER_WORDS.items() if 1 <= v <= 9)
    text = re.sub(
        rf"\b({'|'.join(_TENS)})(?:[\s-]+({units}))?\b",
        lambda m: str(_TENS[m.group(1)] + (_NUMBER_WORDS[m.group(2)] if m.group(2) else 0)), text,
    )
    return re.sub(
        r"\b(" + "|".join(_NUMBER_WORDS) + r")\b", lambda m: str(_NUMBER_WORDS[m.group(1)]), text
    )


def _norm_name(text: str) -> str:
    text = text.lower().replace("'", "").replace("’", "")
    text = re.sub(r"[-_/]", " ", text)
    return re.sub(r"\s+", " ", text).strip()


def normalize_text(text: str, vocab: Vocabulary) -> str:
    """Lower case, number words as digits, ids as display names, tidy punctuation."""
    t = text.lower()
    t = t.replace("’", "'").replace("‘", "'").replace("“", '"').replace("”", '"')
    t = t.replace("–", "-").replace("—", "-").replace("−", "-").replace("°", " degrees ")
    t = t.replace("&", " and ").replace("'", "")
    # "a bowl (bowl in the center)", "a mug (the mug goes left)": the bracket says where, not another one
    t = re.sub(r"\b((?:[a-z0-9]+ ){0,2}[a-z0-9]+)\s*\(\s*(?:the\s+|that\s+|this\s+)?\1\b(?:\s+(?:is|goes|sits|stands))?\s*",
               r"\1 (", t)
    t = re.sub(r"(?m)^\s*\d{1,2}[.)]\s+(?=[a-z])", "", t)  # "5. lights 10% dimmer": a list's numbering
    t = re.sub(r"\b(?:just )?for (?:fun|clutter)\b|\bas (?:a )?(?:joke|gag|clutter|distractors?)\b", " ", t)
    t = re.sub(r"\b(?:um+|uh+|erm|er|like)\b(?=\s)", " ", t)  # hesitations ("like three degrees")
    t = re.sub(r"\ba handful of\b", " some ", t)
    # "half a centimetre", "more close", "more far": said the long way
    t = re.sub(r"\bhalf an? (cm|centimet(?:er|re)|mm|millimet(?:er|re)|degree|inch)\b", r"0.5 \1", t)
    t = re.sub(r"\bmore close\b", "closer", t)
    t = re.sub(r"\bmore far\b", "farther", t)
    t = re.sub(r"\b(near|close|next) of\b", lambda m: "next to" if m.group(1) == "next" else m.group(1), t)  # "near of the plate"
    # "on the left of the table", "at the back side of the table": a region of the table, not a relation
    t = re.sub(r"\b(?:(?:on|at|to|in|toward|towards)\s+)?the\s+(left|right|front|back|rear|far|near|middle|center|centre)"
               r"(?:\s+(?:hand\s+)?(?:side|edge|part|half|end))?\s+of\s+the\s+(?:table|tabletop|table top|workspace|scene)\b",
               lambda m: f"at the {m.group(1)}{' side' if m.group(1) in ('far', 'near') else ''}", t)
    # "more dark", "less bright": comparatives said with more / less
    t = re.sub(r"\bmore (?:dark|dim)\b|\bless (?:bright|light)\b", " darker ", t)
    t = re.sub(r"\bmore (?:bright|light|strong)\b|\bless (?:dark|dim)\b", " brighter ", t)
    t = re.sub(r"\s*\}+\s*,?", " ; ", t.replace("{", " "))  # "{objects: [...], light: ...}": braces as separators
    # "a pair of lemons" (not "a pair of scissors": one object)
    t = re.sub(rf"\ba (?:pair|couple) of\b(?! (?:{PAIRED_NOUNS})\b)", "two", t)
    t = re.sub(r"\ba trio of\b", "three", t)
    t = re.sub(r"(?<![\d.])(\d+)[ \t]*x[ \t]+(?=[a-z])", r"\1 ", t)  # "2x random", "3 x apple": a count
    # "something else of your choice", "one more thing, anything": a free choice
    t = re.sub(
        r"\b(?:something|anything|one (?:more )?thing|another (?:thing|object|item))(?: else)?"
        r"(?= (?:of your choice|you like|you want|at random|random)\b)",
        "1 random object", t,
    )
    for cid, display in vocab.ids.items():
        if len(cid) >= 4 and cid in t:
            t = re.sub(rf"(?<![a-z0-9]){re.escape(cid)}(?![a-z0-9])", display, t)
    t = re.sub(r"(?<=[a-z])-(?=[a-z0-9])|(?<=[0-9])-(?=[a-z])", " ", t)
    t = re.sub(r"[ \t]+", " ", _digits(t.replace("_", " ")))
    # "a box of jell o gelatin": the catalog's "gelatin box" / "box of gelatin", brand words dropped
    def container_of(m: re.Match[str]) -> str:
        kind, words = m.group(1), m.group(2).split()
        for k in range(len(words)):
            rest = " ".join(words[k:])
            for form in (f"{rest} {kind}", f"{kind} of {rest}"):
                if form in vocab.canonical:
                    return form
        return m.group(0)

    t = re.sub(r"\b(box|can|bottle|jar|tin|pack|packet|carton|bag) of ((?:[a-z]+ ){0,2}[a-z]+)\b", container_of, t)
    # Names such as 'cup with a handle' must survive clause splitting at 'with'.
    for name in vocab.names:
        if "~" in name:
            spaced = name.replace("~", " ")
            if spaced in t:
                t = re.sub(rf"(?<![a-z0-9]){re.escape(spaced)}(?![a-z0-9])", name, t)
    return complete_short_names(t, vocab)


def complete_short_names(text: str, vocab: Vocabulary) -> str:
    """ "a red bull can ... swap the red bull for a 7up": a definite mention that is the start of
    exactly one name said before (a brand for its can) is that object."""
    said = [(m.start(), m.group(0)) for m in vocab.name_pattern.finditer(text)]
    if not said:
        return text

    def complete(m: re.Match[str]) -> str:
        words = m.group("words")
        if vocab.name_pattern.fullmatch(words):
            return m.group(0)
        longer = {name for at, name in said if at < m.start() and name.startswith(f"{words} ")}
        return f"{m.group('det')} {longer.pop()}" if len(longer) == 1 else m.group(0)

    return re.sub(
        r"\b(?P<det>the|that|this)\s+(?P<words>[a-z0-9]+(?:\s[a-z0-9]+)?)(?=\s+(?:for|with|on|in|to|near|instead|and|or)\b|\s*[.,;:!?]|$)",
        complete, text,
    )


# -- segmentation ------------------------------------------------------------------


def protect_coordinates(text: str) -> tuple[str, dict[str, tuple[float, ...]]]:
    """Replace coordinate tuples by placeholders so that commas inside them survive splitting."""
    slots: dict[str, tuple[float, ...]] = {}

    def keep3(m: re.Match[str]) -> str:
        key = f"@v{len(slots)}@"
        slots[key] = tuple(float(g) for g in m.groups())
        return f" {key} "

    def keep2(m: re.Match[str]) -> str:
        g = m.groups()
        if g[0] is not None:
            xs, xu, ys, yu = g[0], g[1], g[2], g[3]
        else:
            xs, xu, ys, yu = g[4], g[5], g[6], g[7]
        x, y = float(xs), float(ys)
        unit = xu or yu
        scale = unit_scale(unit, (x, y))
        key = f"@p{len(slots)}@"
        slots[key] = (x * scale, y * scale)
        return f" {key} "

    text = _COORD3.sub(keep3, text)
    # "cam: x=-3 y=0" are camera axes, not an object's position: leave what follows a camera word
    lines = []
    for line in text.split("\n"):
        cam = re.search(r"\b(?:camera|cam|view|viewpoint)\b", line)
        cut = cam.start() if cam is not None else len(line)
        lines.append(_COORD2.sub(keep2, line[:cut]) + line[cut:])
    text = "\n".join(lines)
    # "2 cans: a pepsi can and a sprite can" states the count, like "2 objects: ...".
    text = re.sub(r"\b(\d+)\s+[a-z]+s\s*:", r"\1 objects:", text)
    return text, slots


def split_sentences(text: str) -> list[str]:
    parts = re.split(r"(?<!\d)\.(?!\d)|[;\n!?|•]|(?<=\d)\.(?=\s|$)", text)
    return [p.strip(" \t-*•:,") for p in parts if p and p.strip(" \t-*•:,")]


SPLIT_WORDS = re.compile(
    r"\band then\b|\band\b|\bwhile\b|\bbut\b|\bplus\b|\bwith\b|\bincluding\b|\bsuch as\b|"
    r"\bwhereas\b|\balong with\b|\bas well as\b"
)


def split_clauses(sentence: str) -> list[str]:
    parts = re.split(rf",|:|\s\+\s|(?<!~)(?:{SPLIT_WORDS.pattern})(?!~)", sentence)
    return [p.strip() for p in parts if p and p.strip()]
