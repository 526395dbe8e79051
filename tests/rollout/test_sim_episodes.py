"""Episodes on the real LADEV env: baselines, ``grounded`` both ways, the stage script end to end."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from ladev_lib.catalog import load_catalog
from ladev_lib.rollout.jobs import EpisodeJob, MediaOptions, WorkerSpec
from ladev_lib.rollout.worker import EpisodeWorker
from ladev_lib.scenes.spec import SceneSpec, parse_scene_spec
from ladev_lib.sim.robots import episode_steps
from ladev_lib.tables import CompiledSceneRow, EpisodeRow, InstructionRow, read_table, write_table

pytestmark = pytest.mark.sim
REPO = Path(__file__).resolve().parents[2]


def pick_up_scene(scene_id: str, source: str, other: str) -> SceneSpec:
    """Both objects in front of the robot, in view of the Panda's policy camera."""
    return parse_scene_spec(
        {
            "scene_id": scene_id,
            "objects": [
                {"name": source, "id": source, "x": 0.05, "y": -0.1, "role": "source"},
                {"name": other, "id": other, "x": 0.05, "y": 0.1, "role": "distractor"},
            ],
            "task": {"type": "pick_up", "source": source},
        },
        catalog=load_catalog(),
    )


SHORT = {"name": "panda", "max_episode_steps": {"pick_up": 30}}


def worker(tmp_path: Path, policy: str, robot_config: dict | None = None, **kwargs) -> EpisodeWorker:
    return EpisodeWorker(
        WorkerSpec(policy, kwargs, {"image_size": [128, 128]}, robot_config or {"name": "panda"},
                   MediaOptions(str(tmp_path), "media", frames=True))
    )


def run(w: EpisodeWorker, spec: SceneSpec, instruction: str):
    return w.run(EpisodeJob(spec.scene_id or "e", spec, instruction, spec.seed))


def test_grounded_reader_acts_on_what_it_reads_and_holds_still_otherwise(tmp_path):
    w = worker(tmp_path, "grounded")
    try:
        right = run(w, pick_up_scene("eggplant-apple", "eggplant", "apple"), "could you lift the eggplant up?")
        assert w.policy.reading.task.source == "eggplant", w.policy.explain()
        lost = run(w, pick_up_scene("eggplant-apple-2", "eggplant", "apple"), "pick up the banana")
        assert w.policy.reading.task is None and "banana" in w.policy.explain(), w.policy.explain()
    finally:
        w.close()
    assert right.status == "success", right
    assert lost.status == "failure" and lost.steps <= 2, lost
    assert not lost.predicates["is_grasped"]


def test_grounded_retrieval_succeeds_when_it_understands_and_fails_when_fooled(tmp_path):
    w = worker(tmp_path, "grounded", mode="retrieval")
    try:
        right = run(w, pick_up_scene("eggplant-apple", "eggplant", "apple"), "pick up the purple vegetable")
        assert w.policy.choice.chosen.source == "eggplant"
        fooled = run(w, pick_up_scene("eggplant-carrot", "eggplant", "carrot"), "pick up the purple vegetable")
        assert w.policy.choice.chosen.source == "carrot"
    finally:
        w.close()
    assert right.status == "success", right
    assert fooled.status == "failure" and fooled.predicates["is_grasped"] is False, fooled
    assert (tmp_path / "eggplant-apple_last.png").exists()


@pytest.mark.parametrize("policy", ["noop", "random"])
def test_floors_fail_and_run_the_whole_episode(tmp_path, policy):
    spec = pick_up_scene("floor", "coke_can", "apple")
    w = worker(tmp_path, policy, SHORT)  # the study's episode length for this robot applies
    try:
        out = run(w, spec, "pick up the coke can")
    finally:
        w.close()
    assert out.status == "failure" and out.success is False
    assert out.steps == episode_steps("panda", "pick_up", SHORT["max_episode_steps"]) == 30
    assert set(out.predicates) >= {"success", "lifted"}
    if policy == "noop":  # holding still moves nothing
        assert not any(out.predicates.values())


