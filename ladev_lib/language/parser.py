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
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from ladev_lib.catalog import Catalog, load_catalog
from ladev_lib.catalog.catalog import normalize_name
from ladev_lib.language import lexicon as lx
from ladev_lib.language.clauses import (
    FREE,
    PLACEMENT,
    TASK_OF_RELATION,
    Clause,
    ClauseReader,
    Governed,
    Ref,
    split_clauses,
)
from ladev_lib.language.frames import Frame, NounPhrase, Qualifier
from ladev_lib.language.mentions import name_index
from ladev_lib.language.tasks import TASKS
from ladev_lib.language.tokens import tag_tokens

_ACTIONS = frozenset({"pick", "place", "place_nodest", "other", "release"})


_SPOKEN = (
    (r"full stop|period|new line|new paragraph", "."), (r"comma", ","), (r"question mark", "?"),
    (r"exclamation (?:mark|point)", "!"), (r"colon", ":"),
)


def _spoken_punctuation(text: str) -> str:
    """Punctuation said in words by someone dictating ("... in the basket full stop", "comma please") as the marks
    themselves; the same words after a determiner stay words ("the trial period")."""
    for said, mark in _SPOKEN:
        text = re.sub(rf"(?i)(?<!\bthe )(?<!\ba )\b(?:{said})\b(?=\s*(?:$|[.!?,;]|(?:please|thanks|thank you|then|and|"
                      rf"okay|ok|now|next|after that|robot)\b))", f"{mark} ", text)
    return re.sub(r"[ \t]{2,}", " ", re.sub(r"\s+([.,!?:])", r"\1", text)).strip()


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
        """The relations that state the task (not those that describe a phrase)."""
        return [g for c in self.clauses for g in c.governed if g.qualifier is None]

    def qualifiers(self, role: str) -> list[Governed]:
        return [g for c in self.clauses for g in c.governed if g.qualifier == role]


def _mark_qualifiers(act: _Action) -> None:
    """Relations that describe a phrase rather than state the task.

    "pick up the bowl *next to the plate* and put it on the tray": the first
    relation locates the object; "put it in the compartment *of the caddy*":
    the "of" phrase belongs to the destination. A stative relation right
    after the acted-on phrase (or chained after such a one) is the object's
    only when another relation is left to be the destination; a relation in
    a pick clause that was merged into a placement always is.
    """
    if act.kind not in ("place", "pick"):
        return
    potential: list[Governed] = []
    for c in act.clauses:
        merged_pick = (act.kind == "place" and c.kind == "pick") or c.reverse_pick
        prev: Governed | None = None
        for g in c.governed:
            if g.qualifier is not None:
                prev = g
                continue  # already read ("set it *on top*" completing a destination)
            if merged_pick and (g.refs or g.places) and _locates(g):
                g.qualifier = "object"
            elif not g.directional and _locates(g) and (
                g.follows == "bare" or (g.follows == "governed" and prev is not None and prev in potential)
            ):
                potential.append(g)
            prev = g
    if act.kind == "pick":
        for g in potential:
            g.qualifier = "object"
        return
    rest = [g for c in act.clauses for g in c.governed if g.qualifier is None and g not in potential]
    if any(g.relation in PLACEMENT and g.refs for g in rest):
        for g in potential:
            g.qualifier = "object"
    # "of" right after the destination phrase: part of it ("the back compartment of the caddy"); a
    # relative clause after it describes it ("on the plate *that is on the shelf*")
    for c in act.clauses:
        for prev, g in zip(c.governed, c.governed[1:], strict=False):
            after_destination = g.follows == "governed" and prev.qualifier is None and prev.relation in PLACEMENT
            describes = g.phrase == "of" or (g.relative and g.qualifier is None and bool(prev.refs))
            if after_destination and describes:
                g.qualifier = "destination"
            elif g.phrase == "of" and g.follows == "governed" and prev.qualifier == "object":
                g.qualifier = "object"
            elif (
                g.follows == "governed" and prev.qualifier is None and prev.relation in PLACEMENT and prev.refs
                and not g.refs and _names_a_position(g)
            ):
                g.qualifier = "destination"  # "in the drawer *at the back*": which part, or which one


