"""Split an instruction into clauses and read each one.

A clause is a stretch of tokens between sentence ends, sequence words
("then"), result words ("so that", "until") and conjunctions before a verb.
Reading it finds its main verb, the object phrases outside any relation (the
*bare* ones: what is acted on, whatever the word order), the relation words
with the phrases they govern ("next to" + "the sponge"), negation, particles
and hand-over recipients, and gives it a kind: pick, place, place without a
destination, another task, a description, a topic, a preamble, or a manner
constraint. :mod:`ladev_lib.language.parser` composes the clauses.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from ladev_lib.language import lexicon as lx
from ladev_lib.language.mentions import NameIndex
from ladev_lib.language.tasks import PLACEMENT_RELATIONS, RELATION_TASKS
from ladev_lib.language.tokens import Token, is_sentence_end

TASK_OF_RELATION: dict[str, str] = dict(RELATION_TASKS)
PLACEMENT = PLACEMENT_RELATIONS
FREE = "~"
"""Prefix of the key of a free noun phrase (one the catalog does not name): "~wine bottle"."""
GRIPPER_WORDS = frozenset(
    {"gripper", "grippers", "hand", "fingers", "claw", "claws", "jaws", "jaw", "grip", "pincers", "arm", "wrist", "effector"}
)
GRIP_VERBS = frozenset({"close", "open", "shut", "squeeze", "tighten", "clamp", "wrap", "loosen", "relax"})
_CLOSING = frozenset({"close", "shut", "tighten", "clamp", "wrap"})
_GRIPPED_BY = frozenset({"on", "around", "round", "about", "onto", "over"})
"""The relation words after "close the gripper" that name what it grasps ("... *around* the can")."""


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
    words: tuple[str, ...] = ()
    """The phrase's content words (no determiner), for its noun phrase."""
    free_problem: str | None = None
    """Why a free phrase (key ``~...``) names no one catalog object, for the catalog-only view."""
    candidates: tuple[str, ...] = ()
    """The catalog objects a free phrase fits when the catalog reads it as several ("the can")."""
    plural: bool = False
    """A plural phrase ("the bananas": one group to act on) or the pronoun "them"."""

    @property
    def free(self) -> bool:
        return self.object_id is not None and self.object_id.startswith(FREE)


@dataclass
class Governed:
    """A relation word and the phrases that complete it ("next to" + "the sponge")."""

    relation: str
    phrase: str
    directional: bool
    refs: list[Ref] = field(default_factory=list)
    places: list[str] = field(default_factory=list)
    """Completing phrases that are not objects ("the table", "your left")."""
    follows: str | None = None
    """What the relation word comes right after: "bare" (the acted-on phrase) or "governed"."""
    relative: bool = False
    """Introduced by a relative clause ("the plate *that is* on the shelf"): it describes the phrase before."""
    qualifier: str | None = None
    """Set by the parser when the relation describes a phrase instead of stating the task:
    "object" ("the bowl *next to the plate*") or "destination" ("the compartment *of the caddy*");
    "completes" when it only says how the object ends at a destination named before ("set it *on top*")."""

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
    reverse_pick: bool = False
    covers: bool = False
    """ "cover the pot with the lid": the lid is put on the pot (roles read back to front)."""
    """A pick verb with a "from"/"off" phrase ("lift the bowl from the stove")."""
    unknown_verb: str | None = None
    """An unlisted word in verb position after "and" / "then", or opening an instruction before an
    object ("rinse the beaker, then ..."): an action outside the tasks."""
    temporal: bool = False
    """A relation says when ("at three", "for an hour", "by the end"); it is left out of ``governed``."""
    declarative: str | None = None
    """It opens with a subject and a finite verb: "be" for a copula, an auxiliary or a modal ("I'm
    wrapping ...", "the milk has been ..."), "verb" for a verb's finite form ("my train leaves ...")."""
    particles: list[str] = field(default_factory=list)
    bare_places: list[str] = field(default_factory=list)
    """Phrases outside any relation that name a place or the robot ("the gripper")."""
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
        elif tok.kind == "CONJ" and tok.text == "and" and _gapped_placement(current, tokens, i + 1):
            flush("and")  # "place the block on the right and the can on the left": a second placement
        elif tok.kind == "WORD" and tok.text in lx.CONDITIONALS and current:
            flush(None)  # "... if it isn't too much trouble": a condition, a clause of its own
            current.append(tok)
        else:
            current.append(tok)
    flush(None)
    for k, clause in enumerate(clauses):
        opening = k == 0 or clauses[k - 1].sentence != clause.sentence
        task_later = any(t.kind == "VERB" and t.verb_class in ("pick", "place") for c in clauses[k + 1 :] for t in c.tokens)
        result = k + 1 < len(clauses) and clauses[k + 1].intro == "result"  # "make it so (that) ..."
        if opening and task_later and not result and clause.unknown_verb is None and _imperative_opening(clause.tokens):
            clause.unknown_verb = clause.tokens[0].text
    return clauses


