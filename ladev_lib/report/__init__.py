"""Reporting: the paper's tables and beyond, from episode rows.

Aggregation in polars (cells, pooled averages, Wilson intervals), comparisons
between levels (McNemar for the paired instruction factor, Fisher, trend and
homogeneity tests), the published figures beside a study's own, tables as
Markdown / LaTeX / CSV, PNG figures, a self-contained HTML report and the
headline metrics for DVC.
"""

from __future__ import annotations

from ladev_lib.report.build import (
    Aggregates,
    ReportResult,
    StudyInputs,
    aggregate,
    build_report,
    load_inputs,
)
from ladev_lib.report.config import GalleryConfig, PublishedConfig, ReportConfig

__all__ = [
    "Aggregates",
    "GalleryConfig",
    "PublishedConfig",
    "ReportConfig",
    "ReportResult",
    "StudyInputs",
    "aggregate",
    "build_report",
    "load_inputs",
]
