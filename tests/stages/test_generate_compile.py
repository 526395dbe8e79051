"""The generate and compile stages on the default study, directly and under `dvc repro`."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest
import yaml

from ladev_lib.scenes.spec import SceneSpec
from ladev_lib.store import ContentStore
from ladev_lib.tables import CompiledSceneRow, SceneDesignRow, read_table
from tests.repo_copy import BIN, run


def calls(output: str, stage: str) -> tuple[int, int]:
    m = re.search(rf"^{stage}: .*LLM calls: (\d+) made, (\d+) cached", output, re.MULTILINE)
    assert m, output[-2000:]
    return int(m.group(1)), int(m.group(2))


def store_size(repo: Path, stage: str) -> int:
    store = ContentStore(repo / "data/cache/llm" / stage)
    try:
        return len(store)
    finally:
        store.close()


def test_stages_write_valid_tables_and_a_rerun_makes_no_call(repo_copy, catalog):
    out = run([sys.executable, "stages/generate.py"], repo_copy)
    out += run([sys.executable, "stages/compile.py"], repo_copy)
    assert calls(out, "generate") == (36, 0) and calls(out, "compile") == (36, 0)
    scenes = read_table(repo_copy / "data/scenes.parquet", SceneDesignRow)
    compiled = read_table(repo_copy / "data/compiled.parquet", CompiledSceneRow)
    assert scenes.height == compiled.height == 36
    assert compiled["scene_id"].to_list() == scenes["scene_id"].to_list()
    assert set(compiled["status"]) == {"ok"} and "validity" not in compiled.columns  # checked per episode
    for row in compiled.iter_rows(named=True):
        spec = SceneSpec.from_json(row["spec_json"], catalog=catalog)
        assert spec.scene_id == row["scene_id"]
    again = run([sys.executable, "stages/generate.py"], repo_copy)
    again += run([sys.executable, "stages/compile.py"], repo_copy)
    assert calls(again, "generate") == (0, 36) and calls(again, "compile") == (0, 36)


@pytest.mark.slow
def test_dvc_repro_runs_once_then_does_nothing_and_a_grown_study_makes_only_new_calls(repo_copy):
    dvc = str(BIN / "dvc")
    first = run([dvc, "repro", "generate", "compile"], repo_copy)
    assert calls(first, "generate") == (36, 0) and calls(first, "compile") == (36, 0)
    sizes = store_size(repo_copy, "generate"), store_size(repo_copy, "compile")
    assert sizes == (36, 36)

    second = run([dvc, "repro", "generate", "compile"], repo_copy)
    assert "Stage 'generate' didn't change, skipping" in second
    assert "Stage 'compile' didn't change, skipping" in second and "LLM calls" not in second
    assert (store_size(repo_copy, "generate"), store_size(repo_copy, "compile")) == sizes

    old = read_table(repo_copy / "data/scenes.parquet", SceneDesignRow)
    params_path = repo_copy / "params.yaml"
    params = yaml.safe_load(params_path.read_text())
    params["study"]["factors"]["num_objects"]["scenes_per_level"] = 2  # fits in the existing batches
    params["study"]["factors"]["environment"]["scenes_per_level"] = 9  # one more batch per (task, level)
    params_path.write_text(yaml.safe_dump(params, sort_keys=False))
    grown = run([dvc, "repro", "generate", "compile"], repo_copy)

    new = read_table(repo_copy / "data/scenes.parquet", SceneDesignRow)
    assert new.height == 36 + 4 * 3 * 1 + 4 * 3 * 8
    added = new.filter(~new["scene_id"].is_in(old["scene_id"].to_list()))
    # Only new calls: 12 new describe batches; one compile call per new distinct text.
    old_texts = set(zip(old["description"], old["base_instruction"], old["task"], strict=True))
    new_texts = set(zip(added["description"], added["base_instruction"], added["task"], strict=True)) - old_texts
    assert calls(grown, "generate") == (12, 36)
    assert calls(grown, "compile")[0] == len(new_texts) > 100
    assert store_size(repo_copy, "generate") == sizes[0] + 12
    assert store_size(repo_copy, "compile") == sizes[1] + len(new_texts)
    kept = new.filter(new["scene_id"].is_in(old["scene_id"].to_list()))
    assert kept.sort("scene_id").equals(old.sort("scene_id"))
