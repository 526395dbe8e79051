"""Aggregate a study and write its report: tables, comparisons, figures, HTML, metrics.

    inputs = load_inputs("data/episodes", "data/scenes.parquet", ...)
    result = build_report(inputs, ReportConfig(), study="smoke", reports_dir=Path("reports"),
                          metrics_path=Path("reports/metrics.json"), base_dir=Path.cwd())

:func:`aggregate` is the pure part (frames in, frames out); :func:`build_report`
writes files. Layout under ``reports_dir``: ``tables/`` (one file per paper
table and format, plus ``comparisons``), ``figures/`` (PNGs, gallery media),
``report.html``; the metrics go to ``metrics_path``.
"""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import polars as pl

from ladev_lib.report import figures as figs
from ladev_lib.report.cells import count_outcomes, empty_episodes, filter_study, success_cells
from ladev_lib.report.comparisons import Power, compare_levels
from ladev_lib.report.config import ReportConfig
from ladev_lib.report.gallery import gallery_items
from ladev_lib.report.html import (
    Figure,
    comparison_groups,
    comparison_rows,
    html_table,
    overall_table,
    render_html,
    report_context,
)
from ladev_lib.report.layout import (
    PAPER_TABLES,
    TASK_ORDER,
    TableLayout,
    layout_from_frame,
    table_frame,
)
from ladev_lib.report.measurement import (
    BootstrapOptions,
    Measurement,
    measure,
    measurement_markdown,
    measurement_tables,
    split_controls,
    success_caption,
    with_success_definition,
)
from ladev_lib.report.published import load_published, resolve_reference_csv
from ladev_lib.report.render import CellStyle, render_latex, render_markdown, write_csv
from ladev_lib.report.summary import StudySummary, headline_metrics, summarize_study
from ladev_lib.tables import (
    CompiledSceneRow,
    EpisodeRow,
    InstructionRow,
    SceneDesignRow,
    read_table,
)


@dataclass(frozen=True)
class StudyInputs:
    episodes: pl.DataFrame
    scenes: pl.DataFrame | None = None
    compiled: pl.DataFrame | None = None
    instructions: pl.DataFrame | None = None


def load_inputs(
    episodes_dir: str | Path,
    scenes: str | Path | None = None,
    compiled: str | Path | None = None,
    instructions: str | Path | None = None,
) -> StudyInputs:
    """Read every ``episodes_dir/*.parquet`` (schema-checked) and the stage tables that exist."""
    paths = sorted(Path(episodes_dir).glob("*.parquet"))
    frames = [read_table(p, EpisodeRow) for p in paths]
    episodes = pl.concat(frames, how="vertical") if frames else empty_episodes()

    def optional(path: str | Path | None, model: type[SceneDesignRow | CompiledSceneRow | InstructionRow]) -> pl.DataFrame | None:
        return read_table(path, model) if path is not None and Path(path).exists() else None

    return StudyInputs(
        episodes, optional(scenes, SceneDesignRow), optional(compiled, CompiledSceneRow),
        optional(instructions, InstructionRow),
    )


@dataclass(frozen=True)
class Aggregates:
    episodes: pl.DataFrame  # of the study only, real instructions, status per report.success
    dropped_other_studies: int
    policies: list[str]
    tasks: list[str]
    cells: pl.DataFrame
    overall: pl.DataFrame  # per policy x task, and per policy (task "*")
    comparisons: pl.DataFrame
    table_frames: dict[str, pl.DataFrame]  # slug -> long frame
    layouts: list[TableLayout]
    summary: StudySummary
    metrics: dict[str, float | int | None]
    measurement: Measurement
    all_episodes: pl.DataFrame  # of the study, controls included, as recorded


def ordered_policies(episodes: pl.DataFrame, labels: dict[str, str]) -> list[str]:
    present = set(episodes.get_column("policy").unique().to_list())
    return [p for p in labels if p in present] + sorted(present - set(labels))


def ordered_tasks(episodes: pl.DataFrame) -> list[str]:
    present = set(episodes.get_column("task").unique().to_list())
    if not present:
        return list(TASK_ORDER)
    return [t for t in TASK_ORDER if t in present] + sorted(present - set(TASK_ORDER))


