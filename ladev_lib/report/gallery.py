"""The gallery of failed episodes: first and last frame, video, instruction, scene description.

Episodes are picked round-robin over (policy, task), so a small gallery still
shows every model and task. Media paths in episode rows are relative to the
repository (``media_root``); frames are embedded in the HTML or copied beside
it, videos copied or linked, so the report folder can be zipped whole.
"""

from __future__ import annotations

import base64
import json
import os
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

import polars as pl

from ladev_lib.report.config import GalleryConfig

GALLERY_DIR = Path("figures") / "gallery"


@dataclass(frozen=True)
class GalleryItem:
    episode_id: str
    policy: str
    label: str
    task: str
    factor: str
    level: str
    instruction: str
    description: str | None
    predicates: str
    first_frame: str | None  # an <img src>: data URI or a path relative to the report
    last_frame: str | None
    video: str | None  # a link relative to the report


def select_failures(episodes: pl.DataFrame, size: int) -> pl.DataFrame:
    """Up to ``size`` failed episodes: every (policy, task) in turn, factors rotating between them.

    Round r takes the r-th failure of each (policy, task, factor); within a round,
    cell c starts with factor c (mod the number of factors), so a gallery as small
    as the number of cells still shows several factors.
    """
    failed = episodes.filter(pl.col("status") == "failure")
    if size == 0 or failed.is_empty():
        return failed.head(0)
    n_factors = failed.get_column("factor").n_unique()
    cell = pl.struct("policy", "task").rank("dense").cast(pl.Int64) - 1
    factor = pl.col("factor").rank("dense").cast(pl.Int64) - 1
    return (
        failed.sort(["policy", "task", "factor", "level", "episode_id"])
        .with_columns(
            _round=pl.int_range(pl.len()).over(["policy", "task", "factor"]),
            _cell=cell,
            _turn=(factor + cell * (n_factors - 1)) % n_factors,
        )
        .sort(["_round", "_turn", "_cell"])
        .head(size)
        .drop("_round", "_cell", "_turn")
    )


def _safe(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name)[:120]


def _predicates_text(raw: str | None) -> str:
    try:
        values = json.loads(raw or "{}")
    except json.JSONDecodeError:
        return raw or ""
    if not isinstance(values, dict):
        return str(values)
    return ", ".join(f"{k} {'✓' if v else '✗'}" for k, v in values.items())


def _media(
    rel: str | None, media_root: Path, report_dir: Path, stem: str, embed: bool, copy: bool
) -> str | None:
    if not rel:
        return None
    src = Path(rel) if Path(rel).is_absolute() else media_root / rel
    if not src.is_file():
        return None
    if embed:
        mime = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg"}.get(src.suffix.lower(), "image/png")
        return f"data:{mime};base64," + base64.b64encode(src.read_bytes()).decode("ascii")
    if copy:
        dest = report_dir / GALLERY_DIR / f"{stem}{src.suffix}"
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, dest)
        return dest.relative_to(report_dir).as_posix()
    return Path(os.path.relpath(src.resolve(), report_dir.resolve())).as_posix()


def gallery_items(
    episodes: pl.DataFrame,
    scenes: pl.DataFrame | None,
    cfg: GalleryConfig,
    labels: dict[str, str],
    media_root: Path,
    report_dir: Path,
) -> list[GalleryItem]:
    chosen = select_failures(episodes, cfg.size)
    descriptions: dict[str, str | None] = {}
    if scenes is not None and not chosen.is_empty():
        wanted = scenes.filter(pl.col("scene_id").is_in(chosen.get_column("scene_id").to_list()))
        descriptions = dict(wanted.select("scene_id", "description").iter_rows())
    items = []
    for r in chosen.iter_rows(named=True):
        stem = _safe(r["episode_id"])
        items.append(
            GalleryItem(
                episode_id=r["episode_id"], policy=r["policy"], label=labels.get(r["policy"], r["policy"]),
                task=r["task"], factor=r["factor"], level=r["level"], instruction=r["instruction"],
                description=descriptions.get(r["scene_id"]), predicates=_predicates_text(r["predicates_json"]),
                first_frame=_media(r["first_frame_path"], media_root, report_dir, f"{stem}_first",
                                   cfg.embed_frames, True),
                last_frame=_media(r["last_frame_path"], media_root, report_dir, f"{stem}_last",
                                  cfg.embed_frames, True),
                video=_media(r["video_path"], media_root, report_dir, stem, False, cfg.copy_videos),
            )
        )
    return items