def _imperative_opening(tokens: Sequence[Token]) -> bool:
    """A sentence's first word in verb position, before a task verb of a later clause: an unlisted
    base form before an object ("rinse the beaker, then put it on the shelf": a step of its own),
    not a participle or a word that opens a subordinate clause ("assuming the bowl is empty, ...").
    With a relation of its own the clause is the command ("hang the towel on the rack")."""
    w = tokens[0].text if tokens else ""
    return (
        _unknown_verb_at(tokens, 0)
        and tokens[1].kind in ("DET", "QUANT")  # not "fruit bowl: ...", "make it so ..."
        and not any(t.kind in ("BE", "MODAL", "AUX", "VERB", "REL") for t in tokens)
        and w.isalpha() and len(w) > 2 and not w.endswith(("ing", "ed"))
        and w not in _NOT_NOUNS and w not in lx.DESIRE and w not in lx.SKIPPABLE
        and not lx.looks_plural(w)
    )


def _gapped_placement(current: Sequence[Token], tokens: Sequence[Token], i: int) -> bool:
    """ "... and the can on the left": after a clause with a verb and a relation, a noun phrase
    with a relation of its own repeats the verb (gapping)."""
    relations = [t for t in current if t.kind == "REL"]
    if not any(t.kind == "VERB" for t in current) or not relations or relations[-1].text == "between":
        return False
    j = i
    while j < len(tokens) and tokens[j].kind in ("DET", "QUANT"):
        j += 1
    if j == i:
        return False  # a determiner opens the gapped phrase ("and the can on the left")
    start = j
    while j < len(tokens) and tokens[j].kind in ("OBJ", "WORD"):
        j += 1
    return j > start and j < len(tokens) and tokens[j].kind == "REL"


def _action_follows(tokens: Sequence[Token], i: int) -> bool:
    """A new clause starts here: a verb, a negation, a sequence word, an unlisted verb, or a
    subordinate clause ("..., if it isn't too much trouble")."""
    if i < len(tokens) and tokens[i].kind == "WORD" and tokens[i].text in lx.CONDITIONALS:
        return True
    while i < len(tokens) and (
        tokens[i].kind in ("ADV", "CONJ", "AUX", "MODAL", "PERSON") or tokens[i].text in lx.SKIPPABLE
    ):
        i += 1
    return i < len(tokens) and (tokens[i].kind in ("VERB", "NEG", "SEQ") or _unknown_verb_at(tokens, i))


def _unknown_verb_at(tokens: Sequence[Token], i: int) -> bool:
    """An unlisted word right before an object phrase, after "and" / "then": "... and sing a song"
    (not a word that opens a subordinate clause: "if it is ...")."""
    return (
        i + 1 < len(tokens)
        and tokens[i].kind == "WORD"
        and tokens[i].text not in lx.SUBORDINATORS
        and (
            tokens[i + 1].kind in ("DET", "PRON", "OBJ", "QUANT")
            or (tokens[i + 1].kind == "PERSON" and tokens[i + 1].text in lx.RECIPIENTS)
        )
    )


# -- reading one clause -----------------------------------------------------------


