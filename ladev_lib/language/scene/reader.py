"""The description reader: segments text into clauses, routes each to its reader."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from ladev_lib.language.frames import read_instruction
from ladev_lib.language.scene.corrections import apply_corrections, correct_relations
from ladev_lib.language.scene.environment import (
    BRIGHTER,
    CAMERA_WORDS,
    DARKER,
    DEFAULT_WORDS,
    LIGHT_WORDS,
    MOTION,
    merge_camera,
    read_camera,
    read_lighting,
)
from ladev_lib.language.scene.instruction import parse_instruction
from ladev_lib.language.scene.objects import (
    canonical_name,
    expand_groups,
    find_region,
    find_relation,
    quantity,
    singular,
    unknown_phrase,
)
from ladev_lib.language.scene.statements import find_task
from ladev_lib.language.scene.structured import as_fields
from ladev_lib.language.scene.words import (
    COUNT_TOTAL,
    FILLERS,
    HEADERS,
    KEYED_COUNT,
    NON_OBJECT_NOUNS,
    NUM,
    RANDOM_QUALIFIER,
    STOP_PREPOSITIONS,
    Vocabulary,
    normalize_text,
    protect_coordinates,
    split_clauses,
    split_sentences,
)

_RANDOM_GROUP = re.compile(
    r"\b(?P<n>[1-9])\s+(?:(?:are|will be|should be)\s+)?(?:other|random|more|extra|additional|arbitrary|unnamed)\s+"
    r"(?P<noun>[a-z]+(?:\s+[a-z]+)?)\b"
    r"|\b(?P<n2>[1-9])\s+(?P<noun2>[a-z]+)\s+(?:at random|of your choice|chosen at random|randomly)\b"
)
_RELATION_WORDS = r"right next to|next to|near|beside|by|close to|behind|in front of|left of|right of"
_AFTER_NOUN = frozenset(
    {"and", "or", "plus", "that", "which", "too", "also", "somewhere", "anywhere", "as", "please", "is", "are",
     "should", "will", "of", "then", "there", "here", "lying", "sitting", "standing", "placed"}
)
"""Words that may follow an object noun (a category word followed by any other is a modifier)."""
_PLURAL_VERB = r"are|go|sit|stand|lie|stay|belong"
_MEMBER = re.compile(
    r"\b(?:\d+|one|some)\s+of\s+(?:them|which|those|these|the \d+)\b|\bamong\s+(?:them|which|those)\b|"
    r"\binclud(?:e|es|ing)\b|\bone being\b|\bof which\b"
)


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


# -- the reader ----------------------------------------------------------------------


class _Reader:
    def __init__(
        self, vocab: Vocabulary, slots: dict[str, tuple[float, ...]], task_objects: tuple[str, ...] = ()
    ) -> None:
        self.vocab = vocab
        self.slots = slots
        self.task_objects = task_objects
        self.task_object = task_objects[0] if task_objects else None
        """The stated task's object: what "it" refers to before any object is described."""
        self.out = _Reading()
        self._previous_domain: str | None = None
        self._listy = True
        self._sentence_randoms = 0
        self._sentence_first = 0
        self._sentence_text = ""

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
            # Each header governs the text after it, up to the next header ("Number and details of
            # objects: ... Environmental setup: ..." on one line).
            at = 0
            parts: list[tuple[str, str | None]] = []
            for header in HEADERS.finditer(line):
                parts.append((line[at:header.start()], domain_hint))
                name = header.group(1)
                domain_hint = "environment" if name.startswith(("env", "setup")) else "objects"
                at = header.end()
            parts.append((line[at:], domain_hint))
            for part, hint in parts:
                for sentence in split_sentences(part):
                    self._sentence(sentence, hint)
        return self.out

    def _restates(self, sentence: str) -> bool:
        """ "So: apple, bowl.": a list, after a summing-up word, of objects all described already."""
        lead = re.match(r"^\s*(?:so|ie|i\.e\.|that is|to recap|recap|in short|in summary|summary|again|final list)\s*[:,-]\s*",
                        sentence)
        if lead is None or not self.out.objects:
            return False
        items = [x.strip() for x in re.split(r",|\band\b", sentence[lead.end():].strip(" .")) if x.strip()]
        said = [o.mention for o in self.out.objects] + [
            o.position.get("reference") for o in self.out.objects if o.position is not None
        ]
        return bool(items) and all(
            self.vocab.name_pattern.fullmatch(x) is not None
            and any(self._same(m, canonical_name(self.vocab, x)) for m in said)
            for x in items
        )

    def _sentence(self, sentence: str, hint: str | None) -> None:
        if self._restates(sentence):
            self.out.recognised += 1
            return
        if "@swap@" in sentence:
            placed = [o for o in self.out.objects if o.position is not None]
            if len(placed) >= 2:
                placed[-2].position, placed[-1].position = placed[-1].position, placed[-2].position
            sentence = sentence.replace("@swap@", " ")
            self.out.recognised += 1
        self._object_set(sentence)
        # An unknown noun is an object only where the sentence lists objects (names a catalog
        # object, counts objects or adds one), not in chat around the scene.
        self._listy = bool(
            self.vocab.name_pattern.search(sentence)
            or COUNT_TOTAL.search(f" {sentence} ")
            or re.search(
                r"^\s*(?:\+|add|spawn|place|objects?|objs?|items?|a|an|\d+)\b|\b(?:objects?|items?)\s*[:=]", sentence
            )
            or hint == "objects"
        )
        # "yaw: +4.5 degrees", "up: 2 cm": an axis or direction and its value stay together
        sentence = re.sub(
            r"\b(yaw|pitch|roll|dx|dy|dz|up|down|forward|backward|back|left|right|dolly|in|out)\s*[:=]\s*(?=[-+]?\d)",
            r"\1 ", sentence,
        )
        # "towel: back" / "towel = left": a position given as a value
        sentence = re.sub(
            r"\s*[:=]\s*(?=(?:left|right|front|back|center|centre|middle|rear|far side|near side)\b)", " at the ", sentence
        )
        # "objects: 2" would be cut apart at the colon below: read it first.
        self._sentence_randoms = 0
        self._sentence_first = len(self.out.objects)
        self._sentence_text = sentence
        keyed = KEYED_COUNT.search(sentence)
        if keyed is not None:
            qualifier = re.search(r"\b(?:random|other|extra|additional|unnamed|free)\s*$", sentence[: keyed.start()])
            if qualifier is not None:
                self.out.randoms += int(keyed.group(1))  # "random objects: 2"
                sentence = sentence[: qualifier.start()] + " " + sentence[keyed.start():]
                keyed = KEYED_COUNT.search(sentence)
                assert keyed is not None
            elif self.out.total is None:
                self.out.total = int(keyed.group(1))
            self.out.recognised += 1
            sentence = sentence[: keyed.start()] + " " + sentence[keyed.end():]
        previous = self._previous_domain
        last_object: _ObjectOp | None = None
        clauses: list[str] = []
        for clause in split_clauses(sentence):
            if clauses and re.fullmatch(rf"\s*(?:by\s+|about\s+)?{NUM}\s*(?:cm|mm|degrees?|deg|%)\s*", clause):
                clauses[-1] += f" {clause}"  # "tilt the camera slightly downward, 2 degrees": that motion's amount
            elif clauses and re.match(rf"\s*(?:yaw|pitch|roll|dx|dy|dz|x|y|z)\s*[:=]?\s*{NUM}", clause) and (
                not re.search(r"\d", clauses[-1]) or re.match(r"\s*(?:yaw|pitch|roll|dx|dy|dz|x|y|z)\b", clauses[-1])
                or re.search(r"\b(?:yaw|pitch|roll|dx|dy|dz|x|y|z)\s*[:=]?\s*[-+]?\d", clauses[-1])
            ):
                clauses[-1] += f", {clause}"  # "rotate the camera: pitch +5, yaw -5": the values of that motion
            else:
                clauses.append(clause)
        for clause in clauses:
            domain = self._domain(clause, previous, hint)
            if domain == "lighting":
                self.out.recognised += 1
                op = read_lighting(clause)
                if op is None and DEFAULT_WORDS.search(clause):
                    op = {"op": "set_lighting", "intensity_delta": 0.0}  # "... actually, leave the lighting at default"
                if op is not None:
                    self.out.lighting.append(op)
            elif domain == "camera":
                self.out.recognised += 1
                op = read_camera(clause, self.slots)
                if op is not None:
                    self.out.camera.append(op)
                elif DEFAULT_WORDS.search(clause) or re.search(
                    r"\b(?:dont|do not|no need to|never)\s+(?:move|touch|change)\s+(?:the\s+)?(?:camera|cam|view|it)\b", clause
                ):
                    self.out.camera.clear()  # "tilt up 2 degrees, no, leave the camera alone": the last word wins
            elif domain == "environment":
                if DEFAULT_WORDS.search(clause):
                    self.out.recognised += 1
            else:
                last_object = self._objects(clause, last_object)
            previous = domain
        self._previous_domain = previous

    def _domain(self, clause: str, previous: str | None, hint: str | None) -> str:
        # 'light blue cup' is an object, not lighting: look for keywords outside object names.
        masked = self.vocab.name_pattern.sub(" @n@ ", clause)
        # "a desk lamp", "desk lamp": an object, not the lighting
        masked = re.sub(r"\b(?:(?:a|an)\s+(?:\w+\s+)?|(?:desk|table|floor|reading|bedside|lava)\s+)lamps?\b", " @n@ ", masked)
        cam, light = CAMERA_WORDS.search(masked), LIGHT_WORDS.search(masked)
        if cam and light:
            return "camera" if cam.start() < light.start() else "lighting"
        if cam:
            return "camera"
        if light:
            return "lighting"
        if (
            self.vocab.name_pattern.search(clause)
            or COUNT_TOTAL.search(f" {clause} ")
            or "@p" in clause
            or re.search(r"\b(?:objects?|items?|random)\b", clause)
        ):
            return "objects"
        if previous == "camera" and MOTION.search(clause):
            return "camera"
        if previous == "lighting" and (
            DARKER.search(clause) or BRIGHTER.search(clause) or re.search(NUM, clause)
            or re.search(r"\b(?:double|doubled|twice|triple|halve|halved|half)\b", clause)
        ):
            return "lighting"
        if re.search(r"\bbright(?:ness)?\b|\bdark(?:ness)?\b", clause) and re.search(
            r"\b(?:scene|room|environment|it is|its)\b", clause
        ):
            return "lighting"
        if (hint == "environment" or previous in ("lighting", "camera", "environment")) and (
            self.vocab.name_pattern.search(clause) is None and not COUNT_TOTAL.search(clause)
        ):
            return "environment"
        return "objects"

    def _object_set(self, sentence: str) -> None:
        if re.search(r"\bycb\b|\bunseen objects?\b", sentence):
            self.out.object_set = "ycb"
        elif re.search(r"\bsimpler ?env\b|\bsimpler objects?\b|\bseen objects?\b|\bsimpler set\b", sentence):
            self.out.object_set = "simpler"

    # -- objects -----------------------------------------------------------------
    def _same(self, a: str | None, b: str | None) -> bool:
        """Two mentions of one catalog object ("7up" and "7up can")."""
        if a is None or b is None:
            return False
        ids = self.vocab.name_ids
        return a == b or (a in ids and ids.get(a) == ids.get(b))

    def _by_head(self, reference: Any) -> Any:
        """A reference by head noun ("near the cup") to the one object said with that noun ("the
        large blue cup"), among the described objects and the task's."""
        if not isinstance(reference, str) or not reference or reference in self.vocab.name_ids:
            return reference
        head = reference.split()[-1]
        said = {o.mention for o in self.out.objects if o.mention} | set(self.task_objects)
        fits = {m for m in said if m != reference and m.split()[-1] in (head, singular(head))}
        return fits.pop() if len(fits) == 1 else reference

    def _distributes(self, clause: str, found: list[_ObjectOp]) -> bool:
        """Whether a position said after the last of coordinated objects is said of all of them.

        "a bowl and a mug go on the left" (a plural verb), "a padlock and a scrub sponge,
        both near the center", or a sentence that is only the pair ("a marker and a fork at
        the front"); not "a coke can, an apple and a sponge on the right" in a longer list.
        """
        earlier = self.out.objects[self._sentence_first:]
        if len(found) != 1 or not earlier or any(o.position is not None for o in earlier):
            return False
        if re.search(rf"\b(?:{_PLURAL_VERB}|both|all|together|side by side|clustered|grouped|bunched|huddled|lined up)\b", clause):
            return True
        names = self.vocab.name_pattern.pattern
        pair = rf"(?:a|an|the|\d+)\s+{names}\s+and\s+(?:a|an|the|\d+)\s+{names}\b"
        return len(earlier) == 1 and re.match(rf"\s*{pair}", self._sentence_text) is not None

    def _pair_placed(self, found: list[_ObjectOp]) -> bool:
        """Whether a position after a pair that forms its own group is said of both: "..., and a fork
        and a spoon on the right", "with a plum and a pear up at the front", "the cup and the mug at
        the back, and ..." (not the last two of a longer list: "a can, an apple and a sponge on the right")."""
        earlier = self.out.objects[self._sentence_first:]
        if len(found) != 1 or not earlier or earlier[-1].position is not None:
            return False
        names = self.vocab.name_pattern.pattern
        pair = rf"(?:a|an|the|one|\d+)\s+{names}\s+and\s+(?:a|an|the|one|\d+)\s+{names}"
        group = rf"(?:^|:\s*|,\s*(?:and|with|plus)\s+|\bwith\s+)(?:also\s+)?{pair}\s+(?:up\s+|over\s+|down\s+|off\s+|both\s+)?"
        return re.search(rf"{group}(?:at|on|in|to|toward|towards|near|by)\b", self._sentence_text.strip()) is not None

    def _objects(self, clause: str, last: _ObjectOp | None) -> _ObjectOp | None:
        text = f" {clause} "
        position: dict[str, Any] | None = None
        consumed = False

        # Counts: "3 objects", "2 other objects", "objects: 3".
        for m in COUNT_TOTAL.finditer(text):
            n = int(next(g for g in m.groups() if g is not None))
            span = m.group(0)
            if RANDOM_QUALIFIER.search(span) or re.search(r"\b(?:any|random)\s*$", text[: m.start()]):
                self.out.randoms += n
                self._sentence_randoms += n
                self.out.random_positions.append(None)
            elif self.out.total is None:
                self.out.total = n
            else:
                self.out.randoms += n
                self.out.random_positions.append(None)
            consumed = True
            text = text.replace(span, " ", 1)
        # "2 other balls", "3 fruits at random": free choices, whatever the noun
        for m in list(_RANDOM_GROUP.finditer(text)):
            noun_at = m.start("noun") if m.group("noun") else m.start("noun2")
            if (m.group("noun") or m.group("noun2") or "").split()[0] in NON_OBJECT_NOUNS:
                continue  # "one more example", "2 more tries": not objects
            if self.vocab.name_pattern.match(text, noun_at) or (m.group("noun") or "").split()[0:1] in (
                ["objects"], ["object"], ["items"], ["item"], ["things"], ["thing"],
            ):
                continue
            n = int(m.group("n") or m.group("n2"))
            self.out.randoms += n
            self._sentence_randoms += n
            self.out.random_positions.append(None)
            consumed = True
            text = text.replace(m.group(0), " ", 1)
        if not consumed and re.fullmatch(r"\s*(?:[+*\u2022-]\s*|add\s+|plus\s+)?(?:\d+\s+)?(?:random|other|more|any)\s*(?:ones?)?\s*", text):
            n_match = re.search(r"\d+", text)
            n = int(n_match.group(0)) if n_match else 1
            self.out.randoms += n
            self.out.random_positions.append(None)
            self.out.recognised += 1
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

        # "next to it": the object described last (or the task's object, before any is)
        antecedent = self.out.objects[-1].mention if self.out.objects else self.task_object
        if antecedent:
            text = re.sub(
                rf"\b({_RELATION_WORDS})\s+(?:it|that one)\b", lambda m: f"{m.group(1)} the {antecedent}", text
            )
        # "a towel that lies in the centre": the relative clause places the towel, not the subject
        relative: tuple[str, dict[str, Any]] | None = None
        rel_m = re.search(
            rf"(?P<name>{self.vocab.name_pattern.pattern})\s+(?:that|which)\s+(?:is|lies|sits|stands|rests)\b(?P<rest>.*)$",
            text,
        )
        if rel_m is not None and (where := find_region(rel_m.group("rest"))) is not None:
            relative = (canonical_name(self.vocab, rel_m.group("name")), {"region": where[0]})
            text = text[: rel_m.end("name")] + " "
        # Relations to another object: "near the bowl", "left of the plate".
        rel = find_relation(self.vocab, text)
        if rel is not None:
            position, text = rel
            consumed = True
            position["reference"] = self._by_head(position.get("reference"))

        # Regions: "on the left", "front right corner", "in the middle".
        reg = find_region(text)
        if reg is not None:
            region, text = reg
            position = position or {"region": region}
            consumed = True

        placed_at: int | None = None
        if relative is not None:
            name, where_pos = relative
            same = [o for o in self.out.objects if self._same(o.mention, name)]
            if same:
                if same[-1].position is None:
                    same[-1].position = where_pos
            else:
                self.out.objects.append(_ObjectOp(name, where_pos))
                placed_at = rel_m.start("name") if rel_m is not None else None  # not read again below
            if position is not None and position.get("reference") and self._same(position["reference"], name):
                text = text.replace(rel_m.group("name") if rel_m else name, " ", 1)  # the reference is not the subject
        # "the can on the left": an object described before, by its head noun
        if position is not None and not self.vocab.name_pattern.search(text):
            head = re.search(r"\bthe\s+([a-z]+)\b", text)
            if head is not None and head.group(1) not in FILLERS:
                word = head.group(1)
                same = [o for o in self.out.objects if o.mention and o.mention.split()[-1] in (word, singular(word))]
                if len({o.mention for o in same}) == 1 and same[-1].position is None:
                    same[-1].position = position
                    self.out.recognised += 1
                    return same[-1]
                task_named = [t for t in self.task_objects if t.split()[-1] in (word, singular(word))]
                if not same and len(set(task_named)) == 1:
                    # "the can on the left": the task's can, not described before
                    obj = _ObjectOp(task_named[0], position)
                    self.out.objects.append(obj)
                    self.out.recognised += 1
                    return obj
        # Named objects, with quantities ("2 apples"). A definite mention of an
        # object already described ("the bowl in the middle", "towel: back") is
        # that object again, not another one.
        found: list[_ObjectOp] = []
        matches = list(self.vocab.name_pattern.finditer(text))
        for m in matches:
            if m.start() == placed_at:
                continue
            name = canonical_name(self.vocab, m.group(0))
            before = text[: m.start()]
            earlier = [o for o in self.out.objects if self._same(o.mention, name)]
            definite = re.search(r"\b(?:the|that|this|its|both|said|same)\s+(?:\w+\s+)?$", before) is not None
            if definite and not earlier:
                # "a red plate, the plate in the middle": the one described object that the shorter name ends
                longer = {o.mention for o in self.out.objects if o.mention and o.mention.endswith(f" {name}")}
                if len(longer) == 1:
                    earlier = [o for o in self.out.objects if o.mention in longer]
            bare_update = (
                not re.search(r"\b(?:a|an|another|one|\d+|add|plus|and|also)\s+(?:\w+\s+)?$", before)
                and len(matches) == 1 and position is not None and not found
            )
            if earlier and (definite or bare_update):
                target = earlier[-1] if position is None else next(
                    (o for o in reversed(earlier) if o.position is None), earlier[-1]
                )
                if position is not None:
                    target.position = position
                    position = None
                self.out.recognised += 1
                last = target
                continue
            qty = quantity(before)
            if (
                m.group(0) not in self.vocab.canonical
                and name != m.group(0)
                and not re.search(r"(?:^|\s)\d+\s+(?:[a-z]+\s+)?$|\b(?:some|several|many|few)\s+$", before)
            ):
                continue  # "my robot keeps failing on aubergines": a kind of object, not one on the table
            for _ in range(qty):
                found.append(_ObjectOp(name))
        if matches and not found:
            return last
        text_wo_names = self.vocab.name_pattern.sub(" @n@ ", text)
        if not found:
            for m in self.vocab.category_pattern.finditer(text):
                cat = m.group("cat")
                after = re.match(r"\s+([a-z]+)", text[m.end():])
                if after is not None and after.group(1) not in STOP_PREPOSITIONS | _AFTER_NOUN:
                    continue  # "a fruit test", "a tool demo": the category names another noun's kind
                qty = quantity(m.group(0)[: m.start("cat") - m.start()])
                found.extend(_ObjectOp(cat) for _ in range(qty))
            def category_used(m: re.Match[str], source: str = text_wo_names) -> str:
                after = re.match(r"\s+([a-z]+)", source[m.end():])
                if after is not None and after.group(1) not in STOP_PREPOSITIONS | _AFTER_NOUN | NON_OBJECT_NOUNS:
                    return m.group(0)  # "a toy car": the category word is the unknown object's modifier
                return " @n@ "

            text_wo_names = self.vocab.category_pattern.sub(category_used, text_wo_names)
        if not found and self._listy:
            unknown = unknown_phrase(text_wo_names)
            if unknown:
                at = text_wo_names.find(unknown)
                qty = quantity(text_wo_names[:at]) if at >= 0 else 1
                mention = singular(unknown) if qty > 1 else unknown
                said = [o for o in self.out.objects if o.unknown and o.mention and o.mention.split()[-1] == mention.split()[-1]]
                indefinite = re.search(r"\b(?:a|an|another|\d+)\s+(?:\w+\s+)?$", text_wo_names[:at]) if at >= 0 else None
                if said and indefinite is None:
                    # "a TV remote ..., remote at the front": the object named before, by its head noun
                    if position is not None and said[-1].position is None:
                        said[-1].position = position
                    self.out.recognised += 1
                    return said[-1]
                found.extend(_ObjectOp(mention, unknown=True) for _ in range(qty))

        if found and self._sentence_randoms > 0 and _MEMBER.search(text):
            # "four random objects, one of them a banana": the banana is one of the four
            taken = min(len(found), self._sentence_randoms)
            self._sentence_randoms -= taken
            self.out.randoms -= taken
        if found:
            if position is not None and self._distributes(clause, found):
                for obj in self.out.objects[self._sentence_first:]:
                    if obj.position is None:
                        obj.position = dict(position)
            elif position is not None and "x" not in position and self._pair_placed(found):  # not a point
                self.out.objects[-1].position = dict(position)
            if position is not None:
                found[-1].position = position
            self.out.objects.extend(found)
            self.out.recognised += 1
            return found[-1]
        if position is not None and (
            re.search(r"\b(?:all|both|each|all of them|both of them|together|side by side|clustered|grouped|bunched|"
                      r"huddled|lined up)\b", text)
            or re.search(rf"^\s*(?:2|{_PLURAL_VERB})\b", clause)
        ):
            # "a pepsi can and a sprite can, all lined up at the front": every object of the sentence
            for obj in self.out.objects[self._sentence_first:]:
                if obj.position is None:
                    obj.position = dict(position)
            self.out.recognised += 1
            return last
        if position is not None:
            if consumed and self.out.random_positions and self.out.random_positions[-1] is None and last is None:
                self.out.random_positions[-1] = position
            elif last is not None and last.position is None:
                last.position = position
            self.out.recognised += 1
        elif consumed:
            self.out.recognised += 1
        return last


