"""PNG figures (matplotlib, Agg backend): success rates with their intervals.

- success vs number of objects: one panel per task, a line per model;
- one grouped-bar figure per other factor (basic vs paraphrased, SimplerEnv vs
  YCB, default vs lighting vs camera);
- differences between levels with their intervals (a forest plot per comparison).

Cells without judged episodes are not drawn as zero: lines break there and
bars are replaced by an "n/a" mark.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import polars as pl  # noqa: E402
from matplotlib.artist import Artist  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from ladev_lib.arrays import Array  # noqa: E402
from ladev_lib.report.cells import AVERAGE_LEVEL  # noqa: E402
from ladev_lib.report.layout import TableSpec, task_label  # noqa: E402

DPI = 120


def _colors(n: int) -> list[tuple[float, float, float, float]]:
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]


def _series(frame: pl.DataFrame, policy: str, task: str, levels: Sequence[str]) -> tuple[Array, Array, Array]:
    """Rate and asymmetric error-bar lengths (NaN where a cell is empty), in percent."""
    part = frame.filter((pl.col("policy") == policy) & (pl.col("task") == task))
    by_level = {r["level"]: r for r in part.iter_rows(named=True)}
    rate = np.array([_num(by_level.get(lv, {}).get("success_pct")) for lv in levels])
    low = np.array([_num(by_level.get(lv, {}).get("ci_low_pct")) for lv in levels])
    high = np.array([_num(by_level.get(lv, {}).get("ci_high_pct")) for lv in levels])
    return rate, np.vstack([rate - low, high - rate]), np.isnan(rate)


def _num(value: float | None) -> float:
    return float("nan") if value is None else float(value)


def _legend(fig: Figure, handles: list[Artist], labels: list[str], confidence: float) -> None:
    ncol = min(len(labels), 4)
    fig.legend(handles, labels, loc="lower center", ncol=ncol, frameon=False, fontsize=9)
    rows = (len(labels) + ncol - 1) // max(ncol, 1)
    fig.text(0.99, 0.01, f"bars: {round(100 * confidence)}% Wilson interval", ha="right", va="bottom",
             fontsize=7, color="0.4")
    fig.tight_layout(rect=(0, 0.06 + 0.045 * rows, 1, 0.96))


def plot_levels(
    spec: TableSpec, frame: pl.DataFrame, policies: Sequence[str], tasks: Sequence[str],
    labels: dict[str, str], path: Path, confidence: float, title: str,
) -> Path:
    """Success rate per level of ``spec.factor``: lines over numeric levels, else grouped bars."""
    levels = [lv for lv in frame.get_column("level").unique(maintain_order=True).to_list() if lv != AVERAGE_LEVEL]
    numeric = all(lv.replace(".", "", 1).isdigit() for lv in levels)
    colors = _colors(len(policies))
    fig, axes = plt.subplots(1, len(tasks), figsize=(3.3 * len(tasks) + 0.6, 3.6), sharey=True, squeeze=False)
    handles: list[Artist] = []
    for ti, (task, ax) in enumerate(zip(tasks, axes[0], strict=True)):
        width = 0.8 / max(len(policies), 1)
        x = np.arange(len(levels), dtype=float)
        for pi, policy in enumerate(policies):
            rate, err, empty = _series(frame, policy, task, levels)
            offset = (pi - (len(policies) - 1) / 2) * (0.08 if numeric else width)
            if numeric:
                xs = np.array([float(lv) for lv in levels]) + offset
                h = ax.errorbar(xs, rate, yerr=np.nan_to_num(err), marker="o", ms=4, lw=1.5, capsize=3,
                                color=colors[pi])
            else:
                h = ax.bar(x + offset, np.nan_to_num(rate), width=width * 0.95, color=colors[pi],
                           yerr=np.where(empty, 0.0, np.nan_to_num(err)), capsize=2, ecolor="0.25",
                           error_kw={"lw": 0.8})
                for xi in np.flatnonzero(empty):
                    ax.text(x[xi] + offset, 1.5, "n/a", ha="center", va="bottom", fontsize=6,
                            rotation=90, color="0.4")
            if ti == 0:
                handles.append(h)
        ax.set_title(task_label(task), fontsize=11)
        if numeric:
            ax.set_xticks([float(lv) for lv in levels])
        else:
            ax.set_xticks(x, [spec.level_labels.get(lv, lv) for lv in levels])
        ax.set_xlabel({"num_objects": "number of objects"}.get(spec.factor, spec.factor.replace("_", " ")))
        ax.set_ylim(0, 105)
        ax.grid(axis="y", alpha=0.3)
    axes[0][0].set_ylabel("success rate (%)")
    fig.suptitle(title, fontsize=12)
    _legend(fig, handles, [labels.get(p, p) for p in policies], confidence)
    return _save(fig, path)


def plot_differences(comparisons: pl.DataFrame, labels: dict[str, str], path: Path, confidence: float) -> Path | None:
    """Forest plot: each level-vs-baseline difference with its interval, one panel per comparison."""
    diffs = comparisons.filter(pl.col("diff_low_pct").is_not_null())
    if diffs.is_empty():
        return None
    kinds = diffs.select("factor", "baseline", "level").unique(maintain_order=True).rows()
    row_keys = diffs.select("policy", "task").unique(maintain_order=True).rows()
    height = 1.6 + 0.26 * len(row_keys)
    fig, axes = plt.subplots(1, len(kinds), figsize=(3.4 * len(kinds) + 1.6, height), sharey=True, squeeze=False)
    y = np.arange(len(row_keys))[::-1]
    widest = max(abs(v) for v in diffs.select("diff_low_pct", "diff_high_pct").to_numpy().ravel())
    reach = min(100.0, max(20.0, 10.0 * np.ceil(widest / 10.0)))  # one symmetric scale for all panels
    for ax, (factor, baseline, level) in zip(axes[0], kinds, strict=True):
        part = diffs.filter((pl.col("factor") == factor) & (pl.col("baseline") == baseline) & (pl.col("level") == level))
        found = {(r["policy"], r["task"]): r for r in part.iter_rows(named=True)}
        for yi, key in zip(y, row_keys, strict=True):
            r = found.get(key)
            if r is None:
                continue
            significant = r["p_value"] is not None and r["p_value"] < 1 - confidence
            color = "tab:red" if significant else "0.3"
            ax.plot([r["diff_low_pct"], r["diff_high_pct"]], [yi, yi], color=color, lw=1.6)
            ax.plot([r["diff_pct"]], [yi], "o", color=color, ms=4)
        ax.axvline(0, color="0.5", lw=0.8, ls="--")
        ax.set_title(f"{level} − {baseline}", fontsize=10)
        ax.set_xlabel("difference (percentage points)", fontsize=8)
        ax.set_xlim(-reach, reach)
        ax.grid(axis="x", alpha=0.3)
    axes[0][0].set_yticks(y, [f"{labels.get(p, p)} · {task_label(t)}" for p, t in row_keys], fontsize=8)
    fig.suptitle(
        f"Differences between levels, {round(100 * confidence)}% intervals (red: p < {1 - confidence:.2f})",
        fontsize=11,
    )
    fig.tight_layout(rect=(0, 0, 1, 0.97 if len(row_keys) > 8 else 0.9))
    return _save(fig, path)


def _save(fig: Figure, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path