def _resolve_pronouns(clauses: list[Clause]) -> None:
    """A pronoun acted on is the object acted on before (the focus); a pronoun a relation
    governs is, where the clause acts on the focus, the object named last besides it ("carry
    them over to the box and drop them inside *it*": the box). "them" stands for a group only."""
    focus: str | None = None
    named: list[str] = []  # objects named so far, the latest last
    plural: dict[str, bool] = {}
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
                plural[focus] = ref.plural
                named.append(focus)
        moved = {r.object_id for r in c.bare if r.object_id is not None}
        for g in c.governed:
            for ref in g.refs:
                if ref.pronoun:
                    other = next((o for o in reversed(named) if o not in moved), None) if focus in moved else None
                    ref.object_id = other or focus
                    if ref.object_id is None:
                        pending.append(ref)
                elif ref.object_id is not None:
                    plural[ref.object_id] = ref.plural
                    named.append(ref.object_id)
                    if c.kind == "preamble" and not c.bare:
                        focus = ref.object_id  # "move to the ladle, grasp it"
    later = next((r.object_id for c in clauses for r in c.bare if not r.pronoun and r.object_id), None)
    for ref in pending:
        ref.object_id = later
        if later is None:
            ref.problem = f"'{ref.text}' refers to no object named in the instruction"
    for c in clauses:
        for ref in c.refs():
            if ref.pronoun and ref.plural and ref.object_id is not None and not plural.get(ref.object_id, False):
                ref.problem = f"'{ref.text}' means more than one object"


def _mark_context(clauses: list[Clause]) -> None:
    """Statements around a command that do not address the robot: "I'm wrapping a present later,
    so pick up the scissors", "the milk has been sitting out for an hour; put it in the fridge",
    "my meeting starts at three - move ...", "my son broke a glass, so ...". A clause that asks
    for none of the tasks, opens with a subject and a finite verb (or says when something
    happens), wishes for no object and adds nothing ("too", "next") is context: its phrases are
    neither steps nor other objects (they may still be what a pronoun stands for). A finite verb
    with a destination ("the cup goes on the plate") states the end state instead."""
    if not any(c.kind in _ACTIONS for c in clauses):
        return
    for c in clauses:
        stated = c.declarative in ("verb", "past") and c.kind in ("place_nodest", "other", "preamble", "release")
        # "my son left his socks on the rug": what happened, in a verb the lexicon does not list
        stated = stated or (c.declarative == "past" and c.kind == "place" and c.verb is None)
        # "the door is closed", "I'm wrapping a present": a state or an event in progress, no task verb
        stated = stated or (
            c.declarative == "be" and c.kind == "other" and c.verb is not None and c.verb.text != c.verb.lemma
        )
        if c.kind not in ("describe", "topic", "empty") and not stated or c.negation or c.intro == "result":
            continue
        wish = c.desire and any(not r.pronoun for r in c.bare)
        # "the pear is next", "the pear too"; in a statement of the past ("my son left his shoes out
        # again") such a word says what happened, not what to do
        adds = c.declarative != "past" and any(t.text in _ADDITIVE for t in c.tokens)
        if (c.declarative or c.temporal) and not wish and not adds:
            c.kind = "context"


def _mark_topics(clauses: list[Clause]) -> None:
    """ "the banana on the table, lift it": a verbless phrase taken up by a later pronoun."""
    for k, c in enumerate(clauses):
        taken_up = any(r.pronoun for later in clauses[k + 1 :] for r in later.bare)
        if c.verb is None and c.bare and c.kind == "place" and taken_up:
            c.kind = "topic"


_CHAINING = frozenset({"and", "then", "and then", ","})
_ADDITIVE = frozenset({"too", "also", "next", "again", "either", "another", "other"})
"""Words that add to what was asked: a statement holding one ("the pear is next") is no context."""


