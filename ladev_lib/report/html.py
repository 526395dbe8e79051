"""The self-contained HTML report (Jinja2): summary, tables, comparisons, figures, gallery.

Figures are linked relatively (``figures/*.png``) and gallery frames embedded
or copied beside the page, so the report folder can be zipped and opened anywhere.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import jinja2
import polars as pl

from ladev_lib import __version__
from ladev_lib.report.cells import AVERAGE_LEVEL
from ladev_lib.report.gallery import GalleryItem
from ladev_lib.report.layout import Cell, TableLayout, task_label
from ladev_lib.report.measurement import TextTable
from ladev_lib.report.render import CellStyle, cell_tooltip, format_cell, notes
from ladev_lib.report.summary import StudySummary

TEMPLATE = "report.html.jinja"


@dataclass(frozen=True)
class HtmlCell:
    text: str
    title: str
    classes: str


@dataclass(frozen=True)
class HtmlRow:
    label: str
    published: bool
    cells: list[HtmlCell]


@dataclass(frozen=True)
class HtmlTable:
    key: str
    caption: str
    groups: list[tuple[str, int]]
    columns: list[str]
    rows: list[HtmlRow]
    notes: list[str]


@dataclass(frozen=True)
class Figure:
    title: str
    src: str


def _html_cell(cell: Cell, style: CellStyle, *, average: bool, published: bool, group_start: bool) -> HtmlCell:
    classes = []
    if cell.rate is None:
        classes.append("empty")
    if cell.excluded:
        classes.append("excluded")
    if average:
        classes.append("avg")
    if group_start:
        classes.append("group-start")
    title = cell_tooltip(cell, style)
    if published:
        title = "published figure; " + title
    return HtmlCell(format_cell(cell, style, "html", average=average), title, " ".join(classes))


def html_table(layout: TableLayout, style: CellStyle) -> HtmlTable:
    k = len(layout.columns)
    rows = []
    for row in layout.rows:
        cells = [
            _html_cell(layout.cell(row, ti, ci), style, average=lv == AVERAGE_LEVEL,
                       published=row.published, group_start=ci == 0)
            for ti in range(len(layout.tasks)) for ci, lv in enumerate(layout.columns)
        ]
        rows.append(HtmlRow(row.label, row.published, cells))
    return HtmlTable(
        key=layout.spec.key,
        caption=" ".join(x for x in (layout.spec.caption, style.success_caption) if x),
        groups=[(task_label(t), k) for t in layout.tasks],
        columns=[layout.column_label(lv) for _ in layout.tasks for lv in layout.columns],
        rows=rows,
        notes=notes(layout, style, "hover a cell for counts; reasons under Errors"),
    )


def overall_table(overall: pl.DataFrame, policies: list[str], tasks: list[str],
                  labels: dict[str, str], style: CellStyle) -> HtmlTable:
    """Success per policy and task over all factors, plus all tasks together."""
    by_key = {(r["policy"], r["task"]): r for r in overall.iter_rows(named=True)}
    rows = []
    for policy in policies:
        cells = []
        for task in [*tasks, "*"]:
            r = by_key.get((policy, task))
            cell = Cell(0, 0, None, None, None) if r is None else Cell(
                r["n"], r["successes"], r["success_rate"], r["ci_low"], r["ci_high"], r["n_error"],
                r["n_invalid_scene"],
            )
            cells.append(_html_cell(cell, CellStyle(style.decimals + 1, True, True, style.confidence),
                                    average=False, published=False, group_start=True))
        rows.append(HtmlRow(labels.get(policy, policy), False, cells))
    caption = " ".join(x for x in ("Success over all factors.", style.success_caption) if x)
    return HtmlTable("", caption, [], [*map(task_label, tasks), "All tasks"], rows, [])


def _fmt(x: float | None, digits: int = 1, signed: bool = False) -> str:
    if x is None:
        return "–"
    return f"{x:+.{digits}f}" if signed else f"{x:.{digits}f}"


def _fmt_p(p: float | None) -> str:
    if p is None:
        return "–"
    return "<0.001" if p < 0.001 else f"{p:.3f}"


FACTOR_TITLES = {
    "num_objects": "Number of objects: linear trend (Cochran–Armitage)",
    "instruction": "Basic vs paraphrased instructions: paired by scene (McNemar exact)",
    "object_set": "SimplerEnv vs YCB objects (Fisher exact)",
    "environment": "Default vs lighting vs camera (Fisher exact; chi-squared over all three)",
}


def comparison_groups(comparisons: pl.DataFrame, labels: dict[str, str]) -> list[tuple[str, list[dict[str, str]]]]:
    """Comparison rows grouped by factor, in the paper's order, with a title each."""
    rows = comparison_rows(comparisons, labels)
    groups: dict[str, list[dict[str, str]]] = {}
    for row in rows:
        groups.setdefault(row["factor"], []).append(row)
    return [(FACTOR_TITLES.get(f, f), rs) for f, rs in groups.items()]


def comparison_rows(comparisons: pl.DataFrame, labels: dict[str, str]) -> list[dict[str, str]]:
    out = []
    for r in comparisons.iter_rows(named=True):
        interval = (
            f"[{_fmt(r['diff_low_pct'], signed=True)}, {_fmt(r['diff_high_pct'], signed=True)}]"
            if r["diff_low_pct"] is not None else ""
        )
        counts = (
            f"{r['baseline_only']} vs {r['level_only']}" if r["baseline_only"] is not None else ""
        )
        out.append(dict(
            model=labels.get(r["policy"], r["policy"]), task=task_label(r["task"]), factor=r["factor"],
            comparison=r["comparison"], test=r["test"],
            n=f"{r['n_baseline']} / {r['n_level']}" if r["n_baseline"] is not None else "",
            rates=(f"{_fmt(r['baseline_pct'])}% → {_fmt(r['level_pct'])}%" if r["baseline_pct"] is not None else ""),
            diff=_fmt(r["diff_pct"], signed=True) if r["diff_pct"] is not None else "",
            interval=interval, discordant=counts,
            statistic=_fmt(r["statistic"], 2) if r["statistic"] is not None else "",
            p=_fmt_p(r["p_value"]), note=r["note"] or "",
            mdd=_fmt(r["mdd_pct"]) if r.get("mdd_pct") is not None else (
                "> 100" if r["diff_pct"] is not None and r["test"] != "" else ""
            ),
            significant="sig" if r["p_value"] is not None and r["p_value"] < 0.05 else "",
        ))
    return out


def render_html(context: dict[str, Any]) -> str:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(Path(__file__).parent / "templates")),
        autoescape=jinja2.select_autoescape(["html", "jinja"]),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )

    def pct(x: float | None) -> str:
        return "–" if x is None else f"{100 * x:.1f}%"

    env.filters["pct"] = pct
    return env.get_template(TEMPLATE).render(version=__version__, **context)


def report_context(
    *, study: str, summary: StudySummary, overall: HtmlTable, tables: list[HtmlTable],
    comparisons: list[tuple[str, list[dict[str, str]]]], figures: list[Figure], gallery: list[GalleryItem],
    gallery_size: int, confidence: float, dropped_other_studies: int, published_note: str | None,
    files: list[str], measurement: list[TextTable] | None = None, success_caption: str = "",
) -> dict[str, Any]:
    return dict(
        study=study, summary=summary, overall=overall, tables=tables, comparisons=comparisons,
        figures=figures, gallery=gallery, gallery_size=gallery_size, confidence=confidence,
        dropped_other_studies=dropped_other_studies, published_note=published_note, files=files,
        measurement=measurement or [], success_caption=success_caption,
    )