class ClauseReader:
    def __init__(self, index: NameIndex, scene: frozenset[str] | None) -> None:
        self.index = index
        self.scene = scene
        self._last_head: str | None = None
        """The head noun of the last object phrase read, for "the pink *one*"."""
        self._gripper_said = False
        """Whether the clause before named the gripper ("open the gripper, close *it* around the can")."""

    def read(self, clause: Clause) -> Clause:
        self._structure(clause)
        gripper_it = (
            self._gripper_said and clause.verb is not None and clause.verb.lemma in GRIP_VERBS
            and len(clause.bare) == 1 and clause.bare[0].pronoun and clause.bare[0].text == "it"
        )
        if gripper_it:
            clause.bare.clear()
            clause.bare_places.append("gripper")  # "close it around the ribbon": 'it' is the gripper
        clause.kind = self._kind(clause)
        self._gripper_said = any(p.split()[-1] in GRIPPER_WORDS for p in clause.bare_places) or (
            self._gripper_said and not clause.bare
        )
        return clause

    def _structure(self, c: Clause) -> None:
        phrase: list[Token] = []
        gov: Governed | None = None
        saw_or = False
        verbs: list[Token] = []
        before: Token | None = None
        last: str | None = None  # what the previous element was: "bare" | "governed" | None
        relative_to: str | None = None  # what came before a relative pronoun ("the can | that is on ...")

        def fronted(g: Governed | None) -> bool:
            """The relation opens the clause: "at the end, ...", "into the box the pen goes"."""
            return g is not None and bool(c.governed) and c.governed[0] is g and not c.bare and not verbs

        def close(ahead: Token | None = None, after: Token | None = None) -> None:
            nonlocal phrase, last, gov
            if phrase and gov is not None and not gov.refs and not gov.places and _says_when(
                gov.phrase, phrase, ahead, fronted(gov)
            ):
                c.governed.remove(gov)  # "at three", "for an hour", "by the end": when, not where
                c.temporal = True
                gov, phrase = None, []
                return
            if phrase:
                # a free noun phrase needs a noun-phrase position: a determiner, or right after
                # a verb, a particle or a relation word ("put wine bottle on rack"), or opening a
                # verbless clause before a relation word ("test tube into the rack, please"; "rosin,
                # in the case"), or opening a clause as the subject of a finite verb ("textbook goes
                # on the desk", "textbook should go ...")
                slot = before is not None and (before.kind in ("VERB", "REL", "PART", "CONJ") or before.text == ",")
                slot = slot or (before is None and ahead is not None and ahead.kind == "REL" and not verbs)
                slot = slot or (
                    before is None and not verbs and ahead is not None and ahead.text == ","
                    and after is not None and after.kind == "REL"
                )
                slot = slot or (before is None and ahead is not None and _finite(ahead))
                refs, places = self._refs_of(phrase, free_ok=slot or any(t.kind in ("DET", "QUANT") for t in phrase))
                if gov is not None:
                    gov.refs.extend(refs)
                    gov.places.extend(places)
                    last = "governed"
                else:
                    coordinated = places and places[0].split()[-1] not in _NOT_COORDINATED
                    if coordinated and not refs and last == "bare" and before is not None and before.text in ("and", "plus"):
                        refs = [_coordinated(places[0])]  # "the lamp and the side table": a second object
                        places = []
                    c.bare.extend(refs)
                    c.bare_places.extend(places)
                    last = "bare" if refs else last
            phrase = []

        first = 1 if c.unknown_verb is not None else 0
        for j, tok in enumerate(c.tokens):
            if j < first:
                continue
            nxt_text = c.tokens[j + 1].text if j + 1 < len(c.tokens) else ""
            if tok.text in lx.DESIRE and tok.kind != "ADV" and not (tok.text in _PERFECT and nxt_text not in ("to", "got")):
                c.desire = True  # "has to be on ..." (not the perfect: "has been sitting out"; not a hedge)
            if tok.kind == "WORD" and (tok.text in lx.DESIRE or tok.text == "to") and any(
                t.kind in ("OBJ", "WORD") and t.text not in lx.DESIRE for t in phrase
            ):
                close()  # "the pen needs to be ...": the phrase ends before the desire word
                continue
            if tok.kind == "DET" and fronted(gov) and phrase and phrase[0].kind == "DET" and any(
                t.kind == "OBJ" or (t.kind == "WORD" and t.text not in lx.NUMBER_WORDS) for t in phrase
            ):
                close()  # "into the box *the* pen goes": a determiner after a determined noun opens the
                gov = None  # next phrase, the subject, after the fronted relation's own phrase
            if tok.kind in ("OBJ", "PRON", "DET", "QUANT", "WORD"):
                phrase.append(tok)
                continue
            close(tok, c.tokens[j + 1] if j + 1 < len(c.tokens) else None)
            if tok.kind not in ("ADV",):
                before = tok
            if tok.kind == "REL":
                back = j - 1
                while back > 0 and c.tokens[back].kind == "ADV":
                    back -= 1
                relative = False
                if back > 1 and c.tokens[back].kind == "BE" and c.tokens[back - 1].kind == "RELPRON":
                    back -= 2  # "the can *that is* on the plate": the relation describes the phrase before
                    relative = True
                prev_kind = c.tokens[back].kind if back >= 0 and j > 0 else None
                follows = (relative_to if relative else last) if prev_kind in ("OBJ", "WORD", "PRON") else None
                if prev_kind == "REL":
                    follows = "governed"  # "from between the plate and ..."
                gov = Governed(tok.relation or "other", tok.text, tok.directional, follows=follows, relative=relative)
                c.governed.append(gov)
                last = "governed"
            elif tok.kind == "RELPRON":
                relative_to = last
            elif tok.kind in ("VERB", "BE", "MODAL", "NEG"):
                gov = None
                last = None
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
        c.declarative = _declarative(c.tokens[first:])
        c.alternatives = saw_or and len({r.object_id or r.text for r in c.refs()}) > 1
        _with_as_source(c)
        _cover_with(c)
        self._placement_words(c)

    def _placement_words(self, c: Clause) -> None:
        """Relation words whose placement depends on the verb and the noun after them.

        "move the mug *to the tray*": carried to a surface, it ends on it ("in" for a
        receptacle: "bring the apple to the basket"); so with a putting verb, the learner's
        "to" for "in" / "on" ("put the jam to the cupboard"); "to" anything else stays "near"
        ("shift the lamp over to the monitor"). "put the bowl *above* the cabinet": a
        putting verb puts it on.
        """
        if c.verb is None or c.verb.lemma is None:
            return
        lemma = c.verb.lemma
        for g in c.governed:
            words = tuple(g.phrase.split())
            if (lemma in lx.CARRY_VERBS or lemma in lx.PUT_VERBS or lemma in lx.CARRY_ALL_THE_WAY) and g.relation == "near" and (
                    words in lx.CARRY_TO or lemma in lx.CARRY_ALL_THE_WAY and words == ("over", "to")):
                kind = self.receptacle_kind(g.refs[0]) if g.refs else None
                if kind is not None:
                    g.relation = kind
            elif lemma in lx.PUT_VERBS and g.relation == "other" and words in lx.ABOVE_AS_ON and g.refs:
                g.relation = "on"

    def receptacle_kind(self, ref: Ref) -> str | None:
        """ "on" for a surface ("the tray"), "in" for a receptacle ("the basket"), else None."""
        if ref.pronoun or ref.object_id is None:
            return None
        heads = {(ref.words or tuple(ref.text.split()) or ("",))[-1]}
        if not ref.free:
            heads.add(self.index.display_name(ref.object_id).split()[-1])
        if heads & lx.SURFACE_HEADS:
            return "on"
        if heads & lx.CONTAINER_HEADS:
            return "in"
        return _kind_by_wordnet(ref.text if ref.free else self.index.display_name(ref.object_id))

    def _refs_of(self, phrase: list[Token], free_ok: bool = True) -> tuple[list[Ref], list[str]]:
        """The object references in one noun phrase, and its text if it names a place instead."""
        text = " ".join(t.text for t in phrase if t.kind != "DET")
        quantity = next((t.text for t in phrase if t.kind == "QUANT"), None)
        if any(t.kind == "PRON" for t in phrase):
            pron = next(t for t in phrase if t.kind == "PRON")
            # "them" stands for a group named before ("the crayons ... carry them"); the parser
            # says when what it stands for is one object
            return [Ref(pron.text, pronoun=True, plural=pron.text in lx.PLURAL_PRONOUNS)], []
        content = [t for t in phrase if t.kind in ("OBJ", "WORD")]
        while content and content[0].kind == "WORD" and (content[0].text in lx.DESIRE or content[0].text in lx.SKIPPABLE):
            content = content[1:]  # "like the carrot": the desire word is no part of the phrase
        heads = [
            k for k, t in enumerate(content)
            if t.kind == "OBJ" and not self._is_modifier(content, k)
        ]
        refs: list[Ref] = []
        if heads and self._noun_after(content[heads[-1] + 1 :]):
            heads = heads[:-1] if len(heads) > 1 else []  # "the dish rack": a name used as a modifier
            if not heads:
                content = [Token("WORD", t.text) if t.kind == "OBJ" else t for t in content]
        if heads:
            start = 0
            for k in heads:
                words = [w for t in content[start : k + 1] for w in t.text.split()]
                obj = content[k]
                assert obj.object_id is not None
                resolved = self.index.prefer_scene(obj.object_id, words, self.scene, obj.text)
                refs.append(
                    Ref(
                        obj.text, resolved.object_id, quantity=quantity, note=resolved.note, words=tuple(words),
                        plural=lx.looks_plural(words[-1]),
                    )
                )
                start = k + 1
                self._last_head = words[-1]
            return refs, []
        words = [w for t in content for w in t.text.split()]
        if len(words) > 1 and words[-1] == "one" and self._last_head is not None:
            words[-1] = self._last_head  # "the green brick near the pink one": the pink brick
            text = " ".join(words)
        elif words and words[-1] != "one":
            self._last_head = words[-1]
        full = tuple(words)
        if "of" in words[:-1]:
            words = words[len(words) - words[::-1].index("of") :]  # "can of coca cola" -> "coca cola"
        if not words:
            return [], [text] if text else []
        if len(words) > 1 and words[-1] in _SURFACE_PARTS:
            words = words[:-1]  # "the cabinet top": the cabinet
            full = tuple(w for w in full if w not in _SURFACE_PARTS)
        head = words[-1]
        found = self.index.resolve_head(words, self.scene, text)
        if found is not None and head not in self.index.name_words and not self.index.is_object_noun(head):
            found = None  # "the wooden cabinet": a modifier that names catalog objects does not make it one
        if found is None and (
            not free_ok
            or any(w in _NOT_NOUNS and not (w in _NOT_NOUN_NOUNS and w in words[:-1]) for w in full)
            or (head in lx.LOCATION_NOUNS and head not in _FURNITURE)
            or head in GRIPPER_WORDS
            or not head.isalpha()
        ):
            return [], [text]
        unknown_modifier = any(
            w not in self.index.name_words and w not in lx.COLOR_WORDS and w not in lx.SIZE_WORDS for w in words[:-1]
        )
        determiner = next((t.text for t in phrase if t.kind == "DET"), None)
        group = lx.looks_plural(head) and quantity is None and determiner in lx.DEFINITE_DETERMINERS
        if found is not None and found.object_id is None and found.problem and "plural" in found.problem and group:
            # "the bananas": a given group, one object to act on (grounded by its head noun); the
            # catalog, whose objects are single things, names none of it
            free = _free_words(full)
            return [Ref(text, FREE + " ".join(free), words=free, free_problem=found.problem, plural=True)], []
        if found is None or (
            found.object_id is None
            and found.problem
            and ("no known" in found.problem or unknown_modifier or "plural" not in found.problem)
        ):
            # a noun phrase the catalog does not name (or names ambiguously): free text, grounded later
            free = _free_words(full)
            problem = found.problem if found is not None else f"'{text}' names no known object"
            candidates = found.candidates if found is not None else ()
            return [
                Ref(
                    text, FREE + " ".join(free), quantity=quantity, words=free, free_problem=problem,
                    candidates=candidates, plural=lx.looks_plural(head),
                )
            ], []
        return [Ref(text, found.object_id, found.problem, quantity=quantity, note=found.note, words=full)], []

    def _noun_after(self, rest: list[Token]) -> bool:
        """Words after a name that make it a modifier: a head noun of their own ("dish *rack*")."""
        if not rest or any(t.kind != "WORD" for t in rest):
            return False
        last = rest[-1].text
        return (
            last.isalpha() and len(last) > 2 and last not in _NOT_NOUNS and last not in lx.LOCATION_NOUNS
            and last not in lx.SKIPPABLE and last not in lx.DESIRE and last not in lx.COLOR_WORDS
            and last not in lx.SIZE_WORDS
        )

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
        if kind in ("topic", "describe", "empty") and c.verb is None and _imperative_be(c.tokens):
            return "manner"  # "be a dear and ...", "be careful": what the robot is to be; its noun is no object
        return kind

    @staticmethod
    def _held_end_state(c: Clause) -> bool:
        """The object in the robot's gripper as the end state: "I want the key held in your
        gripper", "the key should end up in your hand": picked up. The relation to the gripper is
        the pick's end state, no destination (and is dropped; "off the counter" still says where
        it was)."""
        held = [
            g for g in c.placements()
            if not g.refs and g.places and all(p.split()[-1] in GRIPPER_WORDS for p in g.places)
        ]
        verb = c.verb
        if not held or len(c.bare) != 1 or c.recipient or c.negation:
            return False
        if verb is None and not (c.desire or c.intro == "result"):
            return False  # "the key is in your hand": a description
        if verb is not None and verb.verb_class not in ("pick", "place"):
            return False
        for g in held:
            c.governed.remove(g)
        for g in c.governed:
            if g.relation == "reverse":
                g.follows = "bare"  # "..., off the counter": where the object is lifted from
        return True

    def _action_kind(self, c: Clause) -> str:
        if c.verb is not None and c.verb.lemma in GRIP_VERBS and any(
            p.split()[-1] in GRIPPER_WORDS for p in c.bare_places
        ):
            held = [g for g in c.governed if g.phrase in _GRIPPED_BY and g.refs]
            if c.verb.lemma in _CLOSING and not c.bare and len(held) == 1:
                c.bare.extend(held[0].refs)  # "close the gripper around the can": grasps the can
                c.governed.remove(held[0])
                return "pick"
            return "preamble"  # "open the gripper": a step of the motion, not another task
        if c.covers:
            return "place"
        if self._held_end_state(c):
            return "pick"
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
        if cls == "release" and object_places:
            return "place"  # "release it onto the cutting board": set down there
        if cls == "pick":
            if reverse or (reverse_particle and not object_places):
                c.reverse_pick = bool(reverse) and not c.recipient
                if c.reverse_pick and not object_places and (verb.lemma in lx.LIFT_VERBS or "up" in c.particles):
                    return "pick"  # "lift the hammer off the bench", "take the beaker up from the table": picked up
                return "other"  # "take the carrot off the plate": takes it away (merged before a placement)
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


