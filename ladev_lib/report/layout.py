"""The paper's four tables: which factor, which levels, and the cell grid.

Every table is built once as a long frame (one row per policy x task x level,
empty cells included) and once as a :class:`TableLayout` (models as rows,
tasks as column groups, as in the paper) that the Markdown, LaTeX and HTML
renderers share.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import polars as pl

from ladev_lib.report.cells import AVERAGE_LEVEL
from ladev_lib.vocabulary import TASKS

TASK_ORDER: tuple[str, ...] = TASKS
TASK_LABELS = {"pick_up": "Pick Up", "move_near": "Move Near", "put_on": "Put On", "put_in": "Put In"}


@dataclass(frozen=True)
class TableSpec:
    key: str  # the paper's numeral
    slug: str  # file stem
    factor: str
    levels: tuple[str, ...]  # the paper's columns; levels a study adds come after
    level_labels: dict[str, str]
    average: bool  # an "Avg." column pooling the levels
    caption: str
    wide: bool  # spans both columns (table*) in the paper


PAPER_TABLES: tuple[TableSpec, ...] = (
    TableSpec(
        "I", "table1_num_objects", "num_objects", ("1", "2", "3", "4", "5"),
        {AVERAGE_LEVEL: "Avg."}, True,
        "VLA models' performance with different numbers of objects.", True,
    ),
    TableSpec(
        "II", "table2_instruction", "instruction", ("basic", "paraphrase"),
        {"basic": "Basic", "paraphrase": "Para."}, False,
        "Basic task instructions vs. paraphrased (Para.) task instructions.", False,
    ),
    TableSpec(
        "III", "table3_object_set", "object_set", ("simpler", "ycb"),
        {"simpler": "SE", "ycb": "YCB"}, False,
        "Objects from SimplerEnv (SE) vs. objects from YCB.", False,
    ),
    TableSpec(
        "IV", "table4_environment", "environment", ("default", "lighting", "camera"),
        {"default": "De.", "lighting": "Li.", "camera": "Ca."}, False,
        "Influence of different environmental conditions: default (De.), mutated lighting (Li.), "
        "and mutated camera poses (Ca.).", False,
    ),
)


def task_label(task: str) -> str:
    return TASK_LABELS.get(task, task.replace("_", " ").title())


@dataclass(frozen=True)
class Cell:
    """One rendered cell: a study's counts, or a published figure (no exclusions)."""

    n: int
    successes: int
    rate: float | None  # fraction; None when n == 0
    low: float | None
    high: float | None
    n_error: int = 0
    n_invalid: int = 0

    @property
    def excluded(self) -> int:
        return self.n_error + self.n_invalid


@dataclass(frozen=True)
class Row:
    label: str
    policy: str
    published: bool
    cells: tuple[Cell, ...]  # task-major: tasks x columns


@dataclass(frozen=True)
class TableLayout:
    spec: TableSpec
    tasks: tuple[str, ...]
    columns: tuple[str, ...]  # levels (+ avg)
    rows: tuple[Row, ...]
    published_source: str | None  # set when published rows are present
    has_data: bool  # False when the study has no judged or excluded episode for the factor

    def cell(self, row: Row, task_index: int, column_index: int) -> Cell:
        return row.cells[task_index * len(self.columns) + column_index]

    def column_label(self, level: str) -> str:
        return self.spec.level_labels.get(level, level)

    @property
    def excluded(self) -> int:
        return sum(c.excluded for r in self.rows for c in r.cells)


def table_columns(spec: TableSpec, cells: pl.DataFrame) -> tuple[str, ...]:
    observed = (
        cells.filter((pl.col("factor") == spec.factor) & (pl.col("level") != AVERAGE_LEVEL))
        .get_column("level").unique().to_list()
    )
    extra = sorted((lv for lv in observed if lv not in spec.levels), key=_level_sort_key)
    return (*spec.levels, *extra, *((AVERAGE_LEVEL,) if spec.average else ()))