def _elided_objects(clauses: list[Clause]) -> None:
    """ "lift the bowl from the stove and move to the plate": the object of a pick,
    left out after it, is what "move" carries (alone, "move to the plate" moves the robot)."""
    for prev, c in zip(clauses, clauses[1:], strict=False):
        picked = (prev.kind == "pick" or prev.reverse_pick) and bool(prev.bare) and not prev.negation
        if (
            picked
            and c.kind == "preamble"
            and c.verb is not None
            and c.verb.lemma == "move"
            and not c.bare
            and not c.negation
            and (c.intro or "") in _CHAINING
            and any(g.refs for g in c.governed if g.relation in PLACEMENT or g.phrase in _OVER)
        ):
            c.bare.append(Ref("it", pronoun=True))
            c.kind = "place"


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
    if fronted_a and b.kind == "place" and any(g.refs and g.relation in PLACEMENT for g in b.governed()):
        for c in a.clauses:
            for g in c.governed:
                g.qualifier = "context"  # "on the counter, move the jar next to the bowl": where it all happens
        return _Action("place", both)
    if a.kind == "place_nodest" and fronted_b:
        return _Action("place", both)
    if not _same_object(a, b):
        return None
    picked_from = a.kind == "other" and all(c.reverse_pick for c in a.clauses)
    if (a.kind == "pick" or picked_from) and b.kind in ("place", "pick"):
        return _Action(b.kind, both)  # "grab the hammer and lift it off the bench": one pick-up
    reordered = any((c.intro or "") in ("after", "before", "once") for c in both)
    if reordered and {a.kind, b.kind} == {"pick", "place"}:
        return _Action("place", both)  # "put it on the plate after picking up the carrot"
    if a.kind == "place_nodest" and b.kind == "place":
        return _Action("place", both)
    if a.kind == "place" and b.kind == "place" and _completes_destination(a, b):
        return _Action("place", both)  # "bring it over to the rack and set it on top"
    if a.kind == "place" and b.kind == "release":
        return _Action("place", both)
    lowers = b.kind == "place_nodest" and b.clauses[-1].verb is not None and b.clauses[-1].verb.lemma in _SET_DOWN
    if a.kind == "place" and lowers and any(g.refs and g.phrase in _OVER for g in a.governed()):
        return _Action("place", both)  # "move it above the board, lower it ...": a step of setting it down there
    there = any(t.text in ("there", "here") for c in b.clauses for t in c.tokens)
    if a.kind == "place" and lowers and there and any(g.refs and g.relation in PLACEMENT for g in a.governed()):
        return _Action("place", both)  # "bring it over by the cooler and put it down there": where it was brought
    if a.kind == "place" and b.kind == "place" and _over_then_onto(a, b):
        return _Action("place", both)  # "move it above the board ... release it onto the board"
    rests_there = b.kind == "place_nodest" and all(
        set(c.bare_places) & _SAME_PLACE or any(t.text in ("there", "here") for t in c.tokens) for c in b.clauses
    )
    if a.kind == "place" and (b.kind == "place" or rests_there) and all((c.intro or "") == "result" for c in b.clauses):
        ends = [{r.object_id for g in act.governed() if g.relation in PLACEMENT for r in g.refs} for act in (a, b)]
        there = not ends[1] and all(set(g.places) <= _SAME_PLACE for g in b.governed() if g.relation in PLACEMENT)
        if ends[0] and (ends[0] == ends[1] or there):
            for c in b.clauses:
                for g in c.governed:
                    if not g.refs:
                        g.qualifier = "completes"  # "... so that it rests there"
            return _Action("place", both)  # "... release it so that it rests inside the pot": the end state again
    leaves = b.kind == "place_nodest" and b.clauses[-1].verb is not None and b.clauses[-1].verb.lemma == "leave"
    if a.kind == "place" and leaves:
        return _Action("place", both)  # "... and leave it there"
    return None


_SET_DOWN = frozenset({"lower", "drop", "set", "put", "place", "lay", "rest"})
"""Verbs that set down, without a destination, what was just carried somewhere ("lower it")."""


def _over_then_onto(a: _Action, b: _Action) -> bool:
    """``a`` brings the object over a thing only (no placement); ``b`` sets it on / in that thing."""
    over = [g for g in a.governed() if g.refs and g.phrase in _OVER]
    if len(over) != 1 or any(g.relation in PLACEMENT and g.refs for g in a.governed()):
        return False
    placed = [g for g in b.governed() if g.refs and g.relation in PLACEMENT]
    return bool(placed) and {r.object_id for g in placed for r in g.refs} == {r.object_id for r in over[0].refs}


_SAME_PLACE = frozenset({"top", "there", "top of it"})
_OVER = frozenset({"over", "above"})
"""Relations that bring an object above another before a later step sets it down in / on it."""
"""Places that stand for the destination just named ("set it on top", "drop it in there")."""


