"""The paraphrase stage on tiny hand-made inputs, as a script and under ``dvc repro``."""

from __future__ import annotations

import json
import runpy
import subprocess
from pathlib import Path

import polars as pl
import pytest
import yaml

from ladev_lib.language.llm_jobs import ParaphraseAnswer
from ladev_lib.language.parser import InstructionParse
from ladev_lib.llm.client import LLMClient
from ladev_lib.llm.config import LLMConfig
from ladev_lib.pipeline.instructions import SceneTask, paraphrase_scenes
from ladev_lib.tables import InstructionRow, read_table
from tests.language.conftest import write_stage_inputs
from tests.language.test_llm_jobs import ScriptedBackend
from tests.repo_copy import copy_repo, stage_env


def _run_stage(repo_root: Path, workdir: Path, monkeypatch) -> None:
    monkeypatch.chdir(workdir)
    stage = runpy.run_path(str(repo_root / "stages/paraphrase.py"), run_name="paraphrase_stage")
    assert stage["main"](["--params", "params.yaml"]) == 0


def test_stage_writes_basic_and_validated_paraphrases(repo_root, tmp_path, monkeypatch, capsys):
    cfg = write_stage_inputs(tmp_path, repo_root)
    k = cfg["study"]["paraphrases_per_instruction"]
    _run_stage(repo_root, tmp_path, monkeypatch)
    first = capsys.readouterr().out
    df = read_table(tmp_path / cfg["paths"]["instructions"], InstructionRow)

    scene_ids = set(df["scene_id"])
    assert len(scene_ids) == 16 and "failed-gen" not in scene_ids and "rejected" not in scene_ids
    basic = df.filter(pl.col("kind") == "basic")
    assert basic.height == 16 and basic["valid"].all() and basic["selected"].all()
    assert basic["reason"].is_null().all()  # every basic instruction reads as its spec's task
    para = df.filter(pl.col("kind") == "paraphrase")
    assert para.height == 16 * k
    threshold = cfg["paraphrase"]["similarity_threshold"]
    assert para["similarity"].is_not_null().all()
    # the canonical-name similarity is computed exactly where the as-written one falls short
    assert (para["canonical_similarity"].is_not_null() == (para["similarity"] < threshold)).all()
    assert para["valid"].all()  # the offline paraphraser writes only faithful sentences
    assert (para["parsed_task"] == para.join(basic, on="scene_id")["parsed_task_right"]).all()

    selected = para.filter(pl.col("selected"))
    assert sorted(selected["scene_id"]) == sorted(s for s in scene_ids if "-instruction-" in s)
    assert "16 scenes (2 skipped" in first and "8/8 instruction-factor scenes" in first

    # a second run answers every call from the cache and draws the same paraphrases
    _run_stage(repo_root, tmp_path, monkeypatch)
    assert "LLM calls 0" in capsys.readouterr().out
    again = read_table(tmp_path / cfg["paths"]["instructions"], InstructionRow)
    assert again.filter(pl.col("selected"))["instruction_id"].to_list() == df.filter(pl.col("selected"))["instruction_id"].to_list()


def test_bad_llm_answers_become_rows_with_reasons(validator, repo_root):
    from ladev_lib.config import compose_config
    from ladev_lib.llm.prompts import load_prompts

    prompts = load_prompts(compose_config([], repo_root / "conf"), ["paraphrase"])
    good = SceneTask("s1", "instruction", "put the carrot on the plate",
                     InstructionParse("put the carrot on the plate", "put_on", "carrot", "plate"),
                     frozenset({"carrot", "plate", "sponge"}))
    broken = SceneTask("s2", "instruction", "pick up the apple",
                       InstructionParse("pick up the apple", "pick_up", "apple", None), frozenset({"apple"}))
    answer = ParaphraseAnswer(paraphrases=[
        "Put the carrot on the plate.",            # the original itself: dropped
        "could you set the carrot on the dish?",   # valid
        "Could you set the carrot on the dish",    # a duplicate: dropped
        "put the plate on the carrot",             # role swap
        "put the carrot on the sponge",            # destination change
    ]).model_dump_json()
    backend = ScriptedBackend([answer, "not json", "not json", "not json"])
    client = LLMClient(backend, repair_attempts=2)
    out = paraphrase_scenes([good, broken], client=client, prompt=prompts["paraphrase"], llm=LLMConfig(),
                            validator=validator, k=4, seed=0)
    rows = {r.instruction_id: r for r in out.rows}
    assert rows["s1/para-1"].valid and rows["s1/para-1"].selected
    assert "roles swapped" in rows["s1/para-2"].reason and not rows["s1/para-2"].valid
    assert "destination changed: plate -> sponge" in rows["s1/para-3"].reason
    assert "s1/para-4" not in rows
    assert not rows["s2/para-error"].valid and "no usable answer" in rows["s2/para-error"].reason
    assert out.summary["instruction_scenes_without_valid_paraphrase"] == ["s2"]
    assert rows["s2/basic"].selected


@pytest.mark.slow
def test_stage_under_dvc_repro(repo_root, tmp_path):
    """`dvc repro paraphrase` in a copy of the repository runs generate -> compile -> paraphrase;
    a second repro does nothing; a changed validation parameter re-runs only the paraphrase
    stage, without new LLM calls."""
    copy = copy_repo(repo_root, tmp_path / "repo", commit=True)
    env = stage_env()

    def repro() -> str:
        done = subprocess.run(["dvc", "repro", "paraphrase"], cwd=copy, env=env,
                              capture_output=True, text=True, timeout=900)
        assert done.returncode == 0, done.stdout + done.stderr
        return done.stdout

    out = repro()
    for stage in ("generate", "compile", "paraphrase"):
        assert f"Running stage '{stage}'" in out
    params = yaml.safe_load((copy / "params.yaml").read_text())
    df = read_table(copy / params["paths"]["instructions"], InstructionRow)
    k = params["study"]["paraphrases_per_instruction"]
    basic = df.filter(pl.col("kind") == "basic")
    assert basic.height > 0 and df.filter(pl.col("kind") == "paraphrase").height == k * basic.height
    chosen = df.filter(pl.col("selected") & (pl.col("kind") == "paraphrase"))
    assert chosen.height == basic.filter(pl.col("scene_id").str.contains("-instruction-")).height > 0
    assert chosen["valid"].all()

    again = repro()
    assert "didn't change" in again and "Running stage" not in again
    params["paraphrase"]["similarity_threshold"] = 0.6
    (copy / "params.yaml").write_text(yaml.safe_dump(params, sort_keys=False))
    out = repro()
    assert "Running stage 'paraphrase'" in out and "Running stage 'compile'" not in out
    assert "LLM calls 0" in out
    lock = yaml.safe_load((copy / "dvc.lock").read_text())
    assert json.dumps(lock["stages"]["paraphrase"]["params"]).count("similarity_threshold") == 1
