"""Which episodes a study calls for, read from the compile and paraphrase tables."""

from __future__ import annotations

from ladev_lib.rollout.plan import PolicyIdentity, plan_episodes
from ladev_lib.tables import CompiledSceneRow, InstructionRow, SceneDesignRow, read_table
from tests.rollout.conftest import write_study

POLICY = PolicyIdentity(label="toy", name="scripted-toy", config={}, code="c0")


def plan(root, **kw):
    return plan_episodes(
        read_table(root / "data/compiled.parquet", CompiledSceneRow),
        read_table(root / "data/instructions.parquet", InstructionRow),
        kw.get("scenes", read_table(root / "data/scenes.parquet", SceneDesignRow)),
        study="toy", policy=kw.get("policy", POLICY), sim_config={}, robot_config={},
    )


def test_basic_always_selected_paraphrase_only_for_the_instruction_factor(tmp_path):
    paras = [("grab the thing", True), ("take the thing", False)]
    write_study(tmp_path, [
        {"scene_id": "a", "paraphrases": paras},
        {"scene_id": "b", "factor": "instruction", "paraphrases": paras},
        {"scene_id": "c", "status": "rejected"},
    ])
    plans = plan(tmp_path)
    got = [(p.meta["scene_id"], p.meta["instruction_kind"], p.meta["level"], p.job.instruction) for p in plans]
    assert got[0][:3] == ("a", "basic", "1")
    assert got[1][:3] == ("b", "basic", "basic")
    assert got[2] == ("b", "paraphrase", "paraphrase", "grab the thing")
    assert len(got) == 3  # the unselected paraphrase and the rejected scene are not rolled out
    assert all(p.meta["policy"] == "toy" and p.meta["study"] == "toy" for p in plans)
    assert len({p.job.episode_id for p in plans}) == 3


def test_compile_invalid_scene_is_planned_as_invalid(tmp_path):
    write_study(tmp_path, [{"scene_id": "a", "validity": "invalid", "validity_reason": "falls off the table"}])
    (p,) = plan(tmp_path)
    assert p.known_invalid == "falls off the table"


def test_scene_missing_from_the_design_gets_metadata_from_its_spec(tmp_path):
    write_study(tmp_path, [{"scene_id": "a", "task": "put_on", "num_objects": 2}])
    (p,) = plan(tmp_path, scenes=None)
    assert p.meta["factor"] == "custom" and p.meta["task"] == "put_on"
    assert p.meta["num_objects"] == 2  # source + distractor; the target is not counted


def test_ids_depend_on_the_policy_config(tmp_path):
    write_study(tmp_path, [{"scene_id": "a"}])
    (a,) = plan(tmp_path)
    (b,) = plan(tmp_path, policy=PolicyIdentity(label="toy", name="scripted-toy", config={"gain": 2}, code="c0"))
    assert a.job.episode_id != b.job.episode_id
