"""Episode rows -> success-rate cells, in polars (no per-row Python).

A cell is one (policy, task, factor, level). Its rate counts only episodes the
policy was judged on (``success`` or ``failure``); ``error`` (the rollout
crashed) and ``invalid_scene`` (the scene could not be built as specified) are
counted apart, because they say nothing about the policy.

With several trials per scene (``study.trials_per_scene``) a cell's episodes
are not independent: its interval is then the Wilson interval over scenes
(each scene counts once, with its trials' mean success), which assumes the
trials of a scene fully agree and so never overstates what the study shows.
The column ``interval`` names the method of each row.
"""

from __future__ import annotations

from collections.abc import Sequence

import polars as pl

from ladev_lib.report.stats import wilson_exprs
from ladev_lib.tables import EpisodeRow, polars_schema

JUDGED = ("success", "failure")
EXCLUDED = ("error", "invalid_scene")
CELL_KEYS = ("policy", "task", "factor", "level")
AVERAGE_LEVEL = "avg"
# Factors whose paper table has an average column over its levels (Table I).
AVERAGED_FACTORS = ("num_objects",)


def empty_episodes() -> pl.DataFrame:
    return pl.DataFrame(schema=polars_schema(EpisodeRow))


def count_outcomes(episodes: pl.DataFrame, keys: Sequence[str], confidence: float = 0.95) -> pl.DataFrame:
    """Outcome counts, success rate and Wilson interval per group of ``keys``.

    Columns: keys..., n_episodes, successes, failures, n_error, n_invalid_scene,
    n (judged episodes), success_rate (null when n is 0), ci_low, ci_high, interval
    ("Wilson", or "Wilson over scenes" where a scene has several judged episodes).
    """
    status = pl.col("status")
    counts = episodes.group_by(list(keys)).agg(
        n_episodes=pl.len().cast(pl.Int64),
        successes=(status == "success").sum().cast(pl.Int64),
        failures=(status == "failure").sum().cast(pl.Int64),
        n_error=(status == "error").sum().cast(pl.Int64),
        n_invalid_scene=(status == "invalid_scene").sum().cast(pl.Int64),
    )
    rated = with_rates(counts, confidence)
    return with_scene_intervals(rated, episodes, keys, confidence).sort(list(keys))


def with_scene_intervals(
    rated: pl.DataFrame, episodes: pl.DataFrame, keys: Sequence[str], confidence: float
) -> pl.DataFrame:
    """Replace the Wilson bounds of groups where a scene has several judged episodes by the
    Wilson bounds over scenes (scene-mean successes out of the number of scenes)."""
    keys = list(keys)
    judged = episodes.filter(pl.col("status").is_in(list(JUDGED)))
    per_scene = judged.group_by([*keys, "scene_id"]).agg(
        mean=(pl.col("status") == "success").cast(pl.Float64).mean(), n=pl.len()
    )
    scenes = per_scene.group_by(keys).agg(
        scene_successes=pl.col("mean").sum(), n_scenes=pl.len().cast(pl.Int64),
        clustered=pl.col("n").max() > 1,
    )
    low, high = wilson_exprs(pl.col("scene_successes"), pl.col("n_scenes"), confidence)
    scenes = scenes.with_columns(scene_low=low, scene_high=high)
    joined = rated.join(scenes, on=keys, how="left") if keys else rated.join(scenes, how="cross")
    clustered = pl.col("clustered").fill_null(False)
    return joined.with_columns(
        ci_low=pl.when(clustered).then(pl.col("scene_low")).otherwise(pl.col("ci_low")),
        ci_high=pl.when(clustered).then(pl.col("scene_high")).otherwise(pl.col("ci_high")),
        interval=pl.when(clustered).then(pl.lit("Wilson over scenes")).otherwise(pl.lit("Wilson")),
    ).select([*rated.columns, "interval"])


def with_rates(counts: pl.DataFrame, confidence: float) -> pl.DataFrame:
    """Add n, success_rate and the Wilson bounds to a frame of counts."""
    n = pl.col("successes") + pl.col("failures")
    low, high = wilson_exprs(pl.col("successes"), n, confidence)
    return counts.with_columns(
        n=n,
        success_rate=pl.when(n > 0).then(pl.col("successes") / n),
        ci_low=low,
        ci_high=high,
    )


def success_cells(episodes: pl.DataFrame, confidence: float = 0.95) -> pl.DataFrame:
    """Cells of the four paper tables, plus the pooled ``avg`` level of Table I.

    The average pools every episode of the factor (successes over judged
    episodes across levels): with equal n per level it is the paper's mean of
    the level rates, and it keeps a proper interval when n differs.
    """
    cells = count_outcomes(episodes, CELL_KEYS, confidence)
    averaged = episodes.filter(pl.col("factor").is_in(list(AVERAGED_FACTORS)))
    pooled = (
        count_outcomes(averaged, ["policy", "task", "factor"], confidence)
        .with_columns(level=pl.lit(AVERAGE_LEVEL))
        .select(cells.columns)
    )
    return pl.concat([cells, pooled]).sort(list(CELL_KEYS))


def filter_study(episodes: pl.DataFrame, study: str | None) -> tuple[pl.DataFrame, int]:
    """Episodes of ``study`` (all when None) and how many rows of other studies were dropped."""
    if study is None:
        return episodes, 0
    kept = episodes.filter(pl.col("study") == study)
    return kept, episodes.height - kept.height
