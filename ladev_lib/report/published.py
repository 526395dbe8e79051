"""Published figures (the LADEV paper's Tables I-IV) to show beside a study's results.

The reference CSV is long format: ``table,factor,level,model,task,
success_rate_pct,n_scenes``. Rows are matched to a study's rows by model label
(``report.model_labels`` maps a policy name to it), task, factor and level.
They are never mixed into a study's own numbers.
"""

from __future__ import annotations

from pathlib import Path

import polars as pl

from ladev_lib.errors import ConfigError
from ladev_lib.report.config import DEFAULT_REFERENCE_CSV, PublishedConfig
from ladev_lib.report.stats import wilson_exprs

REFERENCE_COLUMNS = ("table", "factor", "level", "model", "task", "success_rate_pct", "n_scenes")
# The paper's level names -> the episode table's.
LEVEL_ALIASES = {"paraphrased": "paraphrase", "average": "avg"}


def resolve_reference_csv(cfg: PublishedConfig, base_dir: Path) -> Path | None:
    """The reference CSV to use, or ``None`` when published rows are off or the default is absent.

    An explicitly configured path that does not exist is a configuration error.
    """
    if not cfg.enabled:
        return None
    if cfg.reference_csv is None:
        default = base_dir / DEFAULT_REFERENCE_CSV
        return default if default.is_file() else None
    path = Path(cfg.reference_csv)
    path = path if path.is_absolute() else base_dir / path
    if not path.is_file():
        raise ConfigError(
            f"report.published.reference_csv: {path} does not exist; fix the path, set it to null "
            "to use ../shared/reference/ladev_paper_tables.csv when present, or set "
            "report.published.enabled=false"
        )
    return path


def load_published(path: Path, confidence: float = 0.95) -> pl.DataFrame:
    """Published cells: model, task, factor, level, published_pct, published_n, Wilson bounds (%).

    The successes behind a cell are recovered as ``pct * n / 100`` (rounded), which
    is exact for the paper's 100-scene cells and 500-scene averages.
    """
    try:
        raw = pl.read_csv(path, schema_overrides={"level": pl.String})
    except (OSError, pl.exceptions.PolarsError) as exc:
        raise ConfigError(f"cannot read the published reference CSV {path}: {exc}") from exc
    missing = [c for c in REFERENCE_COLUMNS if c not in raw.columns]
    if missing:
        raise ConfigError(f"{path}: published reference CSV lacks columns {missing}; expected {list(REFERENCE_COLUMNS)}")
    k = (pl.col("published_pct") * pl.col("published_n") / 100.0).round(0)
    low, high = wilson_exprs(k, pl.col("published_n"), confidence)
    return (
        raw.select(
            pl.col("model").cast(pl.String),
            pl.col("task").cast(pl.String),
            pl.col("factor").cast(pl.String),
            pl.col("level").cast(pl.String).replace(LEVEL_ALIASES),
            pl.col("success_rate_pct").cast(pl.Float64).alias("published_pct"),
            pl.col("n_scenes").cast(pl.Int64).alias("published_n"),
        )
        .with_columns(published_ci_low_pct=100.0 * low, published_ci_high_pct=100.0 * high)
        .unique(subset=["model", "task", "factor", "level"], keep="first", maintain_order=True)
    )