# -- entry point ---------------------------------------------------------------------


def read_description(
    description: str,
    vocab: Vocabulary,
    instruction: str | None = None,
    task: str | None = None,
) -> dict[str, Any]:
    """Description (+ instruction or task type) -> a SceneOperations-shaped dict.

    The task is, in order: the explicit ``instruction``; the task the
    description states (its statements are not read as objects); ``task``
    (a type alone). Task statements are taken out of the text either way.
    """
    source = correct_relations(spoken_punctuation(disfluencies(as_fields(description or ""))))
    found = find_task(source, vocab.ids)
    normal = normalize_text(found.rest, vocab)
    text, dropped, replaced = apply_corrections(expand_groups(normal, vocab), vocab)
    protected, slots = protect_coordinates(text)
    only = next(
        (m for m in ONLY_THESE.finditer(normal) if not re.search(
            r"\b(?:camera|cam|view|light|lights|lighting|brightness)\b", _sentence_around(normal, m.start())
        )),
        None,
    )
    task_objects = tuple(
        str(found.task[k]) for k in ("source", "target") if found.task is not None and found.task.get(k)
    )
    reading = _Reader(vocab, slots, task_objects).read(protected)
    for name in dropped:
        canonical = canonical_name(vocab, name)
        key = vocab.name_ids.get(canonical)
        idx = [
            i for i, o in enumerate(reading.objects)
            if o.mention == canonical or (key is not None and vocab.name_ids.get(o.mention or "") == key)
        ] or [i for i, o in enumerate(reading.objects) if _same_object(vocab, o.mention, canonical)]  # "red bull" / "red bull can"
        if idx:
            del reading.objects[idx[-1]]
            if reading.total is not None and name not in replaced:
                reading.total -= 1  # "three objects: a, b and c. drop c": two

    out: dict[str, Any] = {"schema_version": 1, "operations": []}
    if reading.object_set:
        out["object_set"] = reading.object_set
    stated = found.task
    if instruction:
        out.update(explicit_task(instruction, vocab))
        if "error" in out:
            return out
    elif stated is not None:
        out["task"] = stated
    elif found.statement and (retry := _task_in_scene(found.statement, reading, vocab)) is not None:
        out["task"] = retry  # "pick up bottle" in a scene with one bottle
        stated = retry
    elif (retry := next(
        (t for c in found.candidates if (t := _task_in_scene(c, reading, vocab)) is not None), None
    )) is not None:
        out["task"] = retry  # "the robot moves the green brick near the pink one", in its scene
        stated = retry
    elif found.statement or reading.task_line:
        what = found.statement or reading.task_line
        out["error"] = (
            f"the task {what!r} is none of the four task forms "
            "(pick up X; move X near Y; put X on Y; put X in Y)"
        )
        return out
    elif task:
        out["task"] = {"type": task}
    recognised_task = 1 if stated is not None else 0  # a description that states only its task is read
    if isinstance(out.get("task"), dict):
        before = source[: found.start].lower() if found.start is not None and stated is found.task else ""
        _task_names_described(out["task"], reading, vocab, before)

    if description.strip() and reading.recognised + recognised_task == 0:
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
    if only is not None and only.group("n") and reading.total is not None:
        reading.total = int(only.group("n"))  # "4 in all: ... and one random thing. Actually, only these three."
    if reading.total is None and only is not None:
        # "just those two", "nothing else": the named objects and the task's are all there is
        task_said = [str(v) for k, v in (out.get("task") or {}).items() if k in ("source", "target") and v]
        for mention in task_said:
            if not any(_same_object(vocab, o.mention, mention) for o in named):
                ops.append({"op": "add_object", "object": mention})
        randoms = 0
    elif reading.total is not None:
        randoms = max(reading.total - len(named), 0)
    positions = [p for p in reading.random_positions if p is not None]
    for i in range(randoms):
        op = {"op": "add_object", "object": None}
        if i < len(positions):
            op["position"] = positions[i]
        ops.append(op)
    # the last lighting statement wins; "1.0x" / "+0 %" (no change) leaves the light as it is
    ops.extend(op for op in reading.lighting[-1:] if op.get("intensity_delta", 1.0) != 0.0)
    ops.extend(merge_camera(reading.camera))
    out["operations"] = ops
    return out


