"""``ladev summary``: where the report is, and its headline numbers (from metrics.json)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import click

from ladev_lib.config import load_params
from ladev_lib.errors import ConfigError

# The paper's task order (kept here so `ladev summary` does not import polars).
TASK_ORDER = ("pick_up", "move_near", "put_on", "put_in")


def _paths(params_file: Path) -> tuple[str | None, Path, Path]:
    """(study name, metrics path, report path) from params.yaml, or the defaults."""
    study, metrics, reports = None, Path("reports/metrics.json"), Path("reports")
    if params_file.exists():
        try:
            params = load_params(params_file)
        except ConfigError:
            return study, metrics, reports / "report.html"
        study = (params.get("study") or {}).get("name")
        paths = params.get("paths") or {}
        metrics = Path(paths.get("metrics", metrics))
        reports = Path(paths.get("reports_dir", reports))
    return study, metrics, reports / "report.html"


def _pct(value: Any) -> str:
    return "–" if value is None else f"{100 * float(value):.1f}%"


@click.command()
@click.option("--params", "params_file", default="params.yaml", show_default=True, type=click.Path(path_type=Path),
              help="Composed configuration giving paths.metrics and paths.reports_dir.")
@click.option("--metrics", "metrics_file", default=None, type=click.Path(path_type=Path),
              help="Read this metrics.json instead of the one params.yaml names.")
@click.option("--json", "as_json", is_flag=True, help="Print the metrics as JSON.")
def command(params_file: Path, metrics_file: Path | None, as_json: bool) -> None:
    """Print where the study's report is and its headline numbers."""
    study, metrics_path, report = _paths(params_file)
    metrics_path = metrics_file or metrics_path
    if not metrics_path.exists():
        raise click.ClickException(
            f"no metrics at {metrics_path}: the pipeline has not run yet. Run `dvc repro` "
            "(or `make run`) from the repository root, then `ladev summary` again."
        )
    try:
        metrics: dict[str, Any] = json.loads(metrics_path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise click.ClickException(f"{metrics_path} is not valid JSON ({exc}); re-run `dvc repro aggregate`") from exc
    if as_json:
        click.echo(json.dumps(metrics, indent=2))
        return
    click.echo(f"Study: {study or '(unknown: no params.yaml)'}")
    click.echo(f"Report: {report.resolve() if report.exists() else str(report) + ' (missing)'}")
    click.echo(f"Tables: {report.parent / 'tables'}   metrics: {metrics_path}")
    click.echo(
        f"Episodes: {metrics.get('episodes', 0)} (judged {metrics.get('episodes_judged', 0)}, "
        f"errors {metrics.get('errors', 0)}, invalid scenes {metrics.get('invalid_scenes', 0)})"
    )
    click.echo(
        f"Stages: compile ok {_pct(metrics.get('compile_ok_rate'))}, physically valid "
        f"{_pct(metrics.get('physical_validity_rate'))}, paraphrases valid {_pct(metrics.get('paraphrase_valid_rate'))}"
    )
    per_policy = {k.split("/", 1)[1]: v for k, v in metrics.items() if k.startswith("success_rate/") and k.count("/") == 1}
    if not per_policy:
        click.echo("Success: no judged episodes")
        return
    present = {k.split("/")[2] for k in metrics if k.startswith("success_rate/") and k.count("/") == 2}
    tasks = [t for t in TASK_ORDER if t in present] + sorted(present - set(TASK_ORDER))
    width = max(len(p) for p in per_policy) + 2
    click.echo("Success rate".ljust(width) + "all".rjust(8) + "".join(t.rjust(11) for t in tasks))
    for policy, rate in per_policy.items():
        cells = "".join(_pct(metrics.get(f"success_rate/{policy}/{t}")).rjust(11) for t in tasks)
        click.echo(policy.ljust(width) + _pct(rate).rjust(8) + cells)
