"""Read an instruction back into (task, source, target), or say why it cannot be.

    parse_instruction("could you set the orange carrot on the dish?")
    -> InstructionParse(task="put_on", source="carrot", target="plate", reason=None)
    parse_instruction("pick up the coke can and then put it down")
    -> InstructionParse(task="pick_up", source="coke_can", reason="extra step: 'put' ...")

The grammar is small and explicit. Objects are catalog names or synonyms (or,
in a known scene, a head noun that fits one scene object: "the can"). An
instruction is split into clauses at sentence ends, sequence words ("then"),
result words ("so that", "until") and conjunctions before a verb. Each clause
gets a reading (pick, place, place without destination, another task, a
description, a topic, a preamble); the relation word decides the placement
task (near / on / in) and which object is the target; the object outside any
relation is the source, whatever the word order ("on the plate, put the
carrot"). Clauses then compose: "pick up X and put it on Y" is one placement;
anything else that adds an action is an extra step. Negation, extra or
alternative objects, plural or ambiguous names, missing destinations, and
relations outside the four tasks all give a ``reason`` instead of an exception.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.catalog.catalog import normalize_name
from ladev_lib.language import lexicon as lx
from ladev_lib.language.mentions import NameIndex, name_index
from ladev_lib.language.tokens import Token, is_sentence_end, tag_tokens

TASK_OF_RELATION = {"near": "move_near", "on": "put_on", "in": "put_in"}
PLACEMENT = frozenset(TASK_OF_RELATION)
_ACTIONS = frozenset({"pick", "place", "place_nodest", "other", "release"})


@dataclass(frozen=True)
class InstructionParse:
    """What an instruction asks for, as far as it can be read."""

    text: str
    task: str | None
    source: str | None
    """Catalog id of the object to manipulate."""
    target: str | None
    """Catalog id of the reference object (move_near, put_on, put_in)."""
    reason: str | None = None
    """Why the instruction does not state one task of the four clearly; None when it does."""
    notes: tuple[str, ...] = ()
    """How names were resolved when not by an exact catalog name."""

    @property
    def ok(self) -> bool:
        return self.reason is None

    @property
    def roles(self) -> tuple[str | None, str | None, str | None]:
        return (self.task, self.source, self.target)

    def as_dict(self) -> dict[str, Any]:
        return {
            "task": self.task,
            "source": self.source,
            "target": self.target,
            "reason": self.reason,
            "notes": list(self.notes),
        }


# -- clause structure -------------------------------------------------------------


@dataclass
class Ref:
    """A phrase that refers to an object (a name, a head noun, or a pronoun)."""

    text: str
    object_id: str | None = None
    problem: str | None = None
    pronoun: bool = False
    quantity: str | None = None
    note: str | None = None


@dataclass
class Governed:
    """A relation word and the phrases that complete it ("next to" + "the sponge")."""

    relation: str
    phrase: str
    directional: bool
    refs: list[Ref] = field(default_factory=list)
    places: list[str] = field(default_factory=list)
    """Completing phrases that are not objects ("the table", "your left")."""

    @property
    def dangling(self) -> bool:
        return not self.refs and not self.places


@dataclass
class Clause:
    tokens: list[Token]
    intro: str | None
    sentence: int
    verb: Token | None = None
    be: bool = False
    desire: bool = False
    negation: str | None = None
    recipient: bool = False
    alternatives: bool = False
    repeat: str | None = None
    unknown_verb: str | None = None
    """An unlisted word in verb position after "and" / "then" (read as an action outside the tasks)."""
    particles: list[str] = field(default_factory=list)
    bare: list[Ref] = field(default_factory=list)
    governed: list[Governed] = field(default_factory=list)
    kind: str = "empty"

    def refs(self) -> list[Ref]:
        return [*self.bare, *(r for g in self.governed for r in g.refs)]

    def placements(self) -> list[Governed]:
        return [g for g in self.governed if g.relation in PLACEMENT]

    def verb_text(self) -> str:
        if self.verb is not None:
            return self.verb.text
        return self.unknown_verb or "(no verb)"


def split_clauses(tokens: Sequence[Token]) -> list[Clause]:
    clauses: list[Clause] = []
    current: list[Token] = []
    intro: str | None = None
    sentence = 0

    def flush(next_intro: str | None) -> None:
        nonlocal current, intro
        if current:
            clause = Clause(current, intro, sentence)
            if intro is not None and _unknown_verb_at(current, 0):
                clause.unknown_verb = current[0].text
            clauses.append(clause)
        current, intro = [], next_intro

    for i, tok in enumerate(tokens):
        if is_sentence_end(tok):
            flush(None)
            sentence += 1
        elif tok.kind == "SEQ":
            flush(tok.text)
        elif tok.kind == "RESULT":
            flush("result")
        elif tok.kind == "NEG" and tok.text == "without":
            flush("without")
        elif (tok.kind == "CONJ" or tok.text == ",") and _action_follows(tokens, i + 1):
            flush(tok.text if tok.kind == "CONJ" else intro if not current else ",")
        else:
            current.append(tok)
    flush(None)
    return clauses


def _action_follows(tokens: Sequence[Token], i: int) -> bool:
    while i < len(tokens) and (
        tokens[i].kind in ("ADV", "CONJ", "AUX", "MODAL", "PERSON") or tokens[i].text in lx.SKIPPABLE
    ):
        i += 1
    return i < len(tokens) and (tokens[i].kind in ("VERB", "NEG", "SEQ") or _unknown_verb_at(tokens, i))


def _unknown_verb_at(tokens: Sequence[Token], i: int) -> bool:
    """An unlisted word right before an object phrase, after "and" / "then": "... and sing a song"."""
    return (
        i + 1 < len(tokens)
        and tokens[i].kind == "WORD"
        and (
            tokens[i + 1].kind in ("DET", "PRON", "OBJ", "QUANT")
            or (tokens[i + 1].kind == "PERSON" and tokens[i + 1].text in lx.RECIPIENTS)
        )
    )


# -- reading one clause -----------------------------------------------------------


class _ClauseReader:
    def __init__(self, index: NameIndex, scene: frozenset[str] | None) -> None:
        self.index = index
        self.scene = scene

    def read(self, clause: Clause) -> Clause:
        self._structure(clause)
        clause.kind = self._kind(clause)
        return clause

    def _structure(self, c: Clause) -> None:
        phrase: list[Token] = []
        gov: Governed | None = None
        saw_or = False
        verbs: list[Token] = []

        def close() -> None:
            nonlocal phrase
            if phrase:
                refs, places = self._refs_of(phrase)
                if gov is not None:
                    gov.refs.extend(refs)
                    gov.places.extend(places)
                else:
                    c.bare.extend(refs)
            phrase = []

        first = 1 if c.unknown_verb is not None else 0
        for j, tok in enumerate(c.tokens):
            if j < first:
                continue
            if tok.text in lx.DESIRE:
                c.desire = True
            if tok.kind in ("OBJ", "PRON", "DET", "QUANT", "WORD"):
                phrase.append(tok)
                continue
            close()
            if tok.kind == "REL":
                gov = Governed(tok.relation or "other", tok.text, tok.directional)
                c.governed.append(gov)
            elif tok.kind in ("VERB", "BE", "MODAL", "NEG"):
                gov = None
                if tok.kind == "VERB":
                    verbs.append(tok)
                    nxt = c.tokens[j + 1] if j + 1 < len(c.tokens) else None
                    if nxt is not None and nxt.kind == "PERSON" and nxt.text in lx.RECIPIENTS:
                        c.recipient = True
                elif tok.kind == "BE":
                    c.be = True
                elif tok.kind == "NEG" and c.negation is None:
                    c.negation = tok.text
            elif tok.kind == "PART":
                c.particles.append(tok.text)
            elif tok.kind == "REPEAT":
                c.repeat = tok.text
            elif tok.kind == "CONJ" and tok.text in ("or", "either"):
                saw_or = True
        close()
        c.verb = _main_verb(verbs)
        c.alternatives = saw_or and len({r.object_id or r.text for r in c.refs()}) > 1
        _with_as_source(c)

    def _refs_of(self, phrase: list[Token]) -> tuple[list[Ref], list[str]]:
        """The object references in one noun phrase, and its text if it names a place instead."""
        text = " ".join(t.text for t in phrase if t.kind != "DET")
        quantity = next((t.text for t in phrase if t.kind == "QUANT"), None)
        if any(t.kind == "PRON" for t in phrase):
            pron = next(t for t in phrase if t.kind == "PRON")
            problem = f"'{pron.text}' means more than one object" if pron.text in lx.PLURAL_PRONOUNS else None
            return [Ref(pron.text, pronoun=problem is None, problem=problem)], []
        content = [t for t in phrase if t.kind in ("OBJ", "WORD")]
        heads = [
            k for k, t in enumerate(content)
            if t.kind == "OBJ" and not self._is_modifier(content, k)
        ]
        refs: list[Ref] = []
        if heads:
            start = 0
            for k in heads:
                words = [w for t in content[start : k + 1] for w in t.text.split()]
                obj = content[k]
                assert obj.object_id is not None
                resolved = self.index.prefer_scene(obj.object_id, words, self.scene, obj.text)
                refs.append(Ref(obj.text, resolved.object_id, quantity=quantity, note=resolved.note))
                start = k + 1
            return refs, []
        words = [w for t in content for w in t.text.split()]
        if not words:
            return [], [text] if text else []
        found = self.index.resolve_head(words, self.scene, text)
        if found is None:
            return [], [text]
        return [Ref(text, found.object_id, found.problem, quantity=quantity, note=found.note)], []

    def _is_modifier(self, content: list[Token], k: int) -> bool:
        """A name used as a modifier: "the coke label", "orange soda"."""
        if k + 1 >= len(content):
            return False
        nxt = content[k + 1]
        if nxt.kind == "OBJ":
            return True
        return nxt.text in lx.PART_NOUNS or self.index.is_object_noun(nxt.text)

    def _kind(self, c: Clause) -> str:
        if c.intro == "without":
            return "manner"
        kind = self._action_kind(c)
        negated_manner = c.verb is not None and c.verb.lemma in lx.MANNER_VERBS
        if c.negation and kind in ("place_nodest", "other") and negated_manner:
            return "manner"  # "don't drop it": how to do the task, not which task
        if c.negation and kind in ("topic", "describe", "empty", "preamble"):
            return "manner"  # "so it doesn't fall": negates no action of the four tasks
        return kind

    def _action_kind(self, c: Clause) -> str:
        has_ref = bool(c.bare)
        object_places = [g for g in c.placements() if g.refs]
        reverse = [g for g in c.governed if g.relation == "reverse" and g.refs]
        reverse_particle = any(p in lx.REVERSE_PARTICLES for p in c.particles)
        verb = c.verb
        if verb is None and c.unknown_verb is not None:
            return "other"
        if verb is None:
            if c.be and not (c.desire or c.intro == "result"):
                return "describe"
            if c.placements():
                return "place"
            return "topic" if c.refs() else "empty"
        cls = verb.verb_class
        if cls in ("pick", "place") and c.recipient:
            return "other"
        if cls == "pick":
            if reverse or (reverse_particle and not object_places):
                return "other"
            if any(g.directional or verb.lemma in lx.PICK_PLACES_WITH_STATIVE for g in object_places):
                return "place"
            return "pick"
        if cls == "place":
            if not has_ref and verb.lemma in lx.SELF_MOTION:
                return "preamble"
            if reverse and not c.placements():
                return "other"
            other_relations = [g for g in c.governed if g.relation == "other" and g.refs]
            if c.placements() or other_relations:
                return "place"  # "behind the bottle" too: _placement_task names the relation
            if reverse_particle:
                return "other"
            return "place_nodest"
        return cls or "other"


def _main_verb(verbs: list[Token]) -> Token | None:
    for classes in (("pick", "place", "other"), ("release",), ("preamble",)):
        for v in verbs:
            if v.verb_class in classes:
                return v
    return None


def _with_as_source(c: Clause) -> None:
    """ "into the basket with the eggplant": the object after "with" is the one to move."""
    if c.bare or not c.placements():
        return
    for g in c.governed:
        if g.phrase == "with" and len(g.refs) == 1:
            c.bare.append(g.refs.pop())
            return


# -- composing clauses ------------------------------------------------------------


@dataclass
class _Action:
    kind: str
    clauses: list[Clause]

    @property
    def verb(self) -> str:
        return self.clauses[-1].verb_text()

    def bare(self) -> list[Ref]:
        return [r for c in self.clauses for r in c.bare]

    def governed(self) -> list[Governed]:
        return [g for c in self.clauses for g in c.governed]


def _resolve_pronouns(clauses: list[Clause]) -> None:
    focus: str | None = None
    pending: list[Ref] = []
    for c in clauses:
        for ref in c.bare:
            if ref.pronoun:
                if focus is not None:
                    ref.object_id = focus
                else:
                    pending.append(ref)
            elif ref.object_id is not None:
                focus = ref.object_id
        for g in c.governed:
            for ref in g.refs:
                if ref.pronoun:
                    ref.object_id = focus
                    if focus is None:
                        pending.append(ref)
    later = next((r.object_id for c in clauses for r in c.bare if not r.pronoun and r.object_id), None)
    for ref in pending:
        ref.object_id = later
        if later is None:
            ref.problem = f"'{ref.text}' refers to no object named in the instruction"


def _mark_topics(clauses: list[Clause]) -> None:
    """ "the banana on the table, lift it": a verbless phrase taken up by a later pronoun."""
    for k, c in enumerate(clauses):
        taken_up = any(r.pronoun for later in clauses[k + 1 :] for r in later.bare)
        if c.verb is None and c.bare and c.kind == "place" and taken_up:
            c.kind = "topic"


def _same_object(a: _Action, b: _Action) -> bool:
    ids_a = {r.object_id for r in a.bare()}
    ids_b = {r.object_id for r in b.bare()}
    return bool(ids_a) and (ids_a == ids_b or not ids_b)


def _merge(actions: list[_Action]) -> list[_Action]:
    """Collapse sequences that state one task: pick X + put X on Y, move X + so it is near Y."""
    out: list[_Action] = []
    for act in actions:
        prev = out[-1] if out else None
        if prev is not None:
            merged = _merge_pair(prev, act)
            if merged is not None:
                out[-1] = merged
                continue
        out.append(act)
    return out


def _merge_pair(a: _Action, b: _Action) -> _Action | None:
    both = [*a.clauses, *b.clauses]
    fronted_a = a.kind == "place" and not a.bare() and all(c.verb is None for c in a.clauses)
    fronted_b = b.kind == "place" and not b.bare() and all(c.verb is None for c in b.clauses)
    if fronted_a and b.kind == "place_nodest":
        return _Action("place", both)
    if a.kind == "place_nodest" and fronted_b:
        return _Action("place", both)
    if not _same_object(a, b):
        return None
    if a.kind == "pick" and b.kind in ("place", "pick"):
        return _Action(b.kind, both)
    reordered = any((c.intro or "") in ("after", "before", "once") for c in both)
    if reordered and {a.kind, b.kind} == {"pick", "place"}:
        return _Action("place", both)  # "put it on the plate after picking up the carrot"
    if a.kind == "place_nodest" and b.kind == "place":
        return _Action("place", both)
    if a.kind == "place" and b.kind == "release":
        return _Action("place", both)
    return None


class _Composer:
    def __init__(self, text: str, clauses: list[Clause]) -> None:
        self.text = text
        self.clauses = clauses
        self.reasons: list[str] = []

    def compose(self) -> InstructionParse:
        _mark_topics(self.clauses)
        _resolve_pronouns(self.clauses)
        negated = [c for c in self.clauses if c.negation and c.kind != "manner"]
        positive = [
            _Action(c.kind, [c])
            for c in self.clauses
            if not c.negation and (c.kind in _ACTIONS or (c.kind == "place" and c.verb is None))
        ]
        actions = _merge(positive)
        task, source, target = None, None, None
        main: _Action | None = None
        if not actions:
            if negated:
                self.reasons.append(f"negated: '{negated[0].negation} {negated[0].verb_text()}'")
            else:
                self.reasons.append("no task verb found")
        else:
            if len(actions) > 1:
                extra = ", ".join(f"'{a.verb}'" for a in actions[1:])
                word = "alternative action" if any(c.intro == "or" for a in actions for c in a.clauses) else "extra step"
                self.reasons.append(f"{word}: {extra} after '{actions[0].verb}'")
            main = actions[0]
            task, source, target = self._roles(main)
        if source is not None and source == target:
            self.reasons.append(f"the same object is source and destination: {source}")
        repeat = next((c.repeat for c in self.clauses if c.repeat), None)
        if repeat:
            self.reasons.append(f"'{repeat}' asks for the task more than once")
        self._check_negations(negated, source)
        self._check_mentions(main, negated, source, target)
        notes = tuple(r.note for c in self.clauses for r in c.refs() if r.note)
        reason = "; ".join(dict.fromkeys(self.reasons)) or None
        return InstructionParse(self.text, task, source, target, reason, notes)

    def _roles(self, act: _Action) -> tuple[str | None, str | None, str | None]:
        task: str | None = None
        if act.kind == "pick":
            task = "pick_up"
        elif act.kind == "place":
            task = self._placement_task(act)
        elif act.kind == "place_nodest":
            self.reasons.append(f"'{act.verb}' without a destination")
        elif act.kind == "release":
            self.reasons.append(f"'{act.verb}' is not one of the tasks")
        else:
            clause = act.clauses[-1]
            if clause.recipient:
                self.reasons.append(f"'{act.verb}' hands the object to a person")
            elif any(g.relation == "reverse" for g in clause.governed) or clause.particles:
                self.reasons.append(f"'{act.verb} ... {_reverse_word(clause)}' takes the object away")
            else:
                self.reasons.append(f"'{act.verb}' is not one of the tasks")
        source = self._one(act.bare(), "object to act on", required=True)
        target = None
        if task in TASK_OF_RELATION.values():
            refs = [r for g in act.governed() if g.relation in PLACEMENT for r in g.refs]
            target = self._one(refs, "destination", required=True)
        return task, source, target

    def _placement_task(self, act: _Action) -> str | None:
        places = [g for g in act.governed() if g.relation in PLACEMENT]
        with_objects = [g for g in places if g.refs]
        if with_objects:
            kinds = {g.relation for g in with_objects}
            if len(kinds) > 1:
                self.reasons.append("more than one relation: " + ", ".join(sorted(kinds)))
            return TASK_OF_RELATION[with_objects[0].relation]
        if places and places[0].places:
            self.reasons.append(f"destination '{places[0].places[0]}' is not an object")
        elif places:
            self.reasons.append(f"no destination object after '{places[0].phrase}'")
        others = [g for g in act.governed() if g.relation == "other" and g.refs]
        if others:
            self.reasons.append(f"relation '{others[0].phrase}' is none of near / on / in")
        return TASK_OF_RELATION[places[0].relation] if places else None

    def _one(self, refs: list[Ref], role: str, required: bool) -> str | None:
        for r in refs:
            if r.problem:
                self.reasons.append(r.problem)
            if r.quantity:
                self.reasons.append(f"'{r.text}' asks for a quantity")
        ids = list(dict.fromkeys(r.object_id for r in refs if r.object_id))
        if len(ids) > 1:
            self.reasons.append(f"more than one {role}: {', '.join(ids)}")
        if not ids and required and not any(r.problem for r in refs):
            self.reasons.append(f"no {role} named")
        return ids[0] if ids else None

    def _check_negations(self, negated: list[Clause], source: str | None) -> None:
        for c in negated:
            ids = {r.object_id for r in c.refs() if r.object_id}
            if source is not None and source not in ids and ids:
                continue  # an exclusion: "pick up the coke can, not the pepsi can"
            if source is not None:
                self.reasons.append(f"negated: '{c.negation} {c.verb_text()}'")

    def _check_mentions(
        self, main: _Action | None, negated: list[Clause], source: str | None, target: str | None
    ) -> None:
        in_main = {id(c) for c in main.clauses} if main else set()
        excluded = {id(c) for c in negated}
        for c in self.clauses:
            if c.kind == "manner" or id(c) in excluded:
                continue
            if c.alternatives:
                self.reasons.append("alternative objects ('or')")
            for r in c.refs():
                if id(c) not in in_main and r.problem:
                    self.reasons.append(r.problem)
                if r.object_id and r.object_id not in (source, target):
                    self.reasons.append(f"mentions another object: {r.object_id}")


def _reverse_word(clause: Clause) -> str:
    for g in clause.governed:
        if g.relation == "reverse":
            return g.phrase
    return clause.particles[0] if clause.particles else ""


# -- entry point ----------------------------------------------------------------


class InstructionParser:
    """Parses instructions against a catalog (and optionally one scene's objects)."""

    def __init__(self, catalog: Catalog | None = None) -> None:
        self.catalog = catalog or load_catalog()
        self.index = name_index(self.catalog)

    def parse(self, text: str, scene_objects: Iterable[str] | None = None) -> InstructionParse:
        scene = frozenset(scene_objects) if scene_objects else None
        if not text or not text.strip():
            return InstructionParse(text, None, None, None, "empty instruction")
        tokens = tag_tokens(text, self.index)
        reader = _ClauseReader(self.index, scene)
        clauses = [reader.read(c) for c in split_clauses(tokens)]
        if not clauses:
            return InstructionParse(text, None, None, None, "no words to read")
        return _Composer(text, clauses).compose()

    def canonical_text(self, text: str) -> str:
        """The instruction with every object name replaced by its display name.

        Only the names change; the rest of the text is kept as written, so an
        instruction that already uses display names comes back unchanged.
        """
        out, pos = [], 0
        for tok in tag_tokens(text, self.index):
            if tok.kind != "OBJ" or tok.object_id is None:
                continue
            display = self.index.display_name(tok.object_id)
            if normalize_name(display) == tok.text:
                continue
            found = _surface_pattern(tok.text).search(text, pos)
            if found is None:
                continue  # the name's surface form could not be located; leave it
            out.append(text[pos : found.start()])
            out.append(display)
            pos = found.end()
        out.append(text[pos:])
        return "".join(out)


@functools.lru_cache(maxsize=1024)
def _surface_pattern(normalized: str) -> re.Pattern[str]:
    """Matches a normalised name as written: any case, hyphens or spaces, apostrophes."""
    words = ["'?".join(re.escape(ch) for ch in word) for word in normalized.split()]
    return re.compile(r"(?<![a-z0-9])" + r"[\s\-_/]+".join(words) + r"(?![a-z0-9])", re.IGNORECASE)


_DEFAULT: dict[int, InstructionParser] = {}


def parse_instruction(
    text: str, scene_objects: Iterable[str] | None = None, catalog: Catalog | None = None
) -> InstructionParse:
    """Parse one instruction (parser cached per catalog)."""
    cat = catalog or load_catalog()
    parser = _DEFAULT.get(id(cat))
    if parser is None or parser.catalog is not cat:
        parser = InstructionParser(cat)
        _DEFAULT[id(cat)] = parser
    return parser.parse(text, scene_objects)