def _completes_destination(a: _Action, b: _Action) -> bool:
    """``b`` only says how ``a``'s object ends at ``a``'s destination: "carry the cup over to the
    tray and set it on top" puts it on the tray. ``a`` must carry the object *to* an object (a
    directional "near"); ``b`` names no object of its own to put it on. The relation is ``b``'s."""
    towards = [g for g in a.governed() if g.refs and (g.relation in PLACEMENT or g.phrase in _OVER)]
    over = len(towards) == 1 and towards[0].phrase in _OVER  # "move it over the drawer, lower it inside"
    if len(towards) != 1 or not (over or (towards[0].directional and towards[0].relation in ("near", *PLACEMENT))):
        return False
    completing = [g for g in b.governed() if g.relation in PLACEMENT]
    # "set it on top" / "drop it in there", or the same object again: "bring it over toward the
    # window and set it down next to the window", "carry them over to the box and drop them inside it"
    there = {r.object_id for r in towards[0].refs}
    if not completing or any(
        not {r.object_id for r in g.refs} <= there or not set(g.places) <= _SAME_PLACE for g in completing
    ):
        return False
    if any(r for r in b.bare() if not r.pronoun) or len({g.relation for g in completing}) != 1:
        return False
    relation = completing[0].relation
    if towards[0].relation not in ("near", relation) and not over:
        return False
    towards[0].relation = relation
    for g in completing:
        g.qualifier = "completes"
    return True


