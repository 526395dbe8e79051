"""Fixtures for the engine tests: a tiny study on disk and a config that runs it on ToySim."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import polars as pl
import pytest

from ladev_lib.catalog import load_catalog
from ladev_lib.language.instructions import basic_instruction
from ladev_lib.scenes.sampling import sample_scene
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    InstructionRow,
    SceneDesignRow,
    read_table,
    write_table,
)

# Columns that measure time: they differ between any two runs, so they live in the
# timings table (paths.timings_dir), never in the episode table.
TIMING_COLUMNS = ("sim_seconds", "policy_seconds", "total_seconds")


def write_study(
    root: Path,
    scenes: list[dict[str, Any]],
    *,
    study: str = "toy",
) -> None:
    """Write scenes/compiled/instructions tables for ``scenes``.

    Each entry: ``scene_id``, ``task`` (default pick_up), ``factor`` (default
    num_objects), ``level`` ("1"), ``num_objects`` (1), ``seed`` (index),
    ``basic`` (instruction text; default the basic form), ``paraphrases`` (list of
    (text, selected)), ``status`` ("ok").
    """
    catalog = load_catalog()
    design, compiled, instructions = [], [], []
    for i, s in enumerate(scenes):
        task, n = s.get("task", "pick_up"), s.get("num_objects", 1)
        seed = s.get("seed", i)
        spec = sample_scene(
            task, n, "simpler", np.random.default_rng(1000 + seed), catalog,
            seed=seed, scene_id=s["scene_id"],
        )
        disp = catalog.get(spec.source.id).display_name
        tgt = catalog.get(spec.target.id).display_name if spec.target else None
        basic = s.get("basic") or basic_instruction(task, disp, tgt)
        factor = s.get("factor", "num_objects")
        design.append(SceneDesignRow(
            scene_id=s["scene_id"], study=study, task=task, factor=factor,
            level=s.get("level", "basic+paraphrase" if factor == "instruction" else str(n)),
            num_objects=n, object_set="simpler", environment="default", robot="panda", seed=seed,
            description="a toy scene", base_instruction=basic, status="ok",
        ))
        ok = s.get("status", "ok") == "ok"
        compiled.append(CompiledSceneRow(
            scene_id=s["scene_id"], status="ok" if ok else "rejected",
            reason=None if ok else "rejected by the test", spec_json=spec.to_json() if ok else None,
        ))
        instructions.append(InstructionRow(
            instruction_id=f"{s['scene_id']}/basic", scene_id=s["scene_id"], kind="basic",
            text=basic, valid=True, selected=True,
        ))
        for k, (text, selected) in enumerate(s.get("paraphrases", [])):
            instructions.append(InstructionRow(
                instruction_id=f"{s['scene_id']}/para-{k}", scene_id=s["scene_id"], kind="paraphrase",
                text=text, similarity=0.9, valid=True, selected=selected,
            ))
    write_table(design, root / "data/scenes.parquet", SceneDesignRow)
    write_table(compiled, root / "data/compiled.parquet", CompiledSceneRow)
    write_table(instructions, root / "data/instructions.parquet", InstructionRow)


def toy_config(executor: dict[str, Any] | None = None, **rollout: Any) -> dict[str, Any]:
    """A composed configuration (like params.yaml) for the toy study."""
    return {
        "study": {"name": "toy"},
        "policy": {"toy": {"name": "scripted-toy"}},
        "sim": {"image_size": [32, 32]},
        "robot": {"name": "panda"},
        "executor": executor or {"name": "serial"},
        "rollout": {"frames": False, "step_timeout_s": 3.0, "setup_timeout_s": 60.0, **rollout},
        "paths": {
            "scenes": "data/scenes.parquet",
            "compiled": "data/compiled.parquet",
            "instructions": "data/instructions.parquet",
            "episodes_dir": "data/episodes",
            "timings_dir": "data/timings",
            "media_dir": "data/media",
            "episode_store_dir": "data/cache/episodes",
        },
    }


def run_toy(root: Path, cfg: dict[str, Any]) -> Any:
    """Run the rollout stage of the toy study with the test doubles."""
    from ladev_lib.rollout.stage import rollout_stage
    from tests.rollout.doubles import make_scripted_policy, make_toy_sim

    return rollout_stage(
        cfg, "toy", root=root, progress=False, sim_factory=make_toy_sim, policy_factory=make_scripted_policy
    )


def comparable(df: pl.DataFrame) -> pl.DataFrame:
    """The episode table as it must repeat: it holds no timing column to leave out."""
    assert not set(TIMING_COLUMNS) & set(df.columns), "timings belong in the timings table"
    return df


def read_episodes(root: Path, label: str = "toy") -> pl.DataFrame:
    return read_table(root / f"data/episodes/{label}.parquet", EpisodeRow)


@pytest.fixture
def toy_env(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Markers and run log of the scripted policy go to this test's directory."""
    from tests.rollout.doubles import MARKER_DIR_ENV, RUN_LOG_ENV

    (tmp_path / "markers").mkdir()
    monkeypatch.setenv(MARKER_DIR_ENV, str(tmp_path / "markers"))
    monkeypatch.setenv(RUN_LOG_ENV, str(tmp_path / "runs.log"))
    return tmp_path


def run_log(root: Path) -> list[str]:
    path = root / "runs.log"
    return [ln.split("\t")[0] for ln in path.read_text().splitlines()] if path.exists() else []


StudyWriter = Callable[..., None]
