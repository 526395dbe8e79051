"""Each ``ladev_lib.pipeline`` module on a tiny configuration: its table and its typed summary.

The stage scripts and ``ladev compile`` only call these; here they are called
directly, so what they return (not only what they print) is checked.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from ladev_lib.cli import cli
from ladev_lib.config import compose_config
from ladev_lib.errors import ConfigError, LadevError
from ladev_lib.pipeline import StageMessages, run_stage
from ladev_lib.pipeline.compile import (
    CompileSummary,
    compile_design,
    compile_line,
    rejection_lines,
    run_compile,
    scene_compiler,
)
from ladev_lib.pipeline.generate import GenerateSummary, run_generate
from ladev_lib.rollout.engine import RolloutSummary
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    InstructionRow,
    SceneDesignRow,
    read_table,
)


@pytest.fixture
def tiny(repo_root: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict:
    """The tiny study's configuration, its relative paths under this test's directory."""
    monkeypatch.chdir(tmp_path)
    return compose_config(["study=tiny"], repo_root / "conf")


def test_generate_then_compile_return_their_tables_and_summaries(tiny):
    gen = run_generate(tiny, progress=False)
    assert isinstance(gen.summary, GenerateSummary)
    scenes = read_table(gen.table, SceneDesignRow)
    assert gen.table == Path(tiny["paths"]["scenes"]) and scenes.height == len(gen.rows) == gen.summary.scenes
    assert gen.summary.ok == gen.summary.scenes == 12 and not gen.summary.failed_batches
    assert gen.summary.calls > 0 and gen.summary.cached == 0
    assert gen.messages().out[0].startswith("generate: 12 scenes (12 ok, 0 failed)")

    comp = run_compile(tiny)
    assert isinstance(comp.summary, CompileSummary)
    compiled = read_table(comp.table, CompiledSceneRow)
    assert compiled["scene_id"].to_list() == scenes["scene_id"].to_list() == [r.scene_id for r in comp.results]
    assert comp.summary.ok == 12 and comp.summary.calls == 12 and not comp.summary.rejections
    again = run_compile(tiny)  # every call answered from the cache, the same rows
    assert (again.summary.calls, again.summary.cached) == (0, 12)
    assert read_table(again.table, CompiledSceneRow).equals(compiled)


def test_rejections_are_rows_with_reasons_and_are_counted(tiny):
    setup = scene_compiler(tiny, None)
    failed = SceneDesignRow(
        scene_id="s1", study="t", task="pick_up", factor="num_objects", level="1", num_objects=1,
        object_set="simpler", environment="default", robot="panda", seed=0, status="failed", reason="no answer",
        description=None, base_instruction=None,
    )
    row = compile_design(setup.compiler, failed)
    assert (row.status, row.reason, row.calls) == ("rejected", "generation failed: no answer", 0)
    bad = [compile_line(setup.compiler, 1, "{not json", "panda"), compile_line(setup.compiler, 2, '{"id": "x"}', "panda")]
    assert [r.scene_id for r in bad] == ["line-1", "x"] and {r.status for r in bad} == {"rejected"}
    assert bad[0].reason.startswith("line 1: not JSON") and "description" in bad[1].reason
    reasons = [r.reason or "" for r in (row, row, *bad)]  # counted by the part before the first colon
    assert rejection_lines(reasons) == (
        "  rejected x2: generation failed", "  rejected x1: line 1", "  rejected x1: line 2",
    )


def test_cli_compile_and_the_stage_give_the_same_rows(tiny, repo_root, tmp_path):
    gen = run_generate(tiny, progress=False)
    stage = {r.scene_id: r.as_dict() for r in run_compile(tiny).results}
    lines = [
        json.dumps({"id": r.scene_id, "description": r.description, "instruction": r.base_instruction,
                    "task": r.task, "seed": r.seed, "object_set": r.object_set, "robot": r.robot})
        for r in gen.rows
    ]
    (tmp_path / "in.jsonl").write_text("\n".join(lines) + "\n")
    result = CliRunner().invoke(
        cli, ["compile", "in.jsonl", "study=tiny", "-o", "out.jsonl", "--config-dir", str(repo_root / "conf")]
    )
    assert result.exit_code == 0, result.output
    assert "compiled 12 descriptions: 12 ok, 0 rejected -> out.jsonl" in result.output
    cli_rows = [json.loads(line) for line in (tmp_path / "out.jsonl").read_text().splitlines()]
    assert [r["id"] for r in cli_rows] == list(stage)
    for row in cli_rows:
        assert row == stage[row["id"]]


def test_paraphrase_returns_its_table_and_validates_the_study(repo_root, tmp_path, monkeypatch):
    from ladev_lib.pipeline.paraphrase import ParaphraseSummary, run_paraphrase
    from tests.language.conftest import write_stage_inputs

    cfg = write_stage_inputs(tmp_path, repo_root)
    monkeypatch.chdir(tmp_path)
    result = run_paraphrase(cfg)
    assert isinstance(result.summary, ParaphraseSummary)
    table = read_table(result.table, InstructionRow)
    assert table.height == len(result.rows) and result.summary.scenes == 16
    assert result.summary.skipped == {"generation failed": 1, "not compiled": 1}
    assert table.filter(table["kind"] == "paraphrase").height == 16 * cfg["study"]["paraphrases_per_instruction"]

    cfg["study"]["paraphrases_per_instruction"] = 0  # validated by StudyConfig, not read raw
    with pytest.raises(ConfigError, match="study.paraphrases_per_instruction"):
        run_paraphrase(cfg)


def test_rollout_returns_its_table_summary_and_exit_code(tmp_path, monkeypatch):
    from ladev_lib.pipeline.rollout import run_rollout
    from tests.rollout.conftest import toy_config, write_study
    from tests.rollout.doubles import (
        MARKER_DIR_ENV,
        RUN_LOG_ENV,
        make_scripted_policy,
        make_toy_sim,
    )

    (tmp_path / "markers").mkdir()
    monkeypatch.setenv(MARKER_DIR_ENV, str(tmp_path / "markers"))
    monkeypatch.setenv(RUN_LOG_ENV, str(tmp_path / "runs.log"))
    write_study(tmp_path, [{"scene_id": "a"}, {"scene_id": "b", "task": "put_on", "num_objects": 2}])
    result = run_rollout(
        toy_config(), "toy", root=tmp_path, progress=False,
        sim_factory=make_toy_sim, policy_factory=make_scripted_policy,
    )
    assert isinstance(result.summary, RolloutSummary) and result.exit_code == 0
    assert read_table(result.table, EpisodeRow).height == result.summary.planned == 2
    assert result.timings is not None and result.timings.is_file()
    wrote = f"rollout: wrote {result.table} and {result.timings}"
    assert result.messages() == StageMessages((result.summary.format(), wrote))
    with pytest.raises(ConfigError, match="not configured"):
        run_rollout(toy_config(), "nobody", root=tmp_path)


def test_aggregate_returns_its_files_and_summary(tmp_path, monkeypatch):
    import yaml

    from ladev_lib.pipeline.aggregate import AggregateSummary, run_aggregate
    from tests.report.test_stage_and_cli import make_repo

    repo = make_repo(tmp_path)
    monkeypatch.chdir(repo)
    result = run_aggregate(yaml.safe_load((repo / "params.yaml").read_text()))
    assert isinstance(result.summary, AggregateSummary)
    s = result.summary
    assert 0 < s.episodes <= 800 and s.policies == 2 and s.study == "smoke"  # 800 made; rejected scenes' left out
    assert result.files and all(p.exists() for p in result.files) and s.files == len(result.files)
    assert result.messages().out[0].startswith(f"aggregate: study 'smoke': {s.episodes} episodes, 2 policies")


def test_run_stage_prints_messages_and_reports_a_ladev_error_as_the_cli_does(capsys, monkeypatch):
    monkeypatch.delenv("LADEV_DEBUG", raising=False)
    assert run_stage(lambda: StageMessages(("done",), ("careful",), 1)) == 1
    printed = capsys.readouterr()
    assert (printed.out, printed.err) == ("done\n", "careful\n")

    def broken() -> StageMessages:
        raise ConfigError("paths.scenes is not set")

    assert run_stage(broken) == 2
    printed = capsys.readouterr()
    assert (printed.out, printed.err) == ("", "error: paths.scenes is not set\n")
    monkeypatch.setenv("LADEV_DEBUG", "1")
    with pytest.raises(LadevError):
        run_stage(broken)