class _Composer:
    def __init__(
        self,
        text: str,
        clauses: list[Clause],
        in_scene: bool = False,
        head_nouns: Callable[[str], set[str]] | None = None,
    ) -> None:
        self.text = text
        self.clauses = clauses
        self.in_scene = in_scene
        self.head_nouns = head_nouns
        """A catalog object's head nouns ("lid" for the skillet lid), to tell two phrases apart."""
        """Read in a scene's context: two phrases the catalog reads as one object ("the small
        bowl", "the large bowl") may be two objects of the scene; grounding tells."""
        self.reasons: list[str] = []

    def compose(self) -> Frame:
        _mark_topics(self.clauses)
        _mark_context(self.clauses)
        _elided_objects(self.clauses)
        _resolve_pronouns(self.clauses)
        negated = [c for c in self.clauses if c.negation and c.kind != "manner"]
        positive = [
            _Action(c.kind, [c])
            for c in self.clauses
            if not c.negation and (c.kind in _ACTIONS or (c.kind == "place" and c.verb is None))
        ]
        actions = _merge(positive)
        for act in actions:
            _mark_qualifiers(act)
        task: str | None = None
        source: Ref | None = None
        target: Ref | None = None
        main: _Action | None = None
        extra: list[str] = []
        dropped: list[str] = []
        if not actions:
            if negated:
                self.reasons.append(f"negated: '{negated[0].negation} {negated[0].verb_text()}'")
            else:
                self.reasons.append("no task verb found")
        else:
            if len(actions) > 1:
                extra = [a.verb for a in actions[1:]]
                word = "alternative action" if any(c.intro == "or" for a in actions for c in a.clauses) else "extra step"
                self.reasons.append(f"{word}: {', '.join(repr(e) for e in extra)} after '{actions[0].verb}'")
            main = actions[0]
            task, source, target = self._roles(main)
            if main.kind == "place_nodest":
                dropped.append("destination")
        if not self.in_scene and source is not None and target is not None:
            self._tell_apart(source, target)  # "put the lid on the pan": the catalog's "pan lid" is not the pan
        src_id = source.object_id if source else None
        tgt_id = target.object_id if target else None
        told_apart = self.in_scene and source is not None and target is not None and source.words != target.words
        if src_id is not None and src_id == tgt_id and not told_apart:
            self.reasons.append(f"the same object is source and destination: {_shown(src_id)}")
        repeat = next((c.repeat for c in self.clauses if c.repeat), None)
        if repeat:
            self.reasons.append(f"'{repeat}' asks for the task more than once")
        negated_task = self._check_negations(negated, src_id)
        self._check_mentions(main, negated, src_id, tgt_id)
        notes = tuple(r.note for c in self.clauses for r in c.refs() if r.note)
        conditions = tuple(
            " ".join(t.text for t in c.tokens) for c in self.clauses if c.kind == "manner" or c.intro == "result"
        )
        reason = "; ".join(dict.fromkeys(self.reasons)) or None
        return Frame(
            text=self.text,
            task=task,
            object=self._phrase(source, main.qualifiers("object") if main else []),
            destination=self._phrase(target, main.qualifiers("destination") if main else []),
            negated=negated_task or (not actions and bool(negated)),
            extra_steps=tuple(extra),
            dropped_roles=tuple(dropped),
            conditions=conditions,
            reason=reason,
            notes=notes,
        )

    def _tell_apart(self, source: Ref, target: Ref) -> None:
        """Two phrases with different words that the catalog reads as one object name two objects:
        the one whose head noun is not a head noun of the object's names is free text."""
        if source.object_id is None or source.object_id != target.object_id or source.free:
            return
        if not source.words or not target.words or source.words == target.words:
            return
        heads = self.heads_of(source.object_id)
        for ref in (target, source):
            if ref.words[-1] not in heads:
                ref.object_id = FREE + " ".join(ref.words)
                return

    def heads_of(self, object_id: str) -> set[str]:
        return self.head_nouns(object_id) if self.head_nouns is not None else set()

    def _phrase(self, ref: Ref | None, qualifiers: list[Governed] | None = None) -> NounPhrase | None:
        """The noun phrase of a role: the antecedent's words for a pronoun; its qualifiers."""
        if ref is None or ref.object_id is None:
            return None
        quals = tuple(
            Qualifier(
                _qualifier_relation(g),
                tuple(p for p in (self._phrase(r) for r in g.refs) if p is not None),
                tuple(g.places),
            )
            for g in qualifiers or []
        )
        if ref.pronoun or not ref.words:
            named = next(
                (r for c in self.clauses for r in c.refs() if r.object_id == ref.object_id and not r.pronoun and r.words),
                None,
            )
            ref = named or ref
        words = ref.words or tuple(ref.text.split())
        free = ref.object_id is not None and ref.object_id.startswith(FREE)
        if free:
            assert ref.object_id is not None
            words = tuple(ref.object_id[len(FREE) :].split())
        words = words or (ref.text,)
        return NounPhrase(
            " ".join(words), words[-1], tuple(words[:-1]), None if free else ref.object_id, quals, ref.candidates
        )

    def _roles(self, act: _Action) -> tuple[str | None, Ref | None, Ref | None]:
        task: str | None = None
        if act.kind == "pick":
            task = "pick_up"
        elif act.kind == "place":
            task = self._placement_task(act)
        elif act.kind == "place_nodest":
            self.reasons.append(f"'{act.verb}' without a destination")
        elif act.kind == "release":
            task = "other"
            self.reasons.append(f"'{act.verb}' is not one of the tasks")
        else:
            task = "other"
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

    def _one(self, refs: list[Ref], role: str, required: bool) -> Ref | None:
        for r in refs:
            if r.problem:
                self.reasons.append(r.problem)
            if r.quantity:
                self.reasons.append(f"'{r.text}' asks for a quantity")
        ids = list(dict.fromkeys(r.object_id for r in refs if r.object_id))
        said = {r.words for r in refs if r.object_id and not r.pronoun and r.words}
        if len(ids) == 1 and len(said) > 1 and not self.in_scene:
            heads = self.heads_of(ids[0])
            if any(w[-1] not in heads for w in said):  # "the pan and the lid": two objects, one catalog name
                self.reasons.append(f"more than one {role}: " + ", ".join(" ".join(w) for w in sorted(said)))
        if len(ids) > 1:
            self.reasons.append(f"more than one {role}: {', '.join(_shown(i) for i in ids)}")
        if not ids and required and not any(r.problem for r in refs):
            self.reasons.append(f"no {role} named")
        return next(r for r in refs if r.object_id == ids[0]) if ids else None

    def _check_negations(self, negated: list[Clause], source: str | None) -> bool:
        found = False
        for c in negated:
            ids = {r.object_id for r in c.refs() if r.object_id}
            if source is not None and source not in ids and ids:
                continue  # an exclusion: "pick up the coke can, not the pepsi can"
            if source is not None:
                found = True
                self.reasons.append(f"negated: '{c.negation} {c.verb_text()}'")
        return found

    def _check_mentions(
        self, main: _Action | None, negated: list[Clause], source: str | None, target: str | None
    ) -> None:
        in_main = {id(c) for c in main.clauses} if main else set()
        excluded = {id(c) for c in negated}
        described = {id(r) for c in (main.clauses if main else []) for g in c.governed if g.qualifier for r in g.refs}
        # "there's a can on the table. pick it up", "the banana on the table, lift it": a description of
        # the object acted on; its landmarks say where that object is
        described |= {
            id(r)
            for c in self.clauses
            if c.kind in ("describe", "topic") and source is not None and any(b.object_id == source for b in c.bare)
            for g in c.governed
            for r in g.refs
        }
        for c in self.clauses:
            if c.kind in ("manner", "context") or id(c) in excluded:
                continue
            if c.alternatives:
                self.reasons.append("alternative objects ('or')")
            for r in c.refs():
                if id(r) in described:
                    continue
                if id(c) not in in_main and r.problem:
                    self.reasons.append(r.problem)
                if r.object_id and r.object_id not in (source, target):
                    self.reasons.append(f"mentions another object: {_shown(r.object_id)}")