ONLY_THESE = re.compile(
    r"\b(?:just|only)\s+(?:the|those|these)\s+(?P<n>\d+)?\s*(?:objects?|items?|things?|[a-z]+s)?\b(?!\s+(?:of|on|in|at))"
    r"|\b(?:and\s+)?nothing else\b|\bno other objects?\b|\bno (?:random|extra|additional) objects?\b"
)
"""The scene holds the named objects only ("the scene has just those two fruits", "nothing else")."""


def _sentence_around(text: str, pos: int) -> str:
    start = max(text.rfind(c, 0, pos) for c in ".;\n") + 1
    ends = [e for e in (text.find(c, pos) for c in ".;\n") if e >= 0]
    return text[start : min(ends) if ends else len(text)]


def _same_object(vocab: Vocabulary, a: str | None, b: str) -> bool:
    """Two mentions of one object: equal, one catalog id, or one ending the other ("red bull can", "red bull")."""
    if a is None:
        return False
    ida = vocab.name_ids.get(canonical_name(vocab, a))
    idb = vocab.name_ids.get(canonical_name(vocab, b))
    return a == b or (ida is not None and ida == idb) or a.startswith(b) or a.endswith(b) or b.endswith(a)


_NUMBER_AHEAD = r"(?=[-+]?\d|(?:a|one|two|three|four|five|six|seven|eight|nine|ten|half|a few)\b)"


