"""Episode rows -> success-rate cells, in polars (no per-row Python).

A cell is one (policy, task, factor, level). Its rate counts only episodes the
policy was judged on (``success`` or ``failure``); ``error`` (the rollout
crashed) and ``invalid_scene`` (the scene could not be built as specified) are
counted apart, because they say nothing about the policy.
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
    n (judged episodes), success_rate (null when n is 0), ci_low, ci_high.
    """
    status = pl.col("status")
    counts = episodes.group_by(list(keys)).agg(
        n_episodes=pl.len().cast(pl.Int64),
        successes=(status == "success").sum().cast(pl.Int64),
        failures=(status == "failure").sum().cast(pl.Int64),
        n_error=(status == "error").sum().cast(pl.Int64),
        n_invalid_scene=(status == "invalid_scene").sum().cast(pl.Int64),
    )
    return with_rates(counts, confidence).sort(list(keys))


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
    count_cols = ["n_episodes", "successes", "failures", "n_error", "n_invalid_scene"]
    pooled = (
        cells.filter(pl.col("factor").is_in(list(AVERAGED_FACTORS)))
        .group_by(["policy", "task", "factor"])
        .agg([pl.col(c).sum() for c in count_cols])
        .with_columns(level=pl.lit(AVERAGE_LEVEL))
    )
    pooled = with_rates(pooled, confidence).select(cells.columns)
    return pl.concat([cells, pooled]).sort(list(CELL_KEYS))


def filter_study(episodes: pl.DataFrame, study: str | None) -> tuple[pl.DataFrame, int]:
    """Episodes of ``study`` (all when None) and how many rows of other studies were dropped."""
    if study is None:
        return episodes, 0
    kept = episodes.filter(pl.col("study") == study)
    return kept, episodes.height - kept.height
