from __future__ import annotations

import pytest
from pydantic import ValidationError

from ladev_lib.scenes.operations import (
    AddObject,
    MoveCamera,
    Position,
    SceneOperations,
    operations_json_schema,
)


def test_operations_parse_by_op_name_and_round_trip():
    ops = SceneOperations.model_validate(
        {
            "operations": [
                {"op": "add_object", "object": "coke can", "position": {"region": "left"}},
                {"op": "add_object", "object": None},
                {"op": "set_lighting", "intensity_delta": -0.2},
                {"op": "move_camera", "translation_m": [0, 0.03, 0]},
            ],
            "task": {"type": "pick_up", "source": "coke can"},
        }
    )
    assert [type(o).__name__ for o in ops.operations] == ["AddObject", "AddObject", "SetLighting", "MoveCamera"]
    assert len(ops.objects) == 2 and ops.lighting[0].intensity_delta == -0.2
    assert isinstance(ops.camera[0], MoveCamera) and ops.camera[0].translation_m == (0, 0.03, 0)
    assert SceneOperations.model_validate_json(ops.to_json()) == ops


@pytest.mark.parametrize(
    "position",
    [{}, {"x": 0.1}, {"x": 0.1, "y": 0.0, "region": "left"}, {"relation": "near"}, {"region": "upstairs"}],
)
def test_a_position_is_exactly_one_kind(position):
    with pytest.raises(ValidationError):
        Position.model_validate(position)


def test_unknown_operation_and_fields_are_rejected():
    with pytest.raises(ValidationError):
        SceneOperations.model_validate({"operations": [{"op": "explode"}]})
    with pytest.raises(ValidationError):
        AddObject.model_validate({"op": "add_object", "object": "apple", "colour": "red"})
    with pytest.raises(ValidationError):
        SceneOperations.model_validate({"task": {"type": "juggle", "source": "apple"}})


def test_json_schema_names_the_three_operations_and_the_task():
    schema = operations_json_schema()
    text = str(schema)
    for name in ("add_object", "set_lighting", "move_camera", "TaskOperation", "pick_up", "put_in"):
        assert name in text
    assert schema["properties"]["schema_version"]["const"] == 1