def aggregate(
    inputs: StudyInputs, cfg: ReportConfig, study: str | None = None,
    published: pl.DataFrame | None = None, published_source: str | None = None,
) -> Aggregates:
    """Everything the report shows, computed from the inputs (no files written).

    The paper's tables, the comparisons and the headline rates use the real
    instructions (controls apart) with success as ``cfg.success`` defines it;
    the measurement tables use every episode.
    """
    recorded, dropped = filter_study(inputs.episodes, study)
    real, _ = split_controls(recorded)
    episodes = with_success_definition(real, cfg.success)
    opts = BootstrapOptions(cfg.confidence, cfg.bootstrap_samples, cfg.bootstrap_seed)
    power = Power(cfg.mdd_alpha, cfg.mdd_power)
    measurement = measure(recorded, cfg.success, opts, cfg.mdd_alpha, cfg.mdd_power)
    policies, tasks = ordered_policies(episodes, cfg.model_labels), ordered_tasks(episodes)
    cells = success_cells(episodes, cfg.confidence)
    per_task = count_outcomes(episodes, ["policy", "task"], cfg.confidence)
    per_policy = count_outcomes(episodes, ["policy"], cfg.confidence).with_columns(task=pl.lit("*"))
    overall = pl.concat([per_task, per_policy.select(per_task.columns)])
    frames, layouts = {}, []
    for spec in PAPER_TABLES:
        frame = table_frame(spec, cells, published, policies, tasks, cfg.model_labels)
        frames[spec.slug] = frame
        layouts.append(layout_from_frame(spec, frame, policies, tasks, cfg.model_labels, published_source))
    summary = summarize_study(
        with_success_definition(recorded, cfg.success), inputs.scenes, inputs.compiled, inputs.instructions
    )
    return Aggregates(
        episodes=episodes, dropped_other_studies=dropped, policies=policies, tasks=tasks, cells=cells,
        overall=overall, comparisons=compare_levels(episodes, cells, cfg.confidence, policies, tasks, power),
        table_frames=frames, layouts=layouts, summary=summary,
        metrics=headline_metrics(summary, episodes, measurement), measurement=measurement,
        all_episodes=recorded,
    )


@dataclass(frozen=True)
class ReportResult:
    aggregates: Aggregates
    files: list[Path]
    published_csv: Path | None


def _reset_dir(path: Path) -> Path:
    """Empty a folder this stage owns entirely, so no stale file survives a config change."""
    if path.exists():
        shutil.rmtree(path)
    path.mkdir(parents=True)
    return path