_NOT_COORDINATED = GRIPPER_WORDS | {"there", "here", "you", "me", "us", "way", "down", "up", "left", "right"}
"""Places that "and" may join to an object without making a second object ("the cup and your hand")."""
_PERFECT = frozenset({"has", "have", "had"})
"""Desire words only before "to" ("has to be"); before a participle they make the perfect."""


def _says_when(relation: str, phrase: Sequence[Token], ahead: Token | None, fronted: bool = False) -> bool:
    """A relation completed by a time, not a place: "at three", "for an hour", "in a minute",
    "for about an hour", "by the end", "at the end, ..." opening a sentence (not "at the end of
    the shelf")."""
    if relation not in lx.TIME_RELATIONS or any(t.kind == "OBJ" for t in phrase):
        return False
    words = [w for t in phrase for w in t.text.split()]
    counted = [w for w in words if w not in lx.NUMBER_WORDS and not w.isdigit() and w not in lx.APPROXIMATORS]
    if not counted:
        clock = "the" not in words and any(w.isdigit() or w in lx.NUMBER_WORDS - {"a", "an", "of"} for w in words)
        return relation == "at" and clock  # "at three"
    if all(w in lx.TIME_WORDS for w in counted):
        return True
    of_follows = ahead is not None and ahead.kind == "REL" and ahead.text == "of"
    set_off = relation == "at" and fronted and ahead is not None and ahead.text == ","  # "at the end, ..."
    return (
        (relation in ("by", "in", "until", "till") or set_off)
        and counted == [counted[-1]] and counted[-1] in lx.TIME_BOUNDARIES and not of_follows
    )