_NOT_LOCATING = frozenset({"with", "for", "through", "across", "against", "around", "over", "along"})


def _names_a_position(g: Governed) -> bool:
    """A relation completed by a position alone ("at the back", "on the left")."""
    words = [w for p in g.places for w in p.split()]
    return bool(words) and all(
        lx.position_word(w) in lx.OPPOSITE_POSITIONS or w in lx.POSITION_NOUNS for w in words
    )


def _locates(g: Governed) -> bool:
    """Whether a relation can say where a thing is ("next to", "on", "from", "between"; not "with")."""
    return g.phrase not in _NOT_LOCATING


def _qualifier_relation(g: Governed) -> str:
    """near | on | in | from | the relation word itself ("between", "of")."""
    if g.relation in PLACEMENT:
        return g.relation
    if g.relation == "reverse":
        return "from"
    return g.phrase


def _shown(key: str) -> str:
    """A role key as shown in reasons: a catalog id, or a free phrase in quotes."""
    return f"'{key[len(FREE):]}'" if key.startswith(FREE) else key


def to_parse(frame: Frame, free_problems: dict[str, str] | None = None) -> InstructionParse:
    """The catalog-only view of a frame: roles as catalog ids; a free phrase in a role is a reason."""
    reasons = [frame.reason] if frame.reason else []
    ids: list[str | None] = []
    for phrase in (frame.object, frame.destination):
        if phrase is not None and phrase.free:
            reasons.append((free_problems or {}).get(phrase.text) or f"'{phrase.text}' names no known object")
        ids.append(phrase.object_id if phrase is not None else None)
    task = frame.task if frame.task in TASKS else None
    return InstructionParse(frame.text, task, ids[0], ids[1], "; ".join(dict.fromkeys(reasons)) or None, frame.notes)


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

    def read(self, text: str, scene_objects: Iterable[str] | None = None) -> Frame:
        """The frame of an instruction (noun phrases the catalog does not name stay free)."""
        return self._read(text, scene_objects)[0]

    def parse(self, text: str, scene_objects: Iterable[str] | None = None) -> InstructionParse:
        """The catalog-only view: roles as catalog ids (a free phrase in a role is a reason)."""
        frame, problems = self._read(text, scene_objects)
        return to_parse(frame, problems)

    def _read(self, text: str, scene_objects: Iterable[str] | None) -> tuple[Frame, dict[str, str]]:
        scene = frozenset(scene_objects) if scene_objects else None
        if not text or not text.strip():
            return Frame(text, None, reason="empty instruction"), {}
        tokens = tag_tokens(_spoken_punctuation(text), self.index)
        reader = ClauseReader(self.index, scene)
        clauses = [reader.read(c) for c in split_clauses(tokens)]
        if not clauses:
            return Frame(text, None, reason="no words to read"), {}
        problems = {
            r.object_id[len(FREE) :]: r.free_problem
            for c in clauses
            for r in c.refs()
            if r.free and r.object_id is not None and r.free_problem
        }
        composer = _Composer(text, clauses, in_scene=scene is not None, head_nouns=self.index.head_nouns)
        return composer.compose(), problems

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


def default_parser(catalog: Catalog | None = None) -> InstructionParser:
    """The parser of a catalog (the default catalog when None), built once."""
    cat = catalog or load_catalog()
    parser = _DEFAULT.get(id(cat))
    if parser is None or parser.catalog is not cat:
        parser = InstructionParser(cat)
        _DEFAULT[id(cat)] = parser
    return parser


def parse_instruction(
    text: str, scene_objects: Iterable[str] | None = None, catalog: Catalog | None = None
) -> InstructionParse:
    """Parse one instruction into catalog ids (parser cached per catalog)."""
    return default_parser(catalog).parse(text, scene_objects)
