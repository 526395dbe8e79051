"""A rule-based reader of scene descriptions: text -> scene operations (as a dict).

It reads the styles people write, not only the offline writer's:

- the paper's structure ("Number and details of objects: 3 objects, one is a
  plastic bottle on the left. Environmental setup: slightly darker lighting,
  camera moved 3 cm left."), free prose, terse lists ("4 objects: coke can
  (left), plate, 2 random; light -0.2"), command lines ("ADD coke can to
  (0.1, 0.2)", "SET LIGHTING -0.2", "MOVE CAMERA 3 cm left");
- counts in digits or words; objects by display name, synonym, catalog id or
  category ("a fruit"); unknown objects where a phrase introduces one ("one of
  them is a purple elephant"), so the compiler can report them;
- positions as coordinates (metres, or cm/mm with units), regions ("front
  left", "in the middle") or relations ("near the bowl", "left of the plate");
- lighting in words ("slightly darker", "much brighter", "dim"), signed deltas,
  percentages or factors; camera moves and rotations in words and numbers
  ("camera moved 3 cm left", "rotate the camera 4 degrees down");
- silence means defaults; text with nothing recognisable is an error.

The task comes from the basic instruction ("put the carrot on the plate"),
or a "task:" / "instruction:" line in the description, or the task type alone.
"""

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
    (r"\ba pair of\b", "2"), (r"\ba single\b", "1"), (r"\bsingle\b", "1"), (r"\bjust 1\b", "1"),
    (r"\bboth\b", "2"),
]
_NUM = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)"

# -- words ---------------------------------------------------------------------------

_LIGHT_WORDS = re.compile(
    r"\b(?:light|lights|lighting|lit|illumination|illuminated|brightness|lamp|lamps|exposure|"
    r"brighter|darker|dimmer|dimmed|dim|dimly|darken|darkened|brighten|brightened|luminosity|"
    r"set lighting|set_lighting)\b"
)
_CAMERA_WORDS = re.compile(
    r"\b(?:camera|cam|view|viewpoint|viewing angle|perspective|pov|lens|move_camera)\b"
)
_MOTION = re.compile(
    rf"(?:{_NUM}\s*(?:cm|mm|m|centimet(?:er|re)s?|millimet(?:er|re)s?|met(?:er|re)s?|inch(?:es)?|deg|degrees?)\b)|"
    r"\b(?:tilt(?:ed|s)?|pan(?:ned|s)?|rotat(?:e|ed|es|ion)|roll(?:ed|s)?|yaw(?:ed)?|pitch(?:ed)?|"
    r"turn(?:ed|s)?|shift(?:ed|s)?|mov(?:e|ed|es)|rais(?:e|ed)|lower(?:ed)?)\b"
)
_DEFAULT_WORDS = re.compile(
    r"\b(?:default|normal|unchanged|standard|regular|usual|no change|no changes|as is|original|untouched|nominal)\b"
)
_RANDOM_WORDS = re.compile(r"\b(?:random|randomly|randomized|arbitrary|perturbed|altered|different|varied|changed|jittered)\b")

_DARKER = re.compile(
    r"\b(?:darker|dimmer|dim|dimmed|dimly|dark|darken|darkened|lower|lowered|reduce|reduced|decrease|"
    r"decreased|less|weaker|fainter|gloomy|gloomier|low|shadowy|minus|down|cut|lessen)\b|-\s*$"
)
_BRIGHTER = re.compile(
    r"\b(?:brighter|bright|brightly|brighten|brightened|increase|increased|raise|raised|more|stronger|"
    r"intense|higher|boost|boosted|well lit|harsh|harsher|vivid|plus|up|stronger|high)\b"
)
_SLIGHT = re.compile(
    r"\b(?:slightly|slight|a bit|a little|a tad|somewhat|marginally|mildly|a touch|subtly|little|"
    r"small|bit|touch|barely|gently|faintly)\b"
)
_STRONG = re.compile(
    r"\b(?:much|a lot|significantly|considerably|far|very|strongly|greatly|way|substantially|heavily|"
    r"really|extremely|dramatically|noticeably much|lot|large|big|drastically|very much)\b"
)
_MAXIMAL = re.compile(r"\b(?:maximum|maximally|max|as (?:bright|dark|dim) as possible|fully)\b")

