"""The whole report on a synthetic study: files, HTML, gallery, figures, metrics."""

from __future__ import annotations

import json
from html.parser import HTMLParser
from pathlib import Path

import polars as pl
import pytest
from PIL import Image

from ladev_lib.errors import ConfigError
from ladev_lib.report import ReportConfig, StudyInputs, build_report
from ladev_lib.report.gallery import select_failures
from ladev_lib.report.synthetic import random_episodes, stage_tables_for

from .conftest import write_png

REFERENCE = (
    "table,factor,level,model,task,success_rate_pct,n_scenes\n"
    "I,num_objects,1,RT-1-400k,pick_up,44,100\n"
    "II,instruction,paraphrased,RT-1-400k,pick_up,22,100\n"
)


class Collector(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str | None]]] = []
        self.text: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))

    def handle_data(self, data):
        self.text.append(data)


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> tuple[Path, StudyInputs]:
    root = tmp_path_factory.mktemp("study")
    eps = random_episodes(1500, policies=["rt1_400k", "oracle"], seed=2, study="demo")
    # give the first failures media files, as rollout would (paths relative to the repo root)
    failed = select_failures(eps, 4).get_column("episode_id").head(3).to_list()  # shown in the gallery
    media = {}
    for k, eid in enumerate(failed):
        first = write_png(root / f"data/media/{k}_first.png", (200, 30, 30))
        write_png(root / f"data/media/{k}_last.png", (30, 200, 30))
        (root / f"data/media/{k}.mp4").write_bytes(b"\x00\x00\x00\x18ftypmp42")
        media[eid] = first.relative_to(root).parent.as_posix() + f"/{k}"
    eps = eps.with_columns(
        first_frame_path=pl.col("episode_id").replace_strict(media, default=None).map_elements(
            lambda s: f"{s}_first.png", return_dtype=pl.String),
        last_frame_path=pl.col("episode_id").replace_strict(media, default=None).map_elements(
            lambda s: f"{s}_last.png", return_dtype=pl.String),
        video_path=pl.col("episode_id").replace_strict(media, default=None).map_elements(
            lambda s: f"{s}.mp4", return_dtype=pl.String),
    )
    (root / "ref.csv").write_text(REFERENCE)
    scenes, compiled, instructions = stage_tables_for(eps, rejected_scenes=4, invalid_paraphrases_per_scene=3)
    return root, StudyInputs(eps, scenes, compiled, instructions)


def build(root: Path, inputs: StudyInputs, out: str, **cfg) -> tuple[Path, object]:
    config = ReportConfig.model_validate(
        {"model_labels": {"rt1_400k": "RT-1-400k"}, "published": {"reference_csv": "ref.csv"}, **cfg}
    )
    reports = root / out
    result = build_report(inputs, config, study="demo", reports_dir=reports,
                          metrics_path=reports / "metrics.json", base_dir=root)
    return reports, result


@pytest.fixture(scope="module")
def full_report(study) -> Path:
    root, inputs = study
    reports, _ = build(root, inputs, "reports", gallery={"size": 4, "embed_frames": True})
    return reports


def test_report_files_metrics_and_html(study, full_report):
    root, inputs = study
    reports = full_report
    for slug in ("table1_num_objects", "table2_instruction", "table3_object_set", "table4_environment"):
        for ext in ("md", "tex", "csv"):
            assert (reports / "tables" / f"{slug}.{ext}").stat().st_size > 100
    assert (reports / "tables" / "comparisons.csv").exists()

    metrics = json.loads((reports / "metrics.json").read_text())
    eps = inputs.episodes
    assert metrics["episodes"] == eps.height
    assert metrics["errors"] == eps.filter(pl.col("status") == "error").height
    judged = eps.filter(pl.col("status").is_in(["success", "failure"]) & (pl.col("policy") == "oracle"))
    assert metrics["success_rate/oracle"] == round(judged.get_column("success").mean(), 4)
    assert metrics["compile_ok_rate"] == round(1 - 4 / inputs.compiled.height, 4)
    assert metrics["paraphrase_valid_rate"] == 0.25  # 1 valid of 4 candidates per scene
    prefixes = {"success_rate", "success_rate_end", "success_rate_any", "control", "flipping_scenes",
                "repeated_scenes"}
    assert all("/" not in k or k.split("/")[0] in prefixes for k in metrics)
    assert metrics["success_rate_end/oracle"] == metrics["success_rate/oracle"]  # report.success=end
    assert all(isinstance(v, (int, float)) or v is None for v in metrics.values())

    page = Collector()
    page.feed((reports / "report.html").read_text())
    text = " ".join(page.text)
    imgs = [a["src"] for t, a in page.tags if t == "img"]
    assert {"figures/num_objects.png", "figures/instruction.png", "figures/object_set.png",
            "figures/environment.png", "figures/differences.png"} <= set(imgs)
    for src in imgs:
        if not src.startswith("data:"):
            assert (reports / src).is_file(), src  # relative links resolve inside the folder
    embedded = [s for s in imgs if s.startswith("data:image/png;base64,")]
    assert len(embedded) >= 2  # first and last frames of at least one gallery episode
    assert "RT-1-400k (published)" in text and "Table IV." in text
    assert "McNemar exact" in text and "Study summary" in text
    videos = [a["href"] for t, a in page.tags if t == "a" and (a.get("href") or "").endswith(".mp4")]
    assert videos and all((reports / v).is_file() for v in videos)  # copied: the folder zips whole


