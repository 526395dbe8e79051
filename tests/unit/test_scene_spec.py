from __future__ import annotations

import json

import pytest
from pydantic import ValidationError

from ladev_lib.scenes import SceneBounds, SceneSpec, parse_scene_spec, scene_spec_json_schema


def spec_dict(**over):
    d = {
        "scene_id": "s1",
        "robot": "panda",
        "objects": [
            {"name": "carrot", "id": "carrot", "x": 0.0, "y": 0.1, "yaw_deg": 30, "role": "source"},
            {"name": "plate", "id": "plate", "x": 0.05, "y": -0.1, "role": "target"},
            {"name": "apple", "id": "apple", "x": -0.08, "y": 0.0, "role": "distractor"},
        ],
        "lighting": {"intensity_delta": -0.2},
        "camera": {"translation_m": [0.0, 0.03, 0.0], "rotation_deg": [0, 2, 0]},
        "task": {"type": "put_on", "source": "carrot", "target": "plate"},
        "seed": 7,
    }
    d.update(over)
    return d


def parse(d, catalog):
    return parse_scene_spec(d, catalog=catalog, bounds=SceneBounds())


def test_round_trip_json(catalog):
    spec = parse(spec_dict(), catalog)
    again = SceneSpec.from_json(spec.to_json(), catalog=catalog, bounds=SceneBounds())
    assert again == spec
    assert again.source.id == "carrot" and again.target.id == "plate"
    assert json.loads(spec.to_json())["schema_version"] == 1


def test_json_schema_names_the_fields():
    schema = scene_spec_json_schema()
    text = json.dumps(schema)
    for field in ("objects", "lighting", "camera", "task", "intensity_delta", "rotation_deg"):
        assert field in text
    assert schema["$defs"]["TaskSpec"]["properties"]["type"]["enum"] == [
        "pick_up", "move_near", "put_on", "put_in"
    ]


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d["objects"][0].update(id="teapot"), r"objects\[0\]\.id: unknown catalog object 'teapot'"),
        (lambda d: d["task"].pop("target"), r"task\.target: required for put_on"),
        (lambda d: d["objects"][2].update(x=0.4), r"objects\[2\]\.x: 0\.400 m is outside the workspace, allowed \[-0\.15, 0\.15\]"),
        (lambda d: d["objects"][1].update(y=-0.3), r"objects\[1\]\.y: .*allowed \[-0\.25, 0\.25\]"),
        (lambda d: d["lighting"].update(intensity_delta=0.7), r"intensity_delta"),
        (lambda d: d["camera"].update(translation_m=[0.0, 0.08, 0.0]), r"camera\.translation_m: moves 0\.080 m, allowed at most 0\.05 m"),
        (lambda d: d["camera"].update(rotation_deg=[0, 0, 9]), r"camera\.rotation_deg: yaw \+9\.0 deg, allowed at most 5\.0 deg"),
        (lambda d: d["objects"][2].update(role="source"), r"exactly one object must be 'source', found 2"),
        (lambda d: d["objects"][2].update(role="target"), r"at most one object may be 'target', found 2"),
        (lambda d: d["objects"][2].update(name="carrot"), r"name 'carrot' is used 2 times"),
        (lambda d: d["objects"][1].update(id="apple"), r"'apple' cannot hold objects on top"),
        (lambda d: d["task"].update(type="put_in"), r"'plate' is not a container"),
        (lambda d: d["task"].update(source="apple"), r"object 'apple' has role 'distractor', expected 'source'"),
        (lambda d: d["objects"][0].update(id="plate"), r"is not graspable"),
    ],
)
def test_each_bad_field_is_rejected_by_name(catalog, change, message):
    d = spec_dict()
    change(d)
    with pytest.raises(ValidationError, match=message):
        parse(d, catalog)


def test_pick_up_must_not_have_a_target(catalog):
    d = spec_dict(task={"type": "pick_up", "source": "carrot", "target": "plate"})
    with pytest.raises(ValidationError, match="task.target: must be null for pick_up"):
        parse(d, catalog)


def test_too_many_objects_for_the_bounds(catalog):
    d = spec_dict()
    with pytest.raises(ValidationError, match=r"objects: 3 objects, allowed 1 to 2"):
        parse_scene_spec(d, catalog=catalog, bounds=SceneBounds(max_objects=2))


def test_camera_bounds_are_configurable(catalog):
    d = spec_dict(camera={"translation_m": [0, 0.08, 0], "rotation_deg": [0, 0, 0]})
    spec = parse_scene_spec(d, catalog=catalog, bounds=SceneBounds(camera_max_translation_m=0.1))
    assert spec.camera.translation_norm_m == pytest.approx(0.08)


def test_lighting_beyond_half_is_rejected_even_without_context():
    with pytest.raises(ValidationError, match="less than or equal to 0.5"):
        SceneSpec.model_validate(spec_dict(lighting={"intensity_delta": 0.51}))


def test_unknown_fields_are_rejected(catalog):
    d = spec_dict()
    d["objects"][0]["colour"] = "red"
    with pytest.raises(ValidationError, match="colour"):
        parse(d, catalog)


def test_a_twin_of_the_source_is_a_valid_scene(catalog):
    """Two carrots, the task on one of them ("move a carrot near the plate"): a scene a person means."""
    d = spec_dict()
    d["objects"][2].update(id="carrot")
    spec = parse(d, catalog)
    assert [o.id for o in spec.objects].count("carrot") == 2
    assert spec.source.id == "carrot"
