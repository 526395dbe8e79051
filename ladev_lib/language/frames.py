"""Frames over free noun phrases: what an instruction asks for, read once.

    read_instruction("put the wine bottle on the rack")
    -> Frame(task="put_on", object=NounPhrase("wine bottle", head="bottle", modifiers=("wine",)),
             destination=NounPhrase("rack", head="rack"), ok=True)
    read_instruction("pick up the bowl and place it on the plate").task == "put_on"

The reader is the one instruction parser (``parser`` on ``tokens``,
``clauses``, ``mentions``, ``lexicon``). Noun phrases need not be catalog
names: a phrase the catalog does not know stays free text (``object_id`` is
None) and is grounded later, against a scene's objects or the catalog, by
:mod:`ladev_lib.language.grounding`. ``object_id`` is set only where the
phrase is a catalog name or synonym (or, with ``scene_objects``, a head noun
that fits one scene object).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from ladev_lib.catalog import Catalog


@dataclass(frozen=True)
class Qualifier:
    """A relation that describes a phrase: "(the bowl) next to the plate", "(the slot) of the caddy"."""

    relation: str
    """near | on | in | from | another relation word ("between", "of", "at")."""
    landmarks: tuple[NounPhrase, ...] = ()
    places: tuple[str, ...] = ()
    """Landmarks that are places, not objects ("the table center")."""

    def as_dict(self) -> dict[str, Any]:
        return {
            "relation": self.relation,
            "landmarks": [p.as_dict() for p in self.landmarks],
            "places": list(self.places),
        }


@dataclass(frozen=True)
class NounPhrase:
    """An object as written: "the small wine bottle" -> text "small wine bottle", head "bottle"."""

    text: str
    """The phrase without its determiner, normalised (lower case, single spaces)."""
    head: str
    """Its head noun ("bottle"); for "a can of coke" the named thing ("coke")."""
    modifiers: tuple[str, ...] = ()
    """The words before the head ("small", "wine")."""
    object_id: str | None = None
    """The catalog id when the phrase is a catalog name or synonym; None for free text."""
    qualifiers: tuple[Qualifier, ...] = ()
    """Relations that locate or specify it ("the black bowl *next to the ramekin*")."""
    candidates: tuple[str, ...] = ()
    """For a free phrase the catalog reads as several objects ("the can"): those objects. It
    names none of them until a scene tells which."""

    @property
    def free(self) -> bool:
        return self.object_id is None

    def as_dict(self) -> dict[str, Any]:
        return {
            "text": self.text,
            "head": self.head,
            "modifiers": list(self.modifiers),
            "object_id": self.object_id,
            "qualifiers": [q.as_dict() for q in self.qualifiers],
            "candidates": list(self.candidates),
        }


@dataclass(frozen=True)
class Frame:
    """What one instruction asks for.

    ``task`` is one of :data:`ladev_lib.language.tasks.TASKS`, ``"other"``
    (an action outside the four) or None (no action read). ``reason`` says
    why the text does not state one task of the four clearly; ``ok`` when it
    does.
    """

    text: str
    task: str | None
    object: NounPhrase | None = None
    destination: NounPhrase | None = None
    negated: bool = False
    extra_steps: tuple[str, ...] = ()
    """Actions asked for beyond the task ("'shake' after 'put'")."""
    dropped_roles: tuple[str, ...] = ()
    """Roles the task needs that the text leaves out ("destination")."""
    conditions: tuple[str, ...] = ()
    """Conditions and constraints read but not part of the task ("so it doesn't fall")."""
    reason: str | None = None
    notes: tuple[str, ...] = ()
    """How names were resolved when not by an exact catalog name."""

    @property
    def ok(self) -> bool:
        return self.reason is None

    @property
    def roles(self) -> tuple[str | None, str | None, str | None]:
        """(task, object text, destination text)."""
        return (
            self.task,
            self.object.text if self.object else None,
            self.destination.text if self.destination else None,
        )

    def as_dict(self) -> dict[str, Any]:
        return {
            "task": self.task,
            "object": self.object.as_dict() if self.object else None,
            "destination": self.destination.as_dict() if self.destination else None,
            "negated": self.negated,
            "extra_steps": list(self.extra_steps),
            "dropped_roles": list(self.dropped_roles),
            "conditions": list(self.conditions),
            "ok": self.ok,
            "reason": self.reason,
            "notes": list(self.notes),
        }


def read_instruction(
    text: str, scene_objects: Iterable[str] | None = None, catalog: Catalog | None = None
) -> Frame:
    """Read one instruction (or the task sentence of a description) into a frame.

    ``scene_objects`` (catalog ids) lets head nouns resolve to the one scene
    object they fit; without it the catalog is used and unknown nouns stay
    free phrases.
    """
    from ladev_lib.language.parser import default_parser

    return default_parser(catalog).read(text, scene_objects)
