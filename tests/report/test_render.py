"""Rendered tables: layout, empty cells, published rows, Markdown shape, LaTeX that compiles."""

from __future__ import annotations

import re
import shutil
import subprocess

import polars as pl
import pytest

from ladev_lib.report.cells import success_cells
from ladev_lib.report.layout import PAPER_TABLES, layout_from_frame, table_frame
from ladev_lib.report.published import load_published
from ladev_lib.report.render import CellStyle, render_latex, render_markdown, tex_escape

TABLE_I = PAPER_TABLES[0]
POLICIES = ["oracle", "grounded"]
TASKS = ["pick_up", "move_near"]
LABELS = {"oracle": "RT-1-400k", "grounded": "my_policy & co"}


@pytest.fixture()
def published(tmp_path) -> pl.DataFrame:
    csv = tmp_path / "ref.csv"
    csv.write_text(
        "table,factor,level,model,task,success_rate_pct,n_scenes\n"
        "I,num_objects,1,RT-1-400k,pick_up,44,100\n"
        "I,num_objects,avg,RT-1-400k,pick_up,35.0,500\n"
        "II,instruction,paraphrased,RT-1-400k,pick_up,22,100\n"
    )
    return load_published(csv)


def layout_for(episodes, published=None, spec=TABLE_I, source="LADEV paper"):
    cells = success_cells(episodes)
    frame = table_frame(spec, cells, published, POLICIES, TASKS, LABELS)
    return frame, layout_from_frame(spec, frame, POLICIES, TASKS, LABELS, source if published is not None else None)


def md_rows(text: str) -> list[list[str]]:
    return [[c.strip() for c in line.strip().strip("|").split(" | ")] for line in text.splitlines() if line.startswith("| ")]


def test_markdown_cells_known_values_and_empty_cells(known_episodes):
    _, layout = layout_for(known_episodes)
    rows = md_rows(render_markdown(layout, CellStyle()))
    header, oracle, grounded = rows[0], rows[1], rows[2]
    assert header[:3] == ["Model", "Pick Up 1", "Pick Up 2"] and header[6] == "Pick Up Avg."
    assert all(len(r) == len(header) for r in rows[:3])
    # oracle pick_up: 1 object 6/8 with exclusions (marked), 2 objects empty, 3 objects 2/8, avg 8/16
    assert oracle[1:7] == ["75%*", "–", "25%", "–", "–", "50.0%*"]
    # grounded move_near 1 object: 0/5 is a real 0%; cells without episodes are dashes, never 0%
    assert grounded[7] == "0%*" and grounded[1] == "–" and grounded[8] == "–"
    assert "0%" not in [c for c in grounded[1:7]]


def test_intervals_and_n_on_demand(known_episodes):
    _, layout = layout_for(known_episodes)
    oracle = md_rows(render_markdown(layout, CellStyle(intervals=True, show_n=True)))[1]
    assert oracle[1] == "75%* (41–93, n=8)"
    assert oracle[2] == "–"


def test_exclusions_are_listed_apart(known_episodes):
    _, layout = layout_for(known_episodes)
    text = render_markdown(layout, CellStyle())
    exclusions = text.split("Excluded episodes")[1]
    rows = md_rows(exclusions)
    assert rows[1][0] == "RT-1-400k" and rows[1][1] == "1 / 1"  # 1 error, 1 invalid scene
    assert rows[2][0] == r"my_policy & co" and rows[2][7] == "2 / 0"


def test_published_rows_sit_under_their_model_and_are_labelled(known_episodes, published):
    frame, layout = layout_for(known_episodes, published)
    labels = [r.label for r in layout.rows]
    assert labels == ["RT-1-400k", "RT-1-400k (published)", "my_policy & co"]
    rows = md_rows(render_markdown(layout, CellStyle()))
    assert rows[2][0] == "*RT-1-400k (published)*"
    assert rows[2][1] == "*44%*" and rows[2][6] == "*35.0%*" and rows[2][2] == "–"
    text = render_markdown(layout, CellStyle())
    assert "not results of this study" in text
    # the CSV keeps published figures in their own columns, beside the study's
    row = frame.filter((pl.col("policy") == "oracle") & (pl.col("task") == "pick_up") & (pl.col("level") == "1"))
    assert row["published_pct"][0] == 44.0 and row["published_n"][0] == 100
    assert row["success_pct"][0] == pytest.approx(75.0)


