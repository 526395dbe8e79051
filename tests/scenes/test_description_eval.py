"""Scoring compiled scenes against labelled descriptions (rows written for this test)."""

from __future__ import annotations

from pathlib import Path

import pytest

from ladev_lib.scenes.description_eval import (
    FIELDS,
    camera_in_description_frame,
    evaluate_descriptions,
    offline_compile_fn,
    scene_description_section,
)

CONF = Path(__file__).resolve().parents[2] / "conf"

ROWS = [
    {"id": "a", "style": "prose",
     "description": "A sponge on the left and a lemon. The robot should put the lemon on the sponge. "
                    "Lights 10% darker; pan the camera 2 degrees to the right.",
     "expected": {"n_objects": 2, "required_objects": ["sponge", "lemon"],
                  "task": {"type": "put_on", "object": "lemon", "target": "sponge"},
                  "lighting": {"direction": "darker", "magnitude": 0.1},
                  "camera": {"translate_cm": None, "rotate_deg": {"yaw": 2}},
                  "positions": [{"object": "sponge", "where": "left"}]}},
    {"id": "b", "style": "list",
     "description": "objects: a teapot, a pear, a bowl | task: put the pear in the bowl",
     "expected": {"n_objects": 2, "required_objects": ["pear", "bowl"],
                  "task": {"type": "put_in", "object": "pear", "target": "bowl"},
                  "lighting": None, "camera": None, "unavailable": ["teapot"]}},
    {"id": "c", "style": "list",
     "description": "a pear and a bowl; task: put the pear in the teapot",
     "expected": {"n_objects": 2, "required_objects": ["pear", "bowl"],
                  "task": {"type": "put_in", "object": "pear", "target": "teapot"},
                  "lighting": None, "camera": None, "unavailable": ["teapot"], "task_feasible": False}},
]


def test_camera_frames_convert_between_the_spec_and_the_description_conventions():
    cm, rot = camera_in_description_frame((0.02, 0.01, -0.03), (1.0, 2.0, 3.0))
    assert cm == [-1.0, 2.0, -3.0]  # spec +y (left) is -x (right is +); spec +x (away) is forward
    assert rot == {"yaw": -3.0, "pitch": -2.0, "roll": -1.0}


@pytest.fixture(scope="module")
def compiled():
    return offline_compile_fn(CONF)


def test_rows_in_own_words_are_scene_exact(compiled):
    fn, catalog, resolver = compiled
    result = evaluate_descriptions(ROWS, fn, catalog, resolver)
    assert [r.errors for r in result.rows] == [{}, {}, {}]
    assert result.scene_exact == 1.0 and set(result.per_field) == set(FIELDS)


def test_a_wrong_reading_fails_the_fields_it_touches(compiled):
    fn, catalog, resolver = compiled
    row = {**ROWS[0], "expected": {**ROWS[0]["expected"], "lighting": {"direction": "brighter", "magnitude": 0.1},
                                   "task": {"type": "pick_up", "object": "lemon", "target": None}}}
    score = evaluate_descriptions([row], fn, catalog, resolver).rows[0]
    assert not score.exact and set(score.errors) == {"lighting", "task"}


def test_a_crashing_compile_is_a_row_with_a_reason(compiled):
    _, catalog, resolver = compiled

    def boom(text: str):
        raise RuntimeError("bad backend")

    score = evaluate_descriptions(ROWS[:1], boom, catalog, resolver).rows[0]
    assert not score.exact and "crashed" in (score.reason or "")


def test_the_report_section_is_a_table(tmp_path):
    import json

    path = tmp_path / "rows.jsonl"
    path.write_text("\n".join(json.dumps(r) for r in ROWS) + "\n")
    text = scene_description_section(path, CONF, baseline={"label": "before", "scene_exact": 0.0, "per_field": {}})
    assert "| measure | before | LADEV |" in text and "| scene-exact | 0.000 | 1.000 |" in text