def _imperative_be(tokens: Sequence[Token]) -> bool:
    """A clause that opens with the imperative "be" ("be a dear", "be quick"): its complement
    says how the addressee is to be (a predicate noun, never an object acted on)."""
    first = next((t for t in tokens if t.kind not in ("ADV", "PUNCT")), None)
    return first is not None and first.kind == "BE" and first.text == "be" and not any(t.kind == "VERB" for t in tokens)


def _finite(tok: Token) -> bool:
    """A finite verb, a modal or a form of "be": what follows a clause's subject ("the pen *goes* ...")."""
    if tok.kind in ("MODAL", "BE"):
        return True
    return tok.kind == "VERB" and tok.lemma is not None and tok.text != tok.lemma and not tok.text.endswith("ing")


def _coordinated(text: str) -> Ref:
    """A phrase joined by "and" to the object acted on, read as a place ("the side table"):
    another object all the same."""
    words = tuple(text.split())
    return Ref(text, FREE + " ".join(words), words=words, free_problem=f"'{text}' names no known object")


def _declarative(tokens: Sequence[Token]) -> str | None:
    """A clause that opens with a subject and a finite verb: "I'm wrapping a present", "the milk
    has been sitting out", "it's supposed to rain" ("be"), "my train leaves at five" ("verb": a
    form that is no imperative), "my son left his shoes in the hall", "the concert went well",
    "everyone was clapping" ("past": what happened); not addressed to the robot as a command.
    A greeting's addressee is no subject ("hello robot, today is a busy day"); a time noun may be
    one ("today is ...")."""
    k = 0
    time_subject = False
    while k < len(tokens):
        tok = tokens[k]
        if tok.kind in ("ADV", "CONJ", "PUNCT") or tok.text in ("so", "well", "anyway"):
            time_subject = tok.text in _TIME_NOUNS
            k += 1
        elif k > 0 and tokens[k - 1].kind == "ADV" and tok.text in lx.VOCATIVES and k + 1 < len(tokens) and tokens[k + 1].text == ",":
            time_subject = False
            k += 2  # "hello robot, ...": whom the greeting addresses
        else:
            break
    if k >= len(tokens):
        return None
    first = tokens[k]
    if time_subject and _finite(first):
        pass  # "today is a busy day": the time noun is the subject
    elif first.kind == "PERSON":
        if first.text in ("you", "yourself"):
            return None
        k += 1
    elif first.kind == "PRON" and first.text in ("it", "that", "this"):
        k += 1
    else:
        start = k
        while k < len(tokens) and tokens[k].kind in ("DET", "QUANT", "OBJ", "WORD") and tokens[k].text not in _PERFECT:
            if k > start and tokens[k].kind == "WORD" and _past_word(tokens, k) and any(
                t.kind in ("OBJ", "WORD") for t in tokens[start:k]
            ):
                return "past"  # "my daughter *left* her toys out"
            k += 1
        if k == start or not any(t.kind in ("OBJ", "WORD") for t in tokens[start:k]):
            return None
    if k >= len(tokens):
        return None
    finite = tokens[k]
    if finite.kind in ("BE", "AUX", "MODAL") or finite.text in _PERFECT:
        return "past" if finite.text in lx.PAST_FORMS else "be"
    if _finite(finite) and finite.kind == "VERB":
        return "past" if finite.text in lx.PAST_FORMS or finite.text.endswith("ed") else "verb"
    return None


