"""Render a :class:`TableLayout` as Markdown or LaTeX (booktabs), and frames as CSV.

Cell text: the success rate in percent (averages with one more decimal, as in
the paper), optionally the Wilson interval and n; an empty cell (no judged
episode) is a dash, never 0%; a cell some of whose episodes ended in an error
or an invalid scene carries a ``*`` (those episodes are not in n).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import polars as pl

from ladev_lib.report.cells import AVERAGE_LEVEL
from ladev_lib.report.layout import Cell, Row, TableLayout, task_label

Style = Literal["md", "tex", "html"]
EMPTY = {"md": "–", "tex": "--", "html": "–"}
DASH = {"md": "–", "tex": "--", "html": "–"}
PERCENT = {"md": "%", "tex": r"\%", "html": "%"}
EXCLUDED_MARK = {"md": "*", "tex": r"$^{*}$", "html": "*"}


@dataclass(frozen=True)
class CellStyle:
    decimals: int = 0
    intervals: bool = False
    show_n: bool = False
    confidence: float = 0.95
    success_caption: str = ""
    """The success definition (``report.success``), named in every caption."""


def fmt_pct(fraction: float, decimals: int) -> str:
    return f"{100.0 * fraction:.{decimals}f}"


def format_cell(cell: Cell, style: CellStyle, fmt: Style, *, average: bool = False, mark: bool = True) -> str:
    """The text of one cell (see the module docstring)."""
    decimals = style.decimals + (1 if average else 0)
    mark_text = EXCLUDED_MARK[fmt] if mark and cell.excluded else ""
    if cell.rate is None:
        return EMPTY[fmt] + mark_text
    text = fmt_pct(cell.rate, decimals) + PERCENT[fmt] + mark_text
    extras = []
    if style.intervals and cell.low is not None and cell.high is not None:
        extras.append(f"{fmt_pct(cell.low, decimals)}{DASH[fmt]}{fmt_pct(cell.high, decimals)}")
    if style.show_n:
        extras.append(f"n={cell.n}")
    if extras:
        text += f" ({', '.join(extras)})"
    return text


def cell_tooltip(cell: Cell, style: CellStyle) -> str:
    """A full description of a cell, for the HTML title attribute."""
    if cell.rate is None:
        text = "no judged episodes"
    else:
        text = f"{cell.successes}/{cell.n} successes"
        if cell.low is not None and cell.high is not None:
            text += (
                f"; {round(100 * style.confidence)}% Wilson interval "
                f"{fmt_pct(cell.low, 1)}–{fmt_pct(cell.high, 1)}%"
            )
    if cell.excluded:
        text += f"; excluded: {cell.n_error} error(s), {cell.n_invalid} invalid scene(s)"
    return text


def notes(layout: TableLayout, style: CellStyle, where_excluded: str = "counts below") -> list[str]:
    """Plain-text notes under a table."""
    out = [
        "Success rate over judged episodes (success or failure); episodes that ended in an "
        "error or an invalid scene are not policy failures and are not counted in n.",
    ]
    if layout.spec.average:
        out.append("Avg. pools the episodes of all levels.")
    if style.intervals:
        out.append(f"In parentheses: {round(100 * style.confidence)}% Wilson score interval.")
    if layout.excluded:
        out.append(f"* some episodes of this cell ended in an error or an invalid scene ({where_excluded}).")
    if layout.published_source:
        out.append(
            f"Rows marked (published) are figures published in the {layout.published_source}, "
            "shown for comparison; they are not results of this study."
        )
    if not layout.has_data:
        out.append("This study has no episodes for this factor.")
    return out


def _is_avg(level: str) -> bool:
    return level == AVERAGE_LEVEL


# -- Markdown ------------------------------------------------------------------

def _md_escape(text: str) -> str:
    return text.replace("|", r"\|")


def render_markdown(layout: TableLayout, style: CellStyle, title: str | None = None) -> str:
    spec = layout.spec
    header = ["Model"] + [
        f"{task_label(t)} {layout.column_label(lv)}" for t in layout.tasks for lv in layout.columns
    ]
    caption = " ".join(x for x in (title or spec.caption, style.success_caption) if x)
    lines = [f"**Table {spec.key}.** {caption}", ""]
    lines.append("| " + " | ".join(header) + " |")
    lines.append("|" + "---|" + "---:|" * (len(header) - 1))
    for row in layout.rows:
        cells = [
            format_cell(layout.cell(row, ti, ci), style, "md", average=_is_avg(lv))
            for ti in range(len(layout.tasks)) for ci, lv in enumerate(layout.columns)
        ]
        if row.published:
            cells = [f"*{c}*" if c != EMPTY["md"] else c for c in cells]
            label = f"*{_md_escape(row.label)}*"
        else:
            label = _md_escape(row.label)
        lines.append("| " + " | ".join([label, *cells]) + " |")
    lines.append("")
    lines.extend(notes(layout, style))
    if layout.excluded:
        lines.extend(["", *_markdown_exclusions(layout)])
    return "\n".join(lines) + "\n"


def _markdown_exclusions(layout: TableLayout) -> list[str]:
    header = ["Model"] + [
        f"{task_label(t)} {layout.column_label(lv)}" for t in layout.tasks for lv in layout.columns
    ]
    lines = [
        f"Excluded episodes, Table {layout.spec.key} (errors / invalid scenes):",
        "",
        "| " + " | ".join(header) + " |",
        "|" + "---|" + "---:|" * (len(header) - 1),
    ]
    for row in layout.rows:
        if row.published or not any(c.excluded for c in row.cells):
            continue
        cells = [f"{c.n_error} / {c.n_invalid}" if c.excluded else "·" for c in row.cells]
        lines.append("| " + " | ".join([_md_escape(row.label), *cells]) + " |")
    return lines


# -- LaTeX ---------------------------------------------------------------------

_TEX_SPECIALS = {
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
    "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
}


def tex_escape(text: str) -> str:
    return "".join(_TEX_SPECIALS.get(ch, ch) for ch in text)


def render_latex(layout: TableLayout, style: CellStyle, study: str | None = None) -> str:
    """A complete ``table`` environment in the paper's style; needs ``\\usepackage{booktabs}``."""
    spec = layout.spec
    k = len(layout.columns)
    n_tasks = len(layout.tasks)
    env = "table*" if spec.wide else "table"
    colspec = "l" + "c".join("r" * k for _ in range(n_tasks))
    group_head = []
    rules = []
    for i, task in enumerate(layout.tasks):
        first = 2 + i * (k + 1)
        group_head.append(rf"\multicolumn{{{k}}}{{c}}{{{tex_escape(task_label(task))}}}")
        rules.append(rf"\cmidrule{{{first}-{first + k - 1}}}")
    level_head = " && ".join(
        " & ".join(rf"\multicolumn{{1}}{{c}}{{{_tex_level(layout.column_label(lv))}}}" for lv in layout.columns)
        for _ in layout.tasks
    )
    caption = " ".join([tex_escape(spec.caption), *_tex_notes(layout, style)])
    lines = [
        f"% LADEV Table {spec.key}" + (f" (study '{study}')" if study else "") + r"; needs \usepackage{booktabs}",
        rf"\begin{{{env}}}[t]",
        rf"    \caption{{{caption}}}",
        rf"    \label{{tab:ladev_{spec.factor}}}",
        r"    \centering",
        r"    \scriptsize",
        r"    \setlength{\tabcolsep}{3pt}",
        rf"    \begin{{tabular}}{{{colspec}}}",
        r"        \toprule",
        "        & " + " & & ".join(group_head) + r"\\",
        "        " + " ".join(rules),
        "        Model & " + level_head + r" \\",
        r"        \midrule",
    ]
    for row in layout.rows:
        lines.append("        " + _tex_row(layout, row, style) + r" \\")
    lines += [r"        \bottomrule", r"    \end{tabular}", rf"\end{{{env}}}", ""]
    return "\n".join(lines)


