"""Synthetic episode tables with known answers, for tests, benchmarks and demos.

Two generators, both returning frames with exactly the ``EpisodeRow`` schema:

- :func:`episodes_from_counts`: exact outcome counts per cell (and paired
  outcome tables for the ``instruction`` factor), so every rate, interval and
  test has an answer computable by hand.
- :func:`random_episodes`: a study of any size laid out like the paper's
  design, with success drawn from per-(policy, task, factor, level)
  probabilities; vectorised, so 100,000 rows take well under a second.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import polars as pl

from ladev_lib.arrays import Array
from ladev_lib.tables import EpisodeRow, polars_schema
from ladev_lib.vocabulary import ENVIRONMENTS, OBJECT_SETS, TASKS

DESIGN: dict[str, tuple[str, ...]] = {
    "num_objects": ("1", "2", "3", "4", "5"),
    "instruction": ("basic", "paraphrase"),
    "object_set": OBJECT_SETS,
    "environment": ENVIRONMENTS,
}


@dataclass(frozen=True)
class CellCounts:
    """Exact outcomes of one (policy, task, factor, level) cell."""

    policy: str
    task: str
    factor: str
    level: str
    successes: int = 0
    failures: int = 0
    errors: int = 0
    invalid: int = 0


@dataclass(frozen=True)
class PairedCounts:
    """Outcomes of scenes run with both instructions: (basic, paraphrase) success."""

    policy: str
    task: str
    both: int = 0
    basic_only: int = 0
    paraphrase_only: int = 0
    neither: int = 0


def _finish(columns: Mapping[str, Sequence[object] | Array], study: str) -> pl.DataFrame:
    """Fill derived columns and cast to the episode schema."""
    df = pl.DataFrame(columns)
    n = df.height
    factor, level = pl.col("factor"), pl.col("level")
    df = df.with_columns(
        study=pl.lit(study),
        num_objects=pl.when(factor == "num_objects")
        .then(level.cast(pl.Int64, strict=False))
        .otherwise(pl.col("index") % 4 + 1),
        object_set=pl.when(factor == "object_set").then(level).otherwise(pl.lit("simpler")),
        environment=pl.when(factor == "environment").then(level).otherwise(pl.lit("default")),
        instruction_kind=pl.when(level == "paraphrase").then(pl.lit("paraphrase")).otherwise(pl.lit("basic")),
        scene_id=pl.when(factor == "instruction")
        .then(pl.format("{}-instruction-basic+paraphrase-{}", "task", pl.col("index").cast(pl.String).str.zfill(4)))
        .otherwise(pl.format("{}-{}-{}-{}", "task", "factor", "level", pl.col("index").cast(pl.String).str.zfill(4))),
        robot=pl.lit("panda"),
        seed=pl.col("index"),
        success=pl.when(pl.col("status") == "success").then(True)
        .when(pl.col("status") == "failure").then(False),
        predicates_json=pl.lit("{}"),
        steps=pl.lit(80, dtype=pl.Int64),
        trial=pl.lit(0, dtype=pl.Int64),
        control=pl.lit(None, dtype=pl.String),
        success_end=pl.when(pl.col("status") == "success").then(True)
        .when(pl.col("status") == "failure").then(False),
        success_any=pl.when(pl.col("status") == "success").then(True)
        .when(pl.col("status") == "failure").then(False),
        first_success_step=pl.when(pl.col("status") == "success").then(pl.lit(80, dtype=pl.Int64)),
        error=pl.when(pl.col("status") == "error").then(pl.lit("RuntimeError: synthetic crash"))
        .when(pl.col("status") == "invalid_scene").then(pl.lit("objects overlap after settling")),
        video_path=pl.lit(None, dtype=pl.String),
        first_frame_path=pl.lit(None, dtype=pl.String),
        last_frame_path=pl.lit(None, dtype=pl.String),
    ).with_columns(
        instruction_id=pl.when(pl.col("instruction_kind") == "paraphrase")
        .then(pl.format("{}/para-0", "scene_id")).otherwise(pl.format("{}/basic", "scene_id")),
        instruction=pl.when(pl.col("instruction_kind") == "paraphrase")
        .then(pl.lit("could you grab the coke can")).otherwise(pl.lit("pick up the coke can")),
    ).with_columns(
        episode_id=pl.format("{}:{}:{}", "policy", "instruction_id", pl.int_range(n, dtype=pl.Int64)),
    )
    schema = polars_schema(EpisodeRow)
    return df.select([pl.col(c).cast(t) for c, t in schema.items()])


def episodes_from_counts(
    cells: Iterable[CellCounts] = (), paired: Iterable[PairedCounts] = (), study: str = "synthetic"
) -> pl.DataFrame:
    """Episodes realising exactly the given counts (scene ids unique per cell)."""
    cols: dict[str, list[object]] = {k: [] for k in ("policy", "task", "factor", "level", "status", "index")}

    def add(policy: str, task: str, factor: str, level: str, status: str, count: int, start: int) -> int:
        for i in range(start, start + count):
            for key, value in zip(cols, (policy, task, factor, level, status, i), strict=True):
                cols[key].append(value)
        return start + count

    for c in cells:
        i = 0
        for status, count in (
            ("success", c.successes), ("failure", c.failures), ("error", c.errors), ("invalid_scene", c.invalid)
        ):
            i = add(c.policy, c.task, c.factor, c.level, status, count, i)
    for p in paired:
        i = 0
        for basic_ok, para_ok, count in (
            (True, True, p.both), (True, False, p.basic_only), (False, True, p.paraphrase_only), (False, False, p.neither)
        ):
            add(p.policy, p.task, "instruction", "basic", "success" if basic_ok else "failure", count, i)
            i = add(p.policy, p.task, "instruction", "paraphrase", "success" if para_ok else "failure", count, i)
    return _finish(cols, study)


def random_episodes(
    n_rows: int,
    policies: Sequence[str] = ("oracle", "grounded"),
    seed: int = 0,
    study: str = "synthetic",
    error_rate: float = 0.01,
    invalid_rate: float = 0.01,
    base_success: dict[str, float] | None = None,
) -> pl.DataFrame:
    """About ``n_rows`` episodes over the paper's design, drawn at random.

    Success probability: the policy's base rate, lowered by 4 points per extra
    object, 10 for paraphrases, 15 for YCB and 8 for lighting changes.
    Paraphrase episodes share the scene of their basic episode (paired).
    """
    rng = np.random.default_rng(seed)
    levels = [(f, lv) for f, lvs in DESIGN.items() for lv in lvs]
    per_cell = max(1, n_rows // (len(policies) * len(TASKS) * len(levels)))
    base = base_success or {p: 0.8 - 0.5 * i / max(1, len(policies)) for i, p in enumerate(policies)}
    penalty = {("instruction", "paraphrase"): 0.10, ("object_set", "ycb"): 0.15, ("environment", "lighting"): 0.08}
    grid = [(p, t, f, lv) for p in policies for t in TASKS for f, lv in levels]
    cell = np.repeat(np.arange(len(grid)), per_cell)
    index = np.tile(np.arange(per_cell), len(grid))
    prob = np.array(
        [
            base[p] - (0.04 * (int(lv) - 1) if f == "num_objects" else penalty.get((f, lv), 0.0))
            for p, _, f, lv in grid
        ]
    )[cell].clip(0.0, 1.0)
    u = rng.random(cell.size)
    status = np.where(
        u < error_rate,
        "error",
        np.where(u < error_rate + invalid_rate, "invalid_scene",
                 np.where(rng.random(cell.size) < prob, "success", "failure")),
    )
    columns = {
        "policy": np.array([g[0] for g in grid])[cell],
        "task": np.array([g[1] for g in grid])[cell],
        "factor": np.array([g[2] for g in grid])[cell],
        "level": np.array([g[3] for g in grid])[cell],
        "status": status,
        "index": index,
    }
    return _finish(columns, study)


def stage_tables_for(
    episodes: pl.DataFrame, rejected_scenes: int = 0, invalid_paraphrases_per_scene: int = 1
) -> tuple[pl.DataFrame, pl.DataFrame, pl.DataFrame]:
    """Scenes, compiled scenes and instructions consistent with ``episodes``.

    Adds ``rejected_scenes`` scenes that failed to compile (no episodes) and,
    per scene, one selected valid paraphrase plus ``invalid_paraphrases_per_scene``
    rejected ones, so the stage validity rates have known values.
    """
    from ladev_lib.tables import CompiledSceneRow, InstructionRow, SceneDesignRow

    scenes = episodes.select("scene_id", "study", "task", "factor", "num_objects", "object_set",
                             "environment", "robot", "seed").unique("scene_id", keep="first").sort("scene_id")
    scenes = scenes.with_columns(level=pl.col("scene_id").str.split("-").list.get(-2))
    if rejected_scenes:
        extra = scenes.head(1).select(pl.exclude("scene_id")).join(
            pl.DataFrame({"scene_id": [f"rejected-{i:03d}" for i in range(rejected_scenes)]}), how="cross"
        )
        scenes = pl.concat([scenes, extra.select(scenes.columns)])
    scenes = scenes.with_columns(
        description=pl.format("Number and details of objects: {} objects. Task: {}.", "num_objects", "task"),
        base_instruction=pl.lit("pick up the coke can"),
        status=pl.lit("ok"),
        reason=pl.lit(None, dtype=pl.String),
        llm_call_ids=pl.lit([], dtype=pl.List(pl.String)),
    )
    rejected = pl.col("scene_id").str.starts_with("rejected-")
    compiled = scenes.select(
        "scene_id",
        status=pl.when(rejected).then(pl.lit("rejected")).otherwise(pl.lit("ok")),
        reason=pl.when(rejected).then(pl.lit("unknown object 'unicorn'")),
        operations_json=pl.lit("[]"),
        spec_json=pl.when(~rejected).then(pl.lit("{}")),
        notes=pl.lit([], dtype=pl.List(pl.String)),
        llm_call_ids=pl.lit([], dtype=pl.List(pl.String)),
    )
    ok_scenes = scenes.filter(~rejected).select("scene_id")
    basic = ok_scenes.with_columns(instruction_id=pl.format("{}/basic", "scene_id"), kind=pl.lit("basic"),
                                   text=pl.lit("pick up the coke can"), valid=pl.lit(True), selected=pl.lit(True),
                                   reason=pl.lit(None, dtype=pl.String))
    para = [ok_scenes.with_columns(instruction_id=pl.format("{}/para-0", "scene_id"), kind=pl.lit("paraphrase"),
                                   text=pl.lit("could you grab the coke can"), valid=pl.lit(True),
                                   selected=pl.lit(True), reason=pl.lit(None, dtype=pl.String))]
    for k in range(1, invalid_paraphrases_per_scene + 1):
        para.append(ok_scenes.with_columns(
            instruction_id=pl.format("{}/para-{}", "scene_id", pl.lit(k)), kind=pl.lit("paraphrase"),
            text=pl.lit("pick up the pepsi can"), valid=pl.lit(False), selected=pl.lit(False),
            reason=pl.lit("object changed: coke_can -> pepsi_can"),
        ))
    instructions = pl.concat([basic, *para]).with_columns(
        similarity=pl.when(pl.col("kind") == "paraphrase").then(pl.lit(0.8)),
        canonical_similarity=pl.lit(None, dtype=pl.Float64),
        parsed_task=pl.lit("pick_up"), parsed_source=pl.lit("coke_can"),
        parsed_target=pl.lit(None, dtype=pl.String), llm_call_ids=pl.lit([], dtype=pl.List(pl.String)),
        control=pl.lit(None, dtype=pl.String),
    )

    def cast(frame: pl.DataFrame, model: type[SceneDesignRow | CompiledSceneRow | InstructionRow]) -> pl.DataFrame:
        return frame.select([pl.col(c).cast(t) for c, t in polars_schema(model).items()])

    return cast(scenes, SceneDesignRow), cast(compiled, CompiledSceneRow), cast(instructions, InstructionRow)
