"""The engine end to end on the toy simulator: store, growth, executors, error rows, exit status."""

from __future__ import annotations

import polars as pl
import pytest

from ladev_lib.errors import ConfigError
from ladev_lib.rollout.worker import WorkerSetupError
from tests.rollout.conftest import (
    comparable,
    read_episodes,
    run_log,
    run_toy,
    toy_config,
    write_study,
)

HEALTHY = [
    {"scene_id": "a"},
    {"scene_id": "b", "factor": "instruction", "paraphrases": [("grab that object", True), ("no", False)]},
    {"scene_id": "c", "task": "put_on", "num_objects": 2},
    {"scene_id": "d-bad-scene"},  # fails the validity check at the start of its episode
]
# Failures every executor reports the same way (no process dies, nothing hangs).
DETERMINISTIC_FAILURES = [
    {"scene_id": "e-sim-crash"},
    {"scene_id": "f", "basic": "raise"},
    {"scene_id": "g", "basic": "nan"},
    {"scene_id": "h-bad-scene"},
]


def statuses(df: pl.DataFrame) -> dict[str, str]:
    return dict(zip(df["instruction_id"], df["status"], strict=True))


def test_serial_run_then_rerun_runs_nothing(toy_env):
    write_study(toy_env, HEALTHY)
    first = run_toy(toy_env, toy_config())
    assert (first.summary.planned, first.summary.ran) == (5, 5)
    df = read_episodes(toy_env)
    assert statuses(df) == {
        "a/basic": "success", "b/basic": "success", "b/para-0": "success",
        "c/basic": "success", "d-bad-scene/basic": "invalid_scene",
    }
    assert df["level"].to_list() == ["1", "basic", "paraphrase", "2", "1"]
    assert len(run_log(toy_env)) == 4  # the invalid scene never reaches the policy

    again = run_toy(toy_env, toy_config())
    assert (again.summary.ran, again.summary.from_store) == (0, 5)  # the invalid verdict is kept too
    assert len(run_log(toy_env)) == 4  # nothing ran twice
    assert comparable(read_episodes(toy_env)).equals(comparable(df))
    assert read_episodes(toy_env).equals(df)  # timings come from the store too


def test_a_grown_study_runs_only_the_new_episodes(toy_env):
    write_study(toy_env, HEALTHY[:2])
    run_toy(toy_env, toy_config())
    before = run_log(toy_env)
    write_study(toy_env, [*HEALTHY[:2], {"scene_id": "z", "basic": "pick up the new thing"}])
    grown = run_toy(toy_env, toy_config())
    assert grown.summary.ran == 1
    assert run_log(toy_env)[len(before):] == ["pick up the new thing"]
    assert read_episodes(toy_env).height == 4


def test_a_changed_policy_config_reruns(toy_env):
    write_study(toy_env, HEALTHY[:1])
    run_toy(toy_env, toy_config())
    cfg = toy_config()
    cfg["policy"]["toy"]["gain"] = 0.5
    assert run_toy(toy_env, cfg).summary.ran == 1


def test_robot_by_task_drives_each_task_with_its_robot(toy_env):
    """The paper's protocol: one policy config, a robot per task, a policy built per robot."""
    write_study(toy_env, [{"scene_id": "a"}, {"scene_id": "c", "task": "put_on", "num_objects": 2}])
    cfg = toy_config()
    cfg["policy"]["toy"]["robot_by_task"] = {"put_on": "widowx"}
    run_toy(toy_env, cfg)
    df = read_episodes(toy_env)
    assert dict(zip(df["task"], df["robot"], strict=True)) == {"pick_up": "panda", "put_on": "widowx"}
    assert set(df["status"]) == {"success"}
    plain = toy_config()
    assert run_toy(toy_env, plain).summary.ran == 2  # the robot choice is part of the episode id


