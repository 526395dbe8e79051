"""Scene specifications: the contract between the language side and the simulator."""

from ladev_lib.scenes.spec import (
    SCENE_SPEC_VERSION,
    CameraOffset,
    Lighting,
    ObjectPlacement,
    SceneBounds,
    SceneSpec,
    TaskSpec,
    check_scene_spec,
    parse_scene_spec,
    scene_spec_json_schema,
)

__all__ = [
    "SCENE_SPEC_VERSION",
    "CameraOffset",
    "Lighting",
    "ObjectPlacement",
    "SceneBounds",
    "SceneSpec",
    "TaskSpec",
    "check_scene_spec",
    "parse_scene_spec",
    "scene_spec_json_schema",
]
