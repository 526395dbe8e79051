"""Study config -> scenes: the paper's counts, stable ids and seeds, full batches."""

from __future__ import annotations

from collections import Counter

import pytest

from ladev_lib.config import section
from ladev_lib.errors import ConfigError
from ladev_lib.study.design import INSTRUCTION_LEVEL, StudyConfig, design_scenes, plan_batches


def test_the_paper_study_has_the_papers_counts(study_config):
    scenes = design_scenes(study_config("paper"))
    assert len(scenes) == 4400
    per_task = Counter(s.task for s in scenes)
    assert per_task == {"pick_up": 1100, "move_near": 1100, "put_on": 1100, "put_in": 1100}
    cells = Counter((s.task, s.factor, s.level) for s in scenes)
    for task in per_task:
        for n in "12345":
            assert cells[(task, "num_objects", n)] == 100
        assert cells[(task, "instruction", INSTRUCTION_LEVEL)] == 100
        assert cells[(task, "object_set", "simpler")] == cells[(task, "object_set", "ycb")] == 100
        for env in ("default", "lighting", "camera"):
            assert cells[(task, "environment", env)] == 100
    per_factor = Counter((s.task, s.factor) for s in scenes if s.task == "put_in")
    assert per_factor == {("put_in", "num_objects"): 500, ("put_in", "instruction"): 100,
                          ("put_in", "object_set"): 200, ("put_in", "environment"): 300}
    assert len({s.scene_id for s in scenes}) == 4400


def test_levels_set_the_scene_attributes(study_config):
    scenes = design_scenes(study_config("paper"))
    for s in scenes:
        if s.factor == "num_objects":
            assert s.num_objects == int(s.level)
        else:
            assert 1 <= s.num_objects <= 4
        assert s.object_set == (s.level if s.factor == "object_set" else "simpler")
        assert s.environment == (s.level if s.factor == "environment" else "default")
        assert s.total_objects == s.num_objects + (s.task != "pick_up")
    drawn = Counter(s.num_objects for s in scenes if s.factor != "num_objects")
    assert set(drawn) == {1, 2, 3, 4} and min(drawn.values()) > 200  # drawn, not fixed


def test_ids_and_seeds_do_not_change_when_the_study_grows(study_config):
    small = {s.scene_id: s for s in design_scenes(study_config("smoke"))}
    grown = {s.scene_id: s for s in design_scenes(study_config(
        "smoke", "study.factors.num_objects.scenes_per_level=3", "study.factors.environment.scenes_per_level=2"))}
    assert set(small) < set(grown)
    assert all(grown[i] == s for i, s in small.items())
    assert len({s.seed for s in grown.values()}) == len(grown)
    other_seed = design_scenes(study_config("smoke", "study.seed=1"))
    assert {s.scene_id for s in other_seed} == set(small) and all(
        small[s.scene_id].seed != s.seed for s in other_seed
    )


def test_batches_are_always_full_and_keep_their_content_as_the_study_grows(study_config):
    one = plan_batches(study_config("smoke"))
    two = plan_batches(study_config("smoke", "study.factors.num_objects.scenes_per_level=2"))
    assert all(len(b.items) == 8 for b in one + two)
    assert [b.items for b in one] == [b.items for b in two]  # 1 -> 2 per level: the same calls
    assert [b.used for b in two if b.items[0].factor == "num_objects"] == [2] * 12
    big = plan_batches(study_config("smoke", "study.factors.num_objects.scenes_per_level=20"))
    num = [b for b in big if b.items[0].factor == "num_objects"]
    assert len(num) == 4 * 3 * 3 and [b.used for b in num[:3]] == [8, 8, 4]
    assert num[0].items == next(b for b in one if b.items[0].factor == "num_objects").items


@pytest.mark.parametrize(
    "patch, message",
    [
        ({"factors": {"num_objects": {"levels": [0, 6], "scenes_per_level": 1}}}, "num_objects.levels"),
        ({"factors": {"environment": {"levels": ["foggy"], "scenes_per_level": 1, "num_objects": 2}}}, "foggy"),
        ({"factors": {"object_set": {"levels": ["ycb"], "scenes_per_level": 1}}}, "num_objects: required"),
        ({"tasks": ["juggle"]}, "tasks"),
        ({"batch_size": 0}, "batch_size"),
        ({"name": "has space"}, "name"),
    ],
)
def test_bad_study_configs_fail_with_the_key(params, patch, message):
    raw = {**params["study"], **patch}
    with pytest.raises(ConfigError, match=message):
        section({"study": raw}, "study", StudyConfig)