def build_report(
    inputs: StudyInputs,
    cfg: ReportConfig,
    *,
    study: str | None,
    reports_dir: Path,
    metrics_path: Path,
    base_dir: Path,
) -> ReportResult:
    """Aggregate and write every report artifact; returns what was written."""
    reference = resolve_reference_csv(cfg.published, base_dir)
    published = load_published(reference, cfg.confidence) if reference else None
    source = cfg.published.source if reference else None
    agg = aggregate(inputs, cfg, study, published, source)
    style = CellStyle(cfg.decimals, cfg.intervals, cfg.show_n, cfg.confidence, success_caption(cfg.success))
    labels = cfg.model_labels
    tables_dir = _reset_dir(reports_dir / "tables")
    figures_dir = _reset_dir(reports_dir / "figures")
    written: list[Path] = []

    for spec, layout in zip(PAPER_TABLES, agg.layouts, strict=True):
        stem = tables_dir / spec.slug
        if "md" in cfg.formats:
            written.append(_write(stem.with_suffix(".md"), render_markdown(layout, style)))
        if "tex" in cfg.formats:
            written.append(_write(stem.with_suffix(".tex"), render_latex(layout, style, study)))
        if "csv" in cfg.formats:
            written.append(write_csv(agg.table_frames[spec.slug], stem.with_suffix(".csv")))
    if "csv" in cfg.formats:
        written.append(write_csv(agg.comparisons, tables_dir / "comparisons.csv"))
    if "md" in cfg.formats:
        written.append(_write(
            tables_dir / "comparisons.md", _comparisons_markdown(agg.comparisons, labels, style.success_caption)
        ))
        written.append(_write(
            tables_dir / "measurement.md", measurement_markdown(agg.measurement, labels, cfg.confidence)
        ))
    if "csv" in cfg.formats:
        m = agg.measurement
        for name, frame in (("success_definitions", m.success), ("trial_agreement", m.agreement),
                            ("controls", m.controls)):
            written.append(write_csv(frame, tables_dir / f"{name}.csv"))

    figure_list: list[Figure] = []
    if cfg.figures:
        titles = {
            "num_objects": "Success vs number of objects",
            "instruction": "Basic vs paraphrased instructions",
            "object_set": "SimplerEnv vs YCB objects",
            "environment": "Default vs lighting vs camera",
        }
        for spec, layout in zip(PAPER_TABLES, agg.layouts, strict=True):
            if not layout.has_data:
                continue  # the study has no episode for this factor: nothing to draw
            path = figs.plot_levels(
                spec, agg.table_frames[spec.slug], agg.policies, agg.tasks, labels,
                figures_dir / f"{spec.factor}.png", cfg.confidence, titles[spec.factor],
            )
            figure_list.append(Figure(titles[spec.factor], path.relative_to(reports_dir).as_posix()))
            written.append(path)
        diff_path = figs.plot_differences(agg.comparisons, labels, figures_dir / "differences.png", cfg.confidence)
        if diff_path is not None:
            figure_list.append(Figure("Differences between levels", diff_path.relative_to(reports_dir).as_posix()))
            written.append(diff_path)

    if cfg.html:
        gallery = gallery_items(agg.episodes, inputs.scenes, cfg.gallery, labels, base_dir, reports_dir)
        published_note = None
        if cfg.published.enabled:
            published_note = (
                f"Rows marked (published) are figures from the {source} ({_shown(reference, base_dir)}), "
                "shown beside this "
                "study's results for the same model; they are not results of this study."
                if reference else
                "Published figures: no reference CSV found (../shared/reference/ladev_paper_tables.csv); "
                "set report.published.reference_csv to show them."
            )
        context = report_context(
            study=study or "(all)", summary=agg.summary,
            overall=overall_table(agg.overall, agg.policies, agg.tasks, labels, style),
            tables=[html_table(layout, style) for layout in agg.layouts],
            comparisons=comparison_groups(agg.comparisons, labels), figures=figure_list, gallery=gallery,
            gallery_size=cfg.gallery.size, confidence=cfg.confidence,
            dropped_other_studies=agg.dropped_other_studies, published_note=published_note,
            files=[p.relative_to(reports_dir).as_posix() for p in written if p.is_relative_to(reports_dir)],
            measurement=measurement_tables(agg.measurement, labels, cfg.confidence),
            success_caption=style.success_caption,
        )
        written.append(_write(reports_dir / "report.html", render_html(context)))

    metrics_path.parent.mkdir(parents=True, exist_ok=True)
    written.append(_write(metrics_path, json.dumps(agg.metrics, indent=2, sort_keys=False) + "\n"))
    return ReportResult(agg, written, reference)


def _shown(path: Path, base_dir: Path) -> str:
    """A path as the report shows it: relative to the checkout, so that the report is the same
    wherever the checkout lies."""
    try:
        return os.path.relpath(path, base_dir)
    except ValueError:  # another drive (Windows)
        return path.name


def _write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def _comparisons_markdown(comparisons: pl.DataFrame, labels: dict[str, str], success: str = "") -> str:
    rows = comparison_rows(comparisons, labels)
    head: Sequence[str] = (
        "Model", "Task", "Comparison", "Test", "n", "Rates", "Diff (pp)", "Interval", "p", "MDD (pp)", "Note",
    )
    keys = ("model", "task", "comparison", "test", "n", "rates", "diff", "interval", "p", "mdd", "note")
    lines = [
        "**Comparisons between levels.** Differences are level − baseline in percentage points with "
        "Newcombe intervals; p-values unadjusted for multiplicity; MDD: the smallest difference the "
        "comparison would detect at its n (80% power, 5% level). " + success,
        "",
        "| " + " | ".join(head) + " |",
        "|" + "---|" * len(head),
    ]
    lines += ["| " + " | ".join(r[k].replace("|", r"\|") for k in keys) + " |" for r in rows]
    if not rows:
        lines.append("| " + " | ".join(["–"] * len(head)) + " |")
    return "\n".join(lines) + "\n"
