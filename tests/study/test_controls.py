"""Control instructions: which scenes get them, and what each kind says."""

from __future__ import annotations

import numpy as np
import pytest
from pydantic import ValidationError

from ladev_lib.language.parser import parse_instruction
from ladev_lib.scenes.sampling import sample_scene
from ladev_lib.study.controls import UNRELATED_SENTENCES, control_instruction, control_rows
from ladev_lib.study.design import StudyConfig
from ladev_lib.tables import CompiledSceneRow, SceneDesignRow


def study(**kw) -> StudyConfig:
    base = {"name": "t", "tasks": ["pick_up"],
            "factors": {"num_objects": {"levels": [1, 3], "scenes_per_level": 1},
                        "instruction": {"levels": ["basic", "paraphrase"], "scenes_per_level": 1,
                                        "num_objects": 2}}}
    return StudyConfig.model_validate({**base, **kw})


def scene(catalog, scene_id: str, factor: str, task: str = "pick_up", n: int = 3, seed: int = 0):
    spec = sample_scene(task, n, "simpler", np.random.default_rng(seed), catalog, seed=seed, scene_id=scene_id)
    design = SceneDesignRow(
        scene_id=scene_id, study="t", task=task, factor=factor, level="1", num_objects=n,
        object_set="simpler", environment="default", robot="panda", seed=seed, description="d",
        base_instruction="b", status="ok",
    )
    return spec, design, CompiledSceneRow(scene_id=scene_id, status="ok", spec_json=spec.to_json())


def test_each_kind_of_control(catalog):
    spec, _, _ = scene(catalog, "s", "instruction", task="put_on", n=3, seed=4)
    assert control_instruction("empty", spec, catalog, 0, "s") == ("", None)
    text, note = control_instruction("unrelated", spec, catalog, 0, "s")  # type: ignore[misc]
    assert text in UNRELATED_SENTENCES and note is None
    text, note = control_instruction("other_object", spec, catalog, 0, "s")  # type: ignore[misc]
    parsed = parse_instruction(text)
    assert parsed is not None and parsed.task == "put_on" and note is None
    distractors = {o.id for o in spec.objects} - {spec.source.id, spec.target.id}  # type: ignore[union-attr]
    assert parsed.source in distractors and parsed.target == spec.target.id  # type: ignore[union-attr]
    # alone on the table: another object of the set, named as absent
    lone, _, _ = scene(catalog, "l", "num_objects", n=1, seed=2)
    text, note = control_instruction("other_object", lone, catalog, 0, "l")  # type: ignore[misc]
    parsed = parse_instruction(text)
    assert parsed is not None and parsed.source != lone.source.id and note and "not on" in note
    with pytest.raises(ValueError, match="unknown control"):
        control_instruction("loud", spec, catalog, 0, "s")


def test_control_rows_for_the_chosen_factors_only(catalog):
    made = [scene(catalog, "a", "num_objects", seed=1), scene(catalog, "b", "instruction", seed=2)]
    cfg = study(controls=["empty", "other_object"], control_factors=["instruction"])
    rows = control_rows([d for _, d, _ in made], [c for _, _, c in made], cfg, catalog)
    assert [(r.instruction_id, r.kind, r.control, r.selected) for r in rows] == [
        ("b/control-empty", "control", "empty", True),
        ("b/control-other_object", "control", "other_object", True),
    ]
    again = control_rows([d for _, d, _ in made], [c for _, _, c in made], cfg, catalog)
    assert [r.text for r in again] == [r.text for r in rows]  # drawn from the seed, not the clock
    everywhere = control_rows([d for _, d, _ in made], [c for _, _, c in made], study(controls=["empty"]), catalog)
    assert [r.scene_id for r in everywhere] == ["a", "b"]


def test_measurement_options_are_checked():
    assert study(trials_per_scene=3, trial_factors=["instruction"]).trials_for("num_objects") == 1
    assert study(trials_per_scene=3).trials_for("num_objects") == 3
    with pytest.raises(ValidationError, match="trial_factors"):
        study(trial_factors=["colour"])  # not a factor
    with pytest.raises(ValidationError, match="controls"):
        study(controls=["empty", "empty"])
    with pytest.raises(ValidationError):
        study(controls=["silence"])