_TIME_NOUNS = frozenset({"today", "tomorrow", "tonight", "yesterday"})


def _past_word(tokens: Sequence[Token], k: int) -> bool:
    """An unlisted word after a subject that is a verb's past form: an irregular one ("left",
    "came"), or a regular "-ed" form that no noun follows ("my sister painted the fence";
    not "the blue painted cup")."""
    w = tokens[k].text
    if w in lx.PAST_FORMS:
        return True
    nxt = tokens[k + 1] if k + 1 < len(tokens) else None
    return w.endswith("ed") and len(w) > 4 and w.isalpha() and (nxt is None or nxt.kind not in ("OBJ", "WORD"))


_FURNITURE = frozenset({"shelf", "desk", "counter", "countertop", "table"})
"""Place nouns that are objects of their own in open-vocabulary scenes ("put the mug on the shelf")."""
_SURFACE_PARTS = frozenset({"top", "surface", "tabletop"})
"""Head nouns that name a part of the object before them ("the cabinet top")."""
_NOT_NOUNS = frozenset(
    ["how", "about", "what", "where", "why", "when", "whether", "if", "as", "mind", "let", "please", "kindly", "thanks", "okay", "ok", "task", "job", "goal", "aim", "objective", "mission", "instruction", "instructions", "request", "idea", "plan", "step", "steps", "order", "favor", "favour", "time", "moment", "chance", "way", "thing", "things", "something", "anything", "everything", "nothing", "itself", "again", "too", "also", "first", "instead", "already", "anyway", "though", "so", "oh", "ok", "okay", "well", "alright", "hey", "hi", "yes", "yeah", "hmm", "um", "uh", "robot", "manipulator", "agent", "policy", "end", "episode", "trial", "beginning", "start", "success", "aim", "purpose", "percent", "degree", "degrees", "brightness", "lighting", "camera"]
)
"""Words that never belong to a free noun phrase (a phrase holding one is not an object)."""
_NOT_NOUN_NOUNS = frozenset(
    ["task", "job", "goal", "aim", "objective", "mission", "instruction", "request", "idea", "plan", "step", "order", "time", "way", "robot", "end", "start", "camera"]
)
"""Those of them that are nouns: they may still be the first noun of a compound ("the *step*
stool", "the *camera* bag"); as a head, or outside the head's compound, they still are no object."""