def test_figures_are_readable_pngs(full_report):
    reports = full_report
    for name in ("num_objects", "instruction", "object_set", "environment", "differences"):
        with Image.open(reports / "figures" / f"{name}.png") as img:
            assert img.format == "PNG" and img.width > 800 and img.height > 300


def test_options_change_outputs_and_stale_files_go(study):
    root, inputs = study
    reports, _ = build(root, inputs, "reports_opts", figures=False, html=False)
    assert (reports / "tables" / "table1_num_objects.tex").exists()
    reports, _ = build(root, inputs, "reports_opts", formats=["md"], figures=False, html=False,
                       gallery={"size": 0})
    assert sorted(p.name for p in (reports / "tables").iterdir()) == [
        "comparisons.md", "measurement.md", "table1_num_objects.md", "table2_instruction.md",
        "table3_object_set.md", "table4_environment.md",
    ]
    assert not any((reports / "figures").iterdir())


def test_published_reference_paths(study, tmp_path):
    root, inputs = study
    with pytest.raises(ConfigError, match="reference_csv"):  # an explicit path must exist
        build(root, inputs, "reports_bad", published={"reference_csv": "missing.csv"})
    # default: ../shared/reference/... relative to the working directory; absent -> no published rows
    config = ReportConfig(model_labels={"rt1_400k": "RT-1-400k"}, figures=False, html=False)
    result = build_report(inputs, config, study="demo", reports_dir=tmp_path / "r",
                          metrics_path=tmp_path / "r" / "metrics.json", base_dir=tmp_path)
    assert result.published_csv is None
    assert "(published)" not in (tmp_path / "r" / "tables" / "table1_num_objects.md").read_text()
    shared = tmp_path.parent / "shared" / "reference"
    shared.mkdir(parents=True, exist_ok=True)
    (shared / "ladev_paper_tables.csv").write_text(REFERENCE)
    result = build_report(inputs, config, study="demo", reports_dir=tmp_path / "r",
                          metrics_path=tmp_path / "r" / "metrics.json", base_dir=tmp_path)
    assert result.published_csv == tmp_path / ".." / "shared" / "reference" / "ladev_paper_tables.csv"
    assert "RT-1-400k (published)" in (tmp_path / "r" / "tables" / "table1_num_objects.md").read_text()


def test_empty_study_still_reports(tmp_path):
    from ladev_lib.report.cells import empty_episodes

    reports = tmp_path / "reports"
    result = build_report(StudyInputs(empty_episodes()), ReportConfig(), study="none", reports_dir=reports,
                          metrics_path=reports / "metrics.json", base_dir=tmp_path)
    metrics = json.loads((reports / "metrics.json").read_text())
    assert metrics["episodes"] == 0 and metrics["error_rate"] is None
    assert "no episodes for this factor" in (reports / "tables" / "table1_num_objects.md").read_text()
    assert result.aggregates.comparisons.is_empty()


def test_gallery_spreads_over_policy_and_task_and_copies_frames(study, tmp_path):
    root, inputs = study
    chosen = select_failures(inputs.episodes, 8)
    assert chosen.height == 8
    assert chosen.select("policy", "task").unique().height == 8  # 2 policies x 4 tasks, one each
    assert chosen.get_column("status").unique().to_list() == ["failure"]
    assert chosen.get_column("factor").n_unique() >= 3  # not all from one factor
    reports, _ = build(root, inputs, "reports_copy", figures=False,
                       gallery={"size": 4, "embed_frames": False, "copy_videos": False})
    page = Collector()
    page.feed((reports / "report.html").read_text())
    imgs = [a["src"] for t, a in page.tags if t == "img"]
    assert imgs and all(src.startswith("figures/gallery/") and (reports / src).is_file() for src in imgs)
    videos = [a["href"] for t, a in page.tags if t == "a" and (a.get("href") or "").endswith(".mp4")]
    assert videos and all(v.startswith("../data/media/") and (reports / v).resolve().is_file() for v in videos)
    assert "no frame" in " ".join(page.text)  # failures without media say so


def test_html_escapes_text_from_the_llm(study, tmp_path):
    root, inputs = study
    scenes = inputs.scenes.with_columns(description=pl.lit("<script>alert('x')</script> two cans & a bowl"))
    tampered = StudyInputs(inputs.episodes, scenes, inputs.compiled, inputs.instructions)
    reports, _ = build(root, tampered, "reports_escape", figures=False, gallery={"size": 2})
    html = (reports / "report.html").read_text()
    assert "<script>" not in html
    assert "&lt;script&gt;" in html and "two cans &amp; a bowl" in html


def test_physical_validity_is_taken_from_the_episodes():
    from ladev_lib.report.summary import summarize_study
    from ladev_lib.report.synthetic import CellCounts, episodes_from_counts

    episodes = episodes_from_counts(
        [
            CellCounts("oracle", "pick_up", "num_objects", "1", successes=3, invalid=1),
            CellCounts("grounded", "pick_up", "num_objects", "1", successes=2, failures=2),
        ]
    )
    compiled = pl.DataFrame(
        {"scene_id": ["a"], "status": ["ok"], "reason": [None]},
        schema={"scene_id": pl.String, "status": pl.String, "reason": pl.String},
    )
    summary = summarize_study(episodes, None, compiled, None)
    assert summary.validity_source == "rollout"
    scenes_per_policy = episodes.group_by(["policy", "scene_id"]).len().height
    assert summary.validity_invalid == 1
    assert summary.validity_ok == scenes_per_policy - 1
