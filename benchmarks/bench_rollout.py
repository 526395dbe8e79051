"""Rollout engine: its overhead over raw ManiSkill stepping, and episodes per hour.

    LP_NUM_THREADS=1 OMP_NUM_THREADS=1 python benchmarks/bench_rollout.py \
        [--scenes 3] [--steps 60] [--size 256] [--throughput-scenes 6] [--skip-throughput]

1. Overhead, in one process on the same scenes: raw ManiSkill (``make_env``,
   ``env.reset(options={"spec": ...})``, then ``env.step(a)`` and
   ``policy_image()`` per step) against the engine's ``run_episode`` with a
   policy that replays the same action sequence and reads the same camera.
   Raw and engine runs alternate per scene, order swapped every other scene,
   so both see the same machine load. Printed: the whole-episode ratio (the
   engine also runs its physical-validity check, one segmentation render) and
   the stepping-loop ratio (reset and check excluded). Target: <= 1.10.
2. Throughput: the rollout stage (local process pool, fresh store, frames on,
   no video, 256x256 camera) on the same scenes with 1 and 2 workers, for
   ``oracle`` and ``grounded``. Episodes per hour by wall clock (worker start-up,
   the first rendered frame and the embedder load, included: it dominates short
   runs) and once started (workers / mean episode time).
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("LP_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("HF_HUB_OFFLINE", "1")

import numpy as np  # noqa: E402

from ladev_lib.policies.base import Observation, Policy, PolicyInfo, PolicyStep  # noqa: E402

CONTROL_MODE = "pd_ee_delta_pose"


class ReplayPolicy(Policy):
    """Replays a fixed action sequence; wants the policy-camera image like a VLA."""

    def __init__(self, actions: np.ndarray, image_size: tuple[int, int]) -> None:
        self.info = PolicyInfo("replay", ("panda",), CONTROL_MODE, image_size=image_size,
                               max_episode_steps=len(actions))
        self.actions = actions

    def reset(self, instruction: str) -> None:
        pass

    def step(self, obs: Observation) -> PolicyStep:
        assert obs.image is not None
        return PolicyStep(self.actions[obs.step])


def valid_scenes(n: int, size: tuple[int, int]) -> list[Any]:
    """The first ``n`` sampled pick_up / put_on scenes the validity check accepts."""
    from ladev_lib.catalog import load_catalog
    from ladev_lib.rollout.simulator import ManiSkillSim, SimSetup
    from ladev_lib.scenes.sampling import sample_scene

    catalog = load_catalog()
    sim = ManiSkillSim(SimSetup({"image_size": list(size)}, {"name": "panda"}, "panda", "pd_joint_pos", size))
    out, seed = [], 0
    while len(out) < n and seed < 20 * n:
        task = ("pick_up", "put_on")[seed % 2]
        spec = sample_scene(task, 2, "simpler", np.random.default_rng(seed), catalog, seed=seed,
                            scene_id=f"bench-{seed:03d}")
        sim.load(spec, spec.seed)
        if sim.invalid_reason() is None:
            out.append(spec)
        seed += 1
    sim.close()
    return out


class CallTimer:
    """Wraps a bound method, summing the time spent inside it."""

    def __init__(self, fn: Any) -> None:
        self.fn, self.seconds = fn, 0.0

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        t = time.perf_counter()
        try:
            return self.fn(*args, **kwargs)
        finally:
            self.seconds += time.perf_counter() - t


def overhead(specs: list[Any], steps: int, size: tuple[int, int], repeats: int) -> None:
    from ladev_lib.rollout.episode import run_episode
    from ladev_lib.rollout.jobs import EpisodeJob
    from ladev_lib.rollout.simulator import ManiSkillSim, SimSetup
    from ladev_lib.sim import make_env

    cfg = {"image_size": list(size)}
    raw_env = make_env(specs[0], cfg, control_mode=CONTROL_MODE, image_size=size)
    sim = ManiSkillSim(SimSetup(cfg, {"name": "panda"}, "panda", CONTROL_MODE, size))
    low, high = raw_env.action_space.low, raw_env.action_space.high
    # Warm-up: the first rendered frame of each env costs seconds.
    raw_env.reset(seed=0, options={"spec": specs[0].model_dump(mode="json")})
    raw_env.unwrapped.policy_image()
    sim.load(specs[0], 0)
    sim.frame()
    # Time spent inside ManiSkill during the engine's loop (its env.step and camera reads).
    env_step = sim.env.step = CallTimer(sim.env.step)
    env_image = sim.env.unwrapped.policy_image = CallTimer(sim.env.unwrapped.policy_image)
    # The scene set-up the loop starts from: reset with the spec, validity check.
    setup_calls = [CallTimer(sim.load), CallTimer(sim.invalid_reason)]
    sim.load, sim.invalid_reason = setup_calls  # type: ignore[method-assign]

    def raw(spec: Any, actions: np.ndarray) -> tuple[float, float]:
        t0 = time.perf_counter()
        raw_env.reset(seed=spec.seed, options={"spec": spec.model_dump(mode="json")})
        t1 = time.perf_counter()
        for a in actions:
            raw_env.step(a)
            raw_env.unwrapped.policy_image()
        t2 = time.perf_counter()
        return t2 - t0, t2 - t1

    inside: list[float] = []

    def engine(spec: Any, actions: np.ndarray) -> tuple[float, float]:
        policy = ReplayPolicy(actions, size)
        job = EpisodeJob("bench", spec, "replay", spec.seed)
        setup_before = sum(c.seconds for c in setup_calls)
        t0 = time.perf_counter()
        out = run_episode(sim, policy, job, None)
        t2 = time.perf_counter()
        assert out.status in ("success", "failure"), out.error
        return t2 - t0, t2 - t0 - (sum(c.seconds for c in setup_calls) - setup_before)

    whole: dict[str, list[float]] = {"raw": [], "engine": []}
    loop: dict[str, list[float]] = {"raw": [], "engine": []}
    for rep in range(repeats):
        for i, spec in enumerate(specs):
            rng = np.random.default_rng(i)
            actions = (rng.uniform(low, high, size=(steps, len(low))) * 0.3).astype(np.float32)
            actions[:, -1] = high[-1]  # gripper open: nothing gets grasped, every episode runs all steps
            order = [("raw", raw), ("engine", engine)]
            for name, fn in order if (i + rep) % 2 == 0 else order[::-1]:
                before = env_step.seconds + env_image.seconds
                w, lp = fn(spec, actions)
                whole[name].append(w)
                loop[name].append(lp)
                if name == "engine":
                    inside.append(env_step.seconds + env_image.seconds - before)
    raw_env.close()
    sim.close()
    n_steps = steps * len(specs) * repeats
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    print(f"\n== overhead: {len(specs)} scenes x {steps} steps x {repeats} repeats, {CONTROL_MODE}, "
          f"camera {size[0]}x{size[1]} (load average {load})")
    print("side by side (raw ManiSkill vs the engine, alternating; sensitive to other load):")
    for label, d in (("  whole episode (reset + check + steps)", whole), ("  stepping loop", loop)):
        r, e = sum(d["raw"]), sum(d["engine"])
        print(f"{label:42s} raw {r:7.2f} s ({n_steps / r:5.1f} steps/s)   engine {e:7.2f} s "
              f"({n_steps / e:5.1f} steps/s)   ratio {e / r:.3f}")
    per_scene = [e / r for e, r in zip(loop["engine"], loop["raw"], strict=True)]
    print(f"{'  per-episode loop ratios':42s} median {statistics.median(per_scene):.3f} "
          f"(min {min(per_scene):.3f}, max {max(per_scene):.3f})")
    in_env, engine_loop = sum(inside), sum(loop["engine"])
    print("within the engine's own runs (its loop time vs the time inside env.step + policy_image):")
    print(f"{'  engine loop / ManiSkill calls':42s} {engine_loop:7.2f} s / {in_env:7.2f} s = "
          f"{engine_loop / in_env:.3f}   ({1000 * (engine_loop - in_env) / n_steps:.2f} ms per step "
          "outside ManiSkill; target ratio <= 1.10)")


def throughput(specs: list[Any], size: tuple[int, int]) -> None:
    from ladev_lib.catalog import load_catalog
    from ladev_lib.config import load_params
    from ladev_lib.language.instructions import basic_instruction
    from ladev_lib.rollout.stage import rollout_stage
    from ladev_lib.tables import CompiledSceneRow, InstructionRow, write_table

    catalog = load_catalog()

    def display(spec: Any, name: str | None) -> str | None:
        return catalog.get(spec.object(name).id).display_name if name else None

    base = load_params(Path(__file__).resolve().parents[1] / "params.yaml")
    print(f"\n== throughput: {len(specs)} episodes per run, local pool, camera {size[0]}x{size[1]}, "
          "fresh store, first frames of each worker included")
    for policy in ("oracle", "grounded"):
        for workers in (1, 2):
            with tempfile.TemporaryDirectory(prefix="bench-rollout-") as tmp:
                root = Path(tmp)
                write_table([CompiledSceneRow(scene_id=s.scene_id, status="ok", spec_json=s.to_json())
                             for s in specs], root / "data/compiled.parquet", CompiledSceneRow)
                write_table([InstructionRow(
                    instruction_id=f"{s.scene_id}/basic", scene_id=s.scene_id, kind="basic", valid=True,
                    selected=True, text=basic_instruction(s.task.type, display(s, s.task.source) or "",
                                                          display(s, s.task.target)),
                ) for s in specs], root / "data/instructions.parquet", InstructionRow)
                cfg = {**base, "policy": {policy: {"name": policy}},
                       "executor": {"name": "local", "workers": workers},
                       "sim": {**base["sim"], "image_size": list(size)},
                       "rollout": {**base["rollout"], "video": "none", "frames": True}}
                t0 = time.perf_counter()
                result = rollout_stage(cfg, policy, root=root, progress=False)
                wall = time.perf_counter() - t0
                s = result.summary
                import polars as pl

                df = pl.DataFrame([t.model_dump() for t in s.timings])  # the timings table's rows
                load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
                steady = 3600 * workers / df["total_seconds"].mean()
                print(f"{policy:9s} workers {workers}: {s.planned} episodes in {wall:6.1f} s -> "
                      f"{3600 * s.planned / wall:6.0f} episodes/h by wall clock, {steady:6.0f}/h once "
                      f"started (workers / mean episode time)   (success {s.statuses['success']}, "
                      f"failure {s.statuses['failure']}, error {s.statuses['error']}, invalid "
                      f"{s.statuses['invalid_scene']}; mean episode {df['total_seconds'].mean():.1f} s, "
                      f"{df['steps'].mean():.0f} steps; load average {load})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=int, default=3, help="scenes for the overhead comparison")
    parser.add_argument("--steps", type=int, default=60, help="steps per overhead episode")
    parser.add_argument("--repeats", type=int, default=2, help="passes over the overhead scenes")
    parser.add_argument("--size", type=int, default=256, help="camera width = height")
    parser.add_argument("--throughput-scenes", type=int, default=6)
    parser.add_argument("--skip-throughput", action="store_true")
    args = parser.parse_args()
    size = (args.size, args.size)
    from ladev_lib.assets import asset_dir

    print(f"MS_ASSET_DIR: {asset_dir() or 'not set (stand-in objects)'}; cpu cores: {os.cpu_count()}")
    specs = valid_scenes(max(args.scenes, 0 if args.skip_throughput else args.throughput_scenes), size)
    overhead(specs[: args.scenes], args.steps, size, args.repeats)
    if not args.skip_throughput:
        throughput(specs[: args.throughput_scenes], size)


if __name__ == "__main__":
    main()
