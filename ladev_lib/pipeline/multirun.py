"""Run the whole pipeline outside DVC, for Hydra multirun sweeps.

``dvc repro`` is how a study is reproduced; this runner is for sweeping many
configurations quickly (``ladev study -m policy=oracle,grounded study=smoke``):
each Hydra job gets its own output directory with its ``params.yaml``, tables
and report, while the item-level caches (LLM calls, episodes) stay shared in
the checkout's ``data/cache``, so jobs that share scenes share their work.

The stages run as the same scripts ``dvc.yaml`` runs, in the same order
(a test keeps :data:`STAGE_ORDER` and ``dvc.yaml`` in step).
"""

from __future__ import annotations

import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from ladev_lib.errors import ConfigError

STAGE_ORDER = ("generate", "compile", "paraphrase", "rollout", "aggregate")
SHARED_CACHES = ("llm_cache_dir", "episode_store_dir")


@dataclass(frozen=True)
class StageRun:
    stage: str
    args: tuple[str, ...]
    seconds: float
    returncode: int


def stage_commands(params: dict[str, Any]) -> list[tuple[str, list[str]]]:
    """(stage, extra arguments) in pipeline order; rollout once per configured policy."""
    policies = list((params.get("policy") or {}).keys())
    if not policies:
        raise ConfigError("no policy configured: set policy=<name> or policy=[a,b]")
    out: list[tuple[str, list[str]]] = []
    for stage in STAGE_ORDER:
        if stage == "rollout":
            out += [(stage, ["--policy", p]) for p in policies]
        else:
            out.append((stage, []))
    return out


def job_params(params: dict[str, Any], cache_root: Path) -> dict[str, Any]:
    """``params`` with the item-level caches pointed at ``cache_root`` (shared by all jobs)."""
    paths = dict(params.get("paths") or {})
    for key in SHARED_CACHES:
        if key in paths:
            paths[key] = str((cache_root / Path(paths[key]).relative_to("data/cache")).resolve())
    return {**params, "paths": paths}


def run_pipeline(
    params: dict[str, Any],
    workdir: Path,
    repo_root: Path,
    *,
    cache_root: Path | None = None,
    echo: Callable[[str], None] = print,
) -> list[StageRun]:
    """Write ``workdir/params.yaml`` and run every stage script there; stop at a failure."""
    workdir.mkdir(parents=True, exist_ok=True)
    if cache_root is not None:
        params = job_params(params, cache_root)
    params_path = workdir / "params.yaml"
    params_path.write_text(yaml.safe_dump(params, sort_keys=False))
    runs: list[StageRun] = []
    for stage, extra in stage_commands(params):
        script = repo_root / "stages" / f"{stage}.py"
        args = [sys.executable, str(script), "--params", str(params_path), *extra]
        echo(f"[{workdir.name}] {stage} {' '.join(extra)}".rstrip())
        start = time.perf_counter()
        done = subprocess.run(args, cwd=workdir)
        runs.append(StageRun(stage, tuple(extra), time.perf_counter() - start, done.returncode))
        if done.returncode != 0:
            echo(f"[{workdir.name}] {stage} failed (exit {done.returncode}); later stages not run")
            break
    return runs
