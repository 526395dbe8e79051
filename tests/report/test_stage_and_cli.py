"""The aggregate stage as DVC runs it, its config, and ``ladev summary``."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import polars as pl
import pytest
import yaml
from click.testing import CliRunner

from ladev_lib.cli import cli
from ladev_lib.config import compose_config, section
from ladev_lib.errors import ConfigError
from ladev_lib.report import ReportConfig
from ladev_lib.report.synthetic import random_episodes, stage_tables_for
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    InstructionRow,
    SceneDesignRow,
    write_table,
)

ROOT = Path(__file__).resolve().parents[2]


def make_repo(tmp: Path, study: str = "smoke", report: dict | None = None) -> Path:
    """A directory laid out like the repository after rollout, for the aggregate stage."""
    params = yaml.safe_load((ROOT / "params.yaml").read_text())
    params["study"]["name"] = study
    if report is not None:
        params["report"] = report
    (tmp / "params.yaml").write_text(yaml.safe_dump(params, sort_keys=False))
    eps = random_episodes(800, policies=["oracle", "grounded"], seed=5, study=study)
    for policy in ("oracle", "grounded"):
        write_table(eps.filter(pl.col("policy") == policy), tmp / f"data/episodes/{policy}.parquet", EpisodeRow)
    scenes, compiled, instructions = stage_tables_for(eps, rejected_scenes=2)
    write_table(scenes, tmp / "data/scenes.parquet", SceneDesignRow)
    write_table(compiled, tmp / "data/compiled.parquet", CompiledSceneRow)
    write_table(instructions, tmp / "data/instructions.parquet", InstructionRow)
    return tmp


def run_stage(cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, str(ROOT / "stages" / "aggregate.py")], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def test_conf_report_default_validates_and_params_match_it():
    cfg = compose_config([])
    report = section(cfg, "report", ReportConfig)
    assert report.formats == ["md", "tex", "csv"]
    assert report.model_labels["rt1_400k"] == "RT-1-400k"
    params = yaml.safe_load((ROOT / "params.yaml").read_text())
    assert params["report"] == cfg["report"]  # params.yaml is conf/ composed


def test_bad_report_option_names_the_key():
    with pytest.raises(ConfigError, match="report.confidence"):
        section({"report": {"confidence": 1.5}}, "report", ReportConfig)
    with pytest.raises(ConfigError, match="report.colour"):
        section({"report": {"colour": "red"}}, "report", ReportConfig)


@pytest.fixture(scope="module")
def ran_repo(tmp_path_factory) -> tuple[Path, subprocess.CompletedProcess[str]]:
    """A repository layout after the aggregate stage ran once (shared by the tests below)."""
    repo = make_repo(tmp_path_factory.mktemp("repo"))
    return repo, run_stage(repo)


def test_stage_writes_what_dvc_yaml_declares(ran_repo):
    repo, proc = ran_repo
    assert proc.returncode == 0, proc.stderr
    assert "study 'smoke'" in proc.stdout
    stage = yaml.safe_load((ROOT / "dvc.yaml").read_text())["stages"]["aggregate"]
    params = yaml.safe_load((repo / "params.yaml").read_text())
    outs = [next(iter(o)) if isinstance(o, dict) else o for o in stage["outs"]]
    outs += [next(iter(m)) for m in stage["metrics"]]
    for out in outs:
        path = out.replace("${paths.reports_dir}", params["paths"]["reports_dir"]).replace(
            "${paths.metrics}", params["paths"]["metrics"])
        assert (repo / path).exists(), path
    written = {p.relative_to(repo / "reports").parts[0] for p in (repo / "reports").rglob("*") if p.is_file()}
    assert written == {"tables", "figures", "report.html", "metrics.json"}  # nothing undeclared


def test_stage_reads_only_report_and_study_name():
    stage = yaml.safe_load((ROOT / "dvc.yaml").read_text())["stages"]["aggregate"]
    assert sorted(stage["params"]) == ["report", "study.name"]
    source = (ROOT / "ladev_lib" / "pipeline" / "aggregate.py").read_text()  # what stages/aggregate.py runs
    reads = {k for k in ("study", "report", "paths", "llm", "policy", "sim", "robot", "executor") if f'"{k}"' in source}
    assert reads == {"study", "report", "paths"}
    assert 'get("name")' in source  # of study, only the name


def test_stage_fails_clearly_on_bad_config(tmp_path):
    repo = make_repo(tmp_path, report={"formats": ["docx"]})
    proc = run_stage(repo)
    assert proc.returncode == 2  # a configuration error, as the ladev CLI reports one
    assert "error: " in proc.stderr and "report.formats" in proc.stderr


def test_summary_prints_report_and_headline_numbers(ran_repo, monkeypatch):
    repo, proc = ran_repo
    assert proc.returncode == 0, proc.stderr
    monkeypatch.chdir(repo)
    result = CliRunner().invoke(cli, ["summary"])
    assert result.exit_code == 0, result.output
    metrics = json.loads((repo / "reports/metrics.json").read_text())
    assert "Study: smoke" in result.output and "report.html" in result.output
    assert f"{100 * metrics['success_rate/oracle']:.1f}%" in result.output
    lines = [ln for ln in result.output.splitlines() if ln.startswith("Success at")]
    assert [ln.split("  ")[0].rstrip(" *") for ln in lines] == ["Success at end", "Success at any step"]
    assert all(ln.split()[-5:] == ["all", "pick_up", "move_near", "put_on", "put_in"] for ln in lines)
    assert "report.success=end" in result.output
    as_json = CliRunner().invoke(cli, ["summary", "--json"])
    assert json.loads(as_json.output) == metrics


def test_summary_without_a_run_says_what_to_do(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["summary"])
    assert result.exit_code != 0
    assert "has not run yet" in result.output and "dvc repro" in result.output


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("git") is None, reason="git needed for a DVC repository")
def test_changing_a_report_option_reruns_aggregate_alone(tmp_path):
    """Under DVC: a report option changes only `aggregate`; an unrelated param changes nothing of it."""
    dvc = str(Path(sys.executable).with_name("dvc"))
    repo = make_repo(tmp_path)
    full = yaml.safe_load((ROOT / "dvc.yaml").read_text())
    (repo / "dvc.yaml").write_text(yaml.safe_dump({"stages": {"aggregate": full["stages"]["aggregate"]}}))
    for dep in full["stages"]["aggregate"]["deps"]:  # the code it depends on (the data is make_repo's)
        if "${" in dep:
            continue
        (repo / dep).parent.mkdir(parents=True, exist_ok=True)
        if (ROOT / dep).is_dir():
            shutil.copytree(ROOT / dep, repo / dep, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy(ROOT / dep, repo / dep)
    # dvc.yaml runs `python`: the interpreter running the tests, first on PATH
    path = f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PATH": path}

    def sh(*args: str) -> str:
        proc = subprocess.run(args, cwd=repo, env=env, capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stdout + proc.stderr
        return proc.stdout

    sh("git", "init", "-q")
    sh(dvc, "init", "-q")
    sh(dvc, "repro", "aggregate")
    assert "up to date" in sh(dvc, "status", "aggregate").lower()
    shown = sh(dvc, "metrics", "show")
    assert "success_rate/oracle/pick_up" in shown and "compile_ok_rate" in shown

    params = yaml.safe_load((repo / "params.yaml").read_text())
    params["llm"]["model"] = "another-model"  # not a param of aggregate
    (repo / "params.yaml").write_text(yaml.safe_dump(params, sort_keys=False))
    assert "up to date" in sh(dvc, "status", "aggregate").lower()

    params["report"]["intervals"] = True  # a report option
    (repo / "params.yaml").write_text(yaml.safe_dump(params, sort_keys=False))
    status = sh(dvc, "status", "aggregate")
    assert "aggregate" in status and "modified" in status and "report" in status
    sh(dvc, "repro", "aggregate")
    assert "(" in (repo / "reports/tables/table1_num_objects.md").read_text().split("| Model")[1]
