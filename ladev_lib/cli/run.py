"""``ladev run SPEC.json --policy oracle``: one episode, its predicates, steps and timings.

    ladev run scene.json --policy grounded --instruction "put the carrot on the plate"
    ladev run scene.json --policy oracle --video episode.mp4
    ladev run scene.json --policy random policy.random.control_mode=pd_joint_pos

The episode runs in this process, through the same loop as the rollout stage
(validity check first, then the policy until success, its stop flag or the
task's step limit). Trailing arguments are Hydra overrides of ``conf/``.
"""

from __future__ import annotations

import json
import shutil
import tempfile
from pathlib import Path

import click

from ladev_lib.cli._spec_file import read_spec_file


@click.command()
@click.argument("spec_path", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.argument("overrides", nargs=-1)
@click.option("--policy", "label", default="oracle", show_default=True,
              help="Policy: a key of the policy config group, or a registry name.")
@click.option("--instruction", default=None, help="Instruction text (default: the task's basic form).")
@click.option("--seed", type=int, default=None, help="Episode seed (default: the spec's).")
@click.option("--video", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write an MP4 of the episode at the policy camera.")
@click.option("--frames", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Write the first and last policy-camera frames (PNG) into this directory.")
@click.option("--json", "as_json", is_flag=True, help="Print the outcome as JSON.")
@click.option("--config-dir", default=None, help="Hydra config directory (default: ./conf).")
def command(
    spec_path: Path,
    overrides: tuple[str, ...],
    label: str,
    instruction: str | None,
    seed: int | None,
    video: Path | None,
    frames: Path | None,
    as_json: bool,
    config_dir: str | None,
) -> None:
    """Roll out one policy on one scene spec and print the predicates."""
    from ladev_lib.config import compose_config, section
    from ladev_lib.errors import LadevError
    from ladev_lib.policies.config import PolicyConfig
    from ladev_lib.rollout.jobs import EpisodeJob, MediaOptions, WorkerSpec
    from ladev_lib.rollout.plan import default_instruction
    from ladev_lib.rollout.worker import EpisodeWorker
    from ladev_lib.sim.config import RobotConfig, SimConfig

    spec = read_spec_file(spec_path)
    text = instruction or default_instruction(spec)
    with tempfile.TemporaryDirectory(prefix="ladev-run-") as tmp:
        try:
            cfg = compose_config(list(overrides), config_dir)
            policies = cfg.get("policy") or {}
            pc = section(policies, label, PolicyConfig) if label in policies else PolicyConfig(name=label)
            worker_spec = WorkerSpec(
                policy_name=pc.name,
                policy_config=pc.kwargs,
                sim_config=section(cfg, "sim", SimConfig).model_dump(mode="json"),
                robot_config=section(cfg, "robot", RobotConfig).model_dump(mode="json"),
                media=MediaOptions(
                    root=tmp, prefix=tmp, video="all" if video else "none", frames=frames is not None
                ),
            )
            worker = EpisodeWorker(worker_spec)
            job = EpisodeJob("episode", spec, text, spec.seed if seed is None else seed)
            outcome = worker.run(job)
            explain = getattr(worker.policy, "explain", None)
            explanation = explain() if callable(explain) else None
            worker.close()
        except LadevError as exc:
            raise click.ClickException(str(exc)) from exc
        written = []
        for src, dest in (
            (outcome.video_path, video),
            (outcome.first_frame_path, frames / f"{spec_path.stem}_first.png" if frames else None),
            (outcome.last_frame_path, frames / f"{spec_path.stem}_last.png" if frames else None),
        ):
            if src and dest:
                dest.parent.mkdir(parents=True, exist_ok=True)
                shutil.move(src, dest)
                written.append(dest)

    if as_json:
        click.echo(json.dumps({"instruction": text, **outcome.model_dump(mode="json")}, indent=2))
        return
    click.echo(f"policy {label} ({pc.name}) on {spec_path.name}, robot {outcome.robot}, seed {job.seed}")
    click.echo(f"instruction: {text!r}")
    if explanation:
        click.echo(explanation)
    verdict = outcome.status.upper() + (f": {outcome.error}" if outcome.error else "")
    click.echo(f"{verdict} after {outcome.steps} steps")
    for name, value in outcome.predicates.items():
        click.echo(f"  {'yes' if value else 'no ':3}  {name}")
    click.echo(
        f"time: simulation {outcome.sim_seconds:.2f} s, policy {outcome.policy_seconds:.2f} s, "
        f"total {outcome.total_seconds:.2f} s"
    )
    for path in written:
        click.echo(f"wrote {path}")