def test_local_pool_turns_every_failure_into_a_row(toy_env):
    write_study(toy_env, [
        *HEALTHY[:1], *DETERMINISTIC_FAILURES,
        {"scene_id": "i", "basic": "hang"},
        {"scene_id": "j", "basic": "die-once"},
        {"scene_id": "k", "basic": "shape"},
    ])
    result = run_toy(toy_env, toy_config({"name": "local", "workers": 2}, step_timeout_s=2.0))
    df = read_episodes(toy_env)
    errors = dict(zip(df["scene_id"], df["error"], strict=True))
    assert statuses(df) == {
        "a/basic": "success", "e-sim-crash/basic": "error", "f/basic": "error", "g/basic": "error",
        "h-bad-scene/basic": "invalid_scene", "i/basic": "error", "j/basic": "success", "k/basic": "error",
    }
    assert errors["e-sim-crash"].startswith("simulator: RuntimeError: injected simulator failure")
    assert errors["f"].startswith("policy: ValueError: injected policy failure")
    assert errors["g"].startswith("action: step 1: contains NaN")
    assert errors["i"] == (
        "timeout: the policy step did not return within 2 s (step 1); the worker was killed and replaced"
    )
    assert errors["k"].startswith("action: step 1: shape (3,)")
    # j's worker died once; the pool replaced it and ran the episode again.
    assert run_log(toy_env).count("die-once") == 2
    # Episodes after the hang and the death ran on fresh workers: 3 distinct pids at least.
    pids = {line.split("\t")[1] for line in (toy_env / "runs.log").read_text().splitlines()}
    assert len(pids) >= 3
    assert result.summary.statuses["error"] == 5
    assert result.exit_code == 1  # 5 of 8 in error, above the default 5 %


def test_a_worker_that_always_dies_gives_an_error_row(toy_env, monkeypatch):
    write_study(toy_env, [{"scene_id": "a", "basic": "die-once"}, {"scene_id": "b"}])
    cfg = toy_config({"name": "local", "workers": 1}, crash_retries=0)
    run_toy(toy_env, cfg)
    df = read_episodes(toy_env)
    assert statuses(df) == {"a/basic": "error", "b/basic": "success"}
    assert df["error"][0] == "worker: the worker process died running this episode (killed by SIGKILL), once"


def test_error_rate_threshold_sets_the_exit_status(toy_env):
    write_study(toy_env, [HEALTHY[0], HEALTHY[2], {"scene_id": "x"}, {"scene_id": "f", "basic": "raise"}])
    assert run_toy(toy_env, toy_config(max_error_rate=0.2)).exit_code == 1  # 1 of 4 = 25 %
    assert run_toy(toy_env, toy_config(max_error_rate=0.25)).exit_code == 0


def test_local_pool_and_serial_give_the_same_rows(toy_env, tmp_path_factory):
    other = tmp_path_factory.mktemp("serial")
    for root, executor in ((toy_env, {"name": "local", "workers": 2}), (other, {"name": "serial"})):
        write_study(root, HEALTHY + DETERMINISTIC_FAILURES)
        run_toy(root, toy_config(executor))
    assert comparable(read_episodes(toy_env)).equals(comparable(read_episodes(other)))


def test_a_policy_that_cannot_be_built_stops_the_run(toy_env):
    write_study(toy_env, HEALTHY[:2])
    cfg = toy_config({"name": "local", "workers": 2})
    cfg["policy"]["toy"]["no_such_option"] = 1
    with pytest.raises(WorkerSetupError, match="no_such_option"):
        run_toy(toy_env, cfg)


def test_bad_configuration_fails_fast_with_the_key(toy_env):
    write_study(toy_env, HEALTHY[:1])
    with pytest.raises(ConfigError, match="executor"):
        run_toy(toy_env, toy_config({"name": "local", "workers": 0}))
    with pytest.raises(ConfigError, match="rollout.video"):
        run_toy(toy_env, toy_config(video="sometimes"))
    cfg = toy_config()
    with pytest.raises(ConfigError, match="policy 'nope' is not configured"):
        from ladev_lib.rollout.stage import rollout_stage

        rollout_stage(cfg, "nope", root=toy_env, progress=False)