def _free_words(words: tuple[str, ...]) -> tuple[str, ...]:
    """A free phrase in head-final order: "bottle of wine" -> "wine bottle"; quantifiers dropped."""
    words = tuple(w for w in words if w not in lx.QUANTIFIERS)
    if "of" in words[1:-1]:
        k = words.index("of")
        if words[k - 1] in lx.MEASURE_NOUNS:
            return words[k + 1 :]  # "stick of chalk": chalk
        if words[k - 1] in lx.CONTAINER_NOUNS:
            return (*words[k + 1 :], *words[:k])
    return words


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


_COVER_VERBS = frozenset({"cover", "cap", "top"})


def _cover_with(c: Clause) -> None:
    """ "cover the pot with the lid": put the lid on the pot."""
    if c.verb is None or c.verb.lemma not in _COVER_VERBS or len(c.bare) != 1:
        return
    withs = [g for g in c.governed if g.phrase == "with" and len(g.refs) == 1]
    if len(withs) != 1 or c.placements():
        return
    covered = c.bare.pop()
    c.bare.append(withs[0].refs[0])
    withs[0].relation, withs[0].phrase, withs[0].directional, withs[0].refs = "on", "on", True, [covered]
    c.covers = True


def _kind_by_wordnet(noun: str) -> str | None:
    """What WordNet says a thing an object is carried to is: a container ("the beaker", "the hamper") holds it;
    a table, a seat, a bed or a support ("the desk", "the bench", "the stand") has it on top; else None (it stays
    near: "the lamp", furniture too, is no place to put things on)."""
    from ladev_lib.language.wordnet import default_nouns

    nouns = default_nouns()
    words = [w for w in noun.lower().split() if w not in lx.DETERMINERS]
    if nouns is None or not words:
        return None
    phrase = " ".join(words)
    if nouns.is_a(phrase, "container"):
        return "in"
    if any(nouns.is_a(phrase, kind) for kind in ("table", "seat", "bed", "support", "platform")):
        return "on"
    return None