def disfluencies(text: str) -> str:
    """Spoken fillers out of the text ("with uh a hammer and um the robot needs ... yeah", "like three degrees").

    A filler set off by commas or dashes ("a bowl, um, a basket") is left: it may mark a correction.
    """
    text = re.sub(r"(?<![,\u2014\u2013-])\s+(?:u+h+|u+m+|e+rm+|you know)\b(?!\s*[,\u2014\u2013-])", " ", text, flags=re.IGNORECASE)
    text = re.sub(r"^\s*(?:u+h+|u+m+|e+rm+)\b\s*", "", text, flags=re.IGNORECASE)
    text = re.sub(r"[,\s]+\byeah\b(?=\s*(?:and|[,.!?]|$))", "", text, flags=re.IGNORECASE)
    return re.sub(rf"\b(?:like|about|around|roughly|approximately|maybe|something like)\s+{_NUMBER_AHEAD}", "", text, flags=re.IGNORECASE)


def spoken_punctuation(text: str) -> str:
    """Dictated punctuation as punctuation ("the wooden block goes in the back period the robot ...")."""
    text = re.sub(r"\s+(?:period|full stop|new line|newline)\b", ".", text, flags=re.IGNORECASE)
    return re.sub(r"\s+comma\b", ",", text, flags=re.IGNORECASE)