def test_stage_script_writes_the_table_and_reuses_the_store(tmp_path):
    """stages/rollout.py on a two-scene study with the noop floor and the serial executor."""
    specs = [pick_up_scene("s1", "coke_can", "apple"), pick_up_scene("s2", "sponge", "carrot")]
    write_table([CompiledSceneRow(scene_id=s.scene_id, status="ok", spec_json=s.to_json()) for s in specs],
                tmp_path / "data/compiled.parquet", CompiledSceneRow)
    write_table([InstructionRow(instruction_id=f"{s.scene_id}/basic", scene_id=s.scene_id, kind="basic",
                                text="pick up the thing", valid=True, selected=True) for s in specs],
                tmp_path / "data/instructions.parquet", InstructionRow)
    params = yaml.safe_load((REPO / "params.yaml").read_text())
    params["policy"] = {"floor": {"name": "noop"}}
    params["executor"] = {"name": "serial"}
    params["rollout"]["video"] = "failures"
    params["sim"]["image_size"] = [96, 96]
    params["robot"]["max_episode_steps"] = {"pick_up": 15}
    (tmp_path / "params.yaml").write_text(yaml.safe_dump(params))
    cmd = [sys.executable, str(REPO / "stages/rollout.py"), "--policy", "floor", "--no-progress"]
    first = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=900)
    assert first.returncode == 0, first.stderr
    assert "2 episodes (2 run now, 0 from the store)" in first.stdout
    df = read_table(tmp_path / "data/episodes/floor.parquet", EpisodeRow)
    assert df["status"].to_list() == ["failure", "failure"]
    assert df["factor"].to_list() == ["custom", "custom"]  # no scenes.parquet: a user's own specs
    for row in df.iter_rows(named=True):
        assert json.loads(row["predicates_json"])["success"] is False
        assert row["video_path"].startswith("data/media/floor/") and (tmp_path / row["video_path"]).exists()
        assert (tmp_path / row["last_frame_path"]).exists()

    again = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=900)
    assert again.returncode == 0, again.stderr
    assert "2 episodes (0 run now, 2 from the store)" in again.stdout
    assert read_table(tmp_path / "data/episodes/floor.parquet", EpisodeRow).equals(df)


def test_ladev_run_prints_the_outcome_and_writes_frames(tmp_path):
    from click.testing import CliRunner

    from ladev_lib.cli import cli

    spec_path = tmp_path / "scene.json"
    spec_path.write_text(pick_up_scene("cli", "coke_can", "apple").to_json())
    args = ["run", str(spec_path), "--policy", "noop", "--frames", str(tmp_path / "frames"),
            "--config-dir", str(REPO / "conf"), "robot.max_episode_steps.pick_up=5", "sim.image_size=[96,96]"]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    assert "instruction: 'pick up the coke can'" in result.output
    assert "FAILURE after 5 steps" in result.output
    assert "no   success" in result.output
    assert (tmp_path / "frames/scene_first.png").exists() and (tmp_path / "frames/scene_last.png").exists()

    as_json = CliRunner().invoke(cli, [*args, "--json", "--instruction", "lift the can"])
    assert as_json.exit_code == 0, as_json.output
    data = json.loads(as_json.output[as_json.output.index("{"):])
    assert data["instruction"] == "lift the can" and data["steps"] == 5 and data["status"] == "failure"


def test_ladev_run_rejects_a_bad_spec(tmp_path):
    from click.testing import CliRunner

    from ladev_lib.cli import cli

    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"objects": [], "task": {"type": "pick_up", "source": "x"}}))
    result = CliRunner().invoke(cli, ["run", str(bad)])
    assert result.exit_code != 0 and "is not a valid scene spec" in result.output
