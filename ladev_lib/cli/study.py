"""``ladev study``: run the whole pipeline for one configuration, or sweep many with Hydra.

    ladev study study=tiny policy=oracle                 # one run under outputs/<date>/<time>/
    ladev study -m policy=oracle,grounded study=smoke    # Hydra multirun: one job per policy

Arguments are Hydra's (overrides, ``-m/--multirun``, ``hydra.sweep.dir=...``). Each
job writes its params.yaml, tables and report into its own directory; the LLM-call
and episode caches stay shared in ``<checkout>/data/cache``. For reproduction
tracked by DVC, use ``dvc repro`` / ``dvc exp run`` instead.
"""

from __future__ import annotations

import sys
from pathlib import Path

import click

from ladev_lib.config import find_config_dir


@click.command(
    context_settings={"ignore_unknown_options": True, "allow_extra_args": True, "help_option_names": []},
    add_help_option=False,
)
@click.argument("hydra_args", nargs=-1, type=click.UNPROCESSED)
def command(hydra_args: tuple[str, ...]) -> None:
    """Run the pipeline for one configuration, or sweep with -m (Hydra multirun)."""
    import hydra
    from hydra.core.hydra_config import HydraConfig
    from omegaconf import DictConfig, OmegaConf

    from ladev_lib.pipeline.multirun import run_pipeline

    config_dir = find_config_dir()
    repo_root = config_dir.parent
    failures: list[str] = []

    @hydra.main(config_path=str(config_dir), config_name="config", version_base="1.3")
    def job(cfg: DictConfig) -> float | None:
        params = OmegaConf.to_container(cfg, resolve=True)
        assert isinstance(params, dict)
        workdir = Path(HydraConfig.get().runtime.output_dir)
        runs = run_pipeline(
            {str(k): v for k, v in params.items()}, workdir, repo_root,
            cache_root=repo_root / "data" / "cache", echo=click.echo,
        )
        if any(r.returncode for r in runs):
            failures.append(str(workdir))
            return None
        click.echo(f"[{workdir.name}] report: {workdir / 'reports' / 'report.html'}")
        return None

    sys.argv = ["ladev study", *hydra_args]
    job()
    if failures:
        raise SystemExit(f"{len(failures)} job(s) failed: {', '.join(failures)}")