_SCENE_NOUNS = {
    "table", "scene", "workspace", "tabletop", "desk", "surface", "counter", "setup", "set",
    "environment", "layout", "arrangement", "configuration", "world", "bench", "area",
}
_FILLERS = {
    "a", "an", "the", "some", "any", "there", "is", "are", "be", "being", "was", "were", "with",
    "and", "or", "plus", "also", "too", "as", "well", "of", "them", "which", "these", "those", "that",
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
    "where", "who", "what", "while", "but", "so", "such", "e.g", "eg", "ie", "etc",
    "sim", "simulation", "simulated", "test", "tabletop", "task", "instruction",
}
_STOP_PREPOSITIONS = {
    "on", "in", "at", "to", "from", "with", "of", "for", "over", "under", "near", "beside", "next",
    "behind", "between", "inside", "onto", "into", "by", "toward", "towards", "around", "left",
    "right", "front", "back",
}

_HEADERS = re.compile(
    r"(?:^|(?<=[.;!?])\s*)\s*(number and details of objects|details of objects|objects and details|"
    r"object configuration|objects|environmental setup|environment setup|environment|setup|scene)\s*:",
)
_COORD2 = re.compile(
    rf"[\(\[]\s*(?:x\s*=\s*)?({_NUM})\s*(cm|mm|m)?\s*[,;]\s*(?:y\s*=\s*)?({_NUM})\s*(cm|mm|m)?\s*[\)\]]"
    rf"|\bx\s*[=:]\s*({_NUM})\s*(cm|mm|m)?\s*,?\s*(?:and\s+)?y\s*[=:]\s*({_NUM})\s*(cm|mm|m)?"
)
_COORD3 = re.compile(rf"[\(\[]\s*({_NUM})\s*,\s*({_NUM})\s*,\s*({_NUM})\s*[\)\]]")
_COUNT_TOTAL = re.compile(
    r"(?:\b(?:number of objects|num_objects|n_objects|objects|object count|count|items|total)\s*(?:is\s*)?[:=]\s*(\d+)\b)"
    r"|(?:\b(?:a total of|total of|in total|altogether)\s*(\d+)\b)"
    r"|(?:\b(\d+)\s+(?:(?:different|distinct|total|items?|objects?|things?|props?|pieces?|random|other|more|additional|extra|"
    r"distractors?|small|household|kitchen|everyday|assorted|various|ycb|simplerenv|simpler)\s+){0,3}?"
    r"(?:objects?|items?|things?|props?|pieces?|distractors?)\b)"
)
_RANDOM_QUALIFIER = re.compile(r"\b(?:random|other|more|additional|extra|distractors?|arbitrary|unspecified|further)\b")


def _unit_scale(unit: str | None, values: Iterable[float]) -> float:
    if unit in ("cm",):
        return 0.01
    if unit in ("mm",):
        return 0.001
    if unit in ("m",):
        return 1.0
    # No unit: metres unless the numbers only make sense as centimetres.
    return 0.01 if any(abs(v) > 1.0 for v in values) else 1.0


def _length_scale(unit: str) -> float:
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

    @classmethod
    def from_objects(cls, objects: Iterable[Mapping[str, Any]]) -> Vocabulary:
        names: set[str] = set()
        ids: dict[str, str] = {}
        categories: set[str] = set()
        for o in objects:
            display = _norm_name(str(o["name"]))
            names.add(display)
            for s in o.get("synonyms", ()) or ():
                names.add(_norm_name(str(s)))
            ids[str(o["id"]).lower()] = display
            if o.get("category"):
                categories.add(str(o["category"]).replace("_", " "))
        canonical = {_digits(n): n for n in names}
        return cls(sorted(canonical, key=lambda n: (-len(n), n)), canonical, ids, categories)

    @property
    def name_pattern(self) -> re.Pattern[str]:
        if not hasattr(self, "_pattern"):
            alts = "|".join(re.escape(n) for n in self.names)
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


