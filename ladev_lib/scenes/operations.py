"""The operations an LLM returns for a scene description (the paper's JSON operations).

    {"schema_version": 1,
     "operations": [
        {"op": "add_object", "object": "plastic bottle", "position": {"region": "left"}},
        {"op": "add_object", "object": null},
        {"op": "add_object", "object": null},
        {"op": "set_lighting", "intensity_delta": -0.15},
        {"op": "move_camera", "translation_m": [0, 0.03, 0], "rotation_deg": [0, 0, 0]}],
     "task": {"type": "pick_up", "source": "plastic bottle", "target": null}}

One ``add_object`` per object on the table: the list's length is the number of
objects (as in the paper). ``object`` is the object as written ("plastic
bottle", a catalog id, or a category such as "fruit"); null asks for a random
object. Names are resolved against the catalog by the compiler
(:mod:`ladev_lib.scenes.compiler`), not here. The task is read from the basic
instruction and names its objects the same way.

Positions and directions are from the robot's point of view, in the workspace
frame of :mod:`ladev_lib.scenes.spec`: ``left`` is the robot's left (+y),
``front``/``far`` is away from the robot (+x), ``back``/``near side`` is
towards it (-x).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ladev_lib.vocabulary import ObjectSetName, TaskType

OPERATIONS_VERSION: Literal[1] = 1

Region = Literal[
    "left", "right", "front", "back", "center",
    "front_left", "front_right", "back_left", "back_right",
]
Relation = Literal["near", "left_of", "right_of", "in_front_of", "behind"]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Position(_Strict):
    """Where an object goes: coordinates, a region of the table, or relative to another object.

    Exactly one of: ``x`` and ``y``; ``region``; ``relation`` and ``reference``.
    """

    x: float | None = Field(default=None, description="Forward coordinate in metres (workspace frame).")
    y: float | None = Field(default=None, description="Leftward coordinate in metres (workspace frame).")
    region: Region | None = Field(default=None, description="Part of the table, from the robot's view.")
    relation: Relation | None = Field(default=None, description="Placement relative to `reference`.")
    reference: str | None = Field(default=None, description="The other object, as written.")

    @model_validator(mode="after")
    def _one_kind(self) -> Position:
        kinds = [
            self.x is not None or self.y is not None,
            self.region is not None,
            self.relation is not None or self.reference is not None,
        ]
        if sum(kinds) != 1:
            raise ValueError("position: give exactly one of (x, y), region, or (relation, reference)")
        if kinds[0] and (self.x is None or self.y is None):
            raise ValueError("position: coordinates need both x and y")
        if kinds[2] and (self.relation is None or not self.reference):
            raise ValueError("position: a relation needs both relation and reference")
        return self


class AddObject(_Strict):
    """Put one object on the table."""

    op: Literal["add_object"] = "add_object"
    object: str | None = Field(
        default=None,
        description="The object as the description names it (display name, synonym, catalog id "
        "or category such as 'fruit'); null for a random object.",
    )
    position: Position | None = Field(default=None, description="Null: anywhere free on the table.")


class SetLighting(_Strict):
    """Change every light's intensity relative to the default."""

    op: Literal["set_lighting"] = "set_lighting"
    intensity_delta: float = Field(
        default=0.0,
        description="Relative change: lights x (1 + delta); -0.2 is 20% darker. The study clamps it "
        "to its bound (0.5 by default).",
    )
    random: bool = Field(default=False, description="True: a random change within the study's bound.")


class MoveCamera(_Strict):
    """Move and/or rotate the policy camera relative to its default pose."""

    op: Literal["move_camera"] = "move_camera"
    translation_m: tuple[float, float, float] = Field(
        default=(0.0, 0.0, 0.0),
        description="[x, y, z] shift in metres: +x away from the robot, +y to its left, +z up.",
    )
    rotation_deg: tuple[float, float, float] = Field(
        default=(0.0, 0.0, 0.0),
        description="[roll, pitch, yaw] in degrees: pitch > 0 tilts the view down, yaw > 0 pans left.",
    )
    random: bool = Field(default=False, description="True: a random change within the study's bounds.")


Operation = Annotated[AddObject | SetLighting | MoveCamera, Field(discriminator="op")]


class TaskOperation(_Strict):
    """The task of the basic instruction, with its objects as written."""

    type: TaskType
    source: str | None = Field(default=None, description="Object to manipulate; null: choose one.")
    target: str | None = Field(
        default=None,
        description="Reference object (move_near), support (put_on) or container (put_in); "
        "null for pick_up, or to choose one.",
    )


class SceneOperations(_Strict):
    """The whole answer for one description."""

    schema_version: Literal[1] = OPERATIONS_VERSION
    operations: list[Operation] = Field(default_factory=list)
    object_set: ObjectSetName | None = Field(
        default=None,
        description="Set random objects come from when the description names one "
        "('SimplerEnv objects', 'YCB objects'); null: the study's choice.",
    )
    task: TaskOperation | None = Field(default=None, description="Null when there is no instruction or task.")
    error: str | None = Field(
        default=None,
        description="Set (and operations left empty) when the text cannot be read as a scene.",
    )

    @property
    def objects(self) -> list[AddObject]:
        return [op for op in self.operations if isinstance(op, AddObject)]

    @property
    def lighting(self) -> list[SetLighting]:
        return [op for op in self.operations if isinstance(op, SetLighting)]

    @property
    def camera(self) -> list[MoveCamera]:
        return [op for op in self.operations if isinstance(op, MoveCamera)]

    def to_json(self) -> str:
        return self.model_dump_json(exclude_none=True)


def operations_json_schema() -> dict[str, Any]:
    """The JSON Schema of :class:`SceneOperations` (for prompts and structured output)."""
    return SceneOperations.model_json_schema()
