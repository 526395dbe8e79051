"""The whole pipeline the way a user runs it, in a temporary copy of the repository:
``dvc repro`` on a tiny study, a second ``dvc repro`` that does nothing, a changed
report option that re-runs ``aggregate`` alone, and a grown study that makes only
the new LLM calls and runs only the new episodes (counted)."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest
import yaml

from ladev_lib.tables import EpisodeRow, SceneDesignRow, read_table
from tests.repo_copy import BIN, copy_repo, git_commit, run

pytestmark = [pytest.mark.slow, pytest.mark.sim]

POLICIES = "policy=[oracle,noop]"
STAGES = ["generate", "compile", "paraphrase", "rollout@oracle", "rollout@noop", "aggregate"]


def dvc(repo: Path, *args: str) -> str:
    return run([str(BIN / "dvc"), *args], repo, timeout=1800)


def configure(repo: Path, *overrides: str) -> None:
    text = run([str(BIN / "ladev"), "config", "study=tiny", POLICIES, *overrides], repo)
    (repo / "params.yaml").write_text(text)


def ran(out: str) -> list[str]:
    return re.findall(r"Running stage '([^']+)'", out)


def llm_calls(out: str, stage: str) -> int:
    m = re.search(rf"^{stage}: .*LLM calls:? (\d+)( made)?", out, re.MULTILINE)
    assert m, out[-3000:]
    return int(m.group(1))


def episodes_run(out: str, policy: str) -> tuple[int, int]:
    m = re.search(rf"rollout {policy}: \d+ episodes \((\d+) run now, (\d+) from the store\)", out)
    assert m, out[-3000:]
    return int(m.group(1)), int(m.group(2))


@pytest.fixture(scope="module")
def repo(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = Path(__file__).resolve().parents[2]
    return copy_repo(root, tmp_path_factory.mktemp("pipeline") / "repo", commit=True)


def test_repro_norepro_report_only_and_growth(repo: Path):
    configure(repo)
    first = dvc(repo, "repro")
    assert ran(first) == STAGES
    scenes = read_table(repo / "data/scenes.parquet", SceneDesignRow)
    assert scenes.height == 12  # 4 tasks x (2 num_objects levels + 1 paired instruction scene)
    assert llm_calls(first, "generate") > 0 and llm_calls(first, "compile") == 12
    assert episodes_run(first, "oracle") == (16, 0)  # 12 basic + 4 paraphrased
    oracle = read_table(repo / "data/episodes/oracle.parquet", EpisodeRow)
    noop = read_table(repo / "data/episodes/noop.parquet", EpisodeRow)
    assert oracle["success"].sum() >= 14 and noop["success"].sum() == 0
    metrics = json.loads((repo / "reports/metrics.json").read_text())
    assert metrics["episodes"] == 32 and metrics["success_rate/noop"] == 0.0
    assert (repo / "reports/report.html").stat().st_size > 10_000

    second = dvc(repo, "repro")
    assert ran(second) == [] and "Data and pipelines are up to date" in second

    configure(repo, "report.intervals=true")
    report_only = dvc(repo, "repro")
    assert ran(report_only) == ["aggregate"]
    assert "(" in (repo / "reports/tables/table1_num_objects.md").read_text().split("| Model")[1]

    configure(repo, "report.intervals=true", "study.factors.num_objects.scenes_per_level=2")
    grown = dvc(repo, "repro")
    assert ran(grown) == STAGES
    new_scenes = read_table(repo / "data/scenes.parquet", SceneDesignRow)
    assert new_scenes.height == 20
    assert llm_calls(grown, "generate") == 0  # full batches were asked for the first time
    assert llm_calls(grown, "compile") == 8  # one call per new scene description
    assert episodes_run(grown, "oracle") == (8, 16)
    assert episodes_run(grown, "noop") == (8, 16)


def test_dvc_queue_sweep_over_policies_and_exp_show(repo: Path):
    configure(repo)
    git_commit(repo, "tiny study")
    queued = dvc(repo, "exp", "run", "-S", "study=tiny", "-S", "policy=oracle,noop", "--queue")
    assert queued.count("Queued experiment") == 2
    dvc(repo, "queue", "start", "--jobs", "1")
    run([sys.executable, "-c", WAIT_FOR_QUEUE], repo, timeout=1800)
    shown = dvc(repo, "exp", "show", "--json")
    payload = json.loads(shown[shown.index("[") :])
    metrics = [
        exp["data"]["metrics"]["reports/metrics.json"]["data"]
        for rev in payload
        for exp in rev.get("experiments") or []
        for exp in exp["revs"]
        if exp.get("data", {}).get("metrics")
    ]
    by_policy = {next(k for k in m if k.startswith("success_rate/")): m for m in metrics}
    assert set(by_policy) == {"success_rate/oracle", "success_rate/noop"}
    assert by_policy["success_rate/noop"]["success_rate/noop"] == 0.0


def test_hydra_multirun_writes_one_report_per_job(repo: Path, tmp_path: Path):
    sweep = tmp_path / "sweep"
    out = run(
        [str(BIN / "ladev"), "study", "-m", "study=tiny", "policy=oracle,noop", f"hydra.sweep.dir={sweep}"],
        repo, timeout=1800,
    )
    assert "Launching 2 jobs" in out
    for job, policy in (("0", "oracle"), ("1", "noop")):
        params = yaml.safe_load((sweep / job / "params.yaml").read_text())
        assert list(params["policy"]) == [policy]
        metrics = json.loads((sweep / job / "reports/metrics.json").read_text())
        assert metrics["episodes"] == 16 and f"success_rate/{policy}" in metrics
        # the item caches are the checkout's, shared by every job
        assert params["paths"]["episode_store_dir"] == str(repo / "data/cache/episodes")


WAIT_FOR_QUEUE = """
import subprocess, time
for _ in range(360):
    status = subprocess.run(["dvc", "queue", "status"], capture_output=True, text=True).stdout
    if "Queued" not in status and "Running" not in status:
        break
    time.sleep(5)
print(status)
assert "Failed" not in status, status
"""
