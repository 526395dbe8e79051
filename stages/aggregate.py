"""DVC stage ``aggregate``: episode rows -> tables, figures, HTML report, metrics.

Reads params.yaml: ``report`` (options), ``study.name`` (which study's episodes
to report) and ``paths.*`` (where things are). Run from the repository root:

    python stages/aggregate.py [--params params.yaml]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

# Run as a script from the repository root: make ladev_lib importable without installing.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ladev_lib.config import load_params, section  # noqa: E402
from ladev_lib.errors import ConfigError, LadevError  # noqa: E402
from ladev_lib.report import ReportConfig, build_report, load_inputs  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--params", default="params.yaml", help="composed configuration (default: params.yaml)")
    args = parser.parse_args(argv)
    try:
        params = load_params(args.params)
        cfg = section(params, "report", ReportConfig)
        study = (params.get("study") or {}).get("name")
        paths = params.get("paths") or {}
        missing = [k for k in ("episodes_dir", "reports_dir", "metrics") if k not in paths]
        if missing:
            raise ConfigError(f"params: paths.{', paths.'.join(missing)} missing (see conf/config.yaml)")
        inputs = load_inputs(paths["episodes_dir"], paths.get("scenes"), paths.get("compiled"), paths.get("instructions"))
        result = build_report(
            inputs, cfg, study=study, reports_dir=Path(paths["reports_dir"]),
            metrics_path=Path(paths["metrics"]), base_dir=Path.cwd(),
        )
    except LadevError as exc:
        print(f"aggregate: {exc}", file=sys.stderr)
        return 1
    agg = result.aggregates
    print(
        f"aggregate: study {study!r}: {agg.episodes.height} episodes, {len(agg.policies)} policies, "
        f"{agg.comparisons.height} comparisons; {len(result.files)} files under {paths['reports_dir']}"
        + (f"; published figures from {result.published_csv}" if result.published_csv else "")
    )
    if agg.dropped_other_studies:
        print(f"aggregate: left out {agg.dropped_other_studies} episode rows of other studies", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
