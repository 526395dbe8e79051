"""Re-aggregating 100,000 episode rows (target: under 10 s on a 2-core machine).

Writes a synthetic study (7 policies, the paper's design) as per-policy Parquet
files, then times, side by side in one run:
  read      load_inputs: read and schema-check every episodes/*.parquet
  aggregate cells, pooled averages, Wilson intervals, comparisons, table frames, metrics
  report    build_report: all of the above plus md/tex/csv, PNG figures and the HTML report

    python benchmarks/bench_aggregate.py [--rows 100000]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import polars as pl  # noqa: E402

from ladev_lib.report import ReportConfig, StudyInputs, aggregate, build_report, load_inputs  # noqa: E402
from ladev_lib.report.synthetic import random_episodes, stage_tables_for  # noqa: E402
from ladev_lib.tables import EpisodeRow, write_table  # noqa: E402

POLICIES = ["rt1_1k", "rt1_58k", "rt1_400k", "rt1_x", "octo_small", "octo_base", "openvla_7b"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=100_000)
    args = parser.parse_args()
    labels = {p: p for p in POLICIES}
    cfg = ReportConfig(model_labels=labels)
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        eps = random_episodes(args.rows, policies=POLICIES, seed=0, study="bench")
        for policy in POLICIES:
            write_table(eps.filter(pl.col("policy") == policy), root / "episodes" / f"{policy}.parquet", EpisodeRow)
        scenes, compiled, instructions = stage_tables_for(eps)

        t0 = time.perf_counter()
        inputs = load_inputs(root / "episodes")
        t1 = time.perf_counter()
        agg = aggregate(StudyInputs(inputs.episodes, scenes, compiled, instructions), cfg, study="bench")
        t2 = time.perf_counter()
        build_report(StudyInputs(inputs.episodes, scenes, compiled, instructions), cfg, study="bench",
                     reports_dir=root / "reports", metrics_path=root / "reports" / "metrics.json", base_dir=root)
        t3 = time.perf_counter()

    print(f"episode rows:          {inputs.episodes.height:,} ({len(POLICIES)} policies, "
          f"{agg.cells.height} cells, {agg.comparisons.height} comparisons)")
    print(f"read parquet:          {t1 - t0:6.2f} s")
    print(f"aggregate:             {t2 - t1:6.2f} s")
    print(f"read + aggregate:      {t2 - t0:6.2f} s   (target < 10 s)")
    print(f"full report (+ files, figures, HTML): {t3 - t2:6.2f} s")


if __name__ == "__main__":
    main()