def _task_names_described(task: dict[str, Any], reading: _Reading, vocab: Vocabulary, before: str = "") -> None:
    """A task object named by the end of an object the description names in full is that object: one
    the catalog does not know ("a TV remote ... place the remote on the towel"), or a catalog name said
    after the fuller one ("a navel orange and a basket; the orange goes in the basket"; ``before`` is
    the text before the task statement)."""
    unknown = [o.mention for o in reading.objects if o.unknown and o.mention]
    described = {o.mention for o in reading.objects if o.mention}
    for key in ("source", "target"):
        name = task.get(key)
        if isinstance(name, str) and not any(_same_object(vocab, m, name) and not m.endswith(f" {name}") for m in described):
            # "a navel orange and a basket; the orange should end up in the basket": the described one
            longer = {m for m in described if m.endswith(f" {name}") and m in before}
            if len(longer) == 1 and not any(m == name for m in described):
                task[key] = longer.pop()
                continue
        if not isinstance(name, str) or name in vocab.name_ids or name in vocab.ids.values():
            continue
        fuller = {m for m in unknown if m != name and m.split()[-1] == name.split()[-1] and m.endswith(name)}
        if len(fuller) == 1:
            task[key] = fuller.pop()


def explicit_task(instruction: str, vocab: Vocabulary) -> dict[str, Any]:
    """``{"task": ...}`` for an explicit instruction (it wins over what the text states), or ``{"error": ...}``."""
    parsed = _instruction_task(instruction, vocab)
    if parsed is None:
        return {"error": f"the instruction {instruction!r} is none of the four task forms "
                         "(pick up X; move X near Y; put X on Y; put X in Y)"}
    return {"task": parsed}


