"""``ladev summary``: where the report is, and its headline numbers (from metrics.json)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import click

from ladev_lib.config import load_params
from ladev_lib.errors import ConfigError
from ladev_lib.vocabulary import TASKS

TASK_ORDER: tuple[str, ...] = TASKS  # the paper's order; vocabulary imports nothing heavy


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
    chosen = {0: "end", 1: "any"}.get(int(metrics.get("success_definition", 0) or 0), "end")
    # Both definitions when the metrics have them (older metrics: the one rate there is).
    definitions = [d for d in ("end", "any") if f"success_rate_{d}/{next(iter(per_policy))}" in metrics]
    rows = [(f"success_rate_{d}", d) for d in definitions] or [("success_rate", chosen)]
    width = max(18, max(len(p) for p in per_policy) + 2)
    for prefix, definition in rows:
        title = {"end": "Success at end", "any": "Success at any step"}[definition]
        mark = " *" if definition == chosen and len(rows) > 1 else ""
        click.echo((title + mark).ljust(width) + "all".rjust(8) + "".join(t.rjust(11) for t in tasks))
        for policy in per_policy:
            cells = "".join(_pct(metrics.get(f"{prefix}/{policy}/{t}")).rjust(11) for t in tasks)
            click.echo(policy.ljust(width) + _pct(metrics.get(f"{prefix}/{policy}")).rjust(8) + cells)
    if len(rows) > 1:
        click.echo(f"* the tables' definition (report.success={chosen})")
    controls = [p for p in per_policy if f"control/{p}/real" in metrics]
    if controls:
        click.echo("Controls (same scenes): " + "; ".join(
            f"{p} real {_pct(metrics[f'control/{p}/real'])}, control {_pct(metrics[f'control/{p}/control'])}"
            f" ({_signed_pp(metrics[f'control/{p}/diff'])})" for p in controls
        ))
    repeated = [p for p in per_policy if metrics.get(f"repeated_scenes/{p}")]
    if repeated:
        click.echo(f"Trials: {metrics.get('trials_per_scene', 1)} per scene; scenes flipping across trials: " + "; ".join(
            f"{p} {metrics[f'flipping_scenes/{p}']}/{metrics[f'repeated_scenes/{p}']}" for p in repeated
        ))


def _signed_pp(value: Any) -> str:
    return "–" if value is None else f"{100 * float(value):+.1f} pp"