def _digits(text: str) -> str:
    for pattern, digit in _NUMBER_PHRASES:
        text = re.sub(pattern, digit, text)
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
    for cid, display in vocab.ids.items():
        if len(cid) >= 4 and cid in t:
            t = re.sub(rf"(?<![a-z0-9]){re.escape(cid)}(?![a-z0-9])", display, t)
    t = re.sub(r"(?<=[a-z])-(?=[a-z0-9])|(?<=[0-9])-(?=[a-z])", " ", t)
    t = _digits(t.replace("_", " "))
    return re.sub(r"[ \t]+", " ", t)


# -- results ---------------------------------------------------------------------


@dataclass
class _ObjectOp:
    mention: str | None
    position: dict[str, Any] | None = None
    unknown: bool = False


@dataclass
class _Reading:
    objects: list[_ObjectOp] = field(default_factory=list)
    total: int | None = None
    randoms: int = 0
    random_positions: list[dict[str, Any] | None] = field(default_factory=list)
    lighting: list[dict[str, Any]] = field(default_factory=list)
    camera: list[dict[str, Any]] = field(default_factory=list)
    object_set: str | None = None
    recognised: int = 0
    task_line: str | None = None


# -- segmentation ------------------------------------------------------------------


def _protect(text: str) -> tuple[str, dict[str, tuple[float, ...]]]:
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
        scale = _unit_scale(unit, (x, y))
        key = f"@p{len(slots)}@"
        slots[key] = (x * scale, y * scale)
        return f" {key} "

    text = _COORD3.sub(keep3, text)
    text = _COORD2.sub(keep2, text)
    return text, slots


def _sentences(text: str) -> list[str]:
    parts = re.split(r"(?<!\d)\.(?!\d)|[;\n!?]|(?<=\d)\.(?=\s|$)", text)
    return [p.strip(" \t-*•:,") for p in parts if p and p.strip(" \t-*•:,")]


def _clauses(sentence: str) -> list[str]:
    parts = re.split(
        r",|\band then\b|\band\b|\bwhile\b|\bbut\b|\bplus\b|\bwith\b|\bincluding\b|\bsuch as\b|"
        r"\bwhereas\b|\balong with\b|\bas well as\b|:",
        sentence,
    )
    return [p.strip() for p in parts if p and p.strip()]


# -- the reader ----------------------------------------------------------------------