def _instruction_task(instruction: str, vocab: Vocabulary) -> dict[str, Any] | None:
    """An explicit instruction's task, objects as the vocabulary names them; None if none of the four."""
    found = find_task(f"task: {instruction}", vocab.ids)
    if found.task is not None:
        return found.task
    frame = read_instruction(instruction)
    if frame.task is not None and frame.task != "other" and frame.object is not None:
        return {
            "type": frame.task,
            "source": frame.object.text,
            "target": frame.destination.text if frame.destination is not None and frame.task != "pick_up" else None,
        }
    return parse_instruction(instruction)


def _task_in_scene(statement: str, reading: _Reading, vocab: Vocabulary) -> dict[str, Any] | None:
    """A task statement read again with the described objects as its scene ("the bottle" = the one there)."""
    by_name = {**vocab.name_ids, **{name: cid for cid, name in vocab.ids.items()}}
    ids = [by_name[o.mention] for o in reading.objects if o.mention in by_name]
    if not ids:
        return None
    # "move the green brick near the pink one": the instruction reader gives 'one' the noun before it
    frame = read_instruction(statement, scene_objects=ids)
    if frame.task is None or frame.task == "other" or frame.object is None or not frame.ok:
        return None
    if frame.task != "pick_up" and frame.destination is None:
        return None

    def name(phrase: Any) -> str | None:
        if phrase is None:
            return None
        oid = getattr(phrase, "object_id", None)
        text = str(phrase.text)
        return vocab.ids.get(oid, text) if oid is not None else text

    return {
        "type": frame.task,
        "source": name(frame.object),
        "target": name(frame.destination) if frame.task != "pick_up" else None,
    }
