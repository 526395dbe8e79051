"""Stage ``aggregate``: episode rows -> tables, figures, HTML report, metrics.

Reads ``report`` (options), ``study.name`` (which study's episodes to report)
and ``paths.*`` (where things are). The work is :mod:`ladev_lib.report`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ladev_lib.config import section
from ladev_lib.errors import ConfigError
from ladev_lib.pipeline import StageMessages
from ladev_lib.report import ReportConfig, build_report, load_inputs


@dataclass(frozen=True)
class AggregateSummary:
    study: str | None
    episodes: int
    policies: int
    comparisons: int
    files: int
    reports_dir: str
    published_csv: Path | None
    dropped_other_studies: int


@dataclass(frozen=True)
class AggregateResult:
    files: list[Path]
    """Everything written (tables, figures, report, metrics)."""
    summary: AggregateSummary

    def messages(self) -> StageMessages:
        s = self.summary
        out = (
            f"aggregate: study {s.study!r}: {s.episodes} episodes, {s.policies} policies, "
            f"{s.comparisons} comparisons; {s.files} files under {s.reports_dir}"
            + (f"; published figures from {s.published_csv}" if s.published_csv else "")
        )
        err: tuple[str, ...] = ()
        if s.dropped_other_studies:
            err = (f"aggregate: left out {s.dropped_other_studies} episode rows of other studies",)
        return StageMessages((out,), err)


def run_aggregate(params: dict[str, Any], *, base_dir: Path | None = None) -> AggregateResult:
    """Aggregate the study's episodes and write the report; paths relative to ``base_dir`` (cwd)."""
    cfg = section(params, "report", ReportConfig)
    study = (params.get("study") or {}).get("name")
    paths = params.get("paths") or {}
    missing = [k for k in ("episodes_dir", "reports_dir", "metrics") if k not in paths]
    if missing:
        raise ConfigError(f"params: paths.{', paths.'.join(missing)} missing (see conf/config.yaml)")
    inputs = load_inputs(paths["episodes_dir"], paths.get("scenes"), paths.get("compiled"), paths.get("instructions"))
    result = build_report(
        inputs, cfg, study=study, reports_dir=Path(paths["reports_dir"]),
        metrics_path=Path(paths["metrics"]), base_dir=base_dir if base_dir is not None else Path.cwd(),
    )
    agg = result.aggregates
    summary = AggregateSummary(
        study=study,
        episodes=agg.episodes.height,
        policies=len(agg.policies),
        comparisons=agg.comparisons.height,
        files=len(result.files),
        reports_dir=str(paths["reports_dir"]),
        published_csv=result.published_csv,
        dropped_other_studies=agg.dropped_other_studies,
    )
    return AggregateResult(result.files, summary)