class _Reader:
    def __init__(self, vocab: Vocabulary, slots: dict[str, tuple[float, ...]]) -> None:
        self.vocab = vocab
        self.slots = slots
        self.out = _Reading()
        self._previous_domain: str | None = None

    def read(self, text: str) -> _Reading:
        domain_hint: str | None = None
        for raw_line in re.split(r"\n", text):
            line = raw_line.strip()
            if not line:
                continue
            task = re.match(r"^\s*(?:task|instruction|command|goal)\s*[:=]\s*(.+)$", line)
            if task:
                self.out.task_line = task.group(1).strip().rstrip(".")
                self.out.recognised += 1
                continue
            for header in _HEADERS.finditer(line):
                name = header.group(1)
                domain_hint = "environment" if name.startswith(("env", "setup")) else "objects"
            line = _HEADERS.sub(" ", line)
            for sentence in _sentences(line):
                self._sentence(sentence, domain_hint)
        return self.out

    def _sentence(self, sentence: str, hint: str | None) -> None:
        self._object_set(sentence)
        previous = self._previous_domain
        last_object: _ObjectOp | None = None
        for clause in _clauses(sentence):
            domain = self._domain(clause, previous, hint)
            if domain == "lighting":
                self._lighting(clause)
            elif domain == "camera":
                self._camera(clause)
            elif domain == "environment":
                if _DEFAULT_WORDS.search(clause):
                    self.out.recognised += 1
            else:
                last_object = self._objects(clause, last_object)
            previous = domain
        self._previous_domain = previous

    def _domain(self, clause: str, previous: str | None, hint: str | None) -> str:
        # 'light blue cup' is an object, not lighting: look for keywords outside object names.
        masked = self.vocab.name_pattern.sub(" @n@ ", clause)
        cam, light = _CAMERA_WORDS.search(masked), _LIGHT_WORDS.search(masked)
        if cam and light:
            return "camera" if cam.start() < light.start() else "lighting"
        if cam:
            return "camera"
        if light:
            return "lighting"
        if (
            self.vocab.name_pattern.search(clause)
            or _COUNT_TOTAL.search(f" {clause} ")
            or "@p" in clause
            or re.search(r"\b(?:objects?|items?|random)\b", clause)
        ):
            return "objects"
        if previous == "camera" and _MOTION.search(clause):
            return "camera"
        if previous == "lighting" and (_DARKER.search(clause) or _BRIGHTER.search(clause) or re.search(_NUM, clause)):
            return "lighting"
        if (hint == "environment" or previous in ("lighting", "camera", "environment")) and (
            self.vocab.name_pattern.search(clause) is None and not _COUNT_TOTAL.search(clause)
        ):
            return "environment"
        if re.search(r"\bbright(?:ness)?\b|\bdark(?:ness)?\b", clause) and re.search(
            r"\b(?:scene|room|environment|it is|its)\b", clause
        ):
            return "lighting"
        return "objects"

    def _object_set(self, sentence: str) -> None:
        if re.search(r"\bycb\b|\bunseen objects?\b", sentence):
            self.out.object_set = "ycb"
        elif re.search(r"\bsimpler ?env\b|\bsimpler objects?\b|\bseen objects?\b|\bsimpler set\b", sentence):
            self.out.object_set = "simpler"

    # -- objects -----------------------------------------------------------------
    def _objects(self, clause: str, last: _ObjectOp | None) -> _ObjectOp | None:
        text = f" {clause} "
        position: dict[str, Any] | None = None
        consumed = False

        # Counts: "3 objects", "2 other objects", "objects: 3".
        for m in _COUNT_TOTAL.finditer(text):
            n = int(next(g for g in m.groups() if g is not None))
            span = m.group(0)
            if _RANDOM_QUALIFIER.search(span):
                self.out.randoms += n
                self.out.random_positions.append(None)
            elif self.out.total is None:
                self.out.total = n
            else:
                self.out.randoms += n
                self.out.random_positions.append(None)
            consumed = True
            text = text.replace(span, " ", 1)
        if re.fullmatch(r"\s*(?:\d+\s+)?(?:random|other|more|any)\s*(?:ones?)?\s*", text):
            n_match = re.search(r"\d+", text)
            n = int(n_match.group(0)) if n_match else 1
            self.out.randoms += n
            self.out.random_positions.append(None)
            return last
        add_random = re.compile(r"\b(?:add|place|put)\s+(?:a\s+|an\s+|1\s+)?random\s+(?:\w+\s+)?(?:object|item|one)\b")
        if add_random.search(text):
            self.out.randoms += 1
            self.out.random_positions.append(None)
            text = add_random.sub(" ", text)
            consumed = True

        # Coordinates.
        for key in re.findall(r"@p\d+@", text):
            x, y = self.slots[key][:2]
            position = {"x": round(x, 4), "y": round(y, 4)}
            text = text.replace(key, " ")
            consumed = True

        # Relations to another object: "near the bowl", "left of the plate".
        rel = self._relation(text)
        if rel is not None:
            position, text = rel
            consumed = True

        # Regions: "on the left", "front right corner", "in the middle".
        reg = self._region(text)
        if reg is not None:
            region, text = reg
            position = position or {"region": region}
            consumed = True

        # Named objects, with quantities ("2 apples").
        found: list[_ObjectOp] = []
        for m in list(self.vocab.name_pattern.finditer(text)):
            name = self._canonical(m.group(0))
            qty = self._quantity(text[: m.start()])
            for _ in range(qty):
                found.append(_ObjectOp(name))
        text_wo_names = self.vocab.name_pattern.sub(" @n@ ", text)
        if not found:
            for m in self.vocab.category_pattern.finditer(text):
                cat = m.group("cat")
                qty = self._quantity(m.group(0)[: m.start("cat") - m.start()])
                found.extend(_ObjectOp(cat) for _ in range(qty))
            text_wo_names = self.vocab.category_pattern.sub(" @n@ ", text_wo_names)
        if not found:
            unknown = self._unknown(text_wo_names)
            if unknown:
                found.append(_ObjectOp(unknown, unknown=True))

        if found:
            if position is not None:
                found[-1].position = position
            self.out.objects.extend(found)
            self.out.recognised += 1
            return found[-1]
        if position is not None:
            if consumed and self.out.random_positions and self.out.random_positions[-1] is None and last is None:
                self.out.random_positions[-1] = position
            elif last is not None and last.position is None:
                last.position = position
            self.out.recognised += 1
        elif consumed:
            self.out.recognised += 1
        return last

    def _canonical(self, matched: str) -> str:
        canonical = self.vocab.canonical
        if matched in canonical:
            return canonical[matched]
        for suffix in ("es", "s"):
            if matched.endswith(suffix) and matched[: -len(suffix)] in canonical:
                return canonical[matched[: -len(suffix)]]
        return matched

    @staticmethod
    def _quantity(before: str) -> int:
        m = re.search(r"(?:^|\s)([1-9]\d?)\s+(?:[a-z]+\s+)?$", before)
        if m and not re.search(r"\bof\s+(?:them|which)\s*$", before):
            n = int(m.group(1))
            return n if n <= 12 else 1
        m = re.search(r"\b([1-9]\d?)\s+of\s+(?:them|which)\s+(?:are|being)\s+(?:[a-z]+\s+)?$", before)
        if m:
            return int(m.group(1))
        return 1

    def _relation(self, text: str) -> tuple[dict[str, Any], str] | None:
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
                ref = self._reference(rest, strict=(m.group(0).strip() in ("on", "in", "onto", "inside", "inside of", "on top of", "by")))
                if ref is None:
                    continue
                name, used = ref
                new_text = text[: m.start()] + " " + rest[used:]
                return {"relation": relation, "reference": name}, new_text
        return None

    def _reference(self, rest: str, strict: bool) -> tuple[str, int] | None:
        m = re.match(r"\s*(?:the|a|an)?\s*", rest)
        start = m.end() if m else 0
        name = self.vocab.name_pattern.match(rest, start)
        if name is not None:
            return self._canonical(name.group(0)), name.end()
        cat = re.match(rf"({'|'.join(re.escape(c) for c in self.vocab.categories)})(?:e?s)?\b", rest[start:])
        if cat is not None:
            return cat.group(1), start + cat.end()
        if strict:
            return None
        words = re.match(r"((?:[a-z]+\s*){1,3})", rest[start:])
        if words is None:
            return None
        phrase_words = []
        for w in words.group(1).split():
            if w in _STOP_PREPOSITIONS or w in ("robot", "edge", "center", "centre", "middle", "camera", "corner", "side"):
                break
            phrase_words.append(w)
        if not phrase_words or phrase_words[0] in _FILLERS:
            return None
        phrase = " ".join(phrase_words)
        return phrase, start + rest[start:].index(phrase) + len(phrase)

    @staticmethod
    def _region(text: str) -> tuple[str, str] | None:
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

    @staticmethod
    def _unknown(text: str) -> str | None:
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
            if w in _SCENE_NOUNS:
                return None
            if run and (w in _STOP_PREPOSITIONS or w in ("that", "which", "who", "is", "are")):
                break
            if w in _FILLERS or re.fullmatch(r"\d+(?:\.\d+)?", w):
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

    # -- lighting ------------------------------------------------------------------
    def _lighting(self, clause: str) -> None:
        self.out.recognised += 1
        text = f" {clause} "
        factor = re.search(rf"(?:\bx|×|\btimes)\s*({_NUM})|({_NUM})\s*(?:x\b|×|times\b)", text)
        if factor is not None:
            value = float(factor.group(1) or factor.group(2))
            self.out.lighting.append({"op": "set_lighting", "intensity_delta": round(value - 1.0, 4)})
            return
        nums = [m for m in re.finditer(rf"(?<![\w.@]){_NUM}(?:\s*(%))?", text)]
        darker, brighter = _DARKER.search(text), _BRIGHTER.search(text)
        sign = -1.0 if darker and not brighter else 1.0 if brighter and not darker else 0.0
        if darker and brighter:
            sign = -1.0 if darker.start() < brighter.start() else 1.0
        if nums:
            m = nums[0]
            raw = m.group(0)
            value = float(re.match(_NUM, raw.strip()).group(0))  # type: ignore[union-attr]
            suffix = m.group(1)
            explicit_sign = raw.strip()[0] in "+-"
            if suffix == "%":
                if sign == 0.0 and re.search(r"\b(?:at|of|to)\s*$", text[: m.start()]):
                    delta = value / 100 - 1.0
                else:
                    delta = (sign or 1.0) * abs(value) / 100 if not explicit_sign else value / 100
            elif explicit_sign:
                delta = value
            elif sign != 0.0:
                delta = sign * abs(value)
            elif 0.5 <= value <= 2.0:
                delta = value - 1.0  # an absolute intensity factor: "intensity 0.8"
            else:
                delta = value
            self.out.lighting.append({"op": "set_lighting", "intensity_delta": round(delta, 4)})
            return
        if sign == 0.0:
            if _RANDOM_WORDS.search(text):
                self.out.lighting.append({"op": "set_lighting", "random": True})
            # "default lighting" and the like: no operation.
            return
        if _MAXIMAL.search(text):
            magnitude = 0.5
        elif _STRONG.search(text):
            magnitude = 0.4
        elif _SLIGHT.search(text):
            magnitude = 0.15
        else:
            magnitude = 0.25
        self.out.lighting.append({"op": "set_lighting", "intensity_delta": sign * magnitude})

    # -- camera ----------------------------------------------------------------------
    def _camera(self, clause: str) -> None:
        self.out.recognised += 1
        text = f" {clause} "
        translation = [0.0, 0.0, 0.0]
        rotation = [0.0, 0.0, 0.0]
        moved = False
        for key in re.findall(r"@v\d+@", text):
            values = self.slots[key]
            is_rotation = bool(re.search(r"\b(?:rotat\w*|deg\w*|orientation|angles?)\b", text))
            if is_rotation:
                rotation = [a + b for a, b in zip(rotation, values, strict=True)]
            else:
                scale = 0.01 if re.search(r"\bcm\b", text) or any(abs(v) > 0.5 for v in values) else 1.0
                translation = [a + b * scale for a, b in zip(translation, values, strict=True)]
            moved = True
            text = text.replace(key, " ")
        for part in re.split(r"\band\b|,|\bthen\b", text):
            t, r, ok = self._camera_motion(part)
            if ok:
                translation = [a + b for a, b in zip(translation, t, strict=True)]
                rotation = [a + b for a, b in zip(rotation, r, strict=True)]
                moved = True
        if moved:
            self.out.camera.append(
                {
                    "op": "move_camera",
                    "translation_m": [round(v, 4) for v in translation],
                    "rotation_deg": [round(v, 2) for v in rotation],
                }
            )
        elif _RANDOM_WORDS.search(text) and not _DEFAULT_WORDS.search(text):
            self.out.camera.append({"op": "move_camera", "random": True})

    @staticmethod
    def _camera_motion(part: str) -> tuple[list[float], list[float], bool]:
        translation = [0.0, 0.0, 0.0]
        rotation = [0.0, 0.0, 0.0]
        strength = 2.0 if _SLIGHT.search(part) else 5.0 if _STRONG.search(part) else 3.0
        found = False
        # Signed axis values: "x+0.02", "dy = -3 cm", "yaw -2", "pitch: 3 deg".
        for m in re.finditer(
            rf"\b(dx|dy|dz|x|y|z|roll|pitch|yaw)\s*[:=]?\s*({_NUM})\s*(cm|mm|m|deg|degrees?)?\b", part
        ):
            axis, value, unit = m.group(1), float(m.group(2)), m.group(3)
            if axis in ("roll", "pitch", "yaw"):
                rotation[("roll", "pitch", "yaw").index(axis)] += value
            else:
                scale = _length_scale(unit) if unit else (0.01 if abs(value) > 0.5 else 1.0)
                translation["xyz".index(axis[-1])] += value * scale
            found = True
        if found:
            return translation, rotation, True
        dist = re.search(
            rf"({_NUM})\s*(cm|mm|m|centimet(?:er|re)s?|millimet(?:er|re)s?|met(?:er|re)s?|inch(?:es)?)\b", part
        )
        angle = re.search(rf"({_NUM})\s*(?:deg|degrees?)\b", part)
        rotate_verb = re.search(r"\b(tilt\w*|pan\w*|rotat\w*|roll\w*|yaw\w*|pitch\w*|turn\w*|angled)\b", part)
        direction = re.search(
            r"\b(left|right|up|upward|upwards|down|downward|downwards|forward|forwards|closer|"
            r"backward|backwards|back|away|farther|further|higher|lower|raised|lowered|in|out|"
            r"clockwise|counterclockwise|counter clockwise|anticlockwise|anti clockwise)\b",
            part,
        )
        dir_word = direction.group(1) if direction else None
        if angle is not None or (rotate_verb is not None and dist is None):
            value = float(angle.group(1)) if angle is not None else strength
            verb = rotate_verb.group(1) if rotate_verb is not None else ""
            if angle is None and dir_word is None and not verb:
                return translation, rotation, False
            if verb.startswith("roll") or dir_word in (
                "clockwise", "counterclockwise", "counter clockwise", "anticlockwise", "anti clockwise"
            ):
                sign = -1.0 if dir_word == "clockwise" or dir_word == "right" else 1.0
                rotation[0] += sign * value
            elif dir_word in ("up", "upward", "upwards", "higher", "raised") or (
                verb.startswith(("tilt", "pitch")) and dir_word not in ("down", "downward", "downwards", "lower", "lowered")
                and dir_word is not None
            ):
                rotation[1] -= value
            elif dir_word in ("down", "downward", "downwards", "lower", "lowered") or verb.startswith(("tilt", "pitch")):
                rotation[1] += value
            elif dir_word == "right":
                rotation[2] -= value
            else:  # left, or a pan / yaw / turn without a direction
                rotation[2] += value
            return translation, rotation, True
        move_verb = re.search(r"\b(mov\w*|shift\w*|translat\w*|slid\w*|displac\w*|rais\w*|lower\w*|offset)\b", part)
        if dist is None and (move_verb is None or dir_word is None):
            return translation, rotation, False
        value = float(dist.group(1)) * _length_scale(dist.group(2)) if dist is not None else strength / 100
        if dir_word is None:
            dir_word = "left"  # a move without a direction: sideways, as the most common case
        axis, sign = {
            "left": (1, 1.0), "right": (1, -1.0), "up": (2, 1.0), "upward": (2, 1.0), "upwards": (2, 1.0),
            "higher": (2, 1.0), "raised": (2, 1.0), "down": (2, -1.0), "downward": (2, -1.0),
            "downwards": (2, -1.0), "lower": (2, -1.0), "lowered": (2, -1.0), "forward": (0, 1.0),
            "forwards": (0, 1.0), "closer": (0, 1.0), "in": (0, 1.0), "backward": (0, -1.0),
            "backwards": (0, -1.0), "back": (0, -1.0), "away": (0, -1.0), "farther": (0, -1.0),
            "further": (0, -1.0), "out": (0, -1.0),
        }.get(dir_word, (1, 1.0))
        if move_verb is not None and move_verb.group(1).startswith("rais"):
            axis, sign = 2, 1.0
        elif move_verb is not None and move_verb.group(1).startswith("lower") and dir_word is None:
            axis, sign = 2, -1.0
        translation[axis] += sign * abs(value)
        return translation, rotation, True


