"""The four tasks and the words that name them: the one definition.

    TASKS == ("pick_up", "move_near", "put_on", "put_in")
    task_of_relation("on") == "put_on";  relation_of_task("put_in") == "in"

Every module that lists the tasks, or maps a relation word to a task, imports
it from here. A reading that asks for something else is ``NOT_A_TASK``.
"""

from __future__ import annotations

from ladev_lib.vocabulary import TASKS as TASKS
from ladev_lib.vocabulary import TaskType as TaskType

NOT_A_TASK = "other"
"""The task of a reading that asks for an action outside the four ("open the drawer")."""

RELATION_TASKS: dict[str, TaskType] = {"near": "move_near", "on": "put_on", "in": "put_in"}
"""Relation kind -> placement task (the lexicon's relation phrases map to these kinds)."""
PLACEMENT_RELATIONS: frozenset[str] = frozenset(RELATION_TASKS)
PLACEMENT_TASKS: frozenset[str] = frozenset(RELATION_TASKS.values())
"""Tasks that need a destination object."""

TASK_VERBS: dict[TaskType, str] = {
    "pick_up": "pick up",
    "move_near": "move",
    "put_on": "put",
    "put_in": "put",
}
TASK_RELATION_WORDS: dict[TaskType, str | None] = {
    "pick_up": None,
    "move_near": "near",
    "put_on": "on",
    "put_in": "in",
}
"""The verb and relation word of each task's short form ("move the X near the Y")."""


def task_of_relation(kind: str) -> TaskType | None:
    """The placement task of a relation kind (near / on / in), else None."""
    return RELATION_TASKS.get(kind)


def relation_of_task(task: str) -> str | None:
    for kind, t in RELATION_TASKS.items():
        if t == task:
            return kind
    return None


def needs_destination(task: str) -> bool:
    return task in PLACEMENT_TASKS


def is_task(name: str) -> bool:
    return name in TASKS
