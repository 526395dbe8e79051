"""Interruption and resume: kill the stage or a worker mid-run; nothing finished is lost or rerun,
and the final table equals an uninterrupted run's."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path

import polars as pl
import pytest

from tests.rollout.conftest import (
    comparable,
    read_episodes,
    run_log,
    run_toy,
    toy_config,
    write_study,
)
from tests.rollout.doubles import MARKER_DIR_ENV, RUN_LOG_ENV

# Slow episodes (0.1 s per step) leave time to kill things mid-run.
STUDY = [{"scene_id": f"s{i}", "basic": f"slow: pick up object {i}"} for i in range(6)]
REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> pl.DataFrame:
    """The uninterrupted run's table."""
    root = tmp_path_factory.mktemp("reference")
    write_study(root, STUDY)
    run_toy(root, toy_config())
    return comparable(read_episodes(root))


def stored(root: Path) -> set[str]:
    path = root / "data/cache/episodes/toy/store.sqlite"
    if not path.exists():
        return set()
    with sqlite3.connect(path, timeout=30) as conn:
        try:
            return {k for (k,) in conn.execute("SELECT key FROM items")}
        except sqlite3.OperationalError:  # the stage has not created its table yet
            return set()


def instructions_of(root: Path, keys: set[str]) -> set[str]:
    df = read_episodes(root)
    return set(df.filter(pl.col("episode_id").is_in(list(keys)))["instruction"])


def test_killing_the_stage_loses_nothing_and_reruns_nothing(toy_env, reference):
    write_study(toy_env, STUDY)
    env = {**os.environ, "PYTHONPATH": str(REPO), MARKER_DIR_ENV: str(toy_env / "markers"),
           RUN_LOG_ENV: str(toy_env / "runs.log")}
    cmd = [sys.executable, "-m", "tests.rollout.run_toy_stage", str(toy_env), "local"]
    proc = subprocess.Popen(cmd, cwd=REPO, env=env, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while len(stored(toy_env)) < 2:
            assert proc.poll() is None, "the stage ended before it could be interrupted"
            assert time.monotonic() < deadline, "no episode finished within 120 s"
            time.sleep(0.05)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the stage and its workers, mid-episode
        proc.wait()
    done_before = stored(toy_env)
    assert 2 <= len(done_before) < len(STUDY), "kill the stage mid-run"
    runs_before = len(run_log(toy_env))

    resumed = subprocess.run(cmd, cwd=REPO, env=env, timeout=300)
    assert resumed.returncode == 0
    again = run_log(toy_env)[runs_before:]
    finished_before = instructions_of(toy_env, done_before)
    assert not finished_before & set(again), "a finished episode ran again"
    assert len(again) == len(STUDY) - len(done_before)
    assert comparable(read_episodes(toy_env)).equals(reference)


def test_killing_a_worker_reruns_its_episode_only(toy_env, reference):
    write_study(toy_env, STUDY)
    killed: list[str] = []

    def kill_a_busy_worker() -> None:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            lines = (toy_env / "runs.log").read_text().splitlines() if (toy_env / "runs.log").exists() else []
            if len(lines) >= 3:
                instruction, pid = lines[-1].split("\t")
                os.kill(int(pid), signal.SIGKILL)  # a worker in the middle of an episode
                killed.append(instruction)
                return
            time.sleep(0.05)

    killer = threading.Thread(target=kill_a_busy_worker)
    killer.start()
    result = run_toy(toy_env, toy_config({"name": "local", "workers": 2}))
    killer.join()
    assert killed, "no worker was killed"
    log = run_log(toy_env)
    assert log.count(killed[0]) == 2  # the killed episode ran again on a fresh worker
    assert len(log) == len(STUDY) + 1  # and nothing else did
    assert result.summary.statuses["success"] == len(STUDY)
    assert comparable(read_episodes(toy_env)).equals(reference)