# -- the task ------------------------------------------------------------------------

_TASK_PATTERNS: list[tuple[str, re.Pattern[str]]] = [
    (
        "move_near",
        re.compile(
            r"^(?:please\s+)?(?:move|bring|push|slide|place|put|set|take|carry|shift|get)\s+(?:the\s+|a\s+|an\s+)?(?P<src>.+?)\s+"
            r"(?:so that it is\s+)?(?:near|next to|close to|closer to|towards?|beside|by|near to|alongside)\s+(?:the\s+|a\s+|an\s+)?(?P<tgt>.+?)$"
        ),
    ),
    (
        "put_in",
        re.compile(
            r"^(?:please\s+)?(?:put|place|drop|insert|stick|set|move|store|toss|throw)\s+(?:the\s+|a\s+|an\s+)?(?P<src>.+?)\s+"
            r"(?:into|inside of|inside|in|within)\s+(?:the\s+|a\s+|an\s+)?(?P<tgt>.+?)$"
        ),
    ),
    (
        "put_on",
        re.compile(
            r"^(?:please\s+)?(?:put|place|set|stack|lay|move|rest)\s+(?:the\s+|a\s+|an\s+)?(?P<src>.+?)\s+"
            r"(?:on top of|onto|on to|on|upon|atop)\s+(?:the\s+|a\s+|an\s+)?(?P<tgt>.+?)$"
        ),
    ),
    (
        "pick_up",
        re.compile(
            r"^(?:please\s+)?(?:pick up|pick|lift up|lift|grab|grasp|take|get|raise)\s+(?:up\s+)?(?:the\s+|a\s+|an\s+)?"
            r"(?P<src>.+?)(?:\s+up)?(?:\s+(?:from|off) the table)?$"
        ),
    ),
]