def _tex_notes(layout: TableLayout, style: CellStyle) -> list[str]:
    """Short notes for a caption (the Markdown notes are longer)."""
    out = [tex_escape(style.success_caption)] if style.success_caption else []
    out += ["Success rate over judged episodes; errors and invalid scenes are excluded from $n$"
           + (r" ($^{*}$: the cell has some; counts in the CSV)." if layout.excluded else ".")]
    if layout.spec.average:
        out.append(r"Avg.\ pools all levels.")
    if style.intervals:
        out.append(rf"In parentheses: {round(100 * style.confidence)}\% Wilson interval.")
    if layout.published_source:
        out.append(rf"Italic rows: figures published in the {tex_escape(layout.published_source)}, not results of this study.")
    if not layout.has_data:
        out.append("No episodes for this factor in this study.")
    return out


def _tex_level(label: str) -> str:
    return f"${label}$" if label.isdigit() else tex_escape(label)


def _tex_row(layout: TableLayout, row: Row, style: CellStyle) -> str:
    groups = []
    for ti in range(len(layout.tasks)):
        cells = []
        for ci, lv in enumerate(layout.columns):
            text = format_cell(layout.cell(row, ti, ci), style, "tex", average=_is_avg(lv))
            cells.append(rf"\textit{{{text}}}" if row.published and text != EMPTY["tex"] else text)
        groups.append(" & ".join(cells))
    label = tex_escape(row.label)
    if row.published:
        label = rf"\textit{{{label}}}"
    return label + " & " + " && ".join(groups)


# -- CSV -----------------------------------------------------------------------

def write_csv(frame: pl.DataFrame, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    frame.write_csv(path, float_precision=4)
    return path