def _level_sort_key(level: str) -> tuple[int, float, str]:
    try:
        return (0, float(level), level)
    except ValueError:
        return (1, 0.0, level)


def table_frame(
    spec: TableSpec,
    cells: pl.DataFrame,
    published: pl.DataFrame | None,
    policies: Sequence[str],
    tasks: Sequence[str],
    labels: dict[str, str],
) -> pl.DataFrame:
    """The table in long form: every policy x task x column, empty cells included (n = 0)."""
    columns = table_columns(spec, cells)

    def axis(name: str, values: Sequence[str]) -> pl.DataFrame:
        return pl.DataFrame({name: list(values)}, schema={name: pl.String}).with_row_index(f"_{name}_i")

    grid = (
        axis("policy", policies).join(axis("task", tasks), how="cross").join(axis("level", columns), how="cross")
        .with_columns(table=pl.lit(spec.key), factor=pl.lit(spec.factor), model=pl.col("policy").replace(labels))
    )
    mine = cells.filter(pl.col("factor") == spec.factor).drop("factor")
    frame = grid.join(mine, on=["policy", "task", "level"], how="left").with_columns(
        pl.col(c).fill_null(0)
        for c in ("n_episodes", "successes", "failures", "n_error", "n_invalid_scene", "n")
    )
    if published is not None:
        pub = published.filter(pl.col("factor") == spec.factor).drop("factor")
        frame = frame.join(pub, on=["model", "task", "level"], how="left")
    else:
        frame = frame.with_columns(
            pl.lit(None, dtype=pl.Float64).alias(c)
            for c in ("published_pct", "published_ci_low_pct", "published_ci_high_pct")
        ).with_columns(published_n=pl.lit(None, dtype=pl.Int64))
    frame = frame.sort("_policy_i", "_task_i", "_level_i")
    return frame.select(
        "table", "policy", "model", "task", "factor", "level",
        "n", "successes",
        (100.0 * pl.col("success_rate")).alias("success_pct"),
        (100.0 * pl.col("ci_low")).alias("ci_low_pct"),
        (100.0 * pl.col("ci_high")).alias("ci_high_pct"),
        "n_error", "n_invalid_scene", "n_episodes",
        "published_pct", "published_n", "published_ci_low_pct", "published_ci_high_pct",
    )


def layout_from_frame(
    spec: TableSpec, frame: pl.DataFrame, policies: Sequence[str], tasks: Sequence[str],
    labels: dict[str, str], published_source: str | None,
) -> TableLayout:
    """Models as rows (each followed by its published row, if any), tasks as column groups."""
    columns = tuple(frame.get_column("level").unique(maintain_order=True).to_list())
    rows: list[Row] = []
    any_published = False
    for policy in policies:
        part = frame.filter(pl.col("policy") == policy)  # already in task x column order
        own, pub = [], []
        for r in part.iter_rows(named=True):
            rate = None if r["success_pct"] is None else r["success_pct"] / 100.0
            own.append(Cell(
                r["n"], r["successes"], rate, _frac(r["ci_low_pct"]), _frac(r["ci_high_pct"]),
                r["n_error"], r["n_invalid_scene"],
            ))
            if r["published_pct"] is None:
                pub.append(Cell(0, 0, None, None, None))
            else:
                n_pub = int(r["published_n"] or 0)
                pub.append(Cell(
                    n_pub, round(r["published_pct"] * n_pub / 100.0), r["published_pct"] / 100.0,
                    _frac(r["published_ci_low_pct"]), _frac(r["published_ci_high_pct"]),
                ))
        label = labels.get(policy, policy)
        rows.append(Row(label, policy, False, tuple(own)))
        if published_source and any(c.rate is not None for c in pub):
            any_published = True
            rows.append(Row(f"{label} (published)", policy, True, tuple(pub)))
    has_data = bool(frame.filter(pl.col("n_episodes") > 0).height)
    return TableLayout(
        spec, tuple(tasks), columns, tuple(rows), published_source if any_published else None, has_data
    )


def _frac(pct: float | None) -> float | None:
    return None if pct is None else pct / 100.0
