"""The Ray executor gives the local pool's rows, row for row, and replaces hung or dead actors."""

from __future__ import annotations

import pytest

from tests.rollout.conftest import (
    comparable,
    read_episodes,
    run_log,
    run_toy,
    toy_config,
    write_study,
)
from tests.rollout.test_engine import DETERMINISTIC_FAILURES, HEALTHY

pytest.importorskip("ray")

STUDY = [
    *HEALTHY,
    *DETERMINISTIC_FAILURES,
    {"scene_id": "j", "basic": "die-once"},
    {"scene_id": "m", "basic": "slow late hang"},
]


def test_ray_and_the_local_pool_give_identical_rows(toy_env, tmp_path_factory, monkeypatch):
    local_root = tmp_path_factory.mktemp("local")
    write_study(toy_env, STUDY)
    write_study(local_root, STUDY)

    run_toy(toy_env, toy_config({"name": "ray", "workers": 2}, step_timeout_s=2.0))
    ray_log = run_log(toy_env)
    (toy_env / "runs.log").unlink()  # the local run logs to the same file
    for marker in (toy_env / "markers").iterdir():
        marker.unlink()
    run_toy(local_root, toy_config({"name": "local", "workers": 2}, step_timeout_s=2.0))

    on_ray, on_local = read_episodes(toy_env), read_episodes(local_root)
    hang = on_ray["scene_id"] == "m"
    # A hang's step is where the driver last saw the actor (polled), so compare it apart.
    assert comparable(on_ray.filter(~hang)).equals(comparable(on_local.filter(~hang)))
    (ray_hang,) = on_ray.filter(hang).rows(named=True)
    assert ray_hang["status"] == "error"
    assert ray_hang["error"].startswith("timeout: the policy step did not return within 2 s")
    assert ray_log.count("die-once") == 2  # the dead actor was replaced and the episode rerun


def test_a_policy_that_cannot_be_built_stops_a_ray_run(toy_env):
    from ladev_lib.rollout.worker import WorkerSetupError

    write_study(toy_env, HEALTHY[:2])
    cfg = toy_config({"name": "ray", "workers": 1})
    cfg["policy"]["toy"]["no_such_option"] = 1
    with pytest.raises(WorkerSetupError, match=r"^cannot build policy 'scripted-toy'.*no_such_option"):
        run_toy(toy_env, cfg)
