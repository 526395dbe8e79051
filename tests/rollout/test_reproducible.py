"""Outcomes that repeat: the same episodes in two processes give the same outcome columns,
every random generator an episode may draw from is seeded from its seed (OMPL's RRT
included), and the paraphrase validator's verdicts do not depend on the arithmetic."""

from __future__ import annotations

import ctypes
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import polars as pl
import pytest

from ladev_lib.language.evaluation import load_labelled_pairs
from ladev_lib.language.validator import ParaphraseValidator, resolve_precision
from ladev_lib.seeding import seed_episode
from ladev_lib.tables import EpisodeTimingRow, read_table
from tests.rollout.conftest import TIMING_COLUMNS, read_episodes, write_study

REPO = Path(__file__).resolve().parents[2]
STUDY = [{"scene_id": f"noisy-{i}", "num_objects": 2} for i in range(4)]


def run_module(module: str, *args: str, timeout: float = 300) -> str:
    env = {**os.environ, "PYTHONPATH": str(REPO), "OMP_NUM_THREADS": "1", "LP_NUM_THREADS": "1"}
    proc = subprocess.run([sys.executable, "-m", module, *args], cwd=REPO, env=env,
                          capture_output=True, text=True, timeout=timeout)
    assert proc.returncode == 0, (proc.stdout + proc.stderr)[-3000:]
    return proc.stdout


def test_noisy_episodes_repeat_in_two_processes_and_trials_differ(tmp_path):
    roots = [tmp_path / "a", tmp_path / "b"]
    for root in roots:
        write_study(root, STUDY)
        run_module("tests.rollout.run_noisy_stage", str(root), "2")
    a, b = (read_episodes(root) for root in roots)
    assert a.height == 2 * len(STUDY) and not set(TIMING_COLUMNS) & set(a.columns)
    assert a.equals(b)  # every outcome column, row for row
    # the noise matters: the same scene's two trials (their own seeds) went differently
    by_trial = a.pivot(on="trial", index="scene_id", values="first_success_step")
    assert (by_trial["0"] != by_trial["1"]).any()
    assert a.group_by("scene_id").agg(pl.col("seed").n_unique())["seed"].to_list() == [2] * len(STUDY)
    timings = read_table(roots[0] / "data/timings/toy.parquet", EpisodeTimingRow)
    assert timings["episode_id"].to_list() == a["episode_id"].to_list()
    assert (timings["total_seconds"] > 0).all() and timings["host"].str.len_chars().min() > 0  # type: ignore[operator]


def test_seed_episode_seeds_python_numpy_and_the_c_library():
    libc = ctypes.CDLL(None)

    def draws(seed: int) -> tuple[float, float, int]:
        seed_episode(seed)
        import random

        return random.random(), float(np.random.random()), libc.rand()

    assert draws(11) == draws(11)
    assert draws(11) != draws(12)


def test_rrt_plans_repeat_with_the_episode_seed():
    """mplib's RRT-Connect (OMPL) around a wall: the same seed plans the same path; without
    seeding, or with another seed, the path differs."""
    import mani_skill
    import mplib

    base = Path(mani_skill.__file__).parent / "assets/robots/panda"
    planner = mplib.Planner(urdf=str(base / "panda_v2.urdf"), srdf=str(base / "panda_v2.srdf"),
                            move_group="panda_hand_tcp")
    xs, zs = np.meshgrid(np.linspace(0.2, 0.7, 60), np.linspace(-0.1, 0.45, 60))
    planner.update_point_cloud(np.stack([xs.ravel(), np.full(xs.size, 0.15), zs.ravel()], axis=1), 0.01)
    start = np.array([0.0, np.pi / 8, 0, -np.pi * 5 / 8, 0, np.pi * 3 / 4, np.pi / 4, 0.04, 0.04])
    goal = np.array([0.4, 0.3, 0.2, 0, 1, 0, 0])

    def plan(seed: int | None) -> np.ndarray:
        if seed is not None:
            assert seed_episode(seed)["ompl"], "OMPL was not reached"
        result = planner.plan_qpos_to_pose(goal, start.copy(), time_step=0.05, planning_time=2.0,
                                           use_point_cloud=True)
        assert result["status"] == "Success"
        return np.asarray(result["position"])

    first, again = plan(3), plan(3)
    assert first.shape == again.shape and np.array_equal(first, again)
    others = [plan(4), plan(None)]
    assert any(o.shape != first.shape or not np.array_equal(o, first) for o in others)


@pytest.fixture(scope="module")
def minilm():
    from ladev_lib.language.embeddings import load_embedder

    return load_embedder()


def test_validator_verdicts_are_the_same_in_fp32_and_bf16_on_the_project_sets(minilm, monkeypatch):
    pairs = [
        (p.original, p.candidate)
        for name in ("paraphrase_pairs.csv", "paraphrase_pairs_holdout.csv")
        for p in load_labelled_pairs(REPO / "tests/data" / name)
    ]
    verdicts = {
        precision: ParaphraseValidator(minilm, precision=precision).validate_pairs(pairs)
        for precision in ("fp32", "bf16")
    }
    fp32, bf16 = verdicts["fp32"], verdicts["bf16"]
    assert [v.valid for v in fp32] == [v.valid for v in bf16]
    assert [v.similar for v in fp32] == [v.similar for v in bf16]
    # the arithmetic differs (bf16 moves similarities), the verdicts do not
    assert any(a.similarity != b.similarity for a, b in zip(fp32, bf16, strict=True))
    assert all(round(v.similarity, 4) == v.similarity for v in fp32)  # rounded before the threshold
    # "auto" is fp32 on every machine, native bf16 or not
    monkeypatch.setattr("ladev_lib.language.validator.cpu_has_native_bf16", lambda: True)
    assert resolve_precision("auto") == "fp32" and resolve_precision("bf16") == "bf16"


@pytest.mark.sim
def test_real_episodes_repeat_in_two_processes_in_any_order():
    """Oracle and grounded on two real scenes, two seeds each: a second process running them in
    the reverse order gets the same outcome, field for field (timings aside)."""

    def results(*args: str) -> dict[str, dict[str, object]]:
        out = run_module("tests.rollout.run_sim_episodes", *args, timeout=600)
        line = next(ln for ln in out.splitlines() if ln.startswith("RESULTS "))
        return dict(json.loads(line.removeprefix("RESULTS ")))

    forward, reverse = results(), results("--reverse")
    assert len(forward) == 8 and forward == reverse
    assert all(r["status"] in ("success", "failure") for r in forward.values())