def test_published_level_names_are_mapped(published):
    assert published.filter(pl.col("factor") == "instruction").get_column("level").to_list() == ["paraphrase"]
    avg = published.filter(pl.col("level") == "avg").to_dicts()[0]
    assert avg["published_ci_low_pct"] < 35.0 < avg["published_ci_high_pct"]


def test_csv_frame_has_every_cell_with_n_and_interval(known_episodes):
    frame, _ = layout_for(known_episodes)
    assert frame.height == len(POLICIES) * len(TASKS) * 6
    for col in ("n", "successes", "success_pct", "ci_low_pct", "ci_high_pct", "n_error", "n_invalid_scene"):
        assert col in frame.columns
    empty = frame.filter(pl.col("n") == 0)
    assert empty.get_column("success_pct").null_count() == empty.height
    full = frame.filter(pl.col("n") > 0)
    assert full.get_column("ci_low_pct").null_count() == 0


# -- LaTeX ---------------------------------------------------------------------

def check_booktabs_tabular(tex: str) -> int:
    """Parse the tabular as booktabs: rules in order, every row spans the column spec."""
    assert tex.count("{") == tex.count("}")
    m = re.search(r"\\begin\{tabular\}\{([lrc]+)\}(.*)\\end\{tabular\}", tex, re.S)
    assert m, "no tabular"
    ncols = len(m.group(1))
    body = m.group(2)
    positions = [body.index(r) for r in (r"\toprule", r"\midrule", r"\bottomrule")]
    assert positions == sorted(positions)
    for start, end in re.findall(r"\\cmidrule\{(\d+)-(\d+)\}", body):
        assert 1 <= int(start) <= int(end) <= ncols
    rows = [r for r in body.split(r"\\") if "&" in r]
    assert rows
    for row in rows:
        row = re.sub(r"\\(top|mid|bottom)rule|\\cmidrule\{[^}]*\}", "", row)
        cells = re.split(r"(?<!\\)&", row)
        spans = sum(int(re.match(r"\s*\\multicolumn\{(\d+)\}", c).group(1)) if "\\multicolumn" in c else 1 for c in cells)
        assert spans == ncols, (spans, ncols, row)
    return ncols


@pytest.mark.parametrize("spec", PAPER_TABLES, ids=lambda s: s.slug)
def test_latex_parses_as_a_booktabs_tabular(known_episodes, published, spec):
    _, layout = layout_for(known_episodes, published, spec)
    tex = render_latex(layout, CellStyle(intervals=True, show_n=True), study="known")
    ncols = check_booktabs_tabular(tex)
    assert ncols == 1 + len(TASKS) * len(layout.columns) + (len(TASKS) - 1)
    assert r"my\_policy \& co" in tex
    # the fixture publishes figures for Tables I and II only
    assert (r"\textit{RT-1-400k (published)}" in tex) == (spec.key in ("I", "II"))
    assert ("table*" in tex) == spec.wide


def test_tex_escape():
    assert tex_escape("a_b & 50% #1 {x}") == r"a\_b \& 50\% \#1 \{x\}"


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex not installed (apt: texlive-latex-base texlive-latex-recommended)")
def test_latex_compiles_with_pdflatex(known_episodes, published, tmp_path):
    bodies = []
    for spec in PAPER_TABLES:
        _, layout = layout_for(known_episodes, published, spec)
        name = f"{spec.slug}.tex"
        (tmp_path / name).write_text(render_latex(layout, CellStyle(intervals=True), study="known"))
        bodies.append(rf"\input{{{name}}}")
    doc = "\\documentclass{article}\n\\usepackage{booktabs}\n\\begin{document}\n" + "\n".join(bodies) + "\n\\end{document}\n"
    (tmp_path / "doc.tex").write_text(doc)
    proc = subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "doc.tex"],
        cwd=tmp_path, capture_output=True, text=True, timeout=120,
    )
    assert proc.returncode == 0, proc.stdout[-3000:]
    assert (tmp_path / "doc.pdf").stat().st_size > 1000
    assert "Undefined control sequence" not in proc.stdout