def parse_instruction(instruction: str) -> dict[str, Any] | None:
    """The task of an instruction in one of the four forms, objects as written; None if none fits."""
    text = instruction.strip().lower().rstrip(".!").replace("_", " ")
    text = re.sub(r"\s+", " ", text)
    for task, pattern in _TASK_PATTERNS:
        m = pattern.match(text)
        if m:
            groups = m.groupdict()
            return {"type": task, "source": groups["src"].strip(), "target": (groups.get("tgt") or None)}
    return None


# -- entry point ---------------------------------------------------------------------


def read_description(
    description: str,
    vocab: Vocabulary,
    instruction: str | None = None,
    task: str | None = None,
) -> dict[str, Any]:
    """Description (+ instruction or task type) -> a SceneOperations-shaped dict."""
    text = normalize_text(description or "", vocab)
    protected, slots = _protect(text)
    reading = _Reader(vocab, slots).read(protected)

    out: dict[str, Any] = {"schema_version": 1, "operations": []}
    if reading.object_set:
        out["object_set"] = reading.object_set
    instruction = instruction or reading.task_line
    if instruction:
        parsed = parse_instruction(instruction)
        if parsed is None:
            out["error"] = (
                f"the instruction {instruction!r} is none of the four task forms "
                "(pick up X; move X near Y; put X on Y; put X in Y)"
            )
            return out
        out["task"] = parsed
    elif task:
        out["task"] = {"type": task}

    if description.strip() and reading.recognised == 0:
        out["error"] = "no object, object count, position, lighting or camera setting found in the description"
        return out

    ops: list[dict[str, Any]] = []
    named = reading.objects
    for obj in named:
        op: dict[str, Any] = {"op": "add_object", "object": obj.mention}
        if obj.position is not None:
            op["position"] = obj.position
        ops.append(op)
    randoms = reading.randoms
    if reading.total is not None:
        randoms = max(reading.total - len(named), 0)
    positions = [p for p in reading.random_positions if p is not None]
    for i in range(randoms):
        op = {"op": "add_object", "object": None}
        if i < len(positions):
            op["position"] = positions[i]
        ops.append(op)
    ops.extend(reading.lighting[-1:])
    ops.extend(_merge_camera(reading.camera))
    out["operations"] = ops
    return out


def _merge_camera(moves: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """All camera moves of a description as one operation (a random one stays apart)."""
    if not moves:
        return []
    if any(m.get("random") for m in moves):
        return [{"op": "move_camera", "random": True}]
    t = [round(sum(m["translation_m"][k] for m in moves), 4) for k in range(3)]
    r = [round(sum(m["rotation_deg"][k] for m in moves), 2) for k in range(3)]
    return [{"op": "move_camera", "translation_m": t, "rotation_deg": r}]
