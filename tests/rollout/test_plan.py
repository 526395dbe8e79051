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


def test_trials_get_their_own_seeds_and_ids_and_controls_run_with_them(tmp_path):
    from ladev_lib.rollout.plan import TrialPlan
    from ladev_lib.seeding import trial_seed
    from ladev_lib.tables import write_table

    write_study(tmp_path, [
        {"scene_id": "a"},
        {"scene_id": "b", "factor": "instruction", "paraphrases": [("grab the thing", True)]},
    ])
    rows = read_table(tmp_path / "data/instructions.parquet", InstructionRow)
    control = InstructionRow(instruction_id="b/control-empty", scene_id="b", kind="control", text="",
                             valid=False, selected=True, control="empty")
    write_table([*rows.to_dicts(), control], tmp_path / "data/instructions.parquet", InstructionRow)

    def planned(trials: TrialPlan):
        return plan_episodes(
            read_table(tmp_path / "data/compiled.parquet", CompiledSceneRow),
            read_table(tmp_path / "data/instructions.parquet", InstructionRow),
            read_table(tmp_path / "data/scenes.parquet", SceneDesignRow),
            study="toy", policy=POLICY, sim_config={}, robot_config={}, trials=trials,
        )

    plans = planned(TrialPlan(trials_per_scene=3, trial_factors=("instruction",)))
    got = [(p.meta["scene_id"], p.meta["trial"], p.meta["instruction_kind"]) for p in plans]
    assert got[0] == ("a", 0, "basic") and sum(s == "a" for s, _, _ in got) == 1  # not a trial factor
    assert [g for g in got if g[0] == "b"] == [
        ("b", t, kind) for t in range(3) for kind in ("basic", "paraphrase", "control")
    ]
    b_basic = [p for p in plans if p.meta["scene_id"] == "b" and p.meta["instruction_kind"] == "basic"]
    scene_seed = b_basic[0].meta["seed"]
    assert [p.job.seed for p in b_basic] == [trial_seed(scene_seed, t) for t in range(3)]
    assert len({p.job.seed for p in b_basic}) == 3 and len({p.job.episode_id for p in plans}) == len(plans)
    ctrl = next(p for p in plans if p.meta["instruction_kind"] == "control")
    assert ctrl.meta["control"] == "empty" and ctrl.job.instruction == ""
    # trial 0 keeps the ids' seed; stopping at the first success is another episode
    one = planned(TrialPlan())
    stop = planned(TrialPlan(stop_on_success=True))
    assert [p.job.seed for p in one] == [p.job.seed for p in plans if p.meta["trial"] == 0]
    assert {p.job.episode_id for p in one}.isdisjoint(p.job.episode_id for p in stop)
    assert all(p.job.stop_on_success for p in stop)
