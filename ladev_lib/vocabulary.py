"""The study's closed vocabularies: the one definition of each, imported everywhere.

    TASKS == ("pick_up", "move_near", "put_on", "put_in")
    as_task("put_on")  -> "put_on" typed TaskType;  as_task("stack") raises ValueError

Tasks, robots, object roles, object sets, study factors and their environment
levels, instruction and control kinds, episode statuses. Each is a ``Literal``
type for the checker and a tuple of its values for code that lists them (CLI
choices, report table order, validators). A ``str`` from a file or a column
becomes one of these types through :func:`narrow` (or its ``as_*`` helpers),
which checks the value instead of asking the type checker to trust it.

This is the base layer: it imports nothing of the library. The language
layer's task words (verbs, relation words) live in
:mod:`ladev_lib.language.tasks`, over these names.
"""

from __future__ import annotations

from typing import Literal, TypeVar, get_args

TaskType = Literal["pick_up", "move_near", "put_on", "put_in"]
TASKS: tuple[TaskType, ...] = get_args(TaskType)
TASKS_WITH_TARGET: frozenset[TaskType] = frozenset({"move_near", "put_on", "put_in"})
"""Tasks that need a destination object."""

Robot = Literal["panda", "widowx", "google_robot"]
ROBOTS: tuple[Robot, ...] = get_args(Robot)

Role = Literal["source", "target", "distractor"]
ROLES: tuple[Role, ...] = get_args(Role)

ObjectSetName = Literal["simpler", "ycb"]
OBJECT_SETS: tuple[ObjectSetName, ...] = get_args(ObjectSetName)

Factor = Literal["num_objects", "instruction", "object_set", "environment"]
FACTORS: tuple[Factor, ...] = get_args(Factor)

Environment = Literal["default", "lighting", "camera"]
ENVIRONMENTS: tuple[Environment, ...] = get_args(Environment)

InstructionKind = Literal["basic", "paraphrase", "control"]
ControlKind = Literal["empty", "unrelated", "other_object"]
CONTROL_KINDS: tuple[ControlKind, ...] = get_args(ControlKind)

EpisodeStatus = Literal["success", "failure", "error", "invalid_scene"]

_L = TypeVar("_L", bound=str)


def narrow(value: str, allowed: tuple[_L, ...], what: str) -> _L:
    """``value`` as one of ``allowed`` (checked), else a ``ValueError`` naming them."""
    for option in allowed:
        if option == value:
            return option
    raise ValueError(f"{what} must be one of {', '.join(allowed)}; got {value!r}")


def as_task(value: str) -> TaskType:
    return narrow(value, TASKS, "task")


def as_robot(value: str) -> Robot:
    return narrow(value, ROBOTS, "robot")


def as_object_set(value: str) -> ObjectSetName:
    return narrow(value, OBJECT_SETS, "object set")


def as_factor(value: str) -> Factor:
    return narrow(value, FACTORS, "factor")


def as_environment(value: str) -> Environment:
    return narrow(value, ENVIRONMENTS, "environment")
